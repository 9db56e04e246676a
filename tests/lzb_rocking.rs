//! Housner's rocking block landing on its other edge, under the LZB law with both corners
//! storing energy, against an integration of our own in time (issue 25, validation).
//!
//! A rectangular block of half-width b, half-height h and unit mass (J_z = (b² + h²)/3 about
//! its centre C) rocks about its old corner A = C + (−b, −h) with angular velocity ω < 0; its
//! new corner B = C + (b, −h) lands. With q̇ = (ẋ, ẏ, θ̇), the indentation rates are
//! δ̇_i = −ẏ − x_i θ̇ (x_A = −b, x_B = b): the old corner starts at δ̇_A = 0, the new one at
//! 2b|ω|. An upward impulse P at B changes δ̇_A by P (3b²/(b² + h²) − 1) — the old corner is
//! pushed into the floor when h < √2 b (it loads and stores energy) and lifts when h > √2 b
//! (Housner's slender block).
//!
//! **The independent integration.** The LZB law in time rather than in the primary impulse:
//! each contact carries u_i = E_i^(1/(η_i+1)) (so u_i = c_i δ_i while it compresses), with
//!
//! ```text
//! du_i/dt = c_i δ̇_i            compressing (δ̇_i > 0)
//!         = c_i δ̇_i / e_i²     expanding (δ̇_i ≤ 0, u_i > 0)
//!         = 0                   resting (u_i = 0, δ̇_i ≤ 0)
//! M q̈ = −Σ_i F_i J_iᵀ,   F_i = (η_i + 1) c_i u_i^η_i,   c_i = (K_i/(η_i + 1))^(1/(η_i+1))
//! ```
//!
//! in the body's coordinates, by classical RK4 with a fixed step and each contact's phase
//! decided at the start of the step — no events, no primary contact, no impulse-space
//! variables; the LZB solver integrates dP_i/dτ = F_i by an adaptive embedded pair with events.
//! (With every e_i = 1 this is the compliant dynamics F = K δ^η; dE_i = F_i δ̇_i dt = v_i dP_i.)
//!
//! **Tolerances.** The time integration runs at dt and dt/2; their difference d bounds the
//! finer run's error (the scheme converges, at least at first order, across the phase
//! switches where the right-hand side is continuous but not smooth; the one discontinuity, a
//! plastic contact's energy dropped at the end of its compression, is located by bisection). The LZB side is allowed
//! its `velocity_bound` as in `tests/lzb.rs`: 2 ‖G‖∞ ε_P plus rounding.

mod common;

use common::row::velocity_bound;
use inertance::impact::multiple::{ContactLaw, solve_lzb};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};

const TOL: f64 = 1e-11;

fn v3(x: f64, y: f64, z: f64) -> Vec3<f64> {
    Vec3::new(x, y, z)
}

/// J_z of the block about its centre.
fn jz(b: f64, h: f64) -> f64 {
    (b * b + h * h) / 3.0
}

/// The block landing on B while rotating about A at ω (< 0), frictionless, normals −y.
fn landing(b: f64, h: f64, omega: f64) -> Problem<f64> {
    let body = RigidBody::principal(1.0, v3(h * h / 3.0 + 0.1, b * b / 3.0 + 0.1, jz(b, h)));
    // v_C = ω ẑ × (C − A) = ω (−h, b).
    let twist = Screw::new(v3(0.0, 0.0, omega), v3(-omega * h, omega * b, 0.0));
    let contacts = [-b, b]
        .iter()
        .map(|&x| Contact::new(v3(x, -h, 0.0), v3(0.0, -1.0, 0.0), 0.0))
        .collect();
    Problem::new(body, twist, contacts).expect("a valid block")
}

/// The LZB law in time and u (module docs): q̇ after the impact.
fn in_time(mass: &[f64], jac: &[[f64; 3]], laws: &[ContactLaw], q0: &[f64], dt: f64) -> Vec<f64> {
    let n = jac.len();
    let c: Vec<f64> = laws
        .iter()
        .map(|l| (l.stiffness / (l.exponent + 1.0)).powf(1.0 / (l.exponent + 1.0)))
        .collect();
    let rate = |q: &[f64], i: usize| (0..3).map(|a| jac[i][a] * q[a]).sum::<f64>();
    // Phases: 0 resting, 1 compressing, 2 expanding.
    let rhs = |s: &[f64], phases: &[u8]| -> Vec<f64> {
        let (u, q) = (&s[..n], &s[n..]);
        let mut d = vec![0.0; n + 3];
        for i in 0..n {
            let dd = rate(q, i);
            let l = &laws[i];
            d[i] = match phases[i] {
                1 => c[i] * dd,
                2 => c[i] * dd / (l.restitution * l.restitution),
                _ => 0.0,
            };
            if phases[i] != 0 {
                let f = (l.exponent + 1.0) * c[i] * u[i].max(0.0).powf(l.exponent);
                for a in 0..3 {
                    d[n + a] -= f * jac[i][a] / mass[a];
                }
            }
        }
        d
    };
    let mut s = vec![0.0; n];
    s.extend_from_slice(q0);
    let mut phases = vec![0u8; n];
    for step in 0.. {
        assert!(step < 50_000_000, "the time integration does not end");
        for i in 0..n {
            let dd = rate(&s[n..], i);
            phases[i] = if dd > 0.0 {
                1
            } else if s[i] > 0.0 && laws[i].restitution > 0.0 {
                2
            } else {
                s[i] = 0.0;
                0
            };
        }
        if phases.iter().all(|p| *p == 0) {
            break;
        }
        let rk4 = |s: &[f64], h: f64| -> Vec<f64> {
            let axpy = |k: &[f64], t: f64| -> Vec<f64> {
                s.iter().zip(k).map(|(a, b)| a + t * b).collect()
            };
            let k1 = rhs(s, &phases);
            let k2 = rhs(&axpy(&k1, h / 2.0), &phases);
            let k3 = rhs(&axpy(&k2, h / 2.0), &phases);
            let k4 = rhs(&axpy(&k3, h), &phases);
            (0..n + 3)
                .map(|q| s[q] + h / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]))
                .collect()
        };
        // A plastic contact (e = 0) loses its energy where its compression ends: the one
        // discontinuity of the right-hand side, located by bisection of the step.
        let plastic_ends = |next: &[f64]| {
            (0..n)
                .any(|i| phases[i] == 1 && laws[i].restitution == 0.0 && rate(&next[n..], i) < 0.0)
        };
        let mut next = rk4(&s, dt);
        if plastic_ends(&next) {
            let (mut lo, mut hi) = (0.0, dt);
            while hi - lo > 1e-15 * dt {
                let mid = 0.5 * (lo + hi);
                let trial = rk4(&s, mid);
                if plastic_ends(&trial) {
                    hi = mid;
                    next = trial;
                } else {
                    lo = mid;
                }
            }
        }
        s = next;
        for u in s.iter_mut().take(n) {
            *u = u.max(0.0);
        }
    }
    s[n..].to_vec()
}

/// Squat and slender blocks, linear and Hertz contacts, equal and unequal stiffness, elastic,
/// partly and fully plastic corners: the LZB solver's twist after impact equals the time
/// integration's within both errors, and the energy balance holds.
#[test]
fn the_rocking_block_landing_follows_the_law_integrated_in_time() {
    let cases = [
        // (b, h, η, K_A, K_B, e_A, e_B)
        (1.0, 1.0, 1.5, 1.0, 1.0, 1.0, 1.0), // squat: the old corner loads
        (1.0, 1.0, 1.0, 1.0, 3.0, 0.5, 0.5), // squat, linear, unequal stiffness
        (0.6, 0.8, 1.5, 2.0, 1.0, 0.8, 0.3), // sin α = 3/5, both store energy
        (0.3, 1.0, 1.5, 1.0, 1.0, 0.0, 0.0), // slender (h > √2 b): the old corner lifts
        (0.3, 1.0, 1.0, 1.0, 1.0, 0.7, 1.0), // slender, linear
    ];
    for (b, h, eta, ka, kb, ea, eb) in cases {
        let omega = -1.0;
        let problem = landing(b, h, omega);
        let laws = [
            ContactLaw::new(ka, eta, ea).expect("valid"),
            ContactLaw::new(kb, eta, eb).expect("valid"),
        ];
        let out = solve_lzb(&problem, &laws, TOL).expect("LZB ends");
        let lzb = [
            out.velocity.bottom()[0],
            out.velocity.bottom()[1],
            out.velocity.top()[2],
        ];
        let mass = [1.0, 1.0, jz(b, h)];
        let jac = [[0.0, -1.0, b], [0.0, -1.0, -b]];
        let q0 = [-omega * h, omega * b, omega];
        // The time scale of one corner's compression: δ* / v, δ* = ((η+1) v²/(2 g K))^(1/(η+1)).
        let dt = 2e-4;
        let coarse = in_time(&mass, &jac, &laws, &q0, dt);
        let fine = in_time(&mass, &jac, &laws, &q0, dt / 2.0);
        let d = coarse
            .iter()
            .zip(&fine)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        let bound = d + 3.0 * velocity_bound(&out, 2.0 * b);
        for (a, t) in lzb.iter().zip(&fine) {
            assert!(
                (a - t).abs() <= bound,
                "b {b}, h {h}, η {eta}, K ({ka}, {kb}), e ({ea}, {eb}): LZB {lzb:?} vs time \
                 {fine:?} (bound {bound:e}, time's own {d:e})"
            );
        }
        // The energy balance: ΔE_c = Σ (1 − e_i²) W_c,i.
        let balance = out.kinetic_energy_loss - out.total_dissipation();
        assert!(
            balance.abs()
                <= 4.0 * velocity_bound(&out, 2.0 * b) * out.impulses.iter().sum::<f64>() + 1e-12,
            "energy residual {balance:e}"
        );
        // Squat blocks load the old corner; slender ones do not.
        let squat = h < 2f64.sqrt() * b;
        assert_eq!(
            out.max_energy[0] > 0.0,
            squat,
            "b {b}, h {h}: {:?}",
            out.max_energy
        );
    }
}
