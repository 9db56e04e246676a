//! Leaving zero slip in space: the directions a slip can restart along, whether the slips
//! around them are drawn in or pushed away, and the slip that restarts at the edge of a cone.
//!
//! **The direction flow.** Contact i slides along the unit u; under fixed modes of the other
//! contacts its slip changes at f(u) = dv_it/ds, a function of u through the rates
//! ([`super::rates`]: dτ_i = μ_i u dp_i, and p′ depends on u). With u = v_t/ρ, ρ = |v_t|,
//!
//! ```text
//! dρ/ds = u · f(u) = λ(u),        dθ/ds = u⊥ · f(u) / ρ = g(u) / ρ       (u⊥ = u turned by +90°)
//! ```
//!
//! so near zero slip the direction turns ever faster. A slip leaves zero slip along an
//! **invariant direction**: g(u) = 0, f(u) = λ u, with λ > 0 (Bhatt and Koechling). Turned from
//! it by a small δθ, g ≈ −κ δθ with κ = −dg/dθ, so dδθ/ds = −κ δθ/ρ: the direction **attracts**
//! the slips around it when κ > 0 (they all close on it: the slip leaving zero is unique and the
//! outcome smooth in the data), and **repels** them when κ < 0 (with ρ ≈ λσ, σ = s − s₀, every
//! δθ ∝ σ^{|κ|/λ} leaves zero tangent to it: a fan of slips, and neighbouring initial conditions
//! end apart — a verdict).
//!
//! **The stick that reaches its cone's edge.** A sticking contact holds v_t = 0 with the
//! required rate τ′ = τ*(s). At s*, where |τ*| reaches μ p′, let w = τ*/|τ*|: sliding along w
//! gives exactly the sticking rates, so f(w) = 0 at s* — w is invariant with λ = 0. After s* the
//! required rate is outside the cone and the contact slides; write f(u, s) ≈ σ c + D(u − w) with
//! c = ∂f/∂s at (w, s*), D = ∂f/∂u there (D ≈ −μ p′ K_tt on the tangent of the circle, K_tt the
//! contact's tangential inertance block, positive definite: for one contact κ ≈ μ p′ w⊥·K_tt w⊥
//! > 0, attracting). With v_t = ρ u and u = w + θ w⊥,
//!
//! ```text
//! θ(σ) = α σ + O(σ²),   α = −(w⊥ · c) / (w⊥ · D w⊥),      the invariant direction u*(s) to first order;
//! λ(σ) = λ₁ σ + O(σ²),  λ₁ = w · (c + α D w⊥) ≥ 0,        ρ = λ₁ σ²/2 + O(σ³).
//! ```
//!
//! The slip restarts from zero **quadratically**, along the invariant direction that grows out
//! of w (λ = 0 at s*, then growing), and δθ obeys dδθ/ds = −κ δθ / (λ₁σ²/2): with κ > 0 every
//! neighbouring direction is drawn in like exp(−2κ/(λ₁σ)) — far more strongly than at an
//! ordinary departure. An explicit step cannot follow that flow, so the integrator
//! ([`super::spatial`]) holds the slip on u*(s), **tracked** at every evaluation as the root of
//! g nearest the direction held ([`track`]), until the step resolves the pull (κ h ≤ ρ).
//!
//! The root must be found by a root finder, not by the fixed-point iteration u ← f(u)/|f(u)|:
//! its derivative in θ at the root is 1 − κ/λ, so it diverges wherever κ > 2λ — at every
//! strongly attracting direction, and always as λ → 0 at a cone's edge. (That iteration failed
//! there, the direction held was left at w while u*(s) turned away from it, and κ measured off
//! the root read as −10⁵: the corner of issue 28, `tests/regression_stick_exit_direction.rs`.)
//! The derivation is written out for the sphere in a corner in
//! `derivations/friction-stick-exit.md`.

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::modes::nonnegative;
use crate::impact::friction::rates::{
    Mode, Normal, RateFailure, Rates, max_abs, rates, rates_into,
};
use crate::linalg::gauss::solve_general_in;
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// |x|.
pub(super) fn norm<T: Scalar>(x: &[T]) -> T {
    let mut s = T::zero();
    for v in x {
        s += v.clone() * v;
    }
    s.sqrt_value().expect("a float scalar has square roots")
}

/// x · y.
pub(super) fn dot<T: Scalar>(x: &[T], y: &[T]) -> T {
    x.iter()
        .zip(y)
        .fold(T::zero(), |acc, (a, b)| acc + a.clone() * b)
}

/// x / |x|.
pub(super) fn unit<T: Scalar>(x: &[T]) -> Vec<T> {
    let r = norm(x);
    x.iter().map(|a| a.clone() / r.clone()).collect()
}

/// An f64 in a float scalar.
pub(super) fn of<T: Scalar>(x: f64) -> T {
    T::from_f64(x).expect("a float scalar takes an f64")
}

/// How contact i's slip changes when it slides along `u` (the other contacts in `modes`):
/// (g, λ, f) with f = dv_it/ds, g = u⊥ · f and λ = u · f — λ = 0 when the contact's normal
/// impulse rate is negative (its friction would push along the slip: not a slide). Leaves
/// `modes[i]` sliding along u.
///
/// # Errors
/// [`RateFailure`] when the modes have no rates.
pub fn slip_rate<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    i: usize,
    u: &[T],
) -> Result<(T, T, Vec<T>), RateFailure> {
    let mut r = Rates::default();
    let (g, lambda) = slip_rate_in(b, normals, modes, i, u, &mut r)?;
    let off = b.offset[i];
    Ok((g, lambda, r.velocity[off + 1..off + 3].to_vec()))
}

/// [`slip_rate`]'s (g, λ), the rates solved into `r`, which the caller keeps from trial to
/// trial of a root search (f is `r.velocity` along the contact's tangent axes); `modes[i]`'s
/// direction is overwritten in place. Bit for bit [`slip_rate`]'s.
///
/// # Errors
/// [`RateFailure`] when the modes have no rates.
pub fn slip_rate_in<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    i: usize,
    u: &[T],
    r: &mut Rates<T>,
) -> Result<(T, T), RateFailure> {
    match &mut modes[i] {
        Mode::Slide(held) if held.len() == u.len() => held.clone_from_slice(u),
        other => *other = Mode::Slide(u.to_vec()),
    }
    rates_into(b, normals, modes, r)?;
    let off = b.offset[i];
    let f = &r.velocity[off + 1..off + 3];
    let g = u[0].clone() * &f[1] - u[1].clone() * &f[0];
    let lambda = if nonnegative(&r.lambda[off], &max_abs(&r.lambda), b.len()) {
        dot(u, f)
    } else {
        T::zero()
    };
    Ok((g, lambda))
}

/// u turned by the angle whose tangent is `t`: (u + t u⊥)/|u + t u⊥|.
fn turned<T: Scalar>(u: &[T], t: &T) -> Vec<T> {
    unit(&[
        u[0].clone() - t.clone() * &u[1],
        u[1].clone() + t.clone() * &u[0],
    ])
}

/// κ = −dg/dθ at `u` (by a central difference of 10⁻⁶ rad): how fast the slips turned from u
/// are pulled back to it, per unit angle, times ρ; κ > 0 attracts, κ < 0 repels. `None` when
/// the rates fail near u. `modes[i]` is restored.
pub fn pull<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    i: usize,
    u: &[T],
) -> Option<f64> {
    let eps: f64 = 1e-6;
    let held = modes[i].clone();
    let mut r = Rates::default();
    let mut at = |t: f64| {
        slip_rate_in(b, normals, modes, i, &turned(u, &of(t)), &mut r)
            .ok()
            .map(|(g, _)| g.to_f64())
    };
    let (plus, minus) = (at(eps.tan()), at(-eps.tan()));
    modes[i] = held;
    Some(-(plus? - minus?) / (2.0 * eps))
}

/// A root of t ↦ g(turned(u, t)) in the bracket [lo, hi] (g(lo), g(hi) of opposite signs) to
/// `settled`, by regula falsi with the Illinois modification (bisection's guarantee, superlinear
/// on a smooth g). `None` when the rates fail inside.
fn refine<T: Scalar>(
    mut g: impl FnMut(&T) -> Option<T>,
    (mut lo, mut glo): (T, T),
    (mut hi, mut ghi): (T, T),
    settled: f64,
) -> Option<T> {
    let two = T::one() + T::one();
    let mut side = 0i8;
    for _ in 0..200 {
        if (hi.clone() - &lo).to_f64().abs() <= settled {
            break;
        }
        let denom = ghi.clone() - &glo;
        let mut t = if denom.is_zero() {
            (lo.clone() + &hi) / two.clone()
        } else {
            lo.clone() - glo.clone() * (hi.clone() - &lo) / denom
        };
        // Keep t strictly inside the bracket (lo and hi in either order).
        if (t.clone() - &lo).signum_i8() * (hi.clone() - &t).signum_i8() <= 0 {
            t = (lo.clone() + &hi) / two.clone();
        }
        let gt = g(&t)?;
        if gt.is_zero() {
            return Some(t);
        }
        if gt.signum_i8() == glo.signum_i8() {
            lo = t;
            glo = gt;
            if side == -1 {
                ghi /= two.clone();
            }
            side = -1;
        } else {
            hi = t;
            ghi = gt;
            if side == 1 {
                glo /= two.clone();
            }
            side = 1;
        }
    }
    Some((lo + hi) / two)
}

/// Track a held slip direction: the invariant direction of contact i (g = 0, λ > 0) nearest
/// the direction `modes[i]` holds, within the angle whose tangent is `reach`, to `settled` in
/// angle — by a secant step from the held direction, else the nearest sign change of g on either
/// side (steps growing fourfold from `settled`), refined by [`refine`]. The root is what a slip
/// restarting from zero follows while the step cannot resolve its pull (module docs); the
/// fixed-point iteration u ← f/|f| diverges there whenever κ > 2λ. Returns whether a root was
/// found: otherwise `modes[i]` keeps the held direction (the direction has moved further than
/// `reach`, or no longer leaves zero slip).
pub fn track<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    i: usize,
    settled: f64,
    reach: f64,
) -> bool {
    let Mode::Slide(held) = modes[i].clone() else {
        return false;
    };
    let mut r = Rates::default();
    let mut g = |t: &T| -> Option<(T, T)> {
        slip_rate_in(b, normals, modes, i, &turned(&held, t), &mut r).ok()
    };
    let found = (|| {
        let zero = T::zero();
        let (g0, l0) = g(&zero)?;
        if g0.is_zero() {
            return Some((zero, l0));
        }
        // A secant step first: a tracked root moves little between evaluations.
        let d: T = of(1e-7);
        let (gd, _) = g(&d)?;
        let slope = (gd.clone() - &g0) / d.clone();
        let mut bracket = None;
        if !slope.is_zero() {
            let t1 = -(g0.clone() / slope);
            let step = t1.to_f64().abs();
            if step <= reach {
                // Bracket the predicted root by 1/8 of its distance (at least `settled`).
                let pad: T = of((step / 8.0).max(settled));
                let sign: T = of(t1.to_f64().signum());
                let (a, c) = (t1.clone() - pad.clone() * &sign, t1 + pad * sign);
                let (ga, _) = g(&a)?;
                let (gc, _) = g(&c)?;
                if ga.signum_i8() * gc.signum_i8() < 0 {
                    bracket = Some(((a, ga), (c, gc)));
                }
            }
        }
        if bracket.is_none() {
            let mut step = settled.min(reach);
            while bracket.is_none() {
                for sign in [1.0, -1.0] {
                    let t: T = of(sign * step);
                    let (gt, _) = g(&t)?;
                    if gt.signum_i8() * g0.signum_i8() <= 0 {
                        bracket = Some(((T::zero(), g0.clone()), (t, gt)));
                        break;
                    }
                }
                if step >= reach {
                    break;
                }
                step = (4.0 * step).min(reach);
            }
        }
        let (a, c) = bracket?;
        let t = refine(|t| g(t).map(|(g, _)| g), a, c, settled)?;
        let (_, l) = g(&t)?;
        Some((t, l))
    })();
    match found {
        Some((t, l)) if l.signum_i8() > 0 => {
            modes[i] = Mode::Slide(turned(&held, &t));
            true
        }
        _ => {
            modes[i] = Mode::Slide(held);
            false
        }
    }
}

/// The last [`track`] of each contact, kept by the spatial integrator between its calls: the
/// rates depend on the modes and rules alone, not on the impulses, so a held slip tracked again
/// under the same rules and the same modes (every other contact sticking, free or held, as at
/// every stage of a step after a stick ends at its cone's edge) has the same root — and the
/// root search, several rate solves, is the integration's largest cost (issue 29). A track is
/// recalled only when its inputs compare equal, so the result is the one a fresh search gives.
pub struct TrackMemo<T: Scalar> {
    /// Per contact, its last search.
    last: Vec<Option<Tracked<T>>>,
}

/// One search of [`TrackMemo`]: the rules and the modes it started from, and what it left in
/// `modes[i]` with its verdict.
struct Tracked<T: Scalar> {
    normals: Vec<Normal<T>>,
    modes: Vec<Mode<T>>,
    mode: Mode<T>,
    found: bool,
}

impl<T: Scalar> TrackMemo<T> {
    /// An empty memo for `n` contacts.
    pub fn new(n: usize) -> Self {
        TrackMemo {
            last: (0..n).map(|_| None).collect(),
        }
    }

    /// [`track`], recalled when contact i's last search had the same `normals` and `modes`.
    pub fn track<S: Screws<T>>(
        &mut self,
        b: &Blocks<T, S>,
        normals: &[Normal<T>],
        modes: &mut [Mode<T>],
        i: usize,
        settled: f64,
        reach: f64,
    ) -> bool {
        if let Some(t) = &self.last[i]
            && t.normals.as_slice() == normals
            && t.modes.as_slice() == &*modes
        {
            modes[i] = t.mode.clone();
            return t.found;
        }
        let before = modes.to_vec();
        let found = track(b, normals, modes, i, settled, reach);
        self.last[i] = Some(Tracked {
            normals: normals.to_vec(),
            modes: before,
            mode: modes[i].clone(),
            found,
        });
        found
    }
}

/// One invariant direction at zero slip, with its pull.
pub struct Invariant<T: Scalar> {
    /// The unit direction u (f(u) = λ u).
    pub u: Vec<T>,
    /// κ ([`pull`]); > 0 attracts.
    pub kappa: f64,
}

/// Every invariant direction along which contact i can leave zero slip (λ > 0: a stick just
/// outside its cone leaves at a small λ, one at its edge at λ → 0⁺): a scan of the circle at
/// 5° for the sign changes of g, each refined by bisection along the chord. `modes[i]` is left
/// sliding along the last direction tried.
///
/// # Errors
/// [`RateFailure`] when the rates fail at a root being refined.
pub fn invariant_directions<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    i: usize,
) -> Result<Vec<Invariant<T>>, RateFailure> {
    const SAMPLES: usize = 72;
    let mut samples = Vec::with_capacity(SAMPLES);
    for k in 0..SAMPLES {
        let th = std::f64::consts::TAU * k as f64 / SAMPLES as f64;
        let w: Vec<T> = vec![of(th.cos()), of(th.sin())];
        samples.push(match slip_rate(b, normals, modes, i, &w) {
            Ok((g, l, _)) => Some((w, g, l)),
            Err(_) => None,
        });
    }
    let mut roots: Vec<Vec<T>> = Vec::new();
    for k in 0..SAMPLES {
        let (Some(a), Some(c)) = (&samples[k], &samples[(k + 1) % SAMPLES]) else {
            continue;
        };
        let (sa, sc) = (a.1.signum_i8(), c.1.signum_i8());
        if sa == 0 {
            if a.2.signum_i8() > 0 {
                roots.push(a.0.clone());
            }
            continue;
        }
        if sa * sc > 0 || sc == 0 {
            continue;
        }
        // Bisection along the chord from a to c, normalised.
        let (mut lo, mut hi) = (T::zero(), T::one());
        let two = T::one() + T::one();
        let at = |t: &T| -> Vec<T> {
            let w: Vec<T> =
                a.0.iter()
                    .zip(&c.0)
                    .map(|(x, y)| x.clone() + (y.clone() - x) * t)
                    .collect();
            unit(&w)
        };
        for _ in 0..120 {
            let mid = (lo.clone() + &hi) / two.clone();
            if (hi.clone() - &lo).to_f64() <= T::epsilon_f64() {
                break;
            }
            let (gm, _, _) = slip_rate(b, normals, modes, i, &at(&mid))?;
            if gm.signum_i8() == sa {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let root = at(&((lo + hi) / two));
        let (_, lambda, _) = slip_rate(b, normals, modes, i, &root)?;
        if lambda.signum_i8() > 0 {
            roots.push(root);
        }
    }
    Ok(roots
        .into_iter()
        .map(|u| {
            let kappa = pull(b, normals, modes, i, &u).unwrap_or(f64::NEG_INFINITY);
            Invariant { u, kappa }
        })
        .collect())
}

/// The slip rates f_k = dv_kt/ds and g_k = u_k⊥ · f_k of the contacts `sliding`, each sliding
/// along its direction in `dirs` (`modes` set so). `None` when the rates fail.
fn joint_rates<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    sliding: &[usize],
    dirs: &[Vec<T>],
) -> Option<(Vec<T>, Vec<Vec<T>>)> {
    for (&i, u) in sliding.iter().zip(dirs) {
        modes[i] = Mode::Slide(u.clone());
    }
    let r = rates(b, normals, modes).ok()?;
    let f: Vec<Vec<T>> = sliding
        .iter()
        .map(|&i| r.velocity[b.offset[i] + 1..b.offset[i] + 3].to_vec())
        .collect();
    let g = dirs
        .iter()
        .zip(&f)
        .map(|(u, f)| u[0].clone() * &f[1] - u[1].clone() * &f[0])
        .collect();
    Some((g, f))
}

/// Several contacts leaving zero slip together: directions u_k of the contacts `sliding` with
/// g_k(u) = u_k⊥ · f_k(u) = 0 for every k at once, f_k = dv_kt/ds with all of them sliding —
/// the joint invariant direction of the module docs — found by Newton's method on their
/// angles from `start` (u_k = `start[k]` turned by the angle whose tangent is t_k; a
/// forward-difference Jacobian of 10⁻⁷; a step halved until max|g| falls), to `settled` in
/// angle. As for one contact, the root needs a root finder: the joint fixed-point iteration
/// u_k ← f_k/|f_k| has the derivative 1 + D J at a root (J = ∂g/∂θ, D = diag(1/λ_k)), and
/// diverges wherever an eigenvalue z of D J lies outside the disc |1 + z| < 1 (a real one below
/// −2) — at strongly attracting directions (the face of a can whose three rim points reverse
/// their slip together, issue 27: about −3, the iteration's errors doubling with alternating
/// sign). Returns the root's directions, their λ_k and the eigenvalues' largest real part
/// (< 0: the directions attract the slips around them), or `None` when Newton's method does
/// not settle on a root or the rates fail; `modes` are left sliding along the last directions
/// tried (along the root's when one is returned).
pub fn joint_root<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &mut [Mode<T>],
    sliding: &[usize],
    start: &[Vec<T>],
    settled: f64,
) -> Option<JointRoot<T>> {
    let k = sliding.len();
    let at =
        |t: &[T]| -> Vec<Vec<T>> { start.iter().zip(t).map(|(u, tk)| turned(u, tk)).collect() };
    let size = |g: &[T]| g.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs()));
    let d: T = of(1e-7);
    // ∂g/∂t at t (g there given), k × k row-major, by forward differences.
    let jacobian = |modes: &mut [Mode<T>], t: &[T], g: &[T]| -> Option<Vec<T>> {
        let mut jac = vec![T::zero(); k * k];
        for c in 0..k {
            let mut tc = t.to_vec();
            tc[c] += d.clone();
            let (gc, _) = joint_rates(b, normals, modes, sliding, &at(&tc))?;
            for r in 0..k {
                jac[r * k + c] = (gc[r].clone() - &g[r]) / d.clone();
            }
        }
        Some(jac)
    };
    let mut t = vec![T::zero(); k];
    let (mut g, _) = joint_rates(b, normals, modes, sliding, &at(&t))?;
    let mut settled_at = false;
    for _ in 0..60 {
        if size(&g) == 0.0 {
            settled_at = true;
            break;
        }
        let jac = jacobian(modes, &t, &g)?;
        let mut a = jac;
        let mut rhs: Vec<T> = g.iter().map(|x| -x.clone()).collect();
        let (mut pivots, mut step) = (Vec::new(), Vec::new());
        if !solve_general_in(&mut a, k, k, &mut rhs, &mut pivots, &mut step) || pivots.len() != k {
            return None;
        }
        // Halve the step until max|g| falls (at most 30 times).
        let before = size(&g);
        let mut scale = T::one();
        let mut accepted = None;
        for _ in 0..30 {
            let trial: Vec<T> = t
                .iter()
                .zip(&step)
                .map(|(x, s)| x.clone() + s.clone() * &scale)
                .collect();
            if let Some((gt, _)) = joint_rates(b, normals, modes, sliding, &at(&trial))
                && size(&gt) < before
            {
                accepted = Some((trial, gt));
                break;
            }
            scale /= T::one() + T::one();
        }
        let moved = step.iter().fold(0.0_f64, |m, x| m.max(x.to_f64().abs())) * scale.to_f64();
        if let Some((trial, gt)) = accepted {
            t = trial;
            g = gt;
        } else if moved > settled {
            return None;
        }
        if moved <= settled {
            settled_at = true;
            break;
        }
    }
    if !settled_at {
        return None;
    }
    let dirs = at(&t);
    let (g, f) = joint_rates(b, normals, modes, sliding, &dirs)?;
    // A root, not where the halved steps stalled: every direction within 16 `settled` of its
    // slip rate's (|g_k| = |f_k| sin of the angle between them).
    if g.iter()
        .zip(&f)
        .any(|(gk, fk)| gk.to_f64().abs() > 16.0 * settled * norm(fk).to_f64())
    {
        return None;
    }
    let lambda: Vec<T> = dirs.iter().zip(&f).map(|(u, f)| dot(u, f)).collect();
    // J = ∂g/∂θ: dθ_c = dt_c / (1 + t_c²).
    let jac = jacobian(modes, &t, &g)?;
    let jac: Vec<T> = (0..k * k)
        .map(|q| jac[q].clone() * (T::one() + t[q % k].clone() * &t[q % k]))
        .collect();
    let attraction = attraction(&jac, &lambda, k);
    for (&i, u) in sliding.iter().zip(&dirs) {
        modes[i] = Mode::Slide(u.clone());
    }
    Some(JointRoot {
        dirs,
        lambda,
        attraction,
    })
}

/// Directions found by [`joint_root`].
pub struct JointRoot<T: Scalar> {
    /// The unit directions u_k, one per sliding contact.
    pub dirs: Vec<Vec<T>>,
    /// λ_k = u_k · f_k.
    pub lambda: Vec<T>,
    /// The largest real part of the eigenvalues of D J (D = diag(1/λ_k), J = ∂g/∂θ): below 0
    /// the joint direction attracts the slips around it (dδθ/ds = D J δθ / σ with ρ_k ≈ λ_k σ).
    pub attraction: f64,
}

/// The largest real part of the eigenvalues of diag(1/λ) J (`jac`, k × k, row-major), in f64;
/// +∞ when a λ_k is not positive or the eigenvalues are not finite.
fn attraction<T: Scalar>(jac: &[T], lambda: &[T], k: usize) -> f64 {
    if lambda.iter().any(|l| l.signum_i8() <= 0) {
        return f64::INFINITY;
    }
    let m = nalgebra::DMatrix::<f64>::from_fn(k, k, |r, c| {
        jac[r * k + c].to_f64() / lambda[r].to_f64()
    });
    m.complex_eigenvalues()
        .iter()
        .map(|z| z.re)
        .fold(f64::NEG_INFINITY, |a, x| {
            if x.is_finite() {
                a.max(x)
            } else {
                f64::INFINITY
            }
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::impact::problem::Problem;
    use crate::mechanics::body::RigidBody;
    use crate::mechanics::contact::{Contact, ContactFrame};
    use crate::mechanics::screw::{Screw, Vec3};

    /// A box corner (half sides 1/2, 3/10, 1/5, unit mass) striking the ground, μ = 1, in
    /// compression (`tests/friction_spatial.rs`, whose slip stops and leaves again): its
    /// tangential block is anisotropic and coupled to the normal one.
    fn corner() -> (Blocks<f64>, Vec<Normal<f64>>) {
        let (a, b, c) = (0.5, 0.3, 0.2);
        let j = |p: f64, q: f64| (p * p + q * q) / 3.0;
        let problem = Problem::new(
            RigidBody::principal(1.0, Vec3::new(j(b, c), j(a, c), j(a, b))),
            Screw::new(Vec3::zeros(), Vec3::new(-0.1, -0.1, -1.0)),
            vec![
                Contact::new(Vec3::new(a, b, -c), Vec3::new(0.0, 0.0, -1.0), 0.5)
                    .with_friction(1.0),
            ],
        )
        .unwrap();
        let frames: Vec<ContactFrame<f64>> = problem
            .contacts()
            .iter()
            .enumerate()
            .map(|(i, c)| ContactFrame::new(i, c, problem.velocity()).unwrap())
            .collect();
        let blocks = Blocks::spatial(&problem, &frames);
        let normals = vec![Normal::Driven(blocks.v0[0])];
        (blocks, normals)
    }

    /// Every invariant direction found is one (g = 0, λ > 0); turned from it by 0.2 rad either
    /// way, `track` comes back to it; and κ is the slope of g there (g ≈ −κ δθ).
    #[test]
    fn a_turned_direction_is_tracked_back_to_its_invariant_direction() {
        let (b, normals) = corner();
        let mut modes = vec![Mode::Slide(vec![1.0, 0.0])];
        let roots = invariant_directions(&b, &normals, &mut modes, 0).unwrap();
        assert!(!roots.is_empty());
        for r in &roots {
            let (g, lambda, f) = slip_rate(&b, &normals, &mut modes, 0, &r.u).unwrap();
            assert!(
                g.abs() <= 1e-12 * norm(&f) && lambda > 0.0,
                "g = {g}, λ = {lambda}"
            );
            for t in [0.2f64, -0.2] {
                modes[0] = Mode::Slide(turned(&r.u, &t.tan()));
                assert!(track(&b, &normals, &mut modes, 0, 1e-13, 0.3));
                let Mode::Slide(u) = &modes[0] else {
                    panic!("a slide")
                };
                let diff = (u[0] - r.u[0]).abs().max((u[1] - r.u[1]).abs());
                assert!(diff <= 1e-10, "{u:?} against {:?}", r.u);
            }
            let d: f64 = 1e-4;
            let (gd, _, _) =
                slip_rate(&b, &normals, &mut modes, 0, &turned(&r.u, &d.tan())).unwrap();
            assert!(
                (gd + r.kappa * d).abs() <= 1e-3 * (r.kappa * d).abs(),
                "g = {gd}, κ δθ = {}",
                r.kappa * d
            );
        }
    }

    /// A direction further than `reach` from every invariant one is not tracked: the held
    /// direction is kept.
    #[test]
    fn a_direction_beyond_reach_is_kept() {
        let (b, normals) = corner();
        let mut modes = vec![Mode::Slide(vec![1.0, 0.0])];
        let roots = invariant_directions(&b, &normals, &mut modes, 0).unwrap();
        let u = &roots[0].u;
        let away = turned(u, &1.0f64.tan());
        modes[0] = Mode::Slide(away.clone());
        let nearest = roots
            .iter()
            .map(|r| dot(&r.u, &away).clamp(-1.0, 1.0).acos())
            .fold(f64::INFINITY, f64::min);
        assert!(nearest > 0.3);
        assert!(!track(&b, &normals, &mut modes, 0, 1e-13, 0.3_f64.tan()));
        assert_eq!(modes[0], Mode::Slide(away));
    }
}
