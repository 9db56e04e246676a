//! The spatial friction integrator ([`inertance::impact::friction::spatial`]) against the exact
//! planar solver on planar scenes, against itself run tighter on spatial ones, through
//! Bhatt and Koechling's singular point, and against its invariants.
//!
//! The planar solver works on hatted axes with t = e × n, the spatial one on unit axes of the
//! contact frames, so only frame-independent quantities are compared: the twist after impact,
//! the impulse vectors, the kinetic-energy loss and the friction dissipation.

use inertance::impact::friction::spatial::{self, Stats};
use inertance::impact::friction::{
    Blocks, FrictionError, Frictional, ModeLabel, Phase, Restitution, solve_frictional,
};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::{Contact, ContactFrame};
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Scalar, int, ratio};
use inertance::solve;

fn v<T: Scalar>(x: T, y: T, z: T) -> Vec3<T> {
    Vec3::new(x, y, z)
}

fn q<T: Scalar>(p: i64, d: i64) -> T {
    ratio(p, d)
}

/// The paper's Example 3 (§7) with friction μ = a/b at both contacts.
fn example_3<T: Scalar>(a: i64, b: i64) -> Problem<T> {
    let c = |y: i64, k: T| {
        Contact::new(v(int(0), int(y), int(0)), v(int(1), int(0), int(0)), k)
            .with_tangent(v(int(0), int(1), int(0)))
            .with_friction(q(a, b))
    };
    Problem::new(
        RigidBody::principal(int(1), v(int(12), q(8, 5), int(12))),
        Screw::new(v(int(0), int(0), q(2, 5)), v(int(3), int(2), int(0))),
        vec![c(-2, q(3, 10)), c(4, q(1, 5))],
    )
    .unwrap()
}

/// One contact at (3/5, −4/5, 0) on the ground (outward normal −y), moving in the xy-plane:
/// K_tn / K_tt = −1.6 / 3.13, so the slip −1/5 comes to rest during compression and sticks
/// when μ = 4/5, and reverses when μ = 3/10 (the cone cannot hold it).
fn rod<T: Scalar>(mu_num: i64, mu_den: i64) -> Problem<T> {
    Problem::new(
        RigidBody::principal(int(1), v(q(3, 10), q(3, 10), q(3, 10))),
        Screw::new(v(int(0), int(0), int(0)), v(q(-1, 5), int(-1), int(0))),
        vec![
            Contact::new(
                v(q(3, 5), q(-4, 5), int(0)),
                v(int(0), int(-1), int(0)),
                q(1, 2),
            )
            .with_friction(q(mu_num, mu_den)),
        ],
    )
    .unwrap()
}

/// The paper's Example 8 (§13, derivations/example-8-sphere-in-corner.md, case `distinct`)
/// with friction μ and a spin ω⁰ that turns both slip directions during the impact.
fn example_8<T: Scalar>(mu: (i64, i64), spin: [i64; 3]) -> Problem<T> {
    let r: T = q(1, 2);
    let c = |p: Vec3<T>, n: Vec3<T>, k: T| Contact::new(p, n, k).with_friction(q(mu.0, mu.1));
    Problem::new(
        RigidBody::principal(int(2), v(q(1, 5), q(1, 5), q(1, 5))),
        Screw::new(
            v(int(spin[0]), int(spin[1]), int(spin[2])),
            v(int(3), int(6), int(0)),
        ),
        vec![
            c(
                v(r.clone(), int(0), int(0)),
                v(int(1), int(0), int(0)),
                q(1, 2),
            ),
            c(v(int(0), r, int(0)), v(int(0), int(1), int(0)), q(3, 10)),
        ],
    )
    .unwrap()
}

/// A box (half sides 1/2, 3/10, 1/5, unit mass) striking the ground with its corner, with a
/// skew slip and spin: its tangential block is anisotropic and coupled to the normal one.
fn box_corner<T: Scalar>(mu: (i64, i64), velocity: [i64; 3], spin: [i64; 3]) -> Problem<T> {
    let (a, b, c) = (q::<T>(1, 2), q::<T>(3, 10), q::<T>(1, 5));
    let third = q::<T>(1, 3);
    let inertia = v(
        third.clone() * (b.clone() * &b + c.clone() * &c),
        third.clone() * (a.clone() * &a + c.clone() * &c),
        third * (a.clone() * &a + b.clone() * &b),
    );
    Problem::new(
        RigidBody::principal(int(1), inertia),
        Screw::new(
            v(q(spin[0], 10), q(spin[1], 10), q(spin[2], 10)),
            v(q(velocity[0], 10), q(velocity[1], 10), q(velocity[2], 10)),
        ),
        vec![
            Contact::new(v(a, b, -c), v(int(0), int(0), int(-1)), q(1, 2))
                .with_friction(q(mu.0, mu.1)),
        ],
    )
    .unwrap()
}

/// A bowling ball (7 kg, R = 0.11 m) driven into the corner of floor and wall with topspin.
fn bowling_ball<T: Scalar>() -> Problem<T> {
    let r: T = q(11, 100);
    let inertia = q::<T>(2, 5) * int::<T>(7) * &r * &r;
    Problem::new(
        RigidBody::principal(int(7), v(inertia.clone(), inertia.clone(), inertia)),
        Screw::new(v(int(0), int(30), int(5)), v(int(3), int(1), q(-1, 2))),
        vec![
            Contact::new(
                v(int(0), int(0), -r.clone()),
                v(int(0), int(0), int(-1)),
                q(3, 10),
            )
            .with_friction(q(1, 5)),
            Contact::new(v(r, int(0), int(0)), v(int(1), int(0), int(0)), q(3, 5))
                .with_friction(q(1, 10)),
        ],
    )
    .unwrap()
}

/// The spatial integrator on `problem`, with the blocks `solve_frictional` would build.
fn spatial<T: Scalar>(
    problem: &Problem<T>,
    law: Restitution,
    tol: f64,
) -> Result<(Frictional<T>, Stats), FrictionError> {
    let frames: Vec<ContactFrame<T>> = problem
        .contacts()
        .iter()
        .enumerate()
        .map(|(i, c)| ContactFrame::new(i, c, problem.velocity()).unwrap())
        .collect();
    spatial::integrate(problem, Blocks::spatial(problem, &frames), law, tol)
}

/// The frame-independent outcome as f64: the twist after, then every impulse vector
/// (normal and tangential, body axes), then ΔE_c and the friction dissipation.
struct Summary {
    twist: Vec<f64>,
    impulses: Vec<f64>,
    energies: [f64; 2],
}

fn summary<T: Scalar>(out: &Frictional<T>) -> Summary {
    let mut impulses = Vec::new();
    for i in 0..out.blocks.contacts() {
        let (n, t) = out.impulse_vectors(i);
        impulses.extend(n.iter().chain(t.iter()).map(|x| x.to_f64()));
    }
    Summary {
        twist: out.velocity.as_slice().iter().map(|x| x.to_f64()).collect(),
        impulses,
        energies: [
            out.kinetic_energy_loss.to_f64(),
            out.friction_dissipation.to_f64(),
        ],
    }
}

fn max_diff(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

fn max_abs(a: &[f64]) -> f64 {
    a.iter().map(|x| x.abs()).fold(0.0, f64::max)
}

/// |a − b| within `est` for the twist and impulses; the energies within est × (the largest
/// speed of the scene × 2 × the number of impulse axes), the power an impulse error of est
/// can carry. Returns the differences (twist and impulses, energies).
fn within(a: &Summary, b: &Summary, est: f64, speed: f64, axes: usize, what: &str) -> (f64, f64) {
    let d = max_diff(&a.twist, &b.twist).max(max_diff(&a.impulses, &b.impulses));
    let de = max_diff(&a.energies, &b.energies);
    assert!(
        d <= est,
        "{what}: twist/impulse difference {d:e} > estimate {est:e}"
    );
    let ee = est * speed * 2.0 * axes as f64;
    assert!(de <= ee, "{what}: energy difference {de:e} > {ee:e}");
    (d, de)
}

/// The estimate is no wider than 10⁴ × tol × the scale of the answer: it sums the local
/// estimates of every accepted step (up to ≈ 10³ through a singular point), each up to
/// tol × scale.
fn not_absurd(s: &Summary, est: f64, tol: f64, what: &str) {
    let scale = max_abs(&s.twist).max(max_abs(&s.impulses)).max(1.0);
    assert!(
        est <= 1e4 * tol * scale,
        "{what}: estimate {est:e} > 1e4 × {tol:e} × {scale}"
    );
}

#[test]
fn planar_scenes_agree_with_the_exact_planar_solver_within_the_estimate() {
    let tol = 1e-8;
    let mut cases: Vec<(String, Problem<RatFun>, Problem<f64>)> = Vec::new();
    for (a, b) in [(1, 10), (1, 2), (1, 1)] {
        cases.push((
            format!("example 3, mu = {a}/{b}"),
            example_3(a, b),
            example_3(a, b),
        ));
    }
    cases.push(("rod that sticks".into(), rod(4, 5), rod(4, 5)));
    cases.push(("rod whose slip reverses".into(), rod(3, 10), rod(3, 10)));
    let mut compared = 0;
    for (name, exact, float) in &cases {
        for law in Restitution::ALL {
            let what = format!("{name}, {law}");
            let ex = solve_frictional(exact, law, 0.0);
            let sp = spatial(float, law, tol);
            let (ex, (sp, stats)) = match (ex, sp) {
                (Ok(e), Ok(s)) => (e, s),
                (Err(e), Err(s)) => {
                    // Both refuse alike (none of these cases does now: Example 3 with μ = 1
                    // under Newton, which both refused at s = 1, frees its pulling A₂ of
                    // friction in both and agrees within the estimate).
                    assert_eq!(e, s, "{what}");
                    println!("{what}: both refuse: {e}");
                    continue;
                }
                (e, s) => panic!("{what}: exact {:?}, spatial {:?}", e.err(), s.err()),
            };
            assert!(Blocks::planar(exact).is_some(), "{what}: planar");
            let est = sp.error_estimate.unwrap();
            let speed = max_abs(&sp.blocks.v0.iter().map(|x| x.to_f64()).collect::<Vec<_>>());
            let (a, b) = (summary(&ex), summary(&sp));
            let (d, de) = within(&a, &b, est, speed, sp.blocks.len(), &what);
            not_absurd(&a, est, tol, &what);
            println!(
                "{what}: |Δ| = {d:.1e}, |ΔE| = {de:.1e}, estimate {est:.1e}, {} steps, history {:?} / {:?}",
                stats.steps(),
                ex.history(0),
                sp.history(0)
            );
            compared += 1;
        }
    }
    assert_eq!(compared, 15);
}

#[test]
fn the_rod_sticks_or_reverses_as_the_exact_solver_says() {
    let (stuck, _) = spatial(&rod::<f64>(4, 5), Restitution::Poisson, 1e-10).unwrap();
    let h = stuck.history(0);
    assert_eq!(h.first(), Some(&ModeLabel::Slide));
    assert!(h.contains(&ModeLabel::Stick), "{h:?}");
    let (reversed, _) = spatial(&rod::<f64>(3, 10), Restitution::Poisson, 1e-10).unwrap();
    assert_eq!(reversed.history(0), vec![ModeLabel::Slide]);
    // Exactly: along y, which §12 points along the slip before impact (−x), then back.
    let exact = solve_frictional(&rod::<RatFun>(3, 10), Restitution::Poisson, 0.0).unwrap();
    assert_eq!(
        exact.history(0),
        vec![ModeLabel::SlidePlus, ModeLabel::SlideMinus]
    );
    // The slip reversed: the tangential velocity after has the opposite sign to before.
    let off = reversed.blocks.offset[0] + 1;
    let before = &reversed.blocks.v0[off..off + 2];
    let after = &reversed.after[off..off + 2];
    assert!(before[0] * after[0] + before[1] * after[1] < 0.0);
}

/// The spatial scenes of the tighter-run checks.
fn spatial_scenes<T: Scalar>() -> Vec<(&'static str, Problem<T>)> {
    vec![
        (
            "box corner, skew slip",
            box_corner((1, 2), [5, -3, -10], [5, 10, -7]),
        ),
        ("bowling ball, topspin", bowling_ball()),
        ("box corner through zero slip", singular()),
    ]
}

#[test]
fn spatial_scenes_agree_with_a_tighter_run_within_the_estimate() {
    let loose_tol = 1e-6;
    let tight_tol = 1e-12;
    for (name, problem) in spatial_scenes::<f64>() {
        assert!(Blocks::planar(&problem).is_none(), "{name}: spatial");
        for law in Restitution::ALL {
            let what = format!("{name}, {law}");
            let (loose, ls) = spatial(&problem, law, loose_tol).unwrap();
            let (tight, ts) = spatial(&problem, law, tight_tol).unwrap();
            let est = loose.error_estimate.unwrap();
            let speed = max_abs(&loose.blocks.v0);
            let (a, b) = (summary(&loose), summary(&tight));
            let (d, de) = within(&a, &b, est, speed, loose.blocks.len(), &what);
            not_absurd(&a, est, loose_tol, &what);
            not_absurd(&b, tight.error_estimate.unwrap(), tight_tol, &what);
            println!(
                "{what}: |Δ| = {d:.1e}, |ΔE| = {de:.1e}, estimate {est:.1e}; steps {} / {}, \
                 stops {} / {}, events {} / {}, history {:?} {:?}",
                ls.steps(),
                ts.steps(),
                ls.stops,
                ts.stops,
                ls.events,
                ts.events,
                tight.history(0),
                tight.history(tight.blocks.contacts() - 1),
            );
        }
    }
}

#[test]
fn double_double_agrees_with_f64_within_its_estimate() {
    let floats = spatial_scenes::<f64>();
    for ((name, problem), (_, fp)) in spatial_scenes::<DoubleDouble>().iter().zip(&floats) {
        for law in Restitution::ALL {
            let what = format!("{name}, {law}");
            let (dd, ds) = spatial(problem, law, 1e-20).unwrap();
            let (f, _) = spatial(fp, law, 1e-12).unwrap();
            let est = f.error_estimate.unwrap();
            let speed = max_abs(&f.blocks.v0);
            let (a, b) = (summary(&f), summary(&dd));
            let (d, de) = within(&a, &b, est, speed, f.blocks.len(), &what);
            println!(
                "{what}: f64 at 1e-12 vs double-double at 1e-20: |Δ| = {d:.1e}, |ΔE| = {de:.1e}, \
                 f64 estimate {est:.1e}, dd estimate {:.1e}, dd steps {}",
                dd.error_estimate.unwrap(),
                ds.steps()
            );
        }
    }
}

/// A box corner with a small skew slip and μ = 1: the slip turns as it falls to zero during
/// compression (s ≈ 0.318), then leaves again along an invariant direction of the
/// anisotropic tangential block.
fn singular<T: Scalar>() -> Problem<T> {
    box_corner((1, 1), [-1, -1, -10], [0, 0, 0])
}

#[test]
fn the_singular_point_is_passed_in_steps_that_grow_slowly_with_the_tolerance() {
    let problem = singular::<f64>();
    let (reference, _) = spatial(&problem, Restitution::Poisson, 1e-13).unwrap();
    // The slip comes to rest in compression: the first segment ends there, before s = 1.
    let first = &reference.segments[0];
    assert_eq!(first.modes[0], ModeLabel::Slide);
    assert_eq!(first.phase, Phase::Compression);
    assert!(first.to < 0.9, "rest at s = {}", first.to);
    // The tangential impulse is not along the initial slip: the direction turned.
    let u0 = &reference.blocks.v0[1..3];
    let tau = &reference.impulses[1..3];
    let cos = (u0[0] * tau[0] + u0[1] * tau[1]) / (u0[0].hypot(u0[1]) * tau[0].hypot(tau[1]));
    assert!(cos < 0.9, "cos = {cos}");
    let reference = summary(&reference);
    let mut counts = Vec::new();
    for tol in [1e-4, 1e-6, 1e-8, 1e-10, 1e-12] {
        let (out, stats) = spatial(&problem, Restitution::Poisson, tol).unwrap();
        let est = out.error_estimate.unwrap();
        let s = summary(&out);
        let speed = max_abs(&out.blocks.v0);
        let (d, _) = within(
            &s,
            &reference,
            est,
            speed,
            out.blocks.len(),
            &format!("{tol:e}"),
        );
        not_absurd(&s, est, tol, &format!("{tol:e}"));
        println!(
            "tol {tol:.0e}: {} steps ({} rejected), {} stops, |Δ| = {d:.1e}, estimate {est:.1e}",
            stats.steps(),
            stats.rejected,
            stats.stops
        );
        assert!(stats.stops + stats.events >= 1, "no stop");
        counts.push(stats.steps() as f64);
    }
    // 1/tol grows by 10⁸ from the first to the last; the steps by far less: the fifth root
    // of the tolerance of a smooth segment (10^1.6 ≈ 40) at most, plus a few per decade.
    let growth = counts[4] / counts[0];
    assert!(growth < 40.0, "steps {counts:?}");
}

#[test]
fn invariants_hold() {
    for (name, problem) in &spatial_scenes::<f64>() {
        for law in Restitution::ALL {
            let tol = 1e-10;
            let (out, _) = spatial(problem, law, tol).unwrap();
            let what = format!("{name}, {law}");
            let t0 = problem.body().kinetic_energy(problem.velocity());
            // T⁰ − T − ΔE_c: T comes from Λ, ΔE_c from the integrated powers v·dΛ; both carry
            // the local errors the integration accepted, so the residual is bounded by the
            // estimate times the largest speed times the axes (as the energies in `within`),
            // plus rounding of T⁰.
            let speed = max_abs(&out.blocks.v0);
            let bound =
                out.error_estimate.unwrap() * speed * 2.0 * out.blocks.len() as f64 + 1e-14 * t0;
            assert!(
                out.energy_residual.abs() <= bound,
                "{what}: residual {:e} > {bound:e}",
                out.energy_residual
            );
            assert!(out.friction_dissipation >= -bound, "{what}");
            if law == Restitution::Energetic {
                assert!(out.kinetic_energy_loss >= -bound, "{what}");
            }
        }
    }
}

#[test]
fn without_friction_the_spatial_path_is_the_frictionless_solve() {
    let scenes: Vec<(&str, Problem<f64>)> = vec![
        ("example 8", example_8((0, 1), [1, -2, 4])),
        ("box corner", box_corner((0, 1), [5, -3, -10], [5, 10, -7])),
        ("example 3", example_3(0, 1)),
    ];
    for (name, problem) in &scenes {
        for (law, model) in [
            (Restitution::Newton, Model::Newton),
            (Restitution::Poisson, Model::Poisson),
        ] {
            let (out, _) = spatial(problem, law, 1e-12).unwrap();
            let exact = solve(problem, model).unwrap();
            let a: Vec<f64> = out.velocity.as_slice().to_vec();
            let b: Vec<f64> = exact.twist.as_slice().to_vec();
            let d = max_diff(&a, &b) / max_abs(&b);
            assert!(d <= 1e-12, "{name}, {law}: relative {d:e}");
            for (i, p) in exact.impulses.iter().enumerate() {
                let got = *out.normal_hat(i);
                let want = p.to_f64();
                assert!(
                    (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                    "{name}, {law}"
                );
            }
        }
    }
}

/// The paper's Example 8 — a ball driven into the wall/floor corner — with friction and a
/// spin that turns the slips: μ = 1/5 and 1/2 with ω⁰ = (1, −2, 4) (spatial: the second
/// contact's slip stops in compression and sticks until its cone's edge, then restarts from zero
/// slip along the direction that grows out of that edge, which the integrator holds while the
/// turn is stiff; `tests/regression_stick_exit_direction.rs` checks these against an independent
/// integration), and ω⁰ = (0, 0, 4) (planar, forced through the spatial integrator: a slip stops
/// exactly at the end of compression and both contacts slide back in restitution, as the exact
/// solver and derivations/friction-example-8.md say). Every law, at 10⁻⁸ against 10⁻¹²: the
/// loose run's estimate covers the difference. The tight run costs at most 16 times the loose
/// one: near a slip restarting at a cone's edge the steps grow like tol^(−1/4)
/// (`src/impact/friction/spatial.rs`), 10 times over these four decades, elsewhere like
/// log(1/tol).
#[test]
fn example_8_with_spin_agrees_with_a_tighter_run() {
    for (mu, spin) in [
        ((1, 5), [1, -2, 4]),
        ((1, 2), [1, -2, 4]),
        ((1, 5), [0, 0, 4]),
    ] {
        let problem = example_8::<f64>(mu, spin);
        for law in Restitution::ALL {
            let (loose, ls) = spatial(&problem, law, 1e-8).unwrap();
            let (tight, ts) = spatial(&problem, law, 1e-12).unwrap();
            let est = loose.error_estimate.unwrap();
            let (a, b) = (summary(&loose), summary(&tight));
            within(
                &a,
                &b,
                est,
                max_abs(&loose.blocks.v0),
                loose.blocks.len(),
                "example 8",
            );
            not_absurd(&a, est, 1e-8, "example 8");
            assert!(
                ts.steps() <= 16 * ls.steps(),
                "{mu:?} {spin:?} {law}: {} steps at 1e-12, {} at 1e-8",
                ts.steps(),
                ls.steps()
            );
        }
    }
    // The planar case agrees with the exact solver: ω_z = −1/4 under Newton.
    let (out, _) = spatial(
        &example_8::<f64>((1, 5), [0, 0, 4]),
        Restitution::Newton,
        1e-12,
    )
    .unwrap();
    assert!((out.velocity.as_slice()[2] + 0.25).abs() < 1e-9);
}

/// A 0.4 × 0.2 × 0.1 m box of 2 kg landing flat on its four bottom corners (automatic
/// tangent axes), v_C⁰ = (1/5, 0, −1), μ = 1/2, k = 1/2 under Newton's law. By hand
/// (derivations/friction-face-landing.md): the face translates throughout — the normal split
/// balances the friction's moment, Σ x_i p_i = (1/20) μ P — so every corner slips at
/// 1/5 − μ P/m and all four stop together at P = 4/5 (s = 2/5, P = 2 s); then the face sticks
/// and Newton's law drives it to v_C = (0, 0, k) = (0, 0, 1/2), ω = 0, with ΔE_c = 1.04 − 0.25
/// = 0.79 J and friction dissipation μ ∫₀^{4/5} (1/5 − P/4) dP = 1/25 J. In floats the four
/// slips differ by the integration's error in ω, which made the normal split's family move the
/// body (the rank of the rate system was decided on that error): slips that agree within the
/// velocity tolerance now share one direction.
#[test]
fn a_face_sliding_in_translation_stops_at_every_corner_together() {
    let corner =
        |x: f64, y: f64| Contact::new(v(x, y, -0.05), v(0.0, 0.0, -1.0), 0.5).with_friction(0.5);
    let body = RigidBody::principal(
        2.0,
        v(
            2.0 * (0.04 + 0.01) / 12.0,
            2.0 * (0.16 + 0.01) / 12.0,
            2.0 * (0.16 + 0.04) / 12.0,
        ),
    );
    let problem = Problem::new(
        body,
        Screw::new(v(0.0, 0.0, 0.0), v(0.2, 0.0, -1.0)),
        vec![
            corner(0.2, 0.1),
            corner(0.2, -0.1),
            corner(-0.2, 0.1),
            corner(-0.2, -0.1),
        ],
    )
    .unwrap();
    let tol = 1e-8;
    let (out, _) = spatial(&problem, Restitution::Newton, tol).unwrap();
    let est = out.error_estimate.unwrap();
    not_absurd(&summary(&out), est, tol, "flat box");
    let twist = out.velocity.as_slice();
    let expected = [0.0, 0.0, 0.0, 0.0, 0.0, 0.5];
    assert!(
        max_diff(twist, &expected) <= est,
        "twist {twist:?} ≠ {expected:?} within {est:e}"
    );
    // The energies within the power an impulse error of `est` carries (as `within`).
    let energy = est * 1.0 * 2.0 * out.blocks.len() as f64;
    assert!((out.kinetic_energy_loss - 0.79).abs() <= energy);
    assert!((out.friction_dissipation - 0.04).abs() <= energy);
    // The slips stop together at s = 2/5, within the tolerance of the event's location.
    let events: Vec<f64> = out.segments.iter().map(|s| s.from.to_f64()).collect();
    assert!(
        events.iter().any(|s| (s - 0.4).abs() <= 1e-6),
        "segments start at {events:?}"
    );
    // The moment of the friction is balanced by the split: Σ x_i p_i^c = (1/20) μ (4/5).
    let moment: f64 = problem
        .contacts()
        .iter()
        .zip(&out.compression)
        .map(|(c, p)| c.point.x * p.to_f64())
        .sum();
    assert!((moment - 0.02).abs() <= est, "Σ x p^c = {moment}");
}
