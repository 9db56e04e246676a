//! Spatial scenes, numerically: the impulse-space equations integrated by the embedded
//! Runge–Kutta pair of Dormand and Prince (RK5(4), local extrapolation), with adaptive steps
//! and event location, in any float scalar (f64, double-double).
//!
//! The state is y = (Λ, W_c, W_r, E_f): the impulses along every axis, each contact's
//! compression and restitution work, and the friction dissipation; the velocities follow from
//! Λ (eq. 144). Between events the modes are fixed: a sliding contact's direction is
//! u_i = v_it / |v_it| at every evaluation, a sticking one takes its tangential rate from the
//! rate system ([`super::rates`]).
//!
//! **Events.** The end of a phase (the step is clipped to it); a sticking contact whose
//! required rate leaves its cone, and an energetic contact whose restitution work reaches
//! k² times its compression work — both located by bisection of the step, re-integrated from
//! its start; a sliding contact whose slip reaches zero. At zero slip the modes are chosen
//! again: stick when the cone allows it, otherwise slip in the direction the dynamics gives —
//! the invariant direction u of the contact's tangential block, dv_it/ds = λ u with λ > 0,
//! found by fixed-point iteration from the direction of the required sticking impulse.
//!
//! **Bhatt and Koechling's singular point.** Near sticking, the slip direction u = v_t/|v_t|
//! turns ever faster (its rate grows like 1/|v_t|) towards an invariant direction, and an
//! error-controlled integrator would shrink its steps without end. Here the step is never
//! longer than nine tenths of the predicted time to zero slip, |v_t| / (−d|v_t|/ds), so |v_t|
//! falls geometrically; once it is below δ = tol · max|v⁰| the contact is declared at zero
//! slip (the impulse skipped is at most δ / min-rate, within the tolerance). The number of
//! steps near the singular point grows like log(1/tol), not like 1/tol.
//!
//! **Error estimate.** The sum of the embedded local error estimates of the accepted steps,
//! plus the δ of every declared stop, in impulse units (unit axes) — reported with the result
//! and tested against a run a thousand times tighter.

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::modes::{nonnegative, positive};
use crate::impact::friction::rates::{Mode, Normal, RateFailure, Rates, max_abs, rates};
use crate::impact::friction::{
    FrictionError, Frictional, Phase, Restitution, Segment, Verdict, label,
};
use crate::impact::problem::Problem;
use crate::scalar::Scalar;

/// The most accepted and rejected steps before the integration is declared runaway.
const MAX_STEPS: usize = 200_000;

/// Dormand–Prince RK5(4) tableau.
const C: [f64; 7] = [0.0, 0.2, 0.3, 0.8, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [0.2, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
/// Fifth-order weights minus fourth-order weights: the local error estimate.
const E: [f64; 7] = [
    71.0 / 57600.0,
    0.0,
    -71.0 / 16695.0,
    71.0 / 1920.0,
    -17253.0 / 339200.0,
    22.0 / 525.0,
    -1.0 / 40.0,
];

/// The integration's fixed data.
struct Run<'a, T: Scalar> {
    problem: &'a Problem<T>,
    b: &'a Blocks<T>,
    law: Restitution,
    tol: f64,
    /// Below this slip speed a contact is at zero slip.
    delta: f64,
    /// Impulse scale for the absolute tolerance.
    lambda_scale: f64,
    /// Work scale.
    work_scale: f64,
}

/// The changing part of the integration.
struct State<T: Scalar> {
    s: T,
    phase: Phase,
    y: Vec<T>,
    modes: Vec<Mode<T>>,
    stopped: Vec<bool>,
    compression: Vec<T>,
}

fn t<T: Scalar>(x: f64) -> T {
    T::from_f64(x).expect("a float scalar takes an f64")
}

fn norm<T: Scalar>(x: &[T]) -> T {
    let mut s = T::zero();
    for v in x {
        s += v.clone() * v;
    }
    s.sqrt_value().expect("a float scalar has square roots")
}

impl<T: Scalar> Run<'_, T> {
    fn n(&self) -> usize {
        self.b.contacts()
    }

    fn len(&self) -> usize {
        self.b.len()
    }

    /// v = v⁰ − K Λ.
    fn velocities(&self, y: &[T]) -> Vec<T> {
        let mut dv = Vec::new();
        self.b.velocity_change(&y[..self.len()], &mut dv);
        dv.iter()
            .zip(&self.b.v0)
            .map(|(d, v0)| v0.clone() + d)
            .collect()
    }

    fn normals(&self, st: &State<T>) -> Vec<Normal<T>> {
        let b = self.b;
        self.problem
            .contacts()
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let v0 = b.v0[b.offset[i]].clone();
                match (st.phase, self.law) {
                    (Phase::Compression, _) => Normal::Driven(v0),
                    (Phase::Restitution, Restitution::Newton) => {
                        Normal::Driven(c.k_newton.clone() * v0)
                    }
                    (Phase::Restitution, Restitution::Poisson) => {
                        Normal::Given(c.k_poisson.clone() * &st.compression[i])
                    }
                    (Phase::Restitution, Restitution::Energetic) if st.stopped[i] => {
                        Normal::Given(T::zero())
                    }
                    (Phase::Restitution, Restitution::Energetic) => {
                        Normal::Given(st.compression[i].clone())
                    }
                }
            })
            .collect()
    }

    /// The modes at `y`: sliding contacts take the direction of their slip (or keep theirs
    /// below δ).
    fn modes_at(&self, y: &[T], v: &[T], modes: &[Mode<T>]) -> Vec<Mode<T>> {
        let _ = y;
        let b = self.b;
        modes
            .iter()
            .enumerate()
            .map(|(i, m)| match m {
                Mode::Slide(u) => {
                    let off = b.offset[i] + 1;
                    let vt = &v[off..off + 2];
                    let r = norm(vt);
                    if r.to_f64() > self.delta {
                        Mode::Slide(vt.iter().map(|x| x.clone() / r.clone()).collect())
                    } else {
                        Mode::Slide(u.clone())
                    }
                }
                other => other.clone(),
            })
            .collect()
    }

    /// dy/ds and the rates at `y`.
    fn rhs(&self, st: &State<T>, y: &[T]) -> Result<(Vec<T>, Rates<T>), FrictionError> {
        let v = self.velocities(y);
        let modes = self.modes_at(y, &v, &st.modes);
        let r = rates(self.b, &self.normals(st), &modes).map_err(|e| match e {
            RateFailure::Undetermined => FrictionError::Undetermined { s: st.s.to_f64() },
            RateFailure::Inconsistent => FrictionError::NoConsistentModes {
                s: st.s.to_f64(),
                phase: st.phase,
            },
        })?;
        let n = self.n();
        let len = self.len();
        let mut dy = Vec::with_capacity(len + 2 * n + 1);
        dy.extend(r.lambda.iter().cloned());
        let mut wc = vec![T::zero(); n];
        let mut wr = vec![T::zero(); n];
        let mut ef = T::zero();
        for q in 0..len {
            let power = v[q].clone() * &r.lambda[q];
            match self.b.offset.iter().position(|&o| o == q) {
                Some(i) if st.phase == Phase::Compression => wc[i] = power,
                Some(i) => wr[i] = -power,
                None => ef += power,
            }
        }
        dy.extend(wc);
        dy.extend(wr);
        dy.push(ef);
        Ok((dy, r))
    }

    /// One Dormand–Prince step of length h from y: the fifth-order solution and the error
    /// estimate (scaled norm, and the largest absolute impulse error).
    fn step(&self, st: &State<T>, y: &[T], h: f64) -> Result<(Vec<T>, f64, f64), FrictionError> {
        let mut k: Vec<Vec<T>> = Vec::with_capacity(7);
        for stage in 0..7 {
            let mut yi = y.to_vec();
            for (j, kj) in k.iter().enumerate() {
                let a = A[stage][j];
                if a != 0.0 {
                    let c: T = t(a * h);
                    for (x, d) in yi.iter_mut().zip(kj) {
                        *x += c.clone() * d;
                    }
                }
            }
            let mut st_i = State {
                s: st.s.clone() + t::<T>(C[stage] * h),
                phase: st.phase,
                y: Vec::new(),
                modes: st.modes.clone(),
                stopped: st.stopped.clone(),
                compression: st.compression.clone(),
            };
            st_i.y.clear();
            k.push(self.rhs(&st_i, &yi)?.0);
        }
        // Stage 7 was evaluated at the fifth-order solution (FSAL): y5 = y + h Σ A[6][j] k_j.
        let mut y5 = y.to_vec();
        for (j, kj) in k.iter().take(6).enumerate() {
            let c: T = t(A[6][j] * h);
            for (x, d) in y5.iter_mut().zip(kj) {
                *x += c.clone() * d;
            }
        }
        let len = self.len();
        let mut scaled: f64 = 0.0;
        let mut abs_impulse: f64 = 0.0;
        for q in 0..y.len() {
            let mut e = 0.0;
            for (j, kj) in k.iter().enumerate() {
                e += E[j] * kj[q].to_f64();
            }
            let e = (e * h).abs();
            let scale = if q < len {
                self.lambda_scale
            } else {
                self.work_scale
            };
            let w = self.tol * (scale + y5[q].to_f64().abs());
            scaled = scaled.max(e / w);
            if q < len {
                abs_impulse = abs_impulse.max(e);
            }
        }
        Ok((y5, scaled, abs_impulse))
    }

    /// Does the state at `y` ask for an event? Sticking contacts out of their cone, energetic
    /// contacts past their restitution work.
    fn event_function(&self, st: &State<T>, y: &[T]) -> Result<f64, FrictionError> {
        let b = self.b;
        let mut worst = f64::INFINITY;
        let (_, r) = self.rhs(st, y)?;
        for i in 0..self.n() {
            if st.modes[i] == Mode::Stick {
                let off = b.offset[i];
                let p = r.lambda[off].to_f64();
                let tau = norm(&r.lambda[off + 1..off + 1 + b.dims[i]]).to_f64();
                worst = worst.min((b.mu[i].to_f64() * p - tau) / self.lambda_scale.max(1e-300));
            }
            if st.phase == Phase::Restitution
                && self.law == Restitution::Energetic
                && !st.stopped[i]
            {
                let k = self.problem.contacts()[i].k_energetic.to_f64();
                let n = self.n();
                let len = self.len();
                let wc = y[len + i].to_f64();
                let wr = y[len + n + i].to_f64();
                worst = worst.min((k * k * wc - wr) / self.work_scale.max(1e-300));
            }
        }
        Ok(worst)
    }
}

/// Integrate a spatial scene under `law` to the relative tolerance `tol`.
///
/// # Errors
/// [`FrictionError`] as for planar scenes, and [`FrictionError::Runaway`] past the step budget.
pub fn solve_spatial<T: Scalar>(
    problem: &Problem<T>,
    b: Blocks<T>,
    law: Restitution,
    tol: f64,
) -> Result<Frictional<T>, FrictionError> {
    let n = b.contacts();
    let len = b.len();
    let vscale = max_abs(&b.v0).to_f64().max(f64::MIN_POSITIVE);
    let kscale = (0..len)
        .map(|q| b.at(q, q).to_f64())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let run = Run {
        problem,
        b: &b,
        law,
        tol,
        delta: tol * vscale,
        lambda_scale: vscale / kscale,
        work_scale: vscale * vscale / kscale,
    };
    let mut st = State {
        s: T::zero(),
        phase: Phase::Compression,
        y: vec![T::zero(); len + 2 * n + 1],
        modes: vec![Mode::Free; n],
        stopped: vec![false; n],
        compression: Vec::new(),
    };
    let mut segments: Vec<Segment<T>> = Vec::new();
    let mut verdicts = Vec::new();
    let mut error = 0.0;
    let mut h: f64 = 0.05;
    let mut steps = 0;
    resolve(&run, &mut st, &mut verdicts)?;
    let mut seg_start = st.s.clone();
    let mut seg_modes = st.modes.clone();
    let mut seg_rates = run.rhs(&st, &st.y)?.1.lambda;
    loop {
        steps += 1;
        if steps > MAX_STEPS {
            return Err(FrictionError::Runaway);
        }
        let end = match (st.phase, law) {
            (Phase::Compression, _) => Some(1.0),
            (Phase::Restitution, Restitution::Energetic) => None,
            (Phase::Restitution, _) => Some(2.0),
        };
        let s = st.s.to_f64();
        let (_, r) = run.rhs(&st, &st.y)?;
        for i in 0..n {
            let known = verdicts.iter().any(|v| {
                matches!(v, Verdict::TensileRate { contact, phase, .. }
                    if *contact == i && *phase == st.phase)
            });
            if !known
                && matches!(run.normals(&st)[i], Normal::Driven(_))
                && r.lambda[b.offset[i]].to_f64() < -tol * run.lambda_scale
            {
                verdicts.push(Verdict::TensileRate {
                    contact: i,
                    s,
                    phase: st.phase,
                });
            }
        }
        // Slip approaching zero: clip the step to 0.9 of the predicted time, or declare it.
        let v = run.velocities(&st.y);
        let mut at_rest = false;
        for i in 0..n {
            if let Mode::Slide(_) = &st.modes[i] {
                let off = b.offset[i] + 1;
                let vt = &v[off..off + 2];
                let rho = norm(vt).to_f64();
                let drho: f64 = vt
                    .iter()
                    .zip(&r.velocity[off..off + 2])
                    .map(|(a, d)| a.to_f64() * d.to_f64())
                    .sum::<f64>()
                    / rho.max(f64::MIN_POSITIVE);
                if rho <= run.delta && drho < 0.0 {
                    at_rest = true;
                    error += run.delta / kscale;
                } else if drho < 0.0 {
                    h = h.min(0.9 * rho / -drho);
                }
            }
        }
        if at_rest {
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            resolve(&run, &mut st, &mut verdicts)?;
            seg_start = st.s.clone();
            seg_modes = st.modes.clone();
            seg_rates = run.rhs(&st, &st.y)?.1.lambda;
            continue;
        }
        let mut hit_end = false;
        if let Some(e) = end
            && s + h >= e
        {
            h = e - s;
            hit_end = true;
        }
        let (y5, err, abs_err) = run.step(&st, &st.y, h)?;
        if err > 1.0 {
            h *= (0.9 * err.powf(-0.2)).max(0.2);
            continue;
        }
        // Events inside the step: locate by bisection.
        let (mut y_new, mut h_taken, mut event) = (y5, h, false);
        if run.event_function(&st, &y_new)? < 0.0 {
            event = true;
            hit_end = false;
            let (mut lo, mut hi) = (0.0, h);
            while hi - lo > tol * 1e-3 * h.max(1e-300) && hi - lo > 1e-15 {
                let mid = 0.5 * (lo + hi);
                let (ym, _, _) = run.step(&st, &st.y, mid)?;
                if run.event_function(&st, &ym)? < 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let (yh, _, _) = run.step(&st, &st.y, hi)?;
            y_new = yh;
            h_taken = hi;
        }
        error += abs_err;
        st.y = y_new;
        st.s = if hit_end {
            t(end.expect("a phase end was hit"))
        } else {
            st.s.clone() + t::<T>(h_taken)
        };
        h = (h * (0.9 * err.max(1e-10).powf(-0.2)).min(5.0)).max(1e-12);
        if event {
            // Energetic contacts that reached their work stop.
            if st.phase == Phase::Restitution && law == Restitution::Energetic {
                for i in 0..n {
                    let k = problem.contacts()[i].k_energetic.to_f64();
                    let wc = st.y[len + i].to_f64();
                    let wr = st.y[len + n + i].to_f64();
                    if !st.stopped[i] && wr >= k * k * wc - tol * run.work_scale {
                        st.stopped[i] = true;
                    }
                }
            }
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            resolve(&run, &mut st, &mut verdicts)?;
            seg_start = st.s.clone();
            seg_modes = st.modes.clone();
            seg_rates = run.rhs(&st, &st.y)?.1.lambda;
        }
        if hit_end {
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            if st.phase == Phase::Restitution {
                break;
            }
            st.phase = Phase::Restitution;
            st.compression = b.offset.iter().map(|&o| st.y[o].clone()).collect();
            if law == Restitution::Energetic {
                for i in 0..n {
                    let k = problem.contacts()[i].k_energetic.to_f64();
                    st.stopped[i] =
                        st.compression[i].is_zero() || k * k * st.y[len + i].to_f64() <= 0.0;
                }
            }
            resolve(&run, &mut st, &mut verdicts)?;
            seg_start = st.s.clone();
            seg_modes = st.modes.clone();
            seg_rates = run.rhs(&st, &st.y)?.1.lambda;
        }
        if st.phase == Phase::Restitution
            && law == Restitution::Energetic
            && st.stopped.iter().all(|&x| x)
        {
            close_segment(&mut segments, &seg_start, &st, &seg_modes, &seg_rates);
            break;
        }
    }
    let v = run.velocities(&st.y);
    let lambda = st.y[..len].to_vec();
    let wc = st.y[len..len + n].to_vec();
    let wr = st.y[len + n..len + 2 * n].to_vec();
    let ef = st.y[len + 2 * n].clone();
    let end = st.s.clone();
    let mut out = Frictional::finish(
        problem,
        b,
        law,
        lambda,
        st.compression,
        v,
        wc,
        wr,
        ef,
        segments,
        verdicts,
        end,
    );
    out.error_estimate = Some(error);
    Ok(out)
}

fn close_segment<T: Scalar>(
    segments: &mut Vec<Segment<T>>,
    from: &T,
    st: &State<T>,
    modes: &[Mode<T>],
    rates: &[T],
) {
    if (st.s.clone() - from).is_zero() {
        return;
    }
    segments.push(Segment {
        from: from.clone(),
        to: st.s.clone(),
        phase: st.phase,
        modes: modes.iter().map(label).collect(),
        rates: rates.to_vec(),
    });
}

/// Choose the modes at the current state: contacts without friction or normal impulse rate
/// are free; slipping ones slide; those at zero slip stick if their cones allow it, else slide
/// along the invariant direction of their tangential block.
fn resolve<T: Scalar>(
    run: &Run<'_, T>,
    st: &mut State<T>,
    verdicts: &mut Vec<Verdict>,
) -> Result<(), FrictionError> {
    let b = run.b;
    let n = run.n();
    let normals = run.normals(st);
    let v = run.velocities(&st.y);
    let mut candidates = Vec::new();
    for i in 0..n {
        let carries = match &normals[i] {
            Normal::Driven(_) => true,
            Normal::Given(r) => !r.is_zero(),
        };
        let off = b.offset[i] + 1;
        if b.dims[i] == 0 || !carries {
            st.modes[i] = Mode::Free;
            continue;
        }
        let vt = &v[off..off + 2];
        let r = norm(vt);
        if r.to_f64() > run.delta {
            st.modes[i] = Mode::Slide(vt.iter().map(|x| x.clone() / r.clone()).collect());
        } else {
            candidates.push(i);
            st.modes[i] = Mode::Stick;
        }
    }
    let fail = |e: RateFailure, s: &T, phase| match e {
        RateFailure::Undetermined => FrictionError::Undetermined { s: s.to_f64() },
        RateFailure::Inconsistent => FrictionError::NoConsistentModes {
            s: s.to_f64(),
            phase,
        },
    };
    // Contacts whose cone cannot hold them slide, one at a time, along the invariant direction.
    for _ in 0..=candidates.len() {
        let r = rates(b, &normals, &st.modes).map_err(|e| fail(e, &st.s, st.phase))?;
        if !r.split_unique {
            verdicts.push(Verdict::SplitNotUnique { s: st.s.to_f64() });
        }
        let scale = max_abs(&r.lambda);
        let violated = candidates.iter().copied().find(|&i| {
            if st.modes[i] != Mode::Stick {
                return false;
            }
            let off = b.offset[i];
            let p = &r.lambda[off];
            let tau = norm(&r.lambda[off + 1..off + 3]);
            !(nonnegative(p, &scale, b.len())
                && nonnegative(&(b.mu[i].clone() * p - tau), &scale, b.len()))
        });
        let Some(i) = violated else {
            return Ok(());
        };
        let off = b.offset[i];
        let tau = r.lambda[off + 1..off + 3].to_vec();
        let tn = norm(&tau);
        let mut u: Vec<T> = if tn.is_zero() {
            vec![T::one(), T::zero()]
        } else {
            tau.iter().map(|x| x.clone() / tn.clone()).collect()
        };
        let mut converged = false;
        for _ in 0..200 {
            st.modes[i] = Mode::Slide(u.clone());
            let r = rates(b, &normals, &st.modes).map_err(|e| fail(e, &st.s, st.phase))?;
            let dv = &r.velocity[off + 1..off + 3];
            let dn = norm(dv);
            if dn.is_zero() {
                break;
            }
            let next: Vec<T> = dv.iter().map(|x| x.clone() / dn.clone()).collect();
            let diff: f64 = next
                .iter()
                .zip(&u)
                .map(|(a, c)| (a.clone() - c).to_f64().abs())
                .fold(0.0, f64::max);
            u = next;
            if diff <= run.tol.max(8.0 * T::epsilon_f64()) {
                converged = true;
                break;
            }
        }
        st.modes[i] = Mode::Slide(u.clone());
        let r = rates(b, &normals, &st.modes).map_err(|e| fail(e, &st.s, st.phase))?;
        let dv = &r.velocity[off + 1..off + 3];
        let lambda: T = dv
            .iter()
            .zip(&u)
            .fold(T::zero(), |acc, (a, c)| acc + a.clone() * c);
        if !converged || !positive(&lambda, &max_abs(&r.velocity), b.len()) {
            return Err(FrictionError::NoConsistentModes {
                s: st.s.to_f64(),
                phase: st.phase,
            });
        }
    }
    Ok(())
}
