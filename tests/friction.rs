//! Coulomb friction in impulse space (issue 13): the model against the paper (μ = 0), against
//! values derived by hand, and against its own invariants — exactly, in rationals and in the
//! radical field.

mod common;

use common::SceneFile;
use inertance::impact::friction::{
    FrictionError, ModeLabel, Phase, Restitution, Verdict, solve_frictional,
};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar, int, ratio};
use num_traits::Zero;
use proptest::prelude::*;

fn v<T: Scalar>(x: T, y: T, z: T) -> Vec3<T> {
    Vec3::new(x, y, z)
}

/// The paper's Example 3 (§7) with friction μ at both contacts.
fn example_3<T: Scalar>(mu: T) -> Problem<T> {
    let c = |y: i64, k: T| {
        Contact::new(v(int(0), int(y), int(0)), v(int(1), int(0), int(0)), k)
            .with_tangent(v(int(0), int(1), int(0)))
            .with_friction(mu.clone())
    };
    Problem::new(
        RigidBody::principal(int(1), v(int(12), ratio(8, 5), int(12))),
        Screw::new(v(int(0), int(0), ratio(2, 5)), v(int(3), int(2), int(0))),
        vec![c(-2, ratio(3, 10)), c(4, ratio(1, 5))],
    )
    .unwrap()
}

#[test]
fn mu_zero_reproduces_example_3_and_flags_the_negative_restitution_rate() {
    let out = solve_frictional(&example_3::<Exact>(int(0)), Restitution::Newton, 0.0).unwrap();
    assert_eq!(out.impulses, vec![ratio(329, 90), ratio(89, 450)]);
    assert_eq!(out.kinetic_energy_loss, ratio(223769, 45000));
    assert!(out.energy_residual.is_zero());
    // The paper's Example 3: dp₂/ds = −1/450 on [1, 2], hidden by the algebraic answer.
    assert_eq!(out.segments[1].rates, vec![ratio(77, 90), ratio(-1, 450)]);
    assert!(out.verdicts.contains(&Verdict::TensileRate {
        contact: 1,
        s: 1.0,
        phase: Phase::Restitution
    }));
    let out = solve_frictional(&example_3::<Exact>(int(0)), Restitution::Poisson, 0.0).unwrap();
    assert_eq!(out.impulses, vec![ratio(91, 25), ratio(6, 25)]);
    assert!(out.verdicts.is_empty());
}

#[test]
fn newton_with_mu_1_frees_the_pulling_contact_of_friction() {
    // Both contacts stick from s = 2/3; at s = 1 Newton asks A₂ for a negative rate, which no
    // cone holds and neither sense of slip is consistent with: A₂ carries no friction while
    // it pulls, A₁ sticks with no tangential rate (nothing drives v_Cy), and the impulses are
    // the frictionless ones with the tangential impulses of s = 2/3
    // (derivations/friction-example-3.md, "μ = 1 under Newton").
    let out = solve_frictional(&example_3::<Exact>(int(1)), Restitution::Newton, 0.0).unwrap();
    assert_eq!(
        out.impulses,
        // Λ = (p₁, τ₁, p₂, τ₂): the impulse on the body is −τ along the tangent
        vec![ratio(329, 90), ratio(28, 15), ratio(89, 450), ratio(2, 15)]
    );
    assert_eq!(
        out.velocity.as_slice(),
        &[
            int(0),
            int(0),
            ratio(-43, 300),
            ratio(-64, 75),
            int(0),
            int(0)
        ][..]
    );
    assert_eq!(out.friction_dissipation, int(2));
    assert_eq!(out.kinetic_energy_loss, ratio(313769, 45000));
    assert!(out.energy_residual.is_zero());
    assert_eq!(
        out.history(1),
        vec![ModeLabel::SlidePlus, ModeLabel::Stick, ModeLabel::Free]
    );
    assert!(out.verdicts.contains(&Verdict::TensileRate {
        contact: 1,
        s: 1.0,
        phase: Phase::Restitution
    }));
}

#[test]
fn energetic_stops_live_in_the_radical_field() {
    let out = solve_frictional(
        &example_3::<RatFun>(ratio(1, 2)),
        Restitution::Energetic,
        0.0,
    )
    .unwrap();
    // P₁ = (279 + √7239)/100: A₁ stops where its restitution work reaches k₁² times its
    // compression work, a root of a quadratic; A₂ (k₂ = 1/5) at s = 6/5.
    let sqrt = RatFun::sqrt(&num_rational::BigRational::from_integer(7239.into())).unwrap();
    assert_eq!(
        out.impulses[0],
        (RatFun::from_integer(279) + sqrt) / RatFun::from_integer(100)
    );
    assert_eq!(out.impulses[2], ratio(6, 25));
    assert_eq!(out.segments[1].to, ratio(6, 5));
    assert!(out.energy_residual.is_zero());
    // The energetic contacts end with restitution work = k² × compression work, exactly.
    for (i, k) in [ratio::<RatFun>(3, 10), ratio(1, 5)].iter().enumerate() {
        assert_eq!(
            out.work_restitution[i],
            k.clone() * k * &out.work_compression[i]
        );
    }
    // The same scene in rationals needs the square root it does not hold.
    let err = solve_frictional(
        &example_3::<Exact>(ratio(1, 2)),
        Restitution::Energetic,
        0.0,
    )
    .unwrap_err();
    assert_eq!(err, FrictionError::NeedsRadical { contact: 0 });
}

fn hatted_frictionless(p: &Problem<Exact>, model: Model) -> Option<Outcome<Exact>> {
    let mut impact = Impact::assemble(p).ok()?;
    let mut out = Outcome::default();
    impact.solve(model, &mut out).ok()?;
    Some(out)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// With every μ_i = 0 the integrator is the paper's eq. 15, 20–23: the same impulses and
    /// twist, in rationals — equality, not a tolerance.
    #[test]
    fn mu_zero_is_the_papers_solve_exactly(p in common::problem(3)) {
        for model in Model::ALL {
            let Some(expected) = hatted_frictionless(&p, model) else { continue };
            let out = solve_frictional(&p, Restitution::from(model), 0.0).unwrap();
            prop_assert_eq!(&out.impulses, &expected.impulses_hat);
            prop_assert_eq!(&out.velocity, &expected.velocity);
            prop_assert_eq!(&out.kinetic_energy_loss, &expected.kinetic_energy_loss);
            prop_assert!(out.energy_residual.is_zero());
        }
    }

    /// Planar frictional impacts: ΔE_c = Σ∫v·dΛ equals T⁰ − T exactly; friction dissipates
    /// (∫ v_t·dτ ≥ 0) whenever no normal rate was negative; the Coulomb cone holds for the
    /// accumulated impulses then; under Poisson's law P_i = (1 + k_i) p_i^c (eq. 23, with
    /// friction); and the energetic law gains no energy from approaching contacts.
    #[test]
    fn planar_friction_balances_energy_exactly(
        p in common::problem(2),
        mus in prop::collection::vec(common::rational(2, 4), 2),
    ) {
        // Flatten to the xy-plane: points and normals with z = 0, a planar twist.
        let body = p.body().clone();
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
                c.tangent = None;
                c.mu = mu.abs();
                c
            })
            .collect();
        prop_assume!(!contacts.is_empty());
        let q = Problem::new(body, twist, contacts).unwrap();
        for law in Restitution::ALL {
            // An energetic stop at an irrational s needs the radical field: skipped here (the
            // rod's closed forms cover that field).
            let Ok(out) = solve_frictional(&q, law, 0.0) else { continue };
            prop_assert!(out.blocks.plane.is_some());
            prop_assert!(out.energy_residual.is_zero());
            let tensile = out.verdicts.iter().any(|v| matches!(v, Verdict::TensileRate { .. }));
            if !tensile {
                prop_assert!(!out.friction_dissipation.is_negative());
                // The energetic law: each contact's normal work is (1 − k²) W_c ≥ 0 when it
                // approached (W_c ≥ 0), and friction dissipates — a theorem, asserted.
                let approaching = out.blocks.offset.iter().all(|&o| out.blocks.v0[o].is_positive());
                if law == Restitution::Energetic && approaching {
                    prop_assert!(!out.kinetic_energy_loss.is_negative());
                }
                for i in 0..out.blocks.contacts() {
                    let o = out.blocks.offset[i];
                    if out.blocks.dims[i] == 1 {
                        let bound = out.blocks.mu[i].clone() * &out.impulses[o];
                        prop_assert!(out.impulses[o + 1].abs() <= bound);
                    }
                }
            }
        }
    }
}

const ROUGH_BAR: &str = r#"
name = "Example 3 with friction"
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
mu = 1
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
mu = 1
[solve]
restitution = "poisson"
"#;

#[test]
fn the_cli_reports_modes_events_and_verdicts() {
    let s = SceneFile::new("friction-cli", ROUGH_BAR);
    let out = s.run(&["solve", "--exact", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = &j["friction"]["poisson"];
    assert_eq!(
        f["contacts"][0]["modes"],
        serde_json::json!(["slide+", "stick"])
    );
    assert_eq!(f["events"], serde_json::json!(["2/3", "1"]));
    assert_eq!(f["friction_dissipation"], "2");
    assert_eq!(
        f["contacts"][0]["tangential_impulse"],
        serde_json::json!(["0", "-28/15", "0"])
    );
    // The split of the shared tangential impulse is a verdict, said on stderr too.
    assert!(String::from_utf8_lossy(&out.stderr).contains("split shown is one member"));
    // Under Newton A₂ pulls from s = 1 and carries no friction then: the answer, with the
    // verdict on stderr and A₂'s modes ending free.
    let newton = SceneFile::new(
        "friction-cli-newton",
        &ROUGH_BAR.replace("poisson", "newton"),
    );
    let out = newton.run(&["solve", "--exact"]);
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("P = 329/90"), "{stdout}");
    assert!(stdout.contains("modes slide+ → stick → free"), "{stdout}");
    assert!(
        String::from_utf8_lossy(&out.stderr)
            .contains("contact 2: negative normal impulse rate from s = 1 (restitution)")
    );
}

#[test]
fn bad_friction_input_names_the_key_and_value() {
    let s = SceneFile::new(
        "friction-negative",
        &ROUGH_BAR.replacen("mu = 1", "mu = -0.2", 1),
    );
    let out = s.run(&["solve"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("contact[0].mu") && err.contains("-0.2"),
        "{err}"
    );
    let s = SceneFile::new(
        "friction-restitution",
        &ROUGH_BAR.replace("\"poisson\"", "\"plastic\""),
    );
    let out = s.run(&["solve"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("solve.restitution"));
}

#[test]
fn a_spatial_scene_is_refused_in_exact_mode() {
    // A spin about the bar's own axis moves the contacts out of the xy-plane.
    let s = SceneFile::new(
        "friction-spatial-exact",
        &ROUGH_BAR.replace(
            "angular_velocity = [0, 0, 0.4]",
            "angular_velocity = [1, 0, 0.4]",
        ),
    );
    let out = s.run(&["solve", "--exact"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("not planar"));
}

#[test]
fn a_sweep_of_mu_integrates_every_point_and_says_which_have_no_answer() {
    let s = SceneFile::new(
        "friction-sweep",
        &ROUGH_BAR.replace("restitution = \"poisson\"", ""),
    );
    let csv = s.dir().join("out.csv");
    let out = s.run(&[
        "sweep",
        "--vary",
        "contact[1].mu=0:1:5",
        "--exact",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split(',').collect()).collect();
    let col = |name: &str| rows[0].iter().position(|h| *h == name).unwrap();
    // Friction along the bar leaves the normal impulses at the paper's values (P₁ = 91/25
    // under Poisson, 329/90 under Newton); with μ₁ = 1 Newton's A₂ pulls from s = 1 and is
    // freed of friction there (derivations/friction-example-3.md): status says it pulls.
    for r in &rows[1..] {
        assert_eq!(r[col("poisson_P1_exact")], "91/25");
        assert_eq!(r[col("newton_P1_exact")], "329/90");
    }
    assert_eq!(rows[1][col("contact[1].mu_exact")], "0");
    assert!(rows[5][col("status")].contains("tensile"), "{:?}", rows[5]);
    assert!(!rows[1][col("poisson_Ef")].is_empty());
}

/// The rod of derivations/friction-rod.md at cos θ = 3/5: `analyze` gives its sticking
/// threshold μ̄ = 3 sin θ cos θ / (1 + 3 sin² θ) = 36/73 exactly, beside the frictional readout.
const ROD: &str = r#"
name = "rod, cos(theta) = 3/5"
[body]
mass = 1
inertia = ["1/300", "1/3", "1/3"]
velocity = ["-13/20", "-4/5", 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [-1, 0, 0]
normal = ["-4/5", "-3/5", 0]
k = 0.5
mu = 0.5
[solve]
restitution = "poisson"
"#;

#[test]
fn analyze_gives_the_sticking_threshold_and_the_frictional_readout() {
    let s = SceneFile::new("friction-analyze", ROD);
    let out = s.run(&["analyze", "--exact", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(
        j["friction"]["stick_thresholds"],
        serde_json::json!(["36/73"])
    );
    // μ = 1/2 ≥ 36/73: the slip stops in compression (s = 7/29) and sticks.
    let p = &j["friction"]["laws"]["poisson"];
    assert_eq!(p["events"], serde_json::json!(["7/29", "1"]));
    assert_eq!(p["contacts"][0]["normal_impulse"], "24/25");
}

/// A slider (prismatic joint along the normal) cannot move along the contact's tangent:
/// g_tt = 0. `analyze` used to divide by it (a panic in exact mode); it has no sticking
/// threshold, and the frictional readout still comes.
#[test]
fn regression_analyze_threshold_with_a_tangent_the_body_cannot_move_along() {
    let slider = r#"
[body]
mass = 2
inertia = [1, 1, 1]
velocity = [3, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [0, 1, 0]
normal = [1, 0, 0]
k = 0.5
mu = 0.5
[[constraints.joint]]
kind = "prismatic"
axis = [1, 0, 0]
"#;
    let s = SceneFile::new("friction-slider", slider);
    for exact in [true, false] {
        let args: &[&str] = if exact {
            &["analyze", "--exact", "--json"]
        } else {
            &["analyze", "--json"]
        };
        let out = s.run(args);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        assert_eq!(j["friction"]["stick_thresholds"], serde_json::json!([null]));
        // P = (1 + k) m v⁰ = 9 N s: the slider's normal impulse, friction absorbed by the joint.
        let p = &j["friction"]["laws"]["poisson"]["contacts"][0]["normal_impulse"];
        assert!(p == "9" || p == 9.0, "{p}");
    }
}

/// A bar (m = 1) landing square at 1 m/s on three rough supports at y = −1, 0, 2 (μ = 1): four
/// unknowns of a rigid body in the plane and three normals, so the normal impulses are a family
/// with one resultant (1 + k) m v. The member taken is the least-norm one: with the supports at
/// y_i, least |p| subject to Σ p_i = M and Σ p_i y_i = 0 is p_i = M (5 − y_i)/14 (Aᵀ(AAᵀ)⁻¹b
/// with A = [1 1 1; −1 0 2], AAᵀ = [3 1; 1 5]) — compression (6, 5, 3)/14, exactly. The twist
/// after is the frictionless one (v = −k, no turn) for every member, and the verdict says so under
/// Newton's law and under Poisson's with one k; with differing k^P it says the twist may depend
/// on the member.
#[test]
fn a_normal_split_takes_the_least_norm_member_exactly() {
    let bar = |kp: [Exact; 3]| {
        let c = |y: i64, kp: Exact| {
            Contact::new(
                v(int(0), int(y), int(0)),
                v(int(1), int(0), int(0)),
                ratio(1, 2),
            )
            .with_coefficients(ratio(1, 2), kp)
            .with_tangent(v(int(0), int(1), int(0)))
            .with_friction(int(1))
        };
        let [a, b, d] = kp;
        Problem::new(
            RigidBody::principal(int(1), v(int(12), ratio(8, 5), int(12))),
            Screw::new(v(int(0), int(0), int(0)), v(int(1), int(0), int(0))),
            vec![c(-1, a), c(0, b), c(2, d)],
        )
        .unwrap()
    };
    let half = || [ratio(1, 2), ratio(1, 2), ratio(1, 2)];
    for law in [Restitution::Newton, Restitution::Poisson] {
        let out = solve_frictional(&bar(half()), law, 0.0).unwrap();
        assert_eq!(
            out.compression,
            vec![ratio(6, 14), ratio(5, 14), ratio(3, 14)],
            "{law:?}"
        );
        assert_eq!(
            out.velocity,
            Screw::new(v(int(0), int(0), int(0)), v(ratio(-1, 2), int(0), int(0))),
            "{law:?}"
        );
        assert!(
            out.verdicts.contains(&Verdict::NormalSplitNotUnique {
                s: 0.0,
                decided: true,
                friction: false
            }),
            "{law:?}: {:?}",
            out.verdicts
        );
    }
    let out = solve_frictional(
        &bar([ratio(1, 2), ratio(1, 4), ratio(3, 4)]),
        Restitution::Poisson,
        0.0,
    )
    .unwrap();
    assert!(
        out.verdicts.contains(&Verdict::NormalSplitNotUnique {
            s: 0.0,
            decided: false,
            friction: false
        }),
        "{:?}",
        out.verdicts
    );
}

/// Two contacts in the plane (μ = 1 and 1/2) that take turns to separate and re-engage in
/// ever shorter intervals of s during compression, accumulating at s = 1 (each cycle ≈ 0.6 of
/// the one before): a Zeno point. Found by the energy-balance property below with
/// `PROPTEST_RNG_SEED=21`, where the exact solve ran for minutes (each event's rationals
/// longer than the last) and the f64 one stalled one ulp short of s = 1 until its budget of
/// 10 000 events. Both now stop with the named chatter error after 64 + 2 × 17 events.
fn chattering<T: Scalar>() -> Problem<T> {
    let body = RigidBody::principal(int(11), v(int(18), int(17), int(2)));
    let twist = Screw::new(v(int(0), int(0), ratio(-1, 2)), v(int(2), int(-2), int(0)));
    let mut a = Contact::new(
        v(int(-1), int(0), int(0)),
        v(int(3), int(1), int(0)),
        ratio(1, 8),
    )
    .with_coefficients(ratio(1, 8), int(1));
    a.mu = int(1);
    let mut b = Contact::new(
        v(int(1), int(4), int(0)),
        v(int(-1), int(-3), int(0)),
        ratio(3, 8),
    )
    .with_coefficients(ratio(3, 8), ratio(5, 8));
    b.mu = ratio(1, 2);
    Problem::new(body, twist, vec![a, b]).unwrap()
}

#[test]
fn chattering_contacts_are_a_named_error_in_floats_and_rationals() {
    let check = |e: FrictionError| match e {
        FrictionError::Chatter {
            s,
            phase,
            period,
            cycles,
        } => {
            assert_eq!((phase, period, cycles), (Phase::Compression, 2, 16));
            assert!(s > 0.999 && s <= 1.0, "s = {s}");
        }
        other => panic!("expected chatter, got {other:?}"),
    };
    check(solve_frictional(&chattering::<f64>(), Restitution::Newton, 0.0).unwrap_err());
    check(solve_frictional(&chattering::<Exact>(), Restitution::Newton, 0.0).unwrap_err());
}
