//! Regression (issue 16): a heavy constrained body with small moments was given wrong
//! diagnoses in f64. On Example 6's joints (a revolute about z through (0, −1, 0) and a
//! prismatic along x) the reduced mass M_red = [[J + m, −m], [−m, m]] has condition about m/J,
//! and the solver, which formed and factored that Gram matrix, called the prismatic joint
//! "already given by the joints before it" (m = 10²⁰, 10¹⁰⁰, 10²⁰⁰) or the twist before impact
//! "not allowed by the constraints" (m = 10¹²), on valid scenes that `--exact` solves. The
//! free and blocked screws are now orthogonalised in the body's metric by Gram–Schmidt on the
//! screws themselves ([`inertance::mechanics::constraint`]), and constrained scenes are scaled
//! exactly before rounding ([`inertance::scene::scale`]).
//!
//! **What is checked.** Mass and moments are swept over 10^±k (the other held fixed) on the
//! hard case `constrained-near-singular-1e-4`, on a one-contact variant whose contact also
//! loads the joints (q ≠ 0), and on Example 6 (paper screws and joints) and Example 7 (α = 45°)
//! from `derivations/`. Every f64 solve either
//!
//! * agrees with the exact solve, group by group (impulses, ω, v_C, q, E_p, ΔE_c), to
//!   ‖f64 − exact‖_∞ ≤ 4 c κ ε · scale, with κ = cond₂ G of the exact solve, c = 2√N(3ℓ + 16N) + 1
//!   the accuracy contract's constant ([`inertance::analysis::accuracy`]) with ℓ = 1 (no contact
//!   screw here has a cancelling component) and μ = 1 (the orthogonalised basis applies W to
//!   working precision whatever cond M_red — the point of the fix, which this test measures),
//!   κ ≥ √κ covering the contract's √κ terms, and scale the group's largest exact value (for q,
//!   at least the largest contact impulse: U q is the reaction to them); or
//! * refuses with the singular-to-working-precision message, and then cond₂ G ≥ 1/(16ε): the
//!   2×2 LDLᵀ refuses when its computed second pivot d̃₂ ≤ 2ε max g_ii; the exact pivot is
//!   within the rounding of G's entries and of d₂ = g_qq − g_qp²/g_pp (a few ε max g_ii, at most
//!   14ε), and λ_min ≤ d₂, λ_max ≥ max g_ii give κ ≥ max g_ii / d₂ ≥ 1/(16ε).
//!
//! Never a "dependent joint" or a "velocity not allowed".

use std::str::FromStr;

use num_rational::BigRational;
use num_traits::ToPrimitive;

use inertance::report::{ModelReport, Report};
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::Scene;
use inertance::scene::pipeline::{RunError, run};

const EPS: f64 = f64::EPSILON;

/// A ```scene NAME block of a derivation.
fn derivation_scene(file: &str, name: &str) -> String {
    let text =
        std::fs::read_to_string(format!("{}/derivations/{file}", env!("CARGO_MANIFEST_DIR")))
            .unwrap();
    let start = text
        .find(&format!("```scene {name}\n"))
        .unwrap_or_else(|| panic!("{file}: no scene {name}"));
    let body = &text[start..];
    let body = &body[body.find('\n').unwrap() + 1..];
    body[..body.find("```").unwrap()].to_string()
}

/// The hard case as written.
fn hard_case() -> String {
    std::fs::read_to_string(format!(
        "{}/tests/hard_cases/constrained-near-singular-1e-4.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .unwrap()
}

/// Example 6's joints with one contact whose normal (1, 2, 0) also pushes on the blocked
/// directions, so q ≠ 0; G is 1×1.
fn loaded() -> String {
    r#"
name = "one contact loading the joints"
[body]
mass = 10
inertia = [3.3, 3.3, 3.3]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 1]
[[contact]]
point = [0, -0.3, 0]
normal = [1, 2, 0]
k = 0.5
[[constraints.joint]]
kind = "revolute"
point = [0, -1, 0]
axis = [0, 0, 1]
[[constraints.joint]]
kind = "prismatic"
axis = [1, 0, 0]
[solve]
models = ["newton", "poisson"]
"#
    .to_string()
}

/// `text` with its `mass = …` line, or its `inertia = […]` moments, replaced.
fn with_line(text: &str, key: &str, value: &str) -> String {
    text.lines()
        .map(|l| {
            if l.starts_with(&format!("{key} =")) {
                format!("{key} = {value}")
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

fn mass(text: &str, m: &str) -> String {
    with_line(text, "mass", &format!("\"{m}\""))
}

fn moments(text: &str, j: &str) -> String {
    with_line(text, "inertia", &format!("[\"{j}\", \"{j}\", \"{j}\"]"))
}

/// cond₂ G of an exact report (N ≤ 2, unit normals): λ_max from G/s (s = max g_ii), λ_min =
/// det/λ_max with det/s² taken from the exact text of Δ (so λ_min is accurate however small,
/// and neither underflows for a body of 10²⁰⁰ kg).
fn cond(report: &Report) -> f64 {
    let g = &report.inertance;
    match g.len() {
        1 => 1.0,
        2 => {
            let s = g[0][0].f64.max(g[1][1].f64);
            let (a, b, c) = (g[0][0].f64 / s, g[1][1].f64 / s, g[0][1].f64 / s);
            let det = match report.det.exact.as_deref().map(BigRational::from_str) {
                Some(Ok(d)) => {
                    let s = BigRational::from_float(s).unwrap();
                    (d / (&s * &s)).to_f64().unwrap()
                }
                _ => report.det.f64 / s / s,
            };
            let half = (a + b) / 2.0;
            let lmax = half + (((a - b) / 2.0).powi(2) + c * c).sqrt();
            lmax * lmax / det
        }
        n => panic!("{n} contacts"),
    }
}

/// The contract's c with ℓ = 1, μ = 1.
fn constant(n: usize) -> f64 {
    let n = n as f64;
    2.0 * n.sqrt() * (3.0 + 16.0 * n) + 1.0
}

/// ‖f − x‖_∞ ≤ bound · max(‖x‖_∞, floor), per group.
fn group(what: &str, f: &[f64], x: &[f64], floor: f64, bound: f64) {
    let scale = x.iter().fold(floor, |s, v| s.max(v.abs()));
    let err = f.iter().zip(x).fold(0f64, |e, (a, b)| e.max((a - b).abs()));
    assert!(
        err <= bound * scale,
        "{what}: error {err:e} > {bound:e} × {scale:e} (f64 {f:?}, exact {x:?})"
    );
}

fn values(v: &[inertance::report::Value]) -> Vec<f64> {
    v.iter().map(|v| v.f64).collect()
}

fn compare(case: &str, body: &Body, float: &ModelReport, exact: &ModelReport, bound: f64) {
    let p = values(&exact.impulses);
    let largest_p = p.iter().fold(0f64, |s, v| s.max(v.abs()));
    group(
        &format!("{case} P"),
        &values(&float.impulses),
        &p,
        0.0,
        bound,
    );
    // The twist in the kinetic-energy norm, against V = ‖v⁰‖_M + ‖Δv‖_M (the contract's).
    let twist = |r: &ModelReport| -> [f64; 6] {
        let (w, v) = (values(&r.angular_velocity), values(&r.velocity));
        [w[0], w[1], w[2], v[0], v[1], v[2]]
    };
    let (tf, tx) = (twist(float), twist(exact));
    let mut dv = tx;
    for (d, before) in dv.iter_mut().zip(&body.before) {
        *d -= before;
    }
    let speed = body.norm(&body.before) + body.norm(&dv);
    let mut err = tf;
    for (e, x) in err.iter_mut().zip(&tx) {
        *e -= x;
    }
    assert!(
        body.norm(&err) <= bound * speed,
        "{case} twist: ‖δv‖_M = {:e} > {bound:e} × V = {speed:e} (f64 {tf:?}, exact {tx:?})",
        body.norm(&err)
    );
    group(
        &format!("{case} q"),
        &values(&float.constraint_impulses),
        &values(&exact.constraint_impulses),
        largest_p,
        bound,
    );
    group(
        &format!("{case} E_p"),
        &[float.lost_velocity_energy.f64],
        &[exact.lost_velocity_energy.f64],
        0.0,
        bound,
    );
    // ΔE_c is a difference of energies of the size of E_p: measured against it.
    group(
        &format!("{case} ΔE_c"),
        &[float.kinetic_energy_loss.f64],
        &[exact.kinetic_energy_loss.f64],
        exact.lost_velocity_energy.f64.abs(),
        bound,
    );
}

/// The body's metric and its twist before impact [ω⁰; v_C⁰], in f64.
struct Body {
    mass: f64,
    moments: [f64; 3],
    before: [f64; 6],
}

impl Body {
    fn of(scene: &Scene) -> Body {
        let x = |n: &inertance::number::Number| n.approx;
        let w = scene.angular_velocity.each_ref().map(x);
        let v = scene.velocity.each_ref().map(x);
        Body {
            mass: x(&scene.mass),
            moments: [
                x(&scene.inertia[0]),
                x(&scene.inertia[1]),
                x(&scene.inertia[2]),
            ],
            before: [w[0], w[1], w[2], v[0], v[1], v[2]],
        }
    }

    /// ‖t‖_M = (ωᵀ J ω + m |v|²)^½, J principal; scaled by the largest component first so
    /// that it neither overflows nor underflows.
    fn norm(&self, t: &[f64; 6]) -> f64 {
        let s = t.iter().fold(0f64, |s, x| s.max(x.abs()));
        if s == 0.0 {
            return 0.0;
        }
        let mut e = 0.0;
        for k in 0..3 {
            e += self.moments[k] * (t[k] / s).powi(2) + self.mass * (t[k + 3] / s).powi(2);
        }
        e.sqrt() * s
    }
}

/// Solve `text` in f64 and exactly; check the f64 outcome as the module docs say. Returns
/// whether f64 solved it.
fn check(case: &str, text: &str) -> bool {
    let scene = Scene::parse(text, "heavy.toml").unwrap();
    // Radicals (Example 7's cos 45°) run exactly in the symbolic field, as `--exact` does.
    let exact = if scene.is_rational() {
        run::<Exact>(&scene, None)
    } else {
        run::<RatFun>(&scene, None)
    }
    .unwrap_or_else(|e| panic!("{case}: exact: {e}"));
    let kappa = cond(&exact.report);
    let body = Body::of(&scene);
    match run::<f64>(&scene, None) {
        Ok(float) => {
            let n = exact.report.inertance.len();
            let bound = 4.0 * constant(n) * kappa * EPS;
            for (f, x) in float.report.models.iter().zip(&exact.report.models) {
                compare(&format!("{case} {:?}", f.model), &body, f, x, bound);
            }
            true
        }
        Err(RunError::Solve(e)) => {
            let message = e.to_string();
            assert!(
                message.contains("singular to working precision"),
                "{case}: {message}"
            );
            assert!(
                kappa >= 1.0 / (16.0 * EPS),
                "{case}: refused as singular with cond G = {kappa:e}"
            );
            false
        }
        Err(e) => panic!("{case}: f64 refused a valid scene: {e}"),
    }
}

/// The exponents swept: 10^k for k in ±{0, 4, 12, 20, 40, 100, 200, 300}.
const EXPONENTS: [i32; 15] = [
    -300, -200, -100, -40, -20, -12, -4, 0, 4, 12, 20, 40, 100, 200, 300,
];

#[test]
fn the_reproductions_are_not_misdiagnosed() {
    // The hard case: cond G ≈ 10⁶ m (two contacts 10⁻⁴ apart on a translating body), so
    // m = 10¹² and up are genuinely singular in f64 and refused as such.
    for m in ["1e12", "1e20", "1e100", "1e200"] {
        check(&format!("hard case, m = {m}"), &mass(&hard_case(), m));
    }
    // With one contact G is 1×1: every mass solves.
    for m in ["1e12", "1e20", "1e100", "1e200"] {
        assert!(check(&format!("loaded, m = {m}"), &mass(&loaded(), m)));
    }
}

#[test]
fn mass_and_moments_swept_over_the_range_of_f64() {
    let scenes = [
        ("hard case", hard_case()),
        ("loaded", loaded()),
        (
            "example 6 paper",
            derivation_scene("example-6-sliding-bar.md", "paper"),
        ),
        (
            "example 6 joints",
            derivation_scene("example-6-sliding-bar.md", "joints"),
        ),
        (
            "example 7 a45",
            derivation_scene("example-7-bar-on-a-line.md", "a45"),
        ),
    ];
    for (name, text) in &scenes {
        let mut solved = 0;
        for k in EXPONENTS {
            let x = format!("1e{k}");
            solved += check(&format!("{name}, m = {x}"), &mass(text, &x)) as usize;
            solved += check(&format!("{name}, J = {x}"), &moments(text, &x)) as usize;
        }
        // The one-contact scene solves everywhere; the others at least where G is well
        // conditioned (m and J near the scene's own).
        if *name == "loaded" {
            assert_eq!(solved, 2 * EXPONENTS.len(), "{name}");
        } else {
            assert!(solved >= 4, "{name}: {solved} solved");
        }
    }
}

#[test]
fn a_constrained_body_of_tiny_mass_and_moments_is_scaled_and_solves() {
    // m = 10⁻³⁰⁰ kg, J = 3.3·10⁻³⁰⁰ kg·m² on one contact: M_red's entries and the impulses
    // are beyond f64's range as written (subnormal products); in units of 2^a kg they are of
    // order 1. (The hard case's two contacts at 10⁻³⁰⁰ kg have Δ = det G ≈ 3·10⁵⁹¹, itself
    // beyond f64, so it runs at 10⁻¹⁵⁰.)
    for (text, m, j) in [
        (loaded(), "1e-300", "3.3e-300"),
        (hard_case(), "1e-150", "3.3e-150"),
    ] {
        let text = moments(&mass(&text, m), j);
        let scene = Scene::parse(&text, "tiny.toml").unwrap();
        let (_, units) =
            inertance::scene::scale::scale(&scene).expect("a constrained scene is scaled");
        assert!(units.mass < -450, "mass unit 2^{}", units.mass);
        assert!(check("tiny body", &text));
        // The constraints' readout is scaled back: D, U and M_red as the exact solve's.
        let float = run::<f64>(&scene, None)
            .unwrap()
            .report
            .constraints
            .unwrap();
        let exact = run::<Exact>(&scene, None)
            .unwrap()
            .report
            .constraints
            .unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 4.0 * EPS * b.abs();
        for (f, x) in float
            .free
            .iter()
            .zip(&exact.free)
            .chain(float.blocked.iter().zip(&exact.blocked))
        {
            for (a, b) in f.iter().zip(x) {
                assert!(close(a.f64, b.f64), "screw {a:?} vs {b:?}");
            }
        }
        for (f, x) in float
            .reduced_mass
            .iter()
            .flatten()
            .zip(exact.reduced_mass.iter().flatten())
        {
            assert!(close(f.f64, x.f64), "M_red {} vs {}", f.f64, x.f64);
        }
    }
}

#[test]
fn scaled_written_screws_give_the_unscaled_reaction() {
    // Example 6 in the paper's form (D and U written out) at a mass of 10⁻¹⁰⁰ kg and moments
    // of 3.3·10⁻¹⁰⁰ kg·m² (G as well conditioned as the paper's): the written
    // screws are rescaled by their own powers of two and q is scaled back by 2^(a+b−c−g_a).
    let text = derivation_scene("example-6-sliding-bar.md", "paper");
    let text = moments(&mass(&text, "1e-100"), "3.3e-100");
    let scene = Scene::parse(&text, "paper.toml").unwrap();
    assert!(inertance::scene::scale::scale(&scene).is_some());
    assert!(check("example 6 paper, m = 1e-100, J = 3.3e-100", &text));
}
