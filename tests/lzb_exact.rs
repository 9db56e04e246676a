//! The LZB law's exact limits (`inertance::impact::multiple::closed_form`): when every contact
//! is alike — one contact, or a body landing flat on equal corners — the outcome is
//! P_i = (1 + e) v/g in closed form, which in rationals is exact and equals the simultaneous
//! Newton law's impulses; the f64 integration meets it within its error bound.

use inertance::impact::multiple::{ContactLaw, alike, solve_lzb};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar, ratio};

fn q(n: i64, d: i64) -> Exact {
    ratio::<Exact>(n, d)
}

/// A box (half sides a, b, c; mass m) falling at w onto `corners` of its underside, normals −z,
/// restitution k; `spin` about z (which leaves the normal velocities alike).
fn box_landing<T: Scalar>(corners: &[(i64, i64)], k: (i64, i64), spin: (i64, i64)) -> Problem<T> {
    let (a, b, c) = (ratio::<T>(3, 10), ratio::<T>(1, 5), ratio::<T>(1, 10));
    let m = ratio::<T>(2, 1);
    let third = m.clone() / ratio::<T>(3, 1);
    let inertia = Vec3::new(
        third.clone() * (b.clone() * b.clone() + c.clone() * c.clone()),
        third.clone() * (a.clone() * a.clone() + c.clone() * c.clone()),
        third * (a.clone() * a.clone() + b.clone() * b.clone()),
    );
    let body = RigidBody::principal(m, inertia);
    let twist = Screw::new(
        Vec3::new(T::zero(), T::zero(), ratio::<T>(spin.0, spin.1)),
        Vec3::new(T::zero(), T::zero(), ratio::<T>(-3, 2)),
    );
    let contacts = corners
        .iter()
        .map(|&(sx, sy)| {
            Contact::new(
                Vec3::new(
                    ratio::<T>(sx, 1) * a.clone(),
                    ratio::<T>(sy, 1) * b.clone(),
                    -c.clone(),
                ),
                Vec3::new(T::zero(), T::zero(), ratio::<T>(-1, 1)),
                ratio::<T>(k.0, k.1),
            )
        })
        .collect();
    Problem::new(body, twist, contacts).expect("a valid box")
}

const FOUR: [(i64, i64); 4] = [(1, 1), (-1, 1), (-1, -1), (1, -1)];
const TWO: [(i64, i64); 2] = [(1, 1), (-1, -1)];
const ONE: [(i64, i64); 1] = [(1, -1)];

/// In rationals: the closed form applies, and its impulses are the simultaneous Newton law's,
/// exactly.
#[test]
fn alike_contacts_take_the_simultaneous_newton_impulses_exactly() {
    for corners in [&FOUR[..], &TWO[..], &ONE[..]] {
        for k in [(0, 1), (1, 2), (1, 1)] {
            let problem = box_landing::<Exact>(corners, k, (0, 1));
            let mut impact = Impact::assemble(&problem).expect("assembles");
            let n = corners.len();
            let g = impact.g_hat().to_vec();
            let v0: Vec<Exact> = impact.before_hat().iter().map(|v| v[0].clone()).collect();
            let laws = vec![ContactLaw::new(5.0, 1.5, k.0 as f64 / k.1 as f64).expect("valid"); n];
            let e = q(k.0, k.1);
            let out = alike(&g, &v0, &laws, &e).expect("every corner alike");
            // Whether G is singular or not (four corners on a plane: rank 3), v⁰ − G P = −e v⁰.
            for i in 0..n {
                let gp = (0..n).fold(Exact::from(0), |s, j| {
                    s + g[i * n + j].clone() * out.impulses[j].clone()
                });
                assert_eq!(v0[i].clone() - gp, -(e.clone() * v0[i].clone()));
            }
            if impact.singular() {
                continue;
            }
            let mut sim = Outcome::default();
            impact.solve(Model::Newton, &mut sim).expect("solves");
            assert_eq!(out.impulses, sim.impulses_hat, "{corners:?}, k {k:?}");
            // The energy balance, exactly: ΔE_c (from the twist after) = n (1 − e²) W_c.
            let lost = out.work_compression.clone() - out.work_expansion.clone();
            assert_eq!(
                sim.kinetic_energy_loss,
                lost * Exact::from(n as i64),
                "{corners:?}, k {k:?}"
            );
        }
    }
}

/// In f64 the integration meets the closed form within its bound, for any K and η (the box
/// spinning about the normal, which changes no normal velocity).
#[test]
fn the_integration_meets_the_closed_form() {
    for corners in [&FOUR[..], &TWO[..], &ONE[..]] {
        for (k, eta, stiffness) in [((1, 2), 1.5, 1.0), ((1, 1), 1.0, 40.0), ((0, 1), 2.0, 0.3)] {
            let exact = box_landing::<Exact>(corners, k, (0, 1));
            let impact = Impact::assemble(&exact).expect("assembles");
            let n = corners.len();
            let v0: Vec<Exact> = impact.before_hat().iter().map(|v| v[0].clone()).collect();
            let e = k.0 as f64 / k.1 as f64;
            let laws = vec![ContactLaw::new(stiffness, eta, e).expect("valid"); n];
            let closed = alike(impact.g_hat(), &v0, &laws, &q(k.0, k.1)).expect("alike");
            let problem = box_landing::<f64>(corners, k, (2, 1));
            let out = solve_lzb(&problem, &laws, 1e-11).expect("ends");
            let bound = 2.0 * out.error_estimate + 64.0 * n as f64 * f64::EPSILON;
            for i in 0..n {
                let p = closed.impulses[i].to_f64();
                assert!(
                    (out.impulses[i] - p).abs() <= bound * p.max(1.0),
                    "{corners:?}, k {k:?}, η {eta}: {:?} vs {p} (bound {bound:e})",
                    out.impulses
                );
            }
        }
    }
}
