//! The modes at zero slip when every normal rate is given: Coulomb's law is then Tresca's, the
//! minimum of a convex function, and always has an answer.
//!
//! Where every contact's normal impulse rate p'_i is prescribed ([`Normal::Given`]: a
//! compliant contact's force under LZB, Poisson's or the energetic restitution), the friction
//! bound μ_i p'_i of each contact is a number, not an unknown: Coulomb's law with a known
//! normal force is Tresca's friction law (Duvaut and Lions 1976, ch. 5; Moreau 1988, §8). Let
//! the contacts at zero slip be c, their tangential rates τ'_c the unknowns, every other rate
//! known (its normal one, and the tangential one of a contact sliding along u, μ p' u). The
//! slip rates at c are affine in τ'_c (eq. 144):
//!
//! ```text
//! v'_c = a − M τ'_c,   a = −K_c,known Λ'_known,   M = K_cc  (symmetric, positive semidefinite)
//! ```
//!
//! Coulomb at each contact of c — τ'_i inside its disc |τ'_i| ≤ μ_i p'_i with v'_i = 0 (stick),
//! or on its rim with v'_i = λ_i τ'_i/|τ'_i|, λ_i ≥ 0 (a slip starting along its friction's
//! direction, [`Mode::Slide`]) — is exactly the optimality condition of
//!
//! ```text
//! minimise  f(τ') = ½ τ'ᵀ M τ' − aᵀ τ'   over the product of the discs
//! ```
//!
//! since −∇f = a − M τ' = v' must lie in the discs' normal cone at τ'. f is convex and the
//! discs compact, so a minimiser exists, and v' there is unique (f is strictly convex along
//! M's range). Where a search over stick and slide assignments finds none consistent — slips
//! stopping at their friction's limit, where a consistent assignment is marginal and rounding
//! decides which the tests see — this one finds it. It is solved by block Gauss–Seidel over the
//! contacts (each block the exact minimum over one disc, a trust-region problem in one or two
//! unknowns), which converges for a positive semidefinite M (Cottle, Pang and Stone 1992,
//! §5.3); floats only (a disc's rim is a square root).

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::departure::norm;
use crate::impact::friction::rates::{Mode, Normal};
use crate::mechanics::screw::Screws;
use crate::scalar::Real;

/// The most block sweeps; a sweep that moves no τ'_i by more than 10⁻¹⁴ of the largest disc,
/// or no slip rate by more than 10⁻¹⁴ of the slips' scale, ends it.
const SWEEPS: usize = 20_000;

/// Sweeps after which the optimality conditions are solved directly ([`kkt_minimiser`]).
const KKT_AFTER: usize = 200;

/// The most contacts at zero slip for which every boundary set is tried (2ⁿ of them).
const KKT_CONTACTS: usize = 6;

/// The modes of the contacts `at_zero_slip` under Tresca's law (module docs), every other
/// contact keeping its mode in `modes`: stick where the minimiser's slip rate is within
/// `tol` (relative to the largest slip rate the known rates or the friction cause) of zero,
/// else a slide along the minimiser's τ'_i. `None` when a normal rate is not given, a
/// contact not at zero slip sticks, or the minimiser is not finite.
pub fn tresca_modes<T: Real, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    modes: &[Mode<T>],
    at_zero_slip: &[usize],
    tol: f64,
) -> Option<Vec<Mode<T>>> {
    let len = b.len();
    let mut given = vec![0.0; b.contacts()];
    for (i, n) in normals.iter().enumerate() {
        match n {
            Normal::Given(p) => given[i] = p.to_f64(),
            Normal::Driven(_) => return None,
        }
    }
    // The known rates Λ'.
    let mut known = vec![0.0; len];
    for i in 0..b.contacts() {
        let o = b.offset[i];
        known[o] = given[i];
        if at_zero_slip.contains(&i) {
            continue;
        }
        match &modes[i] {
            Mode::Free => {}
            Mode::Slide(u) => {
                let bound = b.mu[i].to_f64() * given[i];
                for (k, uk) in u.iter().enumerate() {
                    known[o + 1 + k] = bound * uk.to_f64();
                }
            }
            Mode::Stick => return None,
        }
    }
    // The unknowns: every tangential axis of the contacts at zero slip.
    let axes: Vec<usize> = at_zero_slip
        .iter()
        .flat_map(|&i| (b.offset[i] + 1..b.offset[i] + 1 + b.dims[i]).collect::<Vec<_>>())
        .collect();
    let k = |q: usize, r: usize| b.at(q, r).to_f64();
    let a: Vec<f64> = axes
        .iter()
        .map(|&q| -(0..len).map(|r| k(q, r) * known[r]).sum::<f64>())
        .collect();
    let radius: Vec<f64> = at_zero_slip
        .iter()
        .map(|&i| (b.mu[i].to_f64() * given[i]).max(0.0))
        .collect();
    // Block j of the unknowns: at_zero_slip[j]'s axes, from start[j].
    let mut start = Vec::with_capacity(at_zero_slip.len());
    let mut at = 0;
    for &i in at_zero_slip {
        start.push(at);
        at += b.dims[i];
    }
    let m = |x: usize, y: usize| k(axes[x], axes[y]);
    let mut tau = vec![0.0; axes.len()];
    let largest = radius.iter().fold(0.0_f64, |x, r| x.max(*r));
    // The slips' scale: what the known rates cause, and what the largest disc can.
    let m_largest = (0..axes.len())
        .flat_map(|x| (0..axes.len()).map(move |y| (x, y)))
        .fold(0.0_f64, |z, (x, y)| z.max(m(x, y).abs()));
    let slip_scale = a.iter().fold(m_largest * largest, |z, x| z.max(x.abs()));
    let mut slip = a.clone();
    let mm: Vec<f64> = (0..axes.len())
        .flat_map(|x| (0..axes.len()).map(move |y| (x, y)))
        .map(|(x, y)| m(x, y))
        .collect();
    for sweep in 0..SWEEPS {
        if sweep == KKT_AFTER {
            // Slow sweeps (M nearly singular: two corners of one edge): the optimality
            // conditions solved on the boundary set the sweeps suggest, or a nearby one.
            let discs: Vec<Disc> = at_zero_slip
                .iter()
                .enumerate()
                .map(|(j, &i)| Disc {
                    start: start[j],
                    dim: b.dims[i],
                    radius: radius[j],
                })
                .collect();
            if let Some(t) = kkt_minimiser(&mm, &a, &discs, &tau, slip_scale) {
                tau = t;
                slip = slips(&mm, &a, &tau);
                break;
            }
        }
        let mut moved = 0.0_f64;
        for (j, &i) in at_zero_slip.iter().enumerate() {
            let (s, d) = (start[j], b.dims[i]);
            // c = a_j − Σ_{other blocks} M τ
            let c: Vec<f64> = (s..s + d)
                .map(|x| {
                    a[x] - (0..axes.len())
                        .filter(|y| *y < s || *y >= s + d)
                        .map(|y| m(x, y) * tau[y])
                        .sum::<f64>()
                })
                .collect();
            let block: Vec<Vec<f64>> = (s..s + d)
                .map(|x| (s..s + d).map(|y| m(x, y)).collect())
                .collect();
            let new = disc_minimum(&block, &c, radius[j]);
            for (x, t) in new.into_iter().enumerate() {
                moved = moved.max((t - tau[s + x]).abs());
                tau[s + x] = t;
            }
        }
        // v' = a − M τ' is unique at the minimisers (τ' is not where M is singular, and the
        // sweeps then crawl along the set of minimisers): the sweeps end when v' has settled.
        let now = slips(&mm, &a, &tau);
        let settled = now
            .iter()
            .zip(&slip)
            .all(|(x, y)| (x - y).abs() <= 1e-14 * slip_scale);
        slip = now;
        if moved <= 1e-14 * largest || settled {
            break;
        }
    }
    // The slip rates at the minimiser (`slip`, of the last sweep), and the modes.
    if !tau.iter().chain(&slip).all(|x| x.is_finite()) {
        return None;
    }
    let scale = a
        .iter()
        .chain(slip.iter())
        .fold(f64::MIN_POSITIVE, |x, v| x.max(v.abs()));
    let mut out = modes.to_vec();
    for (j, &i) in at_zero_slip.iter().enumerate() {
        let (s, d) = (start[j], b.dims[i]);
        let v = &slip[s..s + d];
        let t = &tau[s..s + d];
        let (nv, nt) = (norm(v), norm(t));
        out[i] = if nv <= tol * scale || d == 0 {
            Mode::Stick
        } else if nt > 0.0 {
            Mode::Slide(t.iter().map(|x| T::of(x / nt)).collect())
        } else {
            Mode::Slide(v.iter().map(|x| T::of(x / nv)).collect())
        };
    }
    Some(out)
}

/// The slip rates v' = a − M τ' (M row-major, n × n).
fn slips(m: &[f64], a: &[f64], t: &[f64]) -> Vec<f64> {
    let n = a.len();
    (0..n)
        .map(|x| a[x] - (0..n).map(|y| m[x * n + y] * t[y]).sum::<f64>())
        .collect()
}

/// One contact's disc among the unknowns: its first unknown, how many (1 in a plane, 2 in
/// space), and its radius μ_i p'_i.
struct Disc {
    start: usize,
    dim: usize,
    radius: f64,
}

/// The minimiser of f(τ') = ½ τ'ᵀ M τ' − aᵀ τ' over the discs from its optimality conditions
/// (the module docs'), solved by Newton's method on one boundary set at a time: a contact
/// inside its disc has slip v'_i = (a − M τ')_i = 0; one on its rim has |τ'_i| = r_i and v'_i
/// parallel to τ'_i (v'_i × τ'_i = 0, or in a plane τ'_i = ±r_i). A solution that meets the
/// inequalities too — |τ'_i| ≤ r_i inside, v'_i · τ'_i ≥ 0 on the rim — is a minimiser, the
/// problem being convex (the conditions are sufficient). The sets are tried from the one the
/// sweeps' iterate `guess` suggests (on the rim within 10⁻⁶ of r_i) outwards, by how many
/// contacts differ, for up to [`KKT_CONTACTS`] contacts. Every condition is met to 10⁻¹²
/// of its scale (`slip_scale` for the slips, r_i for the rims), or `None`.
fn kkt_minimiser(
    m: &[f64],
    a: &[f64],
    discs: &[Disc],
    guess: &[f64],
    slip_scale: f64,
) -> Option<Vec<f64>> {
    const CLOSE: f64 = 1e-12;
    let n = a.len();
    let k = discs.len();
    if k > KKT_CONTACTS || discs.iter().any(|d| d.radius <= 0.0 || d.dim == 0) {
        return None;
    }
    let slip = |t: &[f64]| slips(m, a, t);
    let on_rim: Vec<bool> = discs
        .iter()
        .map(|d| norm(&guess[d.start..d.start + d.dim]) >= d.radius * (1.0 - 1e-6))
        .collect();
    let mut sets: Vec<u32> = (0..1u32 << k).collect();
    let suggested: u32 = (0..k).filter(|&j| on_rim[j]).map(|j| 1 << j).sum();
    sets.sort_by_key(|s| (s ^ suggested).count_ones());
    for set in sets {
        let rim = |j: usize| set & (1 << j) != 0;
        // The start: the guess, its rim contacts put on their rims.
        let mut t = guess.to_vec();
        for (j, d) in discs.iter().enumerate() {
            let ti = &mut t[d.start..d.start + d.dim];
            let l = norm(ti);
            if rim(j) {
                if l > 0.0 {
                    ti.iter_mut().for_each(|x| *x *= d.radius / l);
                } else {
                    ti[0] = d.radius;
                }
            }
        }
        // Newton's iterations until the step is at rounding level, at most 50; the iterate is
        // then judged by the conditions themselves (where J is singular to rounding the steps
        // can stay some orders above 10⁻¹⁵ |τ'| at a point that meets every condition).
        for _ in 0..50 {
            let v = slip(&t);
            let mut f = vec![0.0; n];
            let mut jac = nalgebra::DMatrix::<f64>::zeros(n, n);
            for (j, d) in discs.iter().enumerate() {
                let s = d.start;
                if !rim(j) {
                    for q in s..s + d.dim {
                        f[q] = v[q];
                        for y in 0..n {
                            jac[(q, y)] = -m[q * n + y];
                        }
                    }
                    continue;
                }
                // |τ_i|² − r_i²
                f[s] = (0..d.dim).map(|x| t[s + x] * t[s + x]).sum::<f64>() - d.radius * d.radius;
                for x in 0..d.dim {
                    jac[(s, s + x)] = 2.0 * t[s + x];
                }
                if d.dim == 2 {
                    // v_x τ_y − v_y τ_x, with dv/dτ = −M
                    let (tx, ty, vx, vy) = (t[s], t[s + 1], v[s], v[s + 1]);
                    f[s + 1] = vx * ty - vy * tx;
                    for y in 0..n {
                        jac[(s + 1, y)] = -m[s * n + y] * ty + m[(s + 1) * n + y] * tx;
                    }
                    jac[(s + 1, s + 1)] += vx;
                    jac[(s + 1, s)] -= vy;
                }
            }
            let Some(step) = newton_step(jac, nalgebra::DVector::from_vec(f)) else {
                break;
            };
            let mut largest = 0.0_f64;
            for (x, dx) in t.iter_mut().zip(step.iter()) {
                *x -= dx;
                largest = largest.max(dx.abs());
            }
            if !largest.is_finite() {
                break;
            }
            let size = discs.iter().fold(0.0_f64, |z, d| z.max(d.radius));
            if largest <= 1e-15 * size {
                break;
            }
        }
        if !t.iter().all(|x| x.is_finite()) {
            continue;
        }
        let v = slip(&t);
        let holds = discs.iter().enumerate().all(|(j, d)| {
            let (ti, vi) = (&t[d.start..d.start + d.dim], &v[d.start..d.start + d.dim]);
            let l = norm(ti);
            if rim(j) {
                let along = ti.iter().zip(vi).map(|(x, y)| x * y).sum::<f64>() / d.radius;
                let across = if d.dim == 2 {
                    (vi[0] * ti[1] - vi[1] * ti[0]).abs() / d.radius
                } else {
                    0.0
                };
                (l - d.radius).abs() <= CLOSE * d.radius
                    && along >= -CLOSE * slip_scale
                    && across <= CLOSE * slip_scale
            } else {
                l <= d.radius * (1.0 + CLOSE) && norm(vi) <= CLOSE * slip_scale
            }
        });
        if holds {
            return Some(t);
        }
    }
    None
}

/// The Newton step: the least-norm least-squares solution J⁺ f of J δ = f (the Gauss–Newton
/// step; singular values below 10⁻¹² of the largest taken as zero), which is J⁻¹ f where J is
/// well conditioned. J is singular, or singular to rounding, wherever M is and contacts lie
/// inside their discs (sticks whose forces only their sum determines: the two corners of one
/// edge): the conditions there hold on an affine family of τ', and the least-norm steps go to
/// its member nearest the start (the sweeps' iterate, in the discs), which the inequalities
/// then judge. An LU step there takes the rounding of the null direction's pivot for a length
/// and leaves the discs (`the_optimality_conditions_hold_on_a_family_of_sticks`).
fn newton_step(
    jac: nalgebra::DMatrix<f64>,
    f: nalgebra::DVector<f64>,
) -> Option<nalgebra::DVector<f64>> {
    let svd = jac.svd(true, true);
    let eps = 1e-12 * svd.singular_values.max();
    svd.solve(&f, eps).ok()
}

/// The minimiser of ½ τᵀ B τ − cᵀ τ over |τ| ≤ r, B symmetric positive semidefinite, in one
/// or two unknowns: B⁻¹c when it lies in the disc, else the τ on the rim with
/// (B + λ I) τ = c, λ ≥ 0 (the trust-region condition; Moré and Sorensen 1983), λ found by
/// bisection on |τ(λ)| = r in B's eigenbasis.
fn disc_minimum(block: &[Vec<f64>], c: &[f64], r: f64) -> Vec<f64> {
    if r <= 0.0 {
        return vec![0.0; c.len()];
    }
    if c.len() == 1 {
        let (m, c) = (block[0][0], c[0]);
        let t = if m > 0.0 { c / m } else { c.signum() * r };
        return vec![t.clamp(-r, r)];
    }
    // B = Q diag(e) Qᵀ, e[0] ≤ e[1]; columns of Q by the angle φ.
    let (p, q, s) = (block[0][0], block[0][1], block[1][1]);
    let mean = 0.5 * (p + s);
    let half = (0.25 * (p - s) * (p - s) + q * q).sqrt();
    let e = [mean - half, mean + half];
    let phi = 0.5 * (2.0 * q).atan2(p - s);
    // the eigenvector of e[1] is (cos φ, sin φ); of e[0], (−sin φ, cos φ)
    let v1 = [phi.cos(), phi.sin()];
    let v0 = [-v1[1], v1[0]];
    let cc = [v0[0] * c[0] + v0[1] * c[1], v1[0] * c[0] + v1[1] * c[1]];
    let at = |lambda: f64| -> [f64; 2] {
        std::array::from_fn(|k| {
            let d = e[k] + lambda;
            if d > 0.0 { cc[k] / d } else { 0.0 }
        })
    };
    let length = |y: [f64; 2]| (y[0] * y[0] + y[1] * y[1]).sqrt();
    let back = |y: [f64; 2]| vec![v0[0] * y[0] + v1[0] * y[1], v0[1] * y[0] + v1[1] * y[1]];
    let floor = 1e-13 * e[1].abs().max(f64::MIN_POSITIVE);
    if e[0] > floor {
        let free = at(0.0);
        if length(free) <= r {
            return back(free);
        }
    } else if cc[0].abs() <= 1e-13 * cc[0].hypot(cc[1]) {
        // B singular and c in its range: the least-norm minimiser, if it lies in the disc
        let free = [0.0, if e[1] > floor { cc[1] / e[1] } else { 0.0 }];
        if length(free) <= r {
            return back(free);
        }
    }
    // |τ(λ)| decreases in λ; at λ_hi = |c|/r − e[0] it is ≤ r.
    let mut lo = (-e[0]).max(0.0);
    let mut hi = lo + (cc[0].hypot(cc[1]) / r).max(f64::MIN_POSITIVE);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if length(at(mid)) > r {
            lo = mid
        } else {
            hi = mid
        }
    }
    let y = at(hi);
    let l = length(y);
    // on the rim (the bisection leaves |τ| ≤ r by at most its last step)
    if l > 0.0 {
        back([y[0] * r / l, y[1] * r / l])
    } else {
        back(y)
    }
}

#[cfg(test)]
mod tests {
    use super::{Disc, KKT_AFTER, disc_minimum, kkt_minimiser, norm, slips};

    /// The minimiser of the disc problem meets its optimality condition: inside, Bτ = c; on
    /// the rim, c − Bτ = λ τ with λ ≥ 0.
    fn optimal(b: &[Vec<f64>], c: &[f64], r: f64) {
        let t = disc_minimum(b, c, r);
        let g = [
            c[0] - b[0][0] * t[0] - b[0][1] * t[1],
            c[1] - b[1][0] * t[0] - b[1][1] * t[1],
        ];
        let nt = (t[0] * t[0] + t[1] * t[1]).sqrt();
        assert!(nt <= r * (1.0 + 1e-12), "|τ| = {nt} outside r = {r}");
        let scale = c[0].hypot(c[1]);
        if nt < r * (1.0 - 1e-9) {
            assert!(g[0].hypot(g[1]) <= 1e-12 * scale, "inside, gradient {g:?}");
        } else {
            // g parallel to τ and along it
            let cross = g[0] * t[1] - g[1] * t[0];
            assert!(cross.abs() <= 1e-9 * scale * r, "cross {cross}");
            assert!(g[0] * t[0] + g[1] * t[1] >= -1e-12 * scale * r);
        }
    }

    #[test]
    fn the_disc_minimum_meets_its_optimality_conditions() {
        let b = vec![vec![2.0, 0.5], vec![0.5, 1.0]];
        optimal(&b, &[1.0, 0.2], 10.0); // inside
        optimal(&b, &[1.0, 0.2], 0.1); // on the rim
        optimal(&b, &[-3.0, 4.0], 0.5);
        // positive semidefinite: rank one
        let s = vec![vec![1.0, 1.0], vec![1.0, 1.0]];
        optimal(&s, &[1.0, -0.5], 0.3);
        optimal(&s, &[1.0, 1.0], 100.0);
        // a block diagonal, the inside point exactly
        let d = vec![vec![4.0, 0.0], vec![0.0, 2.0]];
        assert_eq!(disc_minimum(&d, &[2.0, 1.0], 1.0), vec![0.5, 0.5]);
    }

    #[test]
    fn one_unknown_is_clamped() {
        assert_eq!(disc_minimum(&[vec![2.0]], &[1.0], 1.0), vec![0.5]);
        assert_eq!(disc_minimum(&[vec![2.0]], &[-8.0], 1.0), vec![-1.0]);
        assert_eq!(disc_minimum(&[vec![2.0]], &[8.0], 0.0), vec![0.0]);
    }

    /// M of the box dropped spinning with μ = 0.9 under LZB, on two corners of one edge
    /// (recorded; singular to rounding: eigenvalues 2·10⁻¹⁶, 0.85, 1.6, 3.3).
    const EDGE_M: [f64; 16] = [
        1.9999996099020136,
        -0.6000003614433892,
        -0.3999998049264972,
        -0.5999997112312732,
        -0.6000003614433891,
        0.8882356842450916,
        0.6000001300346134,
        0.8882354891812638,
        -0.399999804926497,
        0.6000001300346134,
        1.9999999999901819,
        0.599999999992203,
        -0.599999711231273,
        0.8882354891812638,
        0.5999999999922031,
        0.8882352941176473,
    ];

    /// f(τ) = ½ τᵀ M τ − aᵀ τ.
    fn objective(m: &[f64], a: &[f64], t: &[f64]) -> f64 {
        let n = a.len();
        (0..n)
            .map(|x| 0.5 * t[x] * (0..n).map(|y| m[x * n + y] * t[y]).sum::<f64>() - a[x] * t[x])
            .sum()
    }

    /// A point of the discs, by a small linear congruential generator (no dependency for a test).
    fn in_discs(discs: &[Disc], n: usize, state: &mut u64) -> Vec<f64> {
        let mut next = || {
            *state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (*state >> 11) as f64 / (1u64 << 53) as f64
        };
        let mut t = vec![0.0; n];
        for d in discs {
            let (rho, phi) = (d.radius * next().sqrt(), std::f64::consts::TAU * next());
            t[d.start] = rho * phi.cos();
            t[d.start + 1] = rho * phi.sin();
        }
        t
    }

    /// Two corners of one edge of a box at rest on a rough floor, their discs loaded, the
    /// problem the sweeps crawl on (M's smallest eigenvalue about 10⁻⁷ of its largest: 20 000
    /// sweeps leave a slip of 10⁻⁴ of its scale) — taken from the box dropped with μ = 0.9
    /// under LZB. The optimality conditions' solution is no worse than any of 20 000 points of
    /// the discs, nor than the sweeps' best.
    #[test]
    fn the_optimality_conditions_solve_what_the_sweeps_crawl_on() {
        let m = EDGE_M;
        let a = [
            3.786595160603276e-5,
            5.5721975889807675e-6,
            3.7865949792561546e-5,
            5.572209899432532e-6,
        ];
        let discs = [
            Disc {
                start: 0,
                dim: 2,
                radius: 3.550402996700237e-5,
            },
            Disc {
                start: 2,
                dim: 2,
                radius: 2.129489472257811e-5,
            },
        ];
        // the sweeps' iterate after 20 000 sweeps
        let swept = [
            2.6034421323809e-5,
            9.47679315128012e-6,
            2.129489463604815e-5,
            -1.9197116515148372e-9,
        ];
        let t = kkt_minimiser(&m, &a, &discs, &swept, 4e-5).expect("a minimiser");
        let best = objective(&m, &a, &t);
        assert!(best <= objective(&m, &a, &swept));
        let mut state = 1;
        for _ in 0..20_000 {
            let p = in_discs(&discs, 4, &mut state);
            assert!(best <= objective(&m, &a, &p), "{p:?} is lower");
        }
    }

    /// On a well-conditioned problem the optimality conditions and the sweeps agree.
    #[test]
    fn the_optimality_conditions_agree_with_converged_sweeps() {
        let m = [
            2.0, 0.3, 0.5, 0.1, //
            0.3, 1.5, 0.2, 0.4, //
            0.5, 0.2, 1.8, 0.3, //
            0.1, 0.4, 0.3, 1.2,
        ];
        let a = [1.0, -0.4, 0.3, 0.8];
        for (r0, r1) in [(10.0, 10.0), (0.2, 10.0), (0.2, 0.1), (10.0, 0.05)] {
            let discs = [
                Disc {
                    start: 0,
                    dim: 2,
                    radius: r0,
                },
                Disc {
                    start: 2,
                    dim: 2,
                    radius: r1,
                },
            ];
            // block Gauss–Seidel to convergence
            let mut t = [0.0; 4];
            sweep(&m, &a, &discs, &mut t, 10_000);
            let k = kkt_minimiser(&m, &a, &discs, &[0.0; 4], 1.0).expect("a minimiser");
            for (x, y) in k.iter().zip(&t) {
                assert!((x - y).abs() <= 1e-12, "{k:?} against the sweeps' {t:?}");
            }
        }
    }

    /// `count` block Gauss–Seidel sweeps over two discs of two unknowns each (M 4 × 4, row-major).
    fn sweep(m: &[f64], a: &[f64], discs: &[Disc], t: &mut [f64; 4], count: usize) {
        for _ in 0..count {
            for d in discs {
                let s = d.start;
                let c: Vec<f64> = (s..s + 2)
                    .map(|x| {
                        a[x] - (0..4)
                            .filter(|y| *y < s || *y >= s + 2)
                            .map(|y| m[x * 4 + y] * t[y])
                            .sum::<f64>()
                    })
                    .collect();
                let block: Vec<Vec<f64>> = (s..s + 2)
                    .map(|x| (s..s + 2).map(|y| m[x * 4 + y]).collect())
                    .collect();
                let new = disc_minimum(&block, &c, d.radius);
                t[s..s + 2].copy_from_slice(&new);
            }
        }
    }

    /// Recorded from the box dropped spinning with μ = 0.9 under LZB (two corners of one edge,
    /// M singular to rounding: eigenvalues 2·10⁻¹⁶, 0.85, 1.6, 3.3): both contacts stick, their
    /// y forces a family of which the sweeps' iterate after 200 sweeps puts the second on its
    /// rim. Newton's LU steps on the conditions took the rounding of the null direction for a
    /// length and left the discs (the sweeps then ran their 20 000); the least-norm steps stay
    /// in the family's member nearest the iterate, and meet every condition.
    #[test]
    fn the_optimality_conditions_hold_on_a_family_of_sticks() {
        let m = EDGE_M;
        let a = [
            3.791162032667639e-5,
            5.57451152835772e-6,
            3.791161851245063e-5,
            5.574523853656664e-6,
        ];
        let discs = [
            Disc {
                start: 0,
                dim: 2,
                radius: 3.554123179855598e-5,
            },
            Disc {
                start: 2,
                dim: 2,
                radius: 2.132619597085898e-5,
            },
        ];
        let mut swept = [0.0; 4];
        sweep(&m, &a, &discs, &mut swept, KKT_AFTER);
        let t = kkt_minimiser(&m, &a, &discs, &swept, 4e-5).expect("a minimiser");
        // both stick: no slip, each force in its disc
        for v in slips(&m, &a, &t) {
            assert!(v.abs() <= 1e-12 * 4e-5, "slip {v}");
        }
        for d in &discs {
            assert!(norm(&t[d.start..d.start + 2]) <= d.radius * (1.0 + 1e-12));
        }
        let best = objective(&m, &a, &t);
        let mut state = 7;
        for _ in 0..20_000 {
            let p = in_discs(&discs, 4, &mut state);
            assert!(best <= objective(&m, &a, &p), "{p:?} is lower");
        }
    }
}
