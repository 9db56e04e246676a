//! The LZB multiple-impact law ([`inertance::impact::multiple`]) against what it did not
//! write:
//!
//! * one contact: Newton's law P = (1 + e) v⁰/g, v = −e v⁰ for a frictionless single contact,
//!   for any η and K (Stronge's energetic law equals Newton's for one frictionless contact);
//! * with every e_i = 1 the law is a re-parametrisation of the compliant-contact dynamics
//!   M q̈ = −Σ_i F_i(δ_i) ∂δ_i/∂q, F_i = K_i δ_i^η_i (zero for δ_i ≤ 0), the contact Jacobians
//!   frozen at the instant of impact (an impact moves nothing): integrated here in time, in the
//!   bodies' own coordinates, by classical RK4 with a fixed step (`compliant`) — Newton's cradle
//!   of 3 and 5 equal balls with linear and Hertz contacts, two unequal balls, and a bar
//!   pitching onto two supports of unequal stiffness;
//! * invariants: a free system's momentum, the energy balance ΔE_c = Σ_i (1 − e_i²) W_c,i (the
//!   energy stored over the compression phases), E = 0 at the end, and no loss with e = 1;
//! * symmetry: a bar landing flat on two equal supports takes the simultaneous Newton law's
//!   impulses (both contacts evolve alike, so they act as one of inertance g₁₁ + g₁₂).
//!
//! **Tolerances.** The integrator reports an error estimate ε_P for its impulses (the sum of
//! its local error estimates, N s). A velocity after impact is a combination of impulses with
//! coefficients g_ij, so its error is at most ‖G‖∞ ε_P; every comparison allows that (times 2,
//! for the propagation the sum does not count) plus the rounding of the sums (64 N ε of the
//! scale). The time integration's error is estimated by running it at dt and dt/2: for an
//! order p ≥ 1 the finer run is within their difference d of the exact solution, so d is
//! allowed on its side.

mod common;

use common::row::{compliant_checked, row, velocity_bound};
use inertance::impact::mechanism::Mechanism;
use inertance::impact::multiple::{ContactLaw, EventKind, Lzb, solve_lzb};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Screws, Vec3};
use inertance::mechanics::system::SystemScrew;

const TOL: f64 = 1e-11;
const EPS: f64 = f64::EPSILON;

fn v3(x: f64, y: f64, z: f64) -> Vec3<f64> {
    Vec3::new(x, y, z)
}

/// The balls' velocities along x after impact.
fn speeds(out: &Lzb<SystemScrew<f64>>) -> Vec<f64> {
    out.velocity.0.iter().map(|s| s.bottom()[0]).collect()
}

/// A row of balls under LZB with e = 1, against the compliant dynamics in time.
fn row_against_time(masses: &[f64], eta: f64, stiffness: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let system = row(masses, 1.0);
    let laws: Vec<ContactLaw> = stiffness
        .iter()
        .map(|&k| ContactLaw::new(k, eta, 1.0).expect("valid"))
        .collect();
    let out = solve_lzb(&system, &laws, TOL).expect("LZB ends");
    let lzb = speeds(&out);
    let n = masses.len();
    let jac: Vec<Vec<f64>> = (0..n - 1)
        .map(|i| {
            let mut r = vec![0.0; n];
            r[i] = 1.0;
            r[i + 1] = -1.0;
            r
        })
        .collect();
    let kl: Vec<(f64, f64)> = stiffness.iter().map(|&k| (k, eta)).collect();
    let mut q0 = vec![0.0; n];
    q0[0] = 1.0;
    let (time, d) = compliant_checked(masses, &jac, &kl, &q0, 2e-4);
    let bound = d + velocity_bound(&out, 1.0);
    for (a, b) in lzb.iter().zip(&time) {
        assert!(
            (a - b).abs() <= bound,
            "masses {masses:?}, η = {eta}, K = {stiffness:?}: LZB {lzb:?} vs time {time:?} (bound \
             {bound:e}: time {d:e}, LZB estimate {:e})",
            out.error_estimate
        );
    }
    (lzb, time)
}

#[test]
fn one_contact_is_newtons_law_for_any_exponent_and_stiffness() {
    // A box of 2 kg hit off its centre, spinning: g includes the rotation.
    let body = RigidBody::principal(2.0, v3(0.1, 0.2, 0.15));
    let twist = Screw::new(v3(0.3, -0.2, 0.5), v3(0.1, -1.2, 0.4));
    for e in [0.0, 0.3, 0.8, 1.0] {
        for eta in [1.0, 1.5, 2.3] {
            for k in [1e-2, 1.0, 1e4] {
                let contact = Contact::new(v3(0.2, -0.1, 0.05), v3(0.1, -1.0, 0.2), e);
                let problem =
                    Problem::new(body.clone(), twist.clone(), vec![contact]).expect("valid");
                let law = ContactLaw::new(k, eta, e).expect("valid");
                let out = solve_lzb(&problem, &[law], TOL).expect("LZB ends");
                let (g, v0) = (out.blocks.k[0], out.blocks.v0[0]);
                assert!(v0 > 0.0);
                let newton = (1.0 + e) * v0 / g;
                let p = out.impulses[0];
                let bound = 2.0 * out.error_estimate + 64.0 * EPS * newton;
                assert!(
                    (p - newton).abs() <= bound,
                    "e {e}, η {eta}, K {k}: P = {p} vs Newton {newton} (bound {bound:e})"
                );
                assert!((out.after[0] + e * v0).abs() <= g * bound + 64.0 * EPS * v0);
                // The crate's own Newton solve, for the same contact.
                let mut impact = Impact::assemble(&problem).expect("assembles");
                let mut sim = Outcome::default();
                impact.solve(Model::Newton, &mut sim).expect("solves");
                let w = out.velocity.minus(&sim.velocity).max_abs_f64();
                assert!(
                    w <= 4.0 * g * bound / g.min(1.0) + 64.0 * EPS,
                    "twist off by {w:e}"
                );
            }
        }
    }
}

#[test]
fn newtons_cradle_of_three_and_five_balls_follows_the_compliant_dynamics() {
    for eta in [1.0, 1.5] {
        for n in [3, 5] {
            row_against_time(&vec![1.0; n], eta, &vec![1.0; n - 1]);
        }
    }
}

#[test]
fn two_unequal_balls_and_an_unequal_chain_follow_the_compliant_dynamics() {
    for eta in [1.0, 1.5] {
        let (lzb, _) = row_against_time(&[1.0, 3.0], eta, &[2.0]);
        // One contact, e = 1: the elastic two-body collision, (m₁ − m₂)/(m₁ + m₂) v and 2m₁/(m₁ + m₂) v.
        assert!(
            (lzb[0] + 0.5).abs() <= 1e-9 && (lzb[1] - 0.5).abs() <= 1e-9,
            "{lzb:?}"
        );
        row_against_time(&[1.0, 2.0, 0.5], eta, &[1.0, 5.0]);
    }
}

#[test]
fn the_cradle_striker_nearly_stops_unlike_the_simultaneous_law() {
    let system = row(&[1.0; 3], 1.0);
    let laws = vec![ContactLaw::new(1.0, 1.5, 1.0).expect("valid"); 2];
    let out = solve_lzb(&system, &laws, TOL).expect("LZB ends");
    let lzb = speeds(&out);
    let mut impact = Impact::assemble(&system).expect("assembles");
    let mut sim = Outcome::default();
    impact.solve(Model::Newton, &mut sim).expect("solves");
    let newton: Vec<f64> = sim.velocity.0.iter().map(|s| s.bottom()[0]).collect();
    println!("Newton's cradle, 3 balls, Hertz, e = 1: LZB {lzb:?}; simultaneous Newton {newton:?}");
    // The simultaneous law: (−1/3, 2/3, 2/3) (derived in tests/systems.rs).
    assert!((newton[0] + 1.0 / 3.0).abs() <= 1e-14 && (newton[2] - 2.0 / 3.0).abs() <= 1e-14);
    // LZB: the striker keeps less than a tenth of its speed, the last ball leaves with more
    // than nine tenths of it.
    assert!(lzb[0].abs() < 0.1 && lzb[2] > 0.9, "{lzb:?}");
    // The contacts end in order, first to last; the second engages from rest (v⁰ = 0) and
    // takes over as the primary contact (the larger energy) on the way.
    assert_eq!(out.ending_order(), vec![0, 1]);
    let happened = |contact: usize, kind: EventKind| {
        out.events
            .iter()
            .any(|e| e.contact == contact && e.kind == kind)
    };
    assert!(happened(1, EventKind::Engages) && happened(1, EventKind::Primary));
}

#[test]
fn a_free_system_keeps_its_momentum_and_its_energy_balance() {
    for e in [0.0, 0.5, 0.9, 1.0] {
        let masses = [1.0, 2.0, 0.5, 1.5];
        let system = row(&masses, 1.3);
        let laws = vec![
            ContactLaw::new(1.0, 1.5, e).expect("valid"),
            ContactLaw::new(4.0, 1.0, e * e).expect("valid"),
            ContactLaw::new(0.3, 1.5, e).expect("valid"),
        ];
        let out = solve_lzb(&system, &laws, TOL).expect("LZB ends");
        let p: f64 = speeds(&out).iter().zip(&masses).map(|(v, m)| v * m).sum();
        let p0 = 1.3;
        assert!(
            (p - p0).abs() <= 64.0 * 4.0 * EPS * p0,
            "momentum {p} vs {p0}"
        );
        check_energy(&system, &out);
    }
}

/// ΔE_c = Σ_i (W_c,i − W_r,i) = Σ_i (1 − e_i²) W_c,i, with every contact at rest and none
/// approaching at the end; with every e_i = 1, ΔE_c = 0. The works are integrated with the
/// impulses: an impulse error ε_P moves a work by at most max|v| ε_P per contact.
fn check_energy<M: Mechanism<f64>>(mechanism: &M, out: &Lzb<M::Screw>) {
    let n = out.impulses.len();
    let speed = out.blocks.v0.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let t0 = mechanism.kinetic_energy(mechanism.velocity());
    let bound = 2.0 * n as f64 * speed * out.error_estimate + 64.0 * n as f64 * EPS * t0;
    assert!(
        out.energy_residual.abs() <= bound,
        "ΔE_c − Σ dissipation = {:e} (bound {bound:e})",
        out.energy_residual
    );
    let mut stored = 0.0;
    for i in 0..n {
        let e2 = out.laws[i].restitution.powi(2);
        assert!(
            (out.work_expansion[i] - e2 * out.work_compression[i]).abs() <= bound,
            "contact {i}: released {} vs e² × stored {}",
            out.work_expansion[i],
            e2 * out.work_compression[i]
        );
        stored += (1.0 - e2) * out.work_compression[i];
        assert!(
            out.after[i] <= speed * 1e-9,
            "contact {i} still approaches: {}",
            out.after[i]
        );
    }
    assert!((out.kinetic_energy_loss - stored).abs() <= 2.0 * bound);
    if out.laws.iter().all(|l| l.restitution == 1.0) {
        assert!(out.kinetic_energy_loss.abs() <= 2.0 * bound);
    }
}

/// A bar of length 2 and mass 1 (J_z = 1/3) over supports at x = ±0.8, falling at 1 m/s and
/// pitching at ω_z, contacts' normals −y (out of the bar's underside).
fn bar(omega: f64, k: f64) -> Problem<f64> {
    let body = RigidBody::principal(1.0, v3(0.01, 1.0 / 3.0, 1.0 / 3.0));
    let twist = Screw::new(v3(0.0, 0.0, omega), v3(0.0, -1.0, 0.0));
    let contacts = [-0.8, 0.8]
        .iter()
        .map(|&x| Contact::new(v3(x, 0.0, 0.0), v3(0.0, -1.0, 0.0), k))
        .collect();
    Problem::new(body, twist, contacts).expect("a valid bar")
}

#[test]
fn a_bar_landing_flat_on_equal_supports_takes_the_simultaneous_impulses() {
    for e in [0.0, 0.5, 1.0] {
        let problem = bar(0.0, e);
        let laws = vec![ContactLaw::new(3.0, 1.5, e).expect("valid"); 2];
        let out = solve_lzb(&problem, &laws, TOL).expect("LZB ends");
        let mut impact = Impact::assemble(&problem).expect("assembles");
        let mut sim = Outcome::default();
        impact.solve(Model::Newton, &mut sim).expect("solves");
        let bound = 2.0 * out.error_estimate + 64.0 * EPS;
        for i in 0..2 {
            // A unit normal: P̂ = P.
            assert!(
                (out.impulses[i] - sim.impulses_hat[i]).abs() <= bound,
                "e {e}: {:?} vs {:?}",
                out.impulses,
                sim.impulses_hat
            );
        }
        check_energy(&problem, &out);
    }
}

#[test]
fn a_pitching_bar_on_unequal_supports_follows_the_compliant_dynamics() {
    for (omega, eta, k2) in [(0.7, 1.5, 4.0), (-0.3, 1.0, 0.25), (0.0, 1.5, 10.0)] {
        let problem = bar(omega, 1.0);
        let laws = vec![
            ContactLaw::new(1.0, eta, 1.0).expect("valid"),
            ContactLaw::new(k2, eta, 1.0).expect("valid"),
        ];
        let out = solve_lzb(&problem, &laws, TOL).expect("LZB ends");
        check_energy(&problem, &out);
        // q = (y, θ): δ̇_i = −ẏ − x_i θ̇.
        let jac = vec![vec![-1.0, 0.8], vec![-1.0, -0.8]];
        let (time, d) = compliant_checked(
            &[1.0, 1.0 / 3.0],
            &jac,
            &[(1.0, eta), (k2, eta)],
            &[-1.0, omega],
            2e-4,
        );
        let lzb = [out.velocity.bottom()[1], out.velocity.top()[2]];
        let bound = d + 3.0 * velocity_bound(&out, 1.0);
        for (a, b) in lzb.iter().zip(&time) {
            assert!(
                (a - b).abs() <= bound,
                "ω {omega}, η {eta}, K₂ {k2}: LZB {lzb:?} vs time {time:?} (bound {bound:e})"
            );
        }
        // Both supports stored energy, the bar leaves them both.
        assert!(out.max_energy.iter().all(|e| *e > 0.0));
        assert!(
            out.events
                .iter()
                .any(|e| e.kind == EventKind::ExpansionEnds)
        );
    }
}

/// A constrained body (`examples/pinned-rod.toml`: a rod pinned at one end, struck at the
/// other) with its one contact: LZB gives Newton's answer for the mechanism, twist and all.
#[test]
fn a_pinned_rod_takes_newtons_answer() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pinned-rod.toml");
    let scene = inertance::scene::Scene::load(&path).expect("loads");
    let problem = inertance::scene::pipeline::prepare::<f64>(&scene).expect("prepares");
    for eta in [1.0, 1.5] {
        let e = problem.contacts()[0].k_newton;
        let law = ContactLaw::new(7.0, eta, e).expect("valid");
        let out = solve_lzb(&problem, &[law], TOL).expect("LZB ends");
        let mut impact = Impact::assemble(&problem).expect("assembles");
        let mut sim = Outcome::default();
        impact.solve(Model::Newton, &mut sim).expect("solves");
        let bound = velocity_bound(&out, out.blocks.v0[0].abs());
        let w = out.velocity.minus(&sim.velocity).max_abs_f64();
        assert!(w <= bound, "twist off by {w:e} (bound {bound:e})");
        check_energy(&problem, &out);
    }
}

/// A system with joints (`examples/double-pendulum-wall.toml`: a double pendulum striking a
/// wall with its tip) and its one contact: LZB gives Newton's answer, every body's twist.
#[test]
fn a_double_pendulum_striking_a_wall_takes_newtons_answer() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/double-pendulum-wall.toml");
    let scene = inertance::scene::Scene::load(&path).expect("loads");
    let system = scene.system::<f64>().expect("a system");
    assert!(!system.joints().is_empty());
    let e = system.contacts()[0].k_newton;
    let law = ContactLaw::new(0.3, 1.5, e).expect("valid");
    let out = solve_lzb(&system, &[law], TOL).expect("LZB ends");
    let mut impact = Impact::assemble(&system).expect("assembles");
    let mut sim = Outcome::default();
    impact.solve(Model::Newton, &mut sim).expect("solves");
    let bound = velocity_bound(&out, out.blocks.v0[0].abs());
    let w = out.velocity.minus(&sim.velocity).max_abs_f64();
    assert!(w <= bound, "twist off by {w:e} (bound {bound:e})");
    check_energy(&system, &out);
}
