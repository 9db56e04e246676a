//! Coulomb friction in impulse space on systems of bodies (issue 24): the frictional
//! integration of `impact::friction`, run on a [`System`], against what the system code did not
//! compute —
//!
//! * a system of one body is the single body: every output of the frictional solve equal,
//!   exactly (random planar bodies placed anywhere in the world; the examples' bars), and in
//!   f64 bit for bit for a spatial scene;
//! * two bodies welded together are the composite body, with friction, exactly;
//! * a planar double pendulum whose tip strikes a rough floor, against Routh's frictional
//!   impact solved by hand in joint coordinates (sliding throughout; slip stopped, then
//!   sticking);
//! * two free bodies rubbing at a contact: momentum conserved exactly and the energy balance
//!   exact (rationals, planar); the energetic law never gains energy (f64, spatial).

mod common;

use inertance::impact::friction::{Frictional, ModeLabel, Restitution, Verdict, solve_frictional};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::mechanics::system::{Pair, System, SystemBody, SystemJoint, SystemScrew};
use inertance::scalar::{Exact, Scalar, int, ratio};
use num_traits::Zero;
use proptest::prelude::*;

fn v(x: Exact, y: Exact, z: Exact) -> Vec3<Exact> {
    Vec3::new(x, y, z)
}

fn vi(x: i64, y: i64, z: i64) -> Vec3<Exact> {
    v(int(x), int(y), int(z))
}

fn pair(first: usize, second: Option<usize>) -> Pair {
    Pair { first, second }
}

/// The one-body system of `p` with its centre at `c` (world points A = c + r).
fn one_body<T: Scalar>(p: &Problem<T>, c: Vec3<T>) -> System<T> {
    let contacts: Vec<Contact<T>> = p
        .contacts()
        .iter()
        .map(|k| Contact {
            point: k.point.clone() + c.clone(),
            ..k.clone()
        })
        .collect();
    let n = contacts.len();
    System::new(
        vec![SystemBody {
            body: p.body().clone(),
            centre: c,
        }],
        SystemScrew(vec![p.velocity().clone()]),
        contacts,
        vec![pair(0, None); n],
        Vec::new(),
    )
    .expect("a valid problem is a valid system")
}

/// Every output of two frictional solves equal but the twist (compared by the caller).
fn same_path<T: Scalar, S: inertance::mechanics::screw::Screws<T>>(
    a: &Frictional<T>,
    b: &Frictional<T, S>,
) {
    assert_eq!(a.impulses, b.impulses);
    assert_eq!(a.compression, b.compression);
    assert_eq!(a.after, b.after);
    assert_eq!(a.blocks.k, b.blocks.k);
    assert_eq!(a.blocks.v0, b.blocks.v0);
    assert_eq!(a.blocks.plane, b.blocks.plane);
    assert_eq!(a.work_compression, b.work_compression);
    assert_eq!(a.work_restitution, b.work_restitution);
    assert_eq!(a.friction_dissipation, b.friction_dissipation);
    assert_eq!(a.kinetic_energy_loss, b.kinetic_energy_loss);
    assert_eq!(a.lost_velocity_energy, b.lost_velocity_energy);
    assert_eq!(a.energy_residual, b.energy_residual);
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.verdicts, b.verdicts);
    assert_eq!(a.end, b.end);
    assert_eq!(a.error_estimate, b.error_estimate);
    for i in 0..a.blocks.contacts() {
        assert_eq!(a.impulse_vectors(i), b.impulse_vectors(i));
    }
}

/// The one-body system of `p` at centre `c` takes exactly the single body's frictional path
/// under every law, and leaves with its twist.
fn one_body_is_the_body(p: &Problem<Exact>, c: Vec3<Exact>) -> usize {
    let system = one_body(p, c);
    let mut solved = 0;
    for law in Restitution::ALL {
        let single = solve_frictional(p, law, 0.0);
        let multi = solve_frictional(&system, law, 0.0);
        match (single, multi) {
            (Ok(a), Ok(b)) => {
                same_path(&a, &b);
                assert_eq!(b.velocity, SystemScrew(vec![a.velocity.clone()]));
                solved += 1;
            }
            (Err(a), Err(b)) => assert_eq!(a, b),
            (a, b) => panic!("{law}: the body gives {a:?}, the system {b:?}"),
        }
    }
    solved
}

/// The paper's Example 3 bar (§7) on two rough supports, `examples/rough-bar.toml` (μ = 1)
/// and slipping variants, placed at a centre away from the origin.
#[test]
fn a_system_of_one_body_is_the_body_for_the_examples_bars() {
    let bar = |mu: Exact, spin: Exact| {
        let c = |y: i64, k: Exact| {
            Contact::new(vi(0, y, 0), vi(1, 0, 0), k)
                .with_tangent(vi(0, 1, 0))
                .with_friction(mu.clone())
        };
        common::valid(
            RigidBody::principal(int(1), v(int(12), ratio(8, 5), int(12))),
            Screw::new(v(int(0), int(0), spin), vi(3, 2, 0)),
            vec![c(-2, ratio(3, 10)), c(4, ratio(1, 5))],
        )
    };
    let mut solved = 0;
    for (mu, spin) in [
        (int(1), ratio(2, 5)),
        (ratio(1, 5), ratio(2, 5)),
        (ratio(3, 20), ratio(-7, 10)),
    ] {
        solved += one_body_is_the_body(&bar(mu, spin), v(ratio(7, 3), int(-5), ratio(1, 2)));
    }
    // A pitching bar (`examples/pitching-bar.toml`'s kind): one rough end on the floor.
    let pitching = common::valid(
        RigidBody::principal(int(2), v(ratio(1, 6), ratio(2, 3), ratio(2, 3))),
        Screw::new(vi(0, 0, -3), vi(1, -2, 0)),
        vec![Contact::new(vi(-1, 0, 0), vi(0, -1, 0), ratio(1, 2)).with_friction(ratio(1, 4))],
    );
    solved += one_body_is_the_body(&pitching, vi(4, 1, -2));
    assert!(solved >= 8, "only {solved} laws solved");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random planar bodies (every contact point, normal, v_C and ω in the xy plane, as
    /// `tests/friction.rs` builds them), placed at a random centre.
    #[test]
    fn a_system_of_one_body_is_the_body(
        p in common::problem(3),
        mus in prop::collection::vec(common::coefficient(), 3),
        c in common::vec3(5, 2),
    ) {
        let vel = p.velocity();
        let twist = Screw::new(
            v(int(0), int(0), vel.top()[2].clone()),
            v(vel.bottom()[0].clone(), vel.bottom()[1].clone(), int(0)),
        );
        let contacts: Vec<Contact<Exact>> = p
            .contacts()
            .iter()
            .zip(&mus)
            .filter(|(c, _)| !(c.normal[0].is_zero() && c.normal[1].is_zero()))
            .map(|(c, mu)| {
                let mut c = c.clone();
                c.point[2] = int(0);
                c.normal[2] = int(0);
                c.mu = mu.clone();
                c
            })
            .collect();
        prop_assume!(!contacts.is_empty());
        let q = Problem::new(p.body().clone(), twist, contacts).unwrap();
        // Either both solve, equal, or both fail alike (24 cases measured: 2–3 laws of 3 solve
        // in each; the energetic law may stop at an irrational s).
        one_body_is_the_body(&q, c);
    }
}

/// A spatial scene (a spinning ball in a corner, floats): the one-body system at the origin
/// takes the single body's adaptive integration bit for bit.
#[test]
fn a_spatial_one_body_system_is_the_body_bit_for_bit() {
    let r = 0.1;
    let p = Problem::new(
        RigidBody::principal(0.5, Vec3::repeat(0.4 * 0.5 * r * r)),
        Screw::new(Vec3::new(3.0, -4.0, 10.0), Vec3::new(2.0, 1.0, -3.0)),
        vec![
            Contact::new(Vec3::new(0.0, 0.0, -r), Vec3::new(0.0, 0.0, -1.0), 0.6)
                .with_friction(0.3),
            Contact::new(Vec3::new(r, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), 0.6).with_friction(0.3),
        ],
    )
    .unwrap();
    let system = one_body(&p, Vec3::zeros());
    for law in Restitution::ALL {
        let tol = 1e-9;
        let a = solve_frictional(&p, law, tol).unwrap();
        let b = solve_frictional(&system, law, tol).unwrap();
        assert!(a.error_estimate.is_some(), "spatial");
        same_path(&a, &b);
        assert_eq!(b.velocity, SystemScrew(vec![a.velocity.clone()]));
    }
}

/// Two bodies welded together with friction at both contacts are the composite body
/// (`tests/systems.rs` builds it by the parallel-axis theorem): masses 1 and 2 at (0, 0, 0) and
/// (3, 0, 0), moments (1, 2, 3) and (2, 1, 1); composite m = 3 at c = (2, 0, 0),
/// J = diag(1 + 2, 2 + 4 + 2 + 2, 3 + 4 + 1 + 2) = diag(3, 10, 10) — d_b is along x only. Struck
/// at two rough points, sliding and sticking, it takes the composite's impulses exactly and
/// both parts leave with the composite's twist.
#[test]
fn a_weld_with_friction_is_the_composite_body() {
    let parts: [(Exact, Vec3<Exact>, Vec3<Exact>); 2] = [
        (int(1), vi(1, 2, 3), vi(0, 0, 0)),
        (int(2), vi(2, 1, 1), vi(3, 0, 0)),
    ];
    let c = vi(2, 0, 0);
    let composite = RigidBody::principal(int(3), vi(3, 10, 10));
    let mut solved = 0;
    for (mu, omega, vc) in [
        (ratio::<Exact>(1, 2), ratio(1, 2), vi(1, -1, 0)),
        (ratio(1, 10), ratio(1, 2), vi(2, -1, 0)),
        (int(1), ratio(-1, 3), v(ratio(-1, 5), int(-2), int(0))),
    ] {
        let omega = v(int(0), int(0), omega);
        let at = |p: &Vec3<Exact>| vc.clone() + omega.cross(&(p.clone() - c.clone()));
        let contacts = vec![
            Contact::new(vi(0, -1, 0), vi(0, -1, 0), ratio(1, 2)).with_friction(mu.clone()),
            Contact::new(vi(3, -1, 0), vi(0, -1, 0), ratio(1, 4)).with_friction(mu.clone()),
        ];
        let system = System::new(
            parts
                .iter()
                .map(|(m, j, centre)| SystemBody {
                    body: RigidBody::principal(m.clone(), j.clone()),
                    centre: centre.clone(),
                })
                .collect(),
            SystemScrew(
                parts
                    .iter()
                    .map(|(_, _, centre)| Screw::new(omega.clone(), at(centre)))
                    .collect(),
            ),
            contacts.clone(),
            vec![pair(0, None), pair(1, None)],
            vec![SystemJoint {
                joint: Joint::Fixed { point: vi(1, 0, 0) },
                pair: pair(0, Some(1)),
            }],
        )
        .expect("valid");
        let single = common::valid(
            composite.clone(),
            Screw::new(omega.clone(), vc.clone()),
            contacts
                .iter()
                .map(|k| Contact {
                    point: k.point.clone() - c.clone(),
                    ..k.clone()
                })
                .collect(),
        );
        for law in [Restitution::Newton, Restitution::Poisson] {
            let e = solve_frictional(&single, law, 0.0).expect("the composite solves");
            let out = solve_frictional(&system, law, 0.0).expect("the weld solves");
            same_path(&e, &out);
            for (s, (_, _, centre)) in out.velocity.0.iter().zip(&parts) {
                assert_eq!(s.top(), e.velocity.top());
                assert_eq!(
                    s.bottom(),
                    e.velocity.bottom() + e.velocity.top().cross(&(centre.clone() - c.clone()))
                );
            }
            solved += 1;
        }
    }
    assert_eq!(solved, 6);
}

/// A planar double pendulum — two uniform rods of length 2, mass 1, J = 1/3 about their
/// centres, the first pinned to the ground at O, the second pinned to the first's end — whose
/// tip strikes a rough floor (`tests/systems.rs` strikes a smooth wall with it). Rods along
/// u₁ = (3/5, −4/5), u₂ = (4/5, −3/5); absolute joint rates θ̇ = (θ̇₁, θ̇₂).
///
/// By hand, in joint coordinates: with u⊥ = e_z × u the tip moves at Ṫ = 2θ̇₁ u₁⊥ + 2θ̇₂ u₂⊥,
/// the mass matrix is M = [[J + 5m, 2m u₁⊥·u₂⊥], [2m u₁⊥·u₂⊥, J + m]], and along the floor's
/// normal n = (0, −1, 0) (out of the pendulum) and tangent t = (1, 0, 0) the tip's velocities
/// are v_n = J_n θ̇, v_t = J_t θ̇ with J_n = 2 (n·u₁⊥, n·u₂⊥), J_t = 2 (t·u₁⊥, t·u₂⊥). An
/// impulse p along −n and τ along −t changes θ̇ by −M⁻¹(J_nᵀ p + J_tᵀ τ), so the contact's
/// inertance is the 2×2 K = [[a, b], [b, c]] = [J_n; J_t] M⁻¹ [J_n; J_t]ᵀ and
///
/// ```text
/// v_n = v_n⁰ − a p − b τ,   v_t = v_t⁰ − b p − c τ.
/// ```
///
/// Routh's frictional impact with σ = sign v_t⁰, Poisson's law p_f = (1 + k) p_c:
///
/// * **sliding throughout** (τ = σμp, with a + σμb > 0: no tensile rate): compression ends at
///   p_c = v_n⁰ / (a + σμb); it holds while σ v_t stays positive up to p_f,
///   σ(v_t⁰ − (b + σμc) p_f) > 0;
/// * **slip stops, then sticks**: the slip stops at p* = v_t⁰ / (b + σμc) < p_f; sticking needs
///   dτ = −(b/c) dp within the cone, |b/c| ≤ μ. Stopped in compression (v_n(p*) > 0) the
///   normal velocity then falls at a − b²/c, so p_c = p* + v_n(p*) / (a − b²/c); stopped in
///   restitution, p_c is the sliding one. τ_f = σμp* − (b/c)(p_f − p*), and v_t = 0 after;
/// * **slip stops, then reverses** (|b/c| > μ): from p* it slides the other way, σ' = −σ; in
///   compression p_c = p* + v_n(p*) / (a + σ'μb); τ_f = σμp* + σ'μ(p_f − p*).
#[test]
fn a_double_pendulum_on_a_rough_floor_against_routh_by_hand() {
    let u1 = v(ratio(3, 5), ratio(-4, 5), int(0));
    let u2 = v(ratio(4, 5), ratio(-3, 5), int(0));
    let perp = |u: &Vec3<Exact>| v(-u[1].clone(), u[0].clone(), int(0));
    let (m, j) = (int::<Exact>(1), ratio::<Exact>(1, 3));
    let two = int::<Exact>(2);
    let (n, t) = (vi(0, -1, 0), vi(1, 0, 0));
    let k = ratio::<Exact>(1, 2);
    // Joint coordinates, by hand.
    let m11 = j.clone() + m.clone() * int::<Exact>(5);
    let m12 = m.clone() * two.clone() * perp(&u1).dot(&perp(&u2));
    let m22 = j.clone() + m.clone();
    let det = m11.clone() * &m22 - m12.clone() * &m12;
    let inv = |x: &(Exact, Exact)| {
        (
            (m22.clone() * &x.0 - m12.clone() * &x.1) / &det,
            (m11.clone() * &x.1 - m12.clone() * &x.0) / &det,
        )
    };
    let row = |d: &Vec3<Exact>| (d.dot(&perp(&u1)) * &two, d.dot(&perp(&u2)) * &two);
    let (jn, jt) = (row(&n), row(&t));
    let dot2 = |x: &(Exact, Exact), y: &(Exact, Exact)| x.0.clone() * &y.0 + x.1.clone() * &y.1;
    let (mn, mt) = (inv(&jn), inv(&jt));
    let (a, b, cc) = (dot2(&jn, &mn), dot2(&jn, &mt), dot2(&jt, &mt));
    // The system.
    let rod = |centre: Vec3<Exact>| SystemBody::<Exact> {
        body: RigidBody::principal(m.clone(), v(j.clone(), j.clone(), j.clone())),
        centre,
    };
    let tip = u1.clone() * two.clone() + u2.clone() * two.clone();
    let ez = vi(0, 0, 1);
    let hinge = |point: Vec3<Exact>, pair: Pair| SystemJoint {
        joint: Joint::Revolute {
            point,
            axis: ez.clone(),
        },
        pair,
    };
    let system = |w: &(Exact, Exact), mu: &Exact| {
        System::new(
            vec![rod(u1.clone()), rod(u1.clone() * two.clone() + u2.clone())],
            SystemScrew(vec![
                Screw::new(ez.clone() * w.0.clone(), perp(&u1) * w.0.clone()),
                Screw::new(
                    ez.clone() * w.1.clone(),
                    perp(&u1) * (w.0.clone() * &two) + perp(&u2) * w.1.clone(),
                ),
            ]),
            vec![Contact::new(tip.clone(), n.clone(), k.clone()).with_friction(mu.clone())],
            vec![pair(1, None)],
            vec![
                hinge(vi(0, 0, 0), pair(0, None)),
                hinge(u1.clone() * two.clone(), pair(0, Some(1))),
            ],
        )
        .expect("valid")
    };
    // The hand solution: (p_f, τ_f) and the joint rates after.
    let check = |w: (Exact, Exact), mu: Exact, regime: Regime| {
        let (vn0, vt0) = (dot2(&jn, &w), dot2(&jt, &w));
        assert!(vn0 > Exact::zero(), "the tip approaches the floor");
        let sigma = if vt0 > Exact::zero() {
            int::<Exact>(1)
        } else {
            int(-1)
        };
        let one = int::<Exact>(1);
        // Sliding along σ, the normal impulse must grow as the normal velocity falls.
        let slide_rate = a.clone() + sigma.clone() * &mu * &b;
        assert!(slide_rate > Exact::zero(), "no tensile rate while sliding");
        // Where the slip stops, and the normal velocity there; compression's end had the
        // contact slid throughout.
        let star = vt0.clone() / (b.clone() + sigma.clone() * &mu * &cc);
        let vn_star = vn0.clone() - slide_rate.clone() * &star;
        let sliding_pc = vn0.clone() / &slide_rate;
        let (pf, tf) = match regime {
            Regime::Slide => {
                let pf = (one + &k) * sliding_pc;
                let vt = vt0.clone() - (b.clone() + sigma.clone() * &mu * &cc) * &pf;
                assert!(sigma.clone() * vt > Exact::zero(), "it slides throughout");
                (pf.clone(), sigma.clone() * &mu * pf)
            }
            Regime::Stick => {
                assert!(star > Exact::zero(), "the slip decelerates");
                assert!((b.clone() / &cc).abs() <= mu, "the cone holds the stick");
                // Stopped in compression, the normal velocity then falls at a − b²/c.
                let pc = if vn_star > Exact::zero() {
                    star.clone() + vn_star / (a.clone() - b.clone() * &b / &cc)
                } else {
                    sliding_pc
                };
                let pf = (one + &k) * pc;
                assert!(star < pf, "the slip stops within the impact");
                let tf = sigma.clone() * &mu * &star - b.clone() / &cc * (pf.clone() - &star);
                (pf, tf)
            }
            Regime::Reverse => {
                // The stick would need |b/c| > μ: the slip restarts the other way, σ' = −σ
                // (σ' dv_t/dp = −σ' b − μ c > 0 needs σ' = −sign b, which is −σ here).
                assert!(star > Exact::zero(), "the slip decelerates");
                assert!((b.clone() / &cc).abs() > mu, "the cone cannot hold a stick");
                let back = -sigma.clone();
                assert!(-(back.clone() * &b) - mu.clone() * &cc > Exact::zero());
                let back_rate = a.clone() + back.clone() * &mu * &b;
                assert!(back_rate > Exact::zero(), "no tensile rate after reversal");
                let pc = if vn_star > Exact::zero() {
                    star.clone() + vn_star / back_rate
                } else {
                    sliding_pc
                };
                let pf = (one + &k) * pc;
                assert!(star < pf, "the slip stops within the impact");
                let tf = sigma.clone() * &mu * &star + back * &mu * (pf.clone() - &star);
                (pf, tf)
            }
        };
        let (dp0, dp1) = (
            mn.0.clone() * &pf + mt.0.clone() * &tf,
            mn.1.clone() * &pf + mt.1.clone() * &tf,
        );
        let after = (w.0.clone() - dp0, w.1.clone() - dp1);
        let vt_after = dot2(&jt, &after);
        let s = system(&w, &mu);
        let out = solve_frictional(&s, Restitution::Poisson, 0.0).expect("solves");
        assert_eq!(out.blocks.plane, Some(ez.clone()));
        let (normal, tangential) = out.impulse_vectors(0);
        assert_eq!(normal, n.clone() * -pf.clone());
        assert_eq!(tangential, t.clone() * -tf.clone());
        assert_eq!(out.velocity.0[0].top(), ez.clone() * after.0.clone());
        assert_eq!(out.velocity.0[1].top(), ez.clone() * after.1.clone());
        assert_eq!(
            out.velocity.0[1].bottom(),
            perp(&u1) * (after.0.clone() * &two) + perp(&u2) * after.1.clone()
        );
        assert_eq!(out.energy_residual, Exact::zero());
        let history = out.history(0);
        let slide = |x: &Exact| {
            if *x > Exact::zero() {
                ModeLabel::SlidePlus
            } else {
                ModeLabel::SlideMinus
            }
        };
        // The tangent the report uses is t = e_x up to its sense (§12's y_i).
        let sense = out.blocks.directions[1][0].clone();
        match regime {
            Regime::Slide => {
                assert!(!vt_after.is_zero());
                assert_eq!(history, vec![slide(&(vt0.clone() * &sense))]);
            }
            Regime::Stick => {
                assert!(vt_after.is_zero());
                assert_eq!(
                    history,
                    vec![slide(&(vt0.clone() * &sense)), ModeLabel::Stick]
                );
            }
            Regime::Reverse => {
                assert_eq!(
                    history,
                    vec![
                        slide(&(vt0.clone() * &sense)),
                        slide(&(-vt0.clone() * &sense))
                    ]
                );
            }
        }
    };
    // θ̇ = (−1, −1): the tip at (−14/5, −14/5) m/s, slipping along −x.
    check((int(-1), int(-1)), ratio(1, 10), Regime::Slide);
    // ... stopped in restitution, then held.
    check((int(-1), int(-1)), ratio(3, 2), Regime::Stick);
    // θ̇ = (2, −2): the tip slipping along +x; held after it stops in restitution (μ < a/|b|:
    // a larger μ would make the normal impulse rate tensile while it slides).
    check((int(2), int(-2)), ratio(1, 2), Regime::Slide);
    check((int(2), int(-2)), ratio(3, 2), Regime::Stick);
    // θ̇ = (1, −3): along −x; stopped in compression, then held or reversed.
    check((int(1), int(-3)), int(3), Regime::Stick);
    check((int(1), int(-3)), ratio(1, 2), Regime::Reverse);
    check((int(1), int(-2)), ratio(1, 5), Regime::Reverse);
}

/// What the pendulum's tip does in the hand solution.
#[derive(Clone, Copy)]
enum Regime {
    Slide,
    Stick,
    Reverse,
}

/// Two free bodies meeting at a rough point, planar, rationals: Newton's, Poisson's laws — the
/// momentum after equals the momentum before exactly (the contact's impulses act equally and
/// oppositely), the energy balance ΔE_c = Σ∫v·dΛ = T⁰ − T holds exactly, and friction
/// dissipates.
fn two_free_bodies(
    masses: (Exact, Exact),
    moments: (Exact, Exact),
    twists: (Vec3<Exact>, Vec3<Exact>),
    point: Vec3<Exact>,
    normal: Vec3<Exact>,
    k: Exact,
    mu: Exact,
) -> System<Exact> {
    let b = |m: Exact, jz: Exact, centre: Vec3<Exact>| SystemBody {
        body: RigidBody::principal(m, v(int(1), int(1), jz)),
        centre,
    };
    // Body 0 at the origin, body 1 at (3, 1, 0); twists (ω_z, v_x, v_y) as given.
    let tw = |x: &Vec3<Exact>| {
        Screw::new(
            v(int(0), int(0), x[0].clone()),
            v(x[1].clone(), x[2].clone(), int(0)),
        )
    };
    let mut c = Contact::new(point, normal, int(0)).with_friction(mu);
    c.k_newton = k.clone();
    c.k_poisson = k.clone();
    c.k_energetic = k;
    System::new(
        vec![
            b(masses.0, moments.0, vi(0, 0, 0)),
            b(masses.1, moments.1, vi(3, 1, 0)),
        ],
        SystemScrew(vec![tw(&twists.0), tw(&twists.1)]),
        vec![c],
        vec![pair(0, Some(1))],
        Vec::new(),
    )
    .expect("valid")
}

/// The one contact slides at s = 0 and its slide's normal response is exactly zero:
/// with K the planar blocks (v = v⁰ − KΛ) and σ the sense of the slip, sliding takes
/// τ' = σ μ p', so v_n' = −(K_nn + σ μ K_nt) p' — when K_nn + σ μ K_nt = 0 no impulse rate
/// moves the normal velocity along the simultaneous law's path (dv_n/ds = −v_n⁰): the sliding
/// impulse leaves the approach speed unchanged (the boundary of Painlevé's impact jam), the
/// path's rates are infinite and the law has no continuation.
fn slide_stalls(s: &System<Exact>) -> bool {
    let b = inertance::impact::friction::Blocks::planar(s).expect("a planar pair");
    if b.dims[0] == 0 {
        return false; // μ = 0: no slide
    }
    let (n, t) = (b.offset[0], b.offset[0] + 1);
    let sigma: Exact = if b.v0[t].signum_i8() > 0 {
        int(1)
    } else {
        int(-1)
    };
    !b.v0[t].is_zero() && (b.at(n, n).clone() + sigma * &b.mu[0] * b.at(n, t)).is_zero()
}

/// The case proptest found where [`slide_stalls`] holds (masses 1 and 2, moments 3/2 and 1/2,
/// the contact at (−1/2, −2) with normal (−1, −1), μ = 5/4): by hand, with n = (−1, −1)/√2,
/// t = ±(1, −1)/√2, r₀ = (−1/2, −2), r₁ = (−7/2, −3),
/// W_nn = 1 + 1/2 + ((3/2)²/(3/2) + (1/2)²/(1/2))/2 = 5/2 and |W_nt| = |(−3/2)(5/2)/(3/2) +
/// (1/2)(13/2)/(1/2)|/2 = 2, so W_nn − μ|W_nt| = 5/2 − (5/4)·2 = 0: the solve says the law
/// has no continuation at s = 0 — an error, never a number.
#[test]
fn a_slide_that_cannot_move_the_normal_velocity_is_an_error_not_a_number() {
    let found = |mu: Exact| {
        two_free_bodies(
            (int(1), int(2)),
            (ratio(3, 2), ratio(1, 2)),
            (vi(0, 0, 0), vi(1, 0, 1)),
            v(ratio(-1, 2), int(-2), int(0)),
            vi(-1, -1, 0),
            int(0),
            mu,
        )
    };
    let s = found(ratio(5, 4));
    assert!(slide_stalls(&s));
    for law in [Restitution::Newton, Restitution::Poisson] {
        assert!(matches!(
            solve_frictional(&s, law, 0.0),
            Err(inertance::impact::friction::FrictionError::NoConsistentModes { s, .. }) if s == 0.0
        ));
    }
    // A little less friction and the slide compresses: the pair solves.
    let less = found(ratio(6, 5));
    assert!(!slide_stalls(&less));
    assert!(solve_frictional(&less, Restitution::Newton, 0.0).is_ok());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(32))]

    /// (A slide that cannot move its normal velocity, [`slide_stalls`], has no continuation
    /// under the simultaneous law: it is left out here and pinned above.)
    #[test]
    fn body_body_friction_conserves_momentum_exactly(
        m0 in common::positive(8, 2), m1 in common::positive(8, 2),
        j0 in common::positive(8, 2), j1 in common::positive(8, 2),
        t0 in common::vec3(4, 2), t1 in common::vec3(4, 2),
        px in common::rational(3, 2), py in common::rational(3, 2),
        nx in -3i64..=3, ny in -3i64..=3,
        k in common::coefficient(), mu in common::coefficient(),
    ) {
        prop_assume!(nx != 0 || ny != 0);
        let s = two_free_bodies(
            (m0, m1), (j0, j1), (t0, t1),
            v(px, py, int(0)), vi(nx, ny, 0), k, mu * int::<Exact>(2),
        );
        prop_assume!(s.relative_velocity(0).dot(&vi(nx, ny, 0)) > Exact::zero());
        prop_assume!(!slide_stalls(&s));
        for law in [Restitution::Newton, Restitution::Poisson] {
            let out = solve_frictional(&s, law, 0.0).expect("a planar free pair solves");
            prop_assert!(out.blocks.plane.is_some());
            prop_assert_eq!(s.momentum(&out.velocity), s.momentum(s.velocity()));
            prop_assert!(out.energy_residual.is_zero());
            let tensile = out.verdicts.iter().any(|v| matches!(v, Verdict::TensileRate { .. }));
            prop_assert!(tensile || out.friction_dissipation >= Exact::zero());
        }
    }
}

/// Random free pairs and pendulums in space (f64, adaptive integration) under the energetic
/// law: the kinetic energy never grows (each contact's normal work is (1 − k²) W_c ≥ 0 and
/// friction dissipates), the energy balance holds to the integration's own estimate, and a
/// free pair's momentum is conserved to rounding.
#[test]
fn the_energetic_law_never_gains_energy_in_space() {
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut checked = 0;
    for _ in 0..40 {
        let mut r = |lo: f64, hi: f64| lo + (hi - lo) * next();
        let body = |r: &mut dyn FnMut(f64, f64) -> f64| {
            RigidBody::principal(
                r(0.5, 3.0),
                Vec3::new(r(0.2, 2.0), r(0.2, 2.0), r(0.2, 2.0)),
            )
        };
        let b0 = body(&mut r);
        let b1 = body(&mut r);
        let twist = |r: &mut dyn FnMut(f64, f64) -> f64| {
            Screw::new(
                Vec3::new(r(-2.0, 2.0), r(-2.0, 2.0), r(-2.0, 2.0)),
                Vec3::new(r(-2.0, 2.0), r(-2.0, 2.0), r(-2.0, 2.0)),
            )
        };
        let (w0, w1) = (twist(&mut r), twist(&mut r));
        let point = Vec3::new(r(0.5, 1.5), r(-0.5, 0.5), r(-0.5, 0.5));
        let normal = Vec3::new(1.0, r(-0.3, 0.3), r(-0.3, 0.3));
        let (k, mu) = (r(0.0, 1.0), r(0.05, 1.0));
        let s = System::new(
            vec![
                SystemBody {
                    body: b0,
                    centre: Vec3::zeros(),
                },
                SystemBody {
                    body: b1,
                    centre: Vec3::new(2.0, 0.0, 0.0),
                },
            ],
            SystemScrew(vec![w0, w1]),
            vec![Contact::new(point, normal, k).with_friction(mu)],
            vec![pair(0, Some(1))],
            Vec::new(),
        )
        .expect("valid");
        let f = s.relative_velocity(0);
        if f.dot(&normal) <= 0.0 {
            continue; // separating: no impact
        }
        let out = solve_frictional(&s, Restitution::Energetic, 1e-9).expect("solves");
        let t0 = s.kinetic_energy(s.velocity());
        let t1 = s.kinetic_energy(&out.velocity);
        assert!(
            out.energy_balance_holds(&t0),
            "energy balance: {}",
            out.energy_residual
        );
        let slack = out.error_estimate.unwrap_or(0.0) * 10.0 * t0.max(1.0) + 1e-12 * t0;
        assert!(t1 <= t0 + slack, "energy grew: {t0} → {t1}");
        let ((p0, l0), (p1, l1)) = (s.momentum(s.velocity()), s.momentum(&out.velocity));
        let scale = p0.amax().max(l0.amax()).max(1.0);
        assert!((p1 - p0).amax() <= 1e-13 * scale && (l1 - l0).amax() <= 1e-13 * scale);
        checked += 1;
    }
    assert!(checked >= 10, "only {checked} impacts");
}

const PUCKS: &str = r#"
name = "two rough pucks glancing off each other"
[[body]]
name = "a"
mass = 1
inertia = [0.25, 0.25, 0.5]
position = [0, 0, 0]
velocity = [2, 0.5, 0]
angular_velocity = [0, 0, 3]
[[body]]
name = "b"
mass = 2
inertia = [0.5, 0.5, 1]
position = [1.6, 1.2, 0]
velocity = [-1, 0, 0]
angular_velocity = [0, 0, -1]
[[contact]]
bodies = ["a", "b"]
point = [0.6, 0.45, 0]
normal = [0.8, 0.6, 0]
k = 0.6
mu = 0.4
[solve]
models = ["newton", "poisson"]
"#;

/// `solve` on a frictional system scene, through the scene pipeline: two free pucks meeting at
/// one rough point, approaching at v_n⁰ = n·(v_a(A) − v_b(A)) = 27/10. The slip stops during
/// the impact and the contact sticks, so under either law the relative velocity after is
/// purely normal, −k v_n⁰ n = −(81/50)(4/5, 3/5, 0) (one contact: Newton's and Poisson's laws
/// agree); the momentum is kept exactly, the energy balance holds exactly, and the report's
/// JSON carries each law under `friction`. Floats, with a spin out of the plane (spatial): the
/// same checks to rounding and to the integration's estimate.
#[test]
fn a_frictional_system_scene_solves_and_reports() {
    use inertance::scene::Scene;
    use inertance::scene::system_pipeline::run_system;
    let scene = Scene::parse(PUCKS, "pucks.toml").unwrap();
    let solved = run_system::<Exact>(&scene, None).unwrap();
    assert_eq!(solved.friction_energy_balance, vec![true, true]);
    assert_eq!(solved.friction_momentum_conserved, vec![true, true]);
    let r = &solved.report;
    assert!(r.models.is_empty() && r.free);
    assert_eq!(r.effects, vec!["friction", "newton", "poisson"]);
    assert_eq!(r.friction.len(), 2);
    let exact = |v: &inertance::report::Value| v.exact.clone().unwrap();
    for f in &r.friction {
        assert_eq!(f.method, "planar, exact events");
        let c = &f.contacts[0];
        assert!(c.sticks, "{:?}", c.history);
        assert_eq!(exact(&c.normal_velocity), "-81/50");
        assert_eq!(exact(&c.velocity[0]), "-162/125");
        assert_eq!(exact(&c.velocity[1]), "-243/250");
        assert_eq!(c.velocity[2].f64, 0.0);
        assert_eq!(f.momentum_after, r.momentum_before);
    }
    let json = r.to_json();
    assert_eq!(
        json["friction"]["poisson"]["contacts"][0]["modes"],
        serde_json::json!(["slide+", "stick"])
    );
    assert_eq!(json["friction"]["newton"]["bodies"][1]["name"], "b");

    let spatial = Scene::parse(
        &PUCKS.replace(
            "angular_velocity = [0, 0, 3]",
            "angular_velocity = [1, 0, 3]",
        ),
        "pucks.toml",
    )
    .unwrap();
    let solved = run_system::<f64>(&spatial, None).unwrap();
    assert_eq!(solved.friction_energy_balance, vec![true, true]);
    assert_eq!(solved.friction_momentum_conserved, vec![true, true]);
    for f in &solved.report.friction {
        assert_eq!(f.method, "spatial, adaptive RK5(4)");
        let c = &f.contacts[0];
        assert!(
            (c.normal_velocity.f64 + 1.62).abs() <= 1e-12,
            "{}",
            c.normal_velocity.f64
        );
        let slip = (c.velocity[0].f64 + 1.296).hypot(c.velocity[1].f64 + 0.972);
        assert!(
            slip.hypot(c.velocity[2].f64) <= 10.0 * f.error_estimate.unwrap(),
            "{slip}"
        );
    }
}

/// A planar system posed in a plane that is no coordinate plane stays exact: two isotropic
/// rough pucks (as in the scene above) turned by the rational rotation R about x (cos 3/5,
/// sin 4/5) move in the plane of normal R e_z = (0, −4/5, 3/5), which the system's planes
/// (from its bodies' spins) find; every impulse equals the unturned pair's and every twist
/// after is the unturned one turned — an invariance the integration does not know of.
#[test]
fn a_system_in_a_rotated_plane_is_the_rotated_system() {
    let r = |x: &Vec3<Exact>| {
        v(
            x[0].clone(),
            ratio::<Exact>(3, 5) * &x[1] - ratio::<Exact>(4, 5) * &x[2],
            ratio::<Exact>(4, 5) * &x[1] + ratio::<Exact>(3, 5) * &x[2],
        )
    };
    let pucks = |turn: &dyn Fn(&Vec3<Exact>) -> Vec3<Exact>, mu: Exact| {
        let body = |m: i64, j: Exact, centre: Vec3<Exact>| SystemBody {
            body: RigidBody::principal(int(m), v(j.clone(), j.clone(), j)),
            centre: turn(&centre),
        };
        let twist = |w: Exact, vx: Exact, vy: Exact| {
            Screw::new(turn(&v(int(0), int(0), w)), turn(&v(vx, vy, int(0))))
        };
        System::new(
            vec![
                body(1, ratio(1, 2), vi(0, 0, 0)),
                body(2, int(1), v(ratio(8, 5), ratio(6, 5), int(0))),
            ],
            SystemScrew(vec![
                twist(int(3), int(2), ratio(1, 2)),
                twist(int(-1), int(-1), int(0)),
            ]),
            vec![
                Contact::new(
                    turn(&v(ratio(3, 5), ratio(9, 20), int(0))),
                    turn(&v(ratio(4, 5), ratio(3, 5), int(0))),
                    ratio(3, 5),
                )
                .with_friction(mu),
            ],
            vec![pair(0, Some(1))],
            Vec::new(),
        )
        .expect("valid")
    };
    let mut solved = 0;
    for mu in [ratio::<Exact>(2, 5), ratio(1, 20), int(2)] {
        let flat = pucks(&|x| x.clone(), mu.clone());
        let turned = pucks(&r, mu);
        for law in [Restitution::Newton, Restitution::Poisson] {
            let a = solve_frictional(&flat, law, 0.0).expect("the flat pair solves");
            let b = solve_frictional(&turned, law, 0.0).expect("the turned pair solves");
            assert_eq!(a.blocks.plane, Some(vi(0, 0, 1)));
            assert_eq!(b.blocks.plane, Some(r(&vi(0, 0, 1))));
            assert_eq!(a.impulses, b.impulses);
            assert_eq!(a.segments, b.segments);
            assert_eq!(a.kinetic_energy_loss, b.kinetic_energy_loss);
            for (x, y) in a.velocity.0.iter().zip(&b.velocity.0) {
                assert_eq!(r(&x.top()), y.top());
                assert_eq!(r(&x.bottom()), y.bottom());
            }
            solved += 1;
        }
    }
    assert_eq!(solved, 6);
}

/// `examples/rough-pendulum.toml` on the command line, exactly: the double pendulum of
/// [`a_double_pendulum_on_a_rough_floor_against_routh_by_hand`] at θ̇ = (1, −3), μ = 3 — its
/// hand solution P = 132/35, the floor's tangential impulse (−7666/2289, 0, 0), and no slip
/// after (the contact sticks).
#[test]
fn the_rough_pendulum_example_solves_as_derived() {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .args(["solve", "examples/rough-pendulum.toml", "--exact", "--json"])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = &json["friction"]["poisson"];
    let c = &f["contacts"][0];
    assert_eq!(c["normal_impulse"], "132/35");
    assert_eq!(
        c["tangential_impulse"],
        serde_json::json!(["-7666/2289", "0", "0"])
    );
    assert_eq!(c["velocity_after"][0], "0");
    assert_eq!(c["sticks"], true);
    assert_eq!(f["method"], "planar, exact events");
}
