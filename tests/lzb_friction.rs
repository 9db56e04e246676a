//! The LZB law with Coulomb friction ([`inertance::impact::multiple`], Zhao, Liu & Brogliato
//! 2009) against what it did not write:
//!
//! * one contact: the normal impulse only grows, so the path in P is the same whatever K and η
//!   (the forces only set the pace), and the LZB expansion ends where Stronge's energetic law
//!   stops (W_r = e² W_c): LZB with friction is the frictional integrator's energetic law
//!   (`solve_frictional`, [`Restitution::Energetic`]) — exactly solved in the radical field in a
//!   plane, integrated with its own error estimate in space — through slide, stick and reversal;
//! * two equal contacts a bar lands flat on, with the same slip: both evolve alike, so LZB is
//!   the simultaneous energetic law with friction;
//! * the compliant dynamics in time (e = 1, F = K δ^η, Coulomb's force −μ F sign v_t while the
//!   contact slides), integrated by RK4 in the body's coordinates on scenes that slide
//!   throughout;
//! * invariants on seeded random scenes: ΔE_c = Σ_i (W_c,i − W_r,i + W_f,i), W_f,i ≥ 0, no
//!   contact approaching at the end; μ → 0 gives the frictionless answer.
//!
//! **Tolerances**, as in `tests/lzb.rs`: the integrator's error estimate ε_P bounds its
//! impulses (×2 for the propagation the sum of local estimates leaves out), a velocity moves by
//! ‖K‖∞ ε_P, a work by max|v| ε_P per axis; plus 64 N ε of the scale for rounding. A spatial
//! frictional solve carries its own estimate, added on its side. The time integration's error
//! is the difference of runs at dt and dt/2.

use inertance::impact::friction::{Frictional, ModeLabel, Restitution, solve_frictional};
use inertance::impact::mechanism::Mechanism;
use inertance::impact::multiple::{ContactLaw, EventKind, Lzb, solve_lzb};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Screws, Vec3};
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Scalar, int, ratio};

const TOL: f64 = 1e-11;
const EPS: f64 = f64::EPSILON;

type Q = (i64, i64);

fn q<T: Scalar>(x: Q) -> T {
    ratio(x.0, x.1)
}

fn v3<T: Scalar>(x: Q, y: Q, z: Q) -> Vec3<T> {
    Vec3::new(q(x), q(y), q(z))
}

/// A rod of length 2 and mass 1 (J = 1/3) in the xy-plane, along (3/5, 4/5), its lower end
/// A = (−3/5, −4/5) striking a floor y = const (normal −y, out of the rod; tangent +x) with
/// C's velocity (vx, −1) and spin ω.
fn rod<T: Scalar>(vx: Q, omega: Q, mu: Q, e: Q) -> Problem<T> {
    let body = RigidBody::principal(int(1), v3((1, 3), (1, 3), (1, 3)));
    let twist = Screw::new(v3((0, 1), (0, 1), omega), v3(vx, (-1, 1), (0, 1)));
    let contact = Contact::new(
        v3((-3, 5), (-4, 5), (0, 1)),
        v3((0, 1), (-1, 1), (0, 1)),
        q(e),
    )
    .with_tangent(v3((1, 1), (0, 1), (0, 1)))
    .with_friction(q(mu));
    Problem::new(body, twist, vec![contact]).expect("a valid rod")
}

/// ‖K‖∞ over every stacked axis.
fn k_norm<S: Screws<f64>>(out: &Lzb<S>) -> f64 {
    let n = out.blocks.len();
    (0..n)
        .map(|i| (0..n).map(|j| out.blocks.at(i, j).abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

fn speed<S: Screws<f64>>(out: &Lzb<S>) -> f64 {
    out.blocks.v0.iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

/// What an impulse of LZB may be off by.
fn impulse_bound<S: Screws<f64>>(out: &Lzb<S>) -> f64 {
    let n = out.blocks.len() as f64;
    2.0 * out.error_estimate + 64.0 * n * EPS * speed(out) / out.blocks.k[0]
}

/// What a velocity after impact may be off by.
fn velocity_bound<S: Screws<f64>>(out: &Lzb<S>) -> f64 {
    let n = out.blocks.len() as f64;
    2.0 * k_norm(out) * out.error_estimate + 64.0 * n * EPS * speed(out)
}

/// ΔE_c = Σ (W_c − W_r + W_f), W_r = e² W_c, W_f ≥ 0, nothing approaches at the end.
fn check_energy<M: Mechanism<f64>>(mechanism: &M, out: &Lzb<M::Screw>, what: &str) {
    let n = out.impulses.len();
    let axes = out.blocks.len() as f64;
    let speed = speed(out);
    let t0 = mechanism.kinetic_energy(mechanism.velocity());
    let bound = 2.0 * axes * speed * out.error_estimate + 64.0 * axes * EPS * t0.max(speed);
    assert!(
        out.energy_residual.abs() <= bound,
        "{what}: ΔE_c − Σ dissipation = {:e} (bound {bound:e})",
        out.energy_residual
    );
    for i in 0..n {
        let e2 = out.laws[i].restitution.powi(2);
        assert!(
            (out.work_expansion[i] - e2 * out.work_compression[i]).abs() <= bound,
            "{what}: contact {i}: released {} vs e² × stored {}",
            out.work_expansion[i],
            e2 * out.work_compression[i]
        );
        assert!(
            out.friction_dissipation[i] >= -bound,
            "{what}: contact {i}: friction gave energy {}",
            out.friction_dissipation[i]
        );
        assert!(
            out.after[i] <= speed * 1e-9,
            "{what}: contact {i} still approaches: {}",
            out.after[i]
        );
    }
}

/// LZB against the exact planar energetic solve of the same problem (the radical field),
/// converted: impulses along every axis and the twist.
fn against_exact(p64: &Problem<f64>, exact: &Frictional<RatFun>, laws: &[ContactLaw], what: &str) {
    let out = solve_lzb(p64, laws, TOL).expect("LZB ends");
    check_energy(p64, &out, what);
    assert_eq!(
        out.blocks.len(),
        exact.blocks.len(),
        "{what}: the same axes"
    );
    let ib = impulse_bound(&out);
    for i in 0..out.impulses.len() {
        let o = out.blocks.offset[i];
        let scale = out.blocks.directions[o].norm();
        let pairs = [(out.impulses[i], exact.impulses[o].to_f64() * scale)]
            .into_iter()
            .chain(
                out.tangential[i]
                    .iter()
                    .zip(&exact.impulses[o + 1..o + 1 + out.blocks.dims[i]])
                    .map(|(a, b)| (*a, b.to_f64() * scale)),
            );
        for (a, b) in pairs {
            assert!(
                (a - b).abs() <= ib,
                "{what}: contact {i}: LZB {a} vs energetic {b} (bound {ib:e})"
            );
        }
    }
    let exact_twist: Vec<f64> = exact
        .velocity
        .components()
        .iter()
        .map(|x| x.to_f64())
        .collect();
    let lzb_twist = out.velocity.components();
    let vb = velocity_bound(&out);
    for (a, b) in lzb_twist.iter().zip(&exact_twist) {
        assert!(
            (a - b).abs() <= vb,
            "{what}: twist {lzb_twist:?} vs energetic {exact_twist:?} (bound {vb:e})"
        );
    }
    let fd: f64 = out.friction_dissipation.iter().sum();
    let fb = 2.0 * out.blocks.len() as f64 * speed(&out) * out.error_estimate + 1e-12;
    assert!(
        (fd - exact.friction_dissipation.to_f64()).abs() <= fb,
        "{what}: friction dissipation {fd} vs {}",
        exact.friction_dissipation.to_f64()
    );
}

/// A rod striking a rough floor: slide throughout, slip that stops and sticks, slip that
/// reverses — each met at least once over the grid — for linear and Hertz contacts of any
/// stiffness: LZB gives the energetic law's answer, exactly solved.
#[test]
fn one_rough_contact_is_the_energetic_law_with_friction_in_a_plane() {
    let mut seen = [false; 3];
    let cases: [(Q, Q, Q); 6] = [
        ((3, 1), (0, 1), (1, 5)),
        ((1, 2), (1, 1), (1, 5)),
        ((1, 5), (0, 1), (1, 1)),
        ((1, 5), (-1, 1), (1, 2)),
        ((1, 10), (2, 1), (1, 4)),
        ((-1, 5), (1, 2), (1, 10)),
    ];
    for (vx, omega, mu) in cases {
        for e in [(0, 1), (1, 2), (1, 1)] {
            let exact = solve_frictional(
                &rod::<RatFun>(vx, omega, mu, e),
                Restitution::Energetic,
                0.0,
            )
            .expect("the energetic law solves it");
            let history = exact.history(0);
            let stick = history.contains(&ModeLabel::Stick);
            let reverses =
                history.contains(&ModeLabel::SlidePlus) && history.contains(&ModeLabel::SlideMinus);
            seen[0] |= history.len() == 1;
            seen[1] |= stick;
            seen[2] |= reverses;
            let p64 = rod::<f64>(vx, omega, mu, e);
            for (k, eta) in [(1.0, 1.0), (30.0, 1.5)] {
                let law = ContactLaw::new(k, eta, q::<f64>(e)).expect("valid");
                let what = format!("v_x {vx:?}, ω {omega:?}, μ {mu:?}, e {e:?}, K {k}, η {eta}");
                against_exact(&p64, &exact, &[law], &what);
                if reverses || stick {
                    let out = solve_lzb(&p64, &[law], TOL).expect("ends");
                    let kind = if stick {
                        EventKind::Sticks
                    } else {
                        EventKind::Reverses
                    };
                    assert!(
                        out.events.iter().any(|x| x.kind == kind),
                        "{what}: {history:?} but LZB's events {:?}",
                        out.events
                    );
                }
            }
        }
    }
    assert_eq!(
        seen, [true; 3],
        "slide throughout, stick, reversal each met"
    );
}

/// A box corner striking the ground in space (half sides a, b, c, unit mass), tangential
/// velocity `vt`, spin `omega`.
fn corner(vt: [f64; 2], omega: [f64; 3], mu: f64, e: f64) -> Problem<f64> {
    let (a, b, c) = (0.5, 0.3, 0.2);
    let j = |p: f64, q: f64| (p * p + q * q) / 3.0;
    Problem::new(
        RigidBody::principal(1.0, Vec3::new(j(b, c), j(a, c), j(a, b))),
        Screw::new(
            Vec3::new(omega[0], omega[1], omega[2]),
            Vec3::new(vt[0], vt[1], -1.0),
        ),
        vec![Contact::new(Vec3::new(a, b, -c), Vec3::new(0.0, 0.0, -1.0), e).with_friction(mu)],
    )
    .expect("a valid corner")
}

/// One rough contact in space: LZB against the spatial energetic integration, each within
/// its estimate.
#[test]
fn one_rough_contact_is_the_energetic_law_with_friction_in_space() {
    let cases = [
        ([2.0, 1.0], [0.3, -0.2, 0.1], 0.2),
        ([-0.1, -0.1], [0.0, 0.0, 0.0], 1.0),
        ([0.3, -0.2], [0.5, 0.4, -0.3], 0.5),
        ([0.05, 0.02], [0.2, -0.1, 0.4], 2.0),
    ];
    for (vt, omega, mu) in cases {
        for e in [0.0, 0.6, 1.0] {
            let p = corner(vt, omega, mu, e);
            let fr = solve_frictional::<f64, _>(&p, Restitution::Energetic, 1e-11)
                .expect("the energetic law integrates it");
            let fr_est = fr.error_estimate.expect("a spatial integration");
            for (k, eta) in [(1.0, 1.0), (5.0, 1.5)] {
                let law = ContactLaw::new(k, eta, e).expect("valid");
                let what = format!("v_t {vt:?}, ω {omega:?}, μ {mu}, e {e}, K {k}, η {eta}");
                let out = solve_lzb(&p, &[law], TOL).expect("LZB ends");
                check_energy(&p, &out, &what);
                let ib = impulse_bound(&out) + 2.0 * fr_est;
                let lzb = [out.impulses[0], out.tangential[0][0], out.tangential[0][1]];
                for (a, b) in lzb.iter().zip(&fr.impulses) {
                    assert!(
                        (a - b).abs() <= ib,
                        "{what}: LZB {lzb:?} vs energetic {:?} (bound {ib:e}, {:?})",
                        fr.impulses,
                        out.events
                    );
                }
                let w = out.velocity.minus(&fr.velocity).max_abs_f64();
                let vb = velocity_bound(&out) + 2.0 * k_norm(&out) * fr_est;
                assert!(w <= vb, "{what}: twist off by {w:e} (bound {vb:e})");
            }
        }
    }
}

/// A bar of length 2 and mass 1 (J_z = 1/3) landing flat on two rough supports at x = ±4/5,
/// both slipping at vx.
fn flat_bar<T: Scalar>(vx: Q, mu: Q, e: Q) -> Problem<T> {
    let body = RigidBody::principal(int(1), v3((1, 100), (1, 3), (1, 3)));
    let twist = Screw::new(v3((0, 1), (0, 1), (0, 1)), v3(vx, (-1, 1), (0, 1)));
    let contacts = [(-4, 5), (4, 5)]
        .iter()
        .map(|&x| {
            Contact::new(v3(x, (0, 1), (0, 1)), v3((0, 1), (-1, 1), (0, 1)), q(e))
                .with_tangent(v3((1, 1), (0, 1), (0, 1)))
                .with_friction(q(mu))
        })
        .collect();
    Problem::new(body, twist, contacts).expect("a valid bar")
}

#[test]
fn a_bar_landing_flat_on_equal_rough_supports_takes_the_simultaneous_energetic_impulses() {
    for (vx, mu) in [((2, 1), (1, 5)), ((1, 10), (1, 2)), ((1, 2), (1, 2))] {
        for e in [(0, 1), (1, 2), (1, 1)] {
            let exact =
                solve_frictional(&flat_bar::<RatFun>(vx, mu, e), Restitution::Energetic, 0.0)
                    .expect("solves");
            let p64 = flat_bar::<f64>(vx, mu, e);
            let law = ContactLaw::new(3.0, 1.5, q::<f64>(e)).expect("valid");
            let what = format!("v_x {vx:?}, μ {mu:?}, e {e:?}");
            against_exact(&p64, &exact, &[law, law], &what);
        }
    }
}

/// A tiny generator of seeded numbers in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// A seeded body falling onto 1–4 contacts of its underside, planar (motion and points in the
/// xy-plane, normals −y) or spatial (normals −z, tilted).
fn random_scene(rng: &mut Lcg, planar: bool) -> (Problem<f64>, Vec<ContactLaw>) {
    let n = 1 + (rng.next() * 4.0) as usize;
    let body = RigidBody::principal(
        rng.range(0.5, 2.0),
        Vec3::new(
            rng.range(0.1, 0.5),
            rng.range(0.1, 0.5),
            rng.range(0.1, 0.5),
        ),
    );
    let mut contacts = Vec::new();
    let mut laws = Vec::new();
    for _ in 0..n {
        let mu = if rng.next() < 0.2 {
            0.0
        } else {
            rng.range(0.05, 1.5)
        };
        let e = rng.range(0.0, 1.0);
        let c = if planar {
            Contact::new(
                Vec3::new(rng.range(-1.0, 1.0), rng.range(-0.5, -0.1), 0.0),
                Vec3::new(0.0, -1.0, 0.0),
                e,
            )
            .with_tangent(Vec3::new(1.0, 0.0, 0.0))
        } else {
            Contact::new(
                Vec3::new(
                    rng.range(-1.0, 1.0),
                    rng.range(-1.0, 1.0),
                    rng.range(-0.5, -0.1),
                ),
                Vec3::new(rng.range(-0.2, 0.2), rng.range(-0.2, 0.2), -1.0),
                e,
            )
        };
        contacts.push(c.with_friction(mu));
        laws.push(
            ContactLaw::new(
                rng.range(0.2, 5.0),
                if rng.next() < 0.5 { 1.0 } else { 1.5 },
                e,
            )
            .expect("valid"),
        );
    }
    let twist = if planar {
        Screw::new(
            Vec3::new(0.0, 0.0, rng.range(-1.0, 1.0)),
            Vec3::new(rng.range(-1.0, 1.0), -1.0, 0.0),
        )
    } else {
        Screw::new(
            Vec3::new(
                rng.range(-0.5, 0.5),
                rng.range(-0.5, 0.5),
                rng.range(-0.5, 0.5),
            ),
            Vec3::new(rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), -1.0),
        )
    };
    (
        Problem::new(body, twist, contacts).expect("a valid scene"),
        laws,
    )
}

/// Seeded random scenes balance their energy. Every scene is solved: a planar one's modes at
/// zero slip chosen by the friction layer's joint resolution; a spatial one where several
/// rough contacts reach zero slip together and more than one of them must slide (their
/// directions found one contact at a time, which could stop with `NoConsistentModes` and was
/// tolerated in two of these scenes before 2026-11-28) by Tresca's problem where that search
/// finds nothing.
#[test]
fn random_rough_scenes_balance_their_energy() {
    for planar in [true, false] {
        let mut rng = Lcg(if planar { 7 } else { 11 });
        for k in 0..12 {
            let (p, laws) = random_scene(&mut rng, planar);
            let what = format!("{} scene {k}", if planar { "planar" } else { "spatial" });
            let out = solve_lzb(&p, &laws, 1e-10).unwrap_or_else(|e| panic!("{what}: {e}"));
            check_energy(&p, &out, &what);
            if planar {
                assert!(
                    p.contacts().iter().all(|c| c.mu == 0.0) || out.blocks.plane.is_some(),
                    "{what}: solved in its plane"
                );
            }
        }
    }
}

/// μ → 0: the frictionless answer, within μ times the impulse scale.
#[test]
fn vanishing_friction_gives_the_frictionless_answer() {
    for planar in [true, false] {
        let mut rng = Lcg(if planar { 3 } else { 5 });
        for k in 0..6 {
            let (p, laws) = random_scene(&mut rng, planar);
            let smooth = |mu: f64| {
                let contacts = p
                    .contacts()
                    .iter()
                    .map(|c| c.clone().with_friction(mu))
                    .collect();
                Problem::new(p.body().clone(), p.velocity().clone(), contacts).expect("valid")
            };
            let mu = 1e-9;
            let rough = solve_lzb(&smooth(mu), &laws, TOL).expect("ends");
            let free = solve_lzb(&smooth(0.0), &laws, TOL).expect("ends");
            assert!(!free.has_friction() && rough.has_friction());
            let scale = free.impulses.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
            let bound = impulse_bound(&rough) + impulse_bound(&free) + 100.0 * mu * scale.max(1.0);
            for (a, b) in rough.impulses.iter().zip(&free.impulses) {
                assert!(
                    (a - b).abs() <= bound,
                    "scene {k}: μ = {mu}: {:?} vs {:?} (bound {bound:e})",
                    rough.impulses,
                    free.impulses
                );
            }
            for t in rough.tangential.iter().flatten() {
                assert!(t.abs() <= mu * scale + bound, "τ = {t}");
            }
        }
    }
}

/// The compliant dynamics in time with Coulomb's force: generalised velocities q̇ with a
/// diagonal mass matrix, normal indentation rate δ̇_i = J_i q̇, slip s_i = T_i q̇;
/// M q̈ = −Σ_i F_i (J_iᵀ + μ_i sign(s_i) T_iᵀ), F_i = K_i δ_i^η_i while δ_i > 0. RK4 at `dt`
/// until no contact is loaded and none approaches; panics if a loaded contact's slip changes
/// sign (the scene must slide throughout). Returns q̇ at the end.
fn compliant_rough(
    mass: &[f64],
    normal: &[Vec<f64>],
    tangent: &[Vec<f64>],
    laws: &[(f64, f64, f64)],
    qdot0: &[f64],
    dt: f64,
) -> Vec<f64> {
    let (m, n) = (mass.len(), normal.len());
    let slip = |s: &[f64], i: usize| (0..m).map(|a| tangent[i][a] * s[n + a]).sum::<f64>();
    let signs: Vec<f64> = (0..n)
        .map(|i| slip(&[vec![0.0; n], qdot0.to_vec()].concat(), i).signum())
        .collect();
    let rhs = |s: &[f64]| -> Vec<f64> {
        let mut d = vec![0.0; n + m];
        for i in 0..n {
            d[i] = (0..m).map(|a| normal[i][a] * s[n + a]).sum();
        }
        for i in 0..n {
            let delta = s[i];
            if delta > 0.0 {
                let (k, eta, mu) = laws[i];
                let f = k * delta.powf(eta);
                for a in 0..m {
                    d[n + a] -= f * (normal[i][a] + mu * signs[i] * tangent[i][a]) / mass[a];
                }
            }
        }
        d
    };
    let mut s: Vec<f64> = vec![0.0; n];
    s.extend_from_slice(qdot0);
    let axpy = |s: &[f64], k: &[f64], h: f64| -> Vec<f64> {
        s.iter().zip(k).map(|(a, b)| a + h * b).collect()
    };
    for step in 0.. {
        assert!(step < 100_000_000, "the compliant integration does not end");
        let k1 = rhs(&s);
        let k2 = rhs(&axpy(&s, &k1, dt / 2.0));
        let k3 = rhs(&axpy(&s, &k2, dt / 2.0));
        let k4 = rhs(&axpy(&s, &k3, dt));
        for q in 0..n + m {
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
        }
        for i in 0..n {
            if s[i] > 0.0 {
                assert!(
                    slip(&s, i) * signs[i] > 0.0,
                    "contact {i} stopped slipping: not a slide-throughout scene"
                );
            }
        }
        let rates = rhs(&s);
        if (0..n).all(|i| s[i] <= 0.0 && rates[i] <= 0.0) {
            break;
        }
    }
    s[n..].to_vec()
}

/// A planar body (q = x, y, θ; mass 1, J = 1/3 about C) on supports at the points `points`
/// (normals −y, tangents +x) with C's velocity (vx, −1) and spin ω, e = 1: LZB with friction
/// against the compliant dynamics with Coulomb's force, on scenes that slide throughout.
#[test]
fn sliding_rough_contacts_follow_the_compliant_dynamics_with_coulombs_force() {
    let cases: [(&[[f64; 2]], f64, f64, f64, &[f64]); 4] = [
        (&[[-0.6, -0.8]], 3.0, 0.5, 0.3, &[1.0]),
        (&[[0.5, -0.2]], -2.0, -0.4, 0.5, &[2.0]),
        (&[[-0.8, 0.0], [0.8, 0.0]], 2.5, 0.3, 0.2, &[1.0, 4.0]),
        (&[[-0.7, -0.1], [0.6, -0.3]], 3.0, -0.2, 0.25, &[2.0, 0.5]),
    ];
    for (points, vx, omega, mu, ks) in cases {
        for eta in [1.0, 1.5] {
            let body = RigidBody::principal(1.0, Vec3::new(1.0 / 3.0, 1.0 / 3.0, 1.0 / 3.0));
            let twist = Screw::new(Vec3::new(0.0, 0.0, omega), Vec3::new(vx, -1.0, 0.0));
            let contacts = points
                .iter()
                .map(|a| {
                    Contact::new(Vec3::new(a[0], a[1], 0.0), Vec3::new(0.0, -1.0, 0.0), 1.0)
                        .with_tangent(Vec3::new(1.0, 0.0, 0.0))
                        .with_friction(mu)
                })
                .collect();
            let p = Problem::new(body, twist, contacts).expect("valid");
            let laws: Vec<ContactLaw> = ks
                .iter()
                .map(|&k| ContactLaw::new(k, eta, 1.0).expect("valid"))
                .collect();
            let what = format!("{points:?}, v_x {vx}, ω {omega}, μ {mu}, η {eta}");
            let out = solve_lzb(&p, &laws, TOL).expect("LZB ends");
            check_energy(&p, &out, &what);
            // A's velocity: v_C + ω × A = (vx − ω a_y, vy + ω a_x); along −y: −ẏ − a_x θ̇.
            let normal: Vec<Vec<f64>> = points.iter().map(|a| vec![0.0, -1.0, -a[0]]).collect();
            let tangent: Vec<Vec<f64>> = points.iter().map(|a| vec![1.0, 0.0, -a[1]]).collect();
            let kl: Vec<(f64, f64, f64)> = ks.iter().map(|&k| (k, eta, mu)).collect();
            let mass = [1.0, 1.0, 1.0 / 3.0];
            let q0 = [vx, -1.0, omega];
            let coarse = compliant_rough(&mass, &normal, &tangent, &kl, &q0, 2e-4);
            let fine = compliant_rough(&mass, &normal, &tangent, &kl, &q0, 1e-4);
            let d = coarse
                .iter()
                .zip(&fine)
                .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
            let lzb = [
                out.velocity.bottom()[0],
                out.velocity.bottom()[1],
                out.velocity.top()[2],
            ];
            let bound = d + 3.0 * velocity_bound(&out);
            for (a, b) in lzb.iter().zip(&fine) {
                assert!(
                    (a - b).abs() <= bound,
                    "{what}: LZB {lzb:?} vs time {fine:?} (bound {bound:e}: time {d:e})"
                );
            }
            assert!(
                out.events
                    .iter()
                    .all(|e| !matches!(e.kind, EventKind::Sticks | EventKind::Reverses)),
                "{what}: slides throughout"
            );
        }
    }
}
