//! Sensitivities by dual numbers — forward-mode automatic differentiation through the
//! unchanged solver (`inertance::scalar::dual`) — checked against derivatives computed another
//! way:
//!
//! * **Exact, against the symbolic scalar.** One number of a scene is made the symbol s; the
//!   solver run over `RatFun` (as `inertance derive` does) gives every output as a rational
//!   function of s, differentiated exactly (`RatFun::derivative`, the quotient rule) and
//!   evaluated at rational points. The tangent of a `Dual<Exact>` run seeded on that number
//!   (`scene::seed::seeded`) at the same point must be **equal**: the hatted impulses, the
//!   compression impulses, the twist after impact, the contact velocities, E_p and ΔE_c, and in
//!   the report the impulses in N s, whose derivative d(P̂|n|) is a surd. The paper's Example 3
//!   (a contact coordinate, a normal component, k, the mass), the same bar held by a planar
//!   joint (with constraint impulses) and a spatial three-contact body (a coordinate, a normal
//!   component, a Poisson coefficient, a moment of inertia, a spin, the mass), Newton and
//!   Poisson.
//! * **The branch taken.** Under the unilateral law, where one contact separates, the tangents
//!   equal the exact derivatives of the scene without that contact: the derivative of the
//!   active branch.
//! * **f64, within a bound from conditioning.** `Dual<f64>` through `run` (which rescales the
//!   scene by powers of two, so the seed's scaling is tested too) against the exact derivatives;
//!   the bound is derived at [`f64_bound`].
//! * **Friction, against central differences.** The planar frictional integration runs event
//!   by event in the scalar type, so a dual run carries the events' dependence on the inputs:
//!   the slender rod whose slip stops in compression and then sticks, or reverses, under
//!   Newton and Poisson, against central differences computed in exact rationals, which must
//!   converge to the dual tangent at the rate h² (no rounding: exact arithmetic); the
//!   energetic law (its stop is a root of a quadratic) in `Dual<f64>` against f64 differences.
//! * **The CLI.** `sweep --sensitivity` writes a derivative column per output and varied input,
//!   equal to the library's `Dual<f64>` run (and `_exact` columns equal to `Dual<Exact>`),
//!   empty at a point without an answer; the header without the flag is unchanged; a spatial
//!   frictional scene is refused before anything is solved.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::Command;

use inertance::analysis::condition_number;
use inertance::impact::friction::Restitution;
use inertance::impact::restitution::Model;
use inertance::impact::solve::Outcome;
use inertance::number::{format_rational, format_surd, parse_number};
use inertance::report::{Report, Value};
use inertance::scalar::dual::Dual;
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::pipeline::{assemble, run};
use inertance::scene::seed::seeded;
use inertance::scene::{Scene, parse_document, set_value};
use num_rational::BigRational;
use num_traits::{Signed, Zero};

/// The paper's Example 3 (§7): a planar bar on two supports.
const EXAMPLE_3: &str = r#"
name = "planar bar on two supports"
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = 0.2
"#;

/// A free body struck at three points in space, normals of irrational length, unequal
/// Newton and Poisson coefficients at one contact.
const SPATIAL: &str = r#"
name = "spatial body on three contacts"
[body]
mass = 2
inertia = [1, 2, 3]
velocity = [1, -2, "1/2"]
angular_velocity = ["1/2", "-1/4", 1]
[[contact]]
point = [1, 0, 0]
normal = [1, "1/4", "-1/2"]
k = 0.5
[[contact]]
point = [0, 1, "1/2"]
normal = ["1/3", 1, 0]
k_newton = 0.25
k_poisson = "2/3"
[[contact]]
point = ["-1/2", "-1/2", 1]
normal = [0, "-1/5", 1]
k = 0.6
"#;

/// Example 3's bar held in its plane by a planar joint (§9–11): the same impacts, with
/// constraint impulses.
fn example_3_in_a_plane() -> &'static str {
    static TEXT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    TEXT.get_or_init(|| {
        format!("{EXAMPLE_3}[[constraints.joint]]\nkind = \"planar\"\nnormal = [0, 0, 1]\n")
    })
}

/// The varied numbers and the rational points they are differentiated at, per scene.
fn cases() -> Vec<(&'static str, &'static str, Vec<&'static str>)> {
    vec![
        (
            example_3_in_a_plane(),
            "contact[1].point[1]",
            vec!["4", "5/2"],
        ),
        (example_3_in_a_plane(), "body.inertia[2]", vec!["12", "1/2"]),
        (
            EXAMPLE_3,
            "contact[1].point[1]",
            vec!["4", "5/2", "7", "-1/3"],
        ),
        // |n|² = 1 + s² is a square at these points, so P_1 and its derivative are rational.
        (
            EXAMPLE_3,
            "contact[0].normal[1]",
            vec!["0", "3/4", "-5/12", "4/3"],
        ),
        (EXAMPLE_3, "contact[0].k", vec!["3/10", "0", "7/8", "1"]),
        (EXAMPLE_3, "body.mass", vec!["1", "1/3", "5/2"]),
        (SPATIAL, "contact[2].point[2]", vec!["1", "1/2", "-3/7"]),
        (SPATIAL, "contact[0].normal[1]", vec!["1/4", "-1", "2/3"]),
        (SPATIAL, "contact[1].k_poisson", vec!["2/3", "1/5"]),
        (SPATIAL, "body.inertia[1]", vec!["2", "1/2", "9/4"]),
        (SPATIAL, "body.angular_velocity[0]", vec!["1/2", "-1", "0"]),
        (SPATIAL, "body.mass", vec!["2", "1/7"]),
    ]
}

fn q(text: &str) -> BigRational {
    parse_number(text).unwrap().exact.unwrap()
}

/// `text` with the number at `key` set to `value` (TOML text), the symbol s declared.
fn scene_with(text: &str, key: &str, value: &str) -> Scene {
    let mut doc = parse_document(text, "scene.toml").unwrap();
    set_value(&mut doc, key, value).unwrap();
    Scene::from_document_with(&doc, "scene.toml", &["s".to_string()]).unwrap()
}

/// `text` at `key` = `at`, seeded to differentiate with respect to that number.
fn seeded_at(text: &str, key: &str, at: &str) -> Scene {
    seeded(&scene_with(text, key, &format!("\"{at}\"")), key).unwrap()
}

/// Every output of a solve, named: the hatted impulses (and compression impulses), the twist
/// after impact, the hatted contact velocities after impact, E_p, ΔE_c.
fn outputs<T: Scalar>(o: &Outcome<T>) -> Vec<(String, T)> {
    let mut v = Vec::new();
    for (i, p) in o.impulses_hat.iter().enumerate() {
        v.push((format!("P̂{}", i + 1), p.clone()));
    }
    for (i, p) in o.compression_hat.iter().enumerate() {
        v.push((format!("P̂c{}", i + 1), p.clone()));
    }
    for (k, x) in ["ωx", "ωy", "ωz", "vCx", "vCy", "vCz"]
        .iter()
        .zip(o.velocity.0.iter())
    {
        v.push((k.to_string(), x.clone()));
    }
    for (i, c) in o.after_hat.iter().enumerate() {
        for (a, x) in ["x", "y", "z"].iter().zip(c) {
            v.push((format!("v̂{}{a}", i + 1), x.clone()));
        }
    }
    v.push(("Ep".into(), o.lost_velocity_energy.clone()));
    v.push(("dEc".into(), o.kinetic_energy_loss.clone()));
    for (i, x) in o.constraint_impulses.iter().enumerate() {
        v.push((format!("q{}", i + 1), x.clone()));
    }
    v
}

/// The exact derivative of an output at s = `at`, and its value there.
fn symbolic_at(f: &RatFun, at: &BigRational) -> (BigRational, BigRational) {
    let point = HashMap::from([("s".to_string(), at.clone())]);
    let d = f.derivative("s").unwrap();
    (f.eval(&point).unwrap(), d.eval(&point).unwrap())
}

/// The derivative carried by a reported value, as its exact text.
fn exact_derivative(v: &Value) -> String {
    v.derivative.as_ref().unwrap().exact.clone().unwrap()
}

#[test]
fn exact_dual_tangents_equal_the_derivatives_of_the_symbolic_solve() {
    let mut checked = 0;
    for (text, key, points) in cases() {
        let symbolic = scene_with(text, key, "\"s\"");
        for model in [Model::Newton, Model::Poisson] {
            let mut a = assemble::<RatFun>(&symbolic).unwrap();
            let (o, _) = a.solve(model).unwrap();
            let formulas = outputs(&o);
            let norms: Vec<RatFun> = a
                .impact
                .frames()
                .iter()
                .map(|f| f.norm2[0].clone())
                .collect();
            for at in &points {
                let s = q(at);
                let what = format!("{key} = {at}, {}", model.name());
                let scene = seeded_at(text, key, at);
                let mut d = assemble::<Dual<Exact>>(&scene).unwrap();
                let (od, _) = d.solve(model).unwrap();
                let duals = outputs(&od);
                assert_eq!(duals.len(), formulas.len());
                for ((name, f), (_, x)) in formulas.iter().zip(&duals) {
                    let (value, derivative) = symbolic_at(f, &s);
                    assert_eq!(x.value.to_big_rational(), value, "{what}: {name}");
                    assert_eq!(
                        x.tangent.to_big_rational(),
                        derivative,
                        "{what}: d{name}/ds"
                    );
                    checked += 1;
                }
                // The report, in N s: P_i = P̂_i |n_i|, so dP_i/ds = (P̂_i′ + P̂_i r_i′/(2 r_i)) √r_i
                // with r_i = |n_i|² — a surd, exactly; the twist and energies as rationals.
                let report = run::<Dual<Exact>>(&scene, Some(&[model])).unwrap().report;
                let m = &report.models[0];
                for (i, r) in norms.iter().enumerate() {
                    let (p, dp) = symbolic_at(&o.impulses_hat[i], &s);
                    let (r, dr) = symbolic_at(r, &s);
                    let two = BigRational::from_integer(2.into());
                    let coeff = dp + p * dr / (two * &r);
                    assert_eq!(
                        exact_derivative(&m.impulses[i]),
                        format_surd(&coeff, &r),
                        "{what}: dP{}/ds",
                        i + 1
                    );
                }
                let twist = m.angular_velocity.iter().chain(&m.velocity);
                let at = 6 + 3 * norms.len() + 2 + o.constraint_impulses.len();
                for (v, (name, f)) in twist.zip(&formulas[formulas.len() - at..]) {
                    let (_, derivative) = symbolic_at(f, &s);
                    assert_eq!(
                        exact_derivative(v),
                        format_rational(&derivative),
                        "{what}: {name}"
                    );
                }
                for (v, f) in [&m.lost_velocity_energy, &m.kinetic_energy_loss]
                    .into_iter()
                    .zip([&o.lost_velocity_energy, &o.kinetic_energy_loss])
                {
                    let (_, derivative) = symbolic_at(f, &s);
                    assert_eq!(exact_derivative(v), format_rational(&derivative), "{what}");
                }
            }
        }
    }
    assert!(checked > 1000, "{checked} derivatives compared");
}

#[test]
fn the_unilateral_law_differentiates_its_active_branch() {
    // Example 3 pitching at ω = 1 > 105/218: under the unilateral law contact 2 separates
    // (P_2 = 0) and contact 1 alone obeys the law, so near this point every output is that of
    // the bar on contact 1 alone — whose exact derivatives the symbolic solve gives.
    let pitching = EXAMPLE_3.replace("[0, 0, 0.4]", "[0, 0, 1]");
    let alone = pitching[..pitching.rfind("[[contact]]").unwrap()].to_string();
    for key in ["body.mass", "contact[0].k", "body.velocity[0]"] {
        let mut a = assemble::<RatFun>(&scene_with(&alone, key, "\"s\"")).unwrap();
        let (one, _) = a.solve(Model::Newton).unwrap();
        let at = scene_value(&alone, key);
        let s = q(&at);
        let mut scene = seeded_at(&pitching, key, &at);
        scene.law = inertance::Law::Unilateral;
        let mut d = assemble::<Dual<Exact>>(&scene).unwrap();
        let both = d.solve_law(Model::Newton, scene.law).unwrap();
        let o = &both.outcome;
        assert!(both.activity.is_some(), "{key}");
        assert_eq!(
            inertance::impact::unilateral::active(o),
            [true, false],
            "{key}"
        );
        assert_eq!(
            o.impulses_hat[1],
            Dual::constant(Exact::zero()),
            "{key}: P2 ≡ 0"
        );
        let (p, dp) = symbolic_at(&one.impulses_hat[0], &s);
        assert_eq!(
            (
                o.impulses_hat[0].value.to_big_rational(),
                o.impulses_hat[0].tangent.to_big_rational()
            ),
            (p, dp),
            "{key}"
        );
        for (x, f) in o.velocity.0.iter().zip(one.velocity.0.iter()) {
            let (v, dv) = symbolic_at(f, &s);
            assert_eq!(
                (x.value.to_big_rational(), x.tangent.to_big_rational()),
                (v, dv),
                "{key}: twist"
            );
        }
        for (x, f) in [
            (&o.lost_velocity_energy, &one.lost_velocity_energy),
            (&o.kinetic_energy_loss, &one.kinetic_energy_loss),
        ] {
            let (v, dv) = symbolic_at(f, &s);
            assert_eq!(
                (x.value.to_big_rational(), x.tangent.to_big_rational()),
                (v, dv),
                "{key}: energies"
            );
        }
    }
}

/// max |x| over a list (0 for none).
fn largest<'a>(xs: impl IntoIterator<Item = &'a Exact>) -> f64 {
    xs.into_iter().fold(0f64, |m, x| m.max(x.to_f64().abs()))
}

/// The largest relative rate max|ẋ|/max|x| of a list of dual numbers (0 when it is all zero).
fn rate<'a>(xs: impl IntoIterator<Item = &'a Dual<Exact>> + Clone) -> f64 {
    let value = largest(xs.clone().into_iter().map(|x| &x.value));
    let tangent = largest(xs.into_iter().map(|x| &x.tangent));
    if tangent == 0.0 { 0.0 } else { tangent / value }
}

/// The bound on a `Dual<f64>` derivative's error, per group of outputs (impulses, twist,
/// energies), from the exact seeded scene:
///
/// **C·cond₂(G)·ε·(max|ẏ| + ρ·max|y|)** with C = 8(N + 4), as for the values
/// (`tests/hard_cases.rs`). A dual number a + a′ε is the 2×2 matrix [[a, 0], [a′, a]], so the
/// dual solve of G P = b is the f64 solve of the block lower-triangular system
/// [[G, 0], [Ġ, G]] [P; Ṗ] = [b; ḃ], whose inverse is [[G⁻¹, 0], [−G⁻¹ĠG⁻¹, G⁻¹]]: Ṗ is
/// computed with the backward error of the value's solve (‖ΔG‖ ≲ N ε ‖G‖, same pivots) on
/// G Ṗ = ḃ − Ġ P, plus the value's own error propagated through G⁻¹Ġ. First-order
/// perturbation theory gives ≲ C·cond(G)·ε·(‖Ṗ‖ + (‖Ġ‖/‖G‖ + ‖ḃ‖/‖b‖)·‖P‖). ρ is the largest
/// relative rate of the data the outputs are computed from — G, the contact velocities
/// before impact, the response screws W{E_j} (which give the twist), the 1 + k_i of both laws
/// and T⁰ — so ρ·|y| bounds the tangent's terms that cancel where |ẏ| is small. The twist and
/// energies come from the impulses through sums of N + 4 products, inside the same C. The
/// energies' scale is max(T⁰, |E_p|, |ΔE_c|) as for their values.
fn f64_bound(scene: &Scene) -> impl Fn(&[f64], &[f64]) -> f64 {
    let a = assemble::<Dual<Exact>>(scene).unwrap();
    let impact = &a.impact;
    let n = impact.contacts();
    let g: Vec<f64> = impact.g_hat().iter().map(|x| x.value.to_f64()).collect();
    let cond = condition_number(&g, n);
    let one = Dual::constant(Exact::from_integer(1.into()));
    let contacts = a.problem().contacts();
    let k_newton: Vec<Dual<Exact>> = contacts.iter().map(|c| c.k_newton.clone() + &one).collect();
    let k_poisson: Vec<Dual<Exact>> = contacts
        .iter()
        .map(|c| c.k_poisson.clone() + &one)
        .collect();
    let rho = [
        rate(impact.g_hat()),
        rate(impact.before_hat().iter().flatten()),
        rate(impact.responses().iter().flat_map(|r| r.0.iter())),
        rate(&k_newton),
        rate(&k_poisson),
        rate([impact.kinetic_before()]),
    ]
    .into_iter()
    .fold(0f64, f64::max);
    let c = 8.0 * (n as f64 + 4.0);
    move |values: &[f64], derivatives: &[f64]| {
        let max = |xs: &[f64]| xs.iter().fold(0f64, |m, x| m.max(x.abs()));
        c * cond * f64::EPSILON * (max(derivatives) + rho * max(values))
    }
}

/// A report's groups of outputs per model: (values, derivatives) of the impulses in N s, the
/// twist after impact, the energies.
fn groups(report: &Report, kinetic: f64) -> Vec<Vec<(f64, f64)>> {
    let pair = |v: &Value| (v.f64, v.derivative.as_ref().unwrap().f64);
    let mut out = Vec::new();
    for m in &report.models {
        out.push(m.impulses.iter().map(pair).collect());
        out.push(
            m.angular_velocity
                .iter()
                .chain(&m.velocity)
                .map(pair)
                .collect(),
        );
        let mut e: Vec<(f64, f64)> = [&m.lost_velocity_energy, &m.kinetic_energy_loss]
            .into_iter()
            .map(pair)
            .collect();
        e.push((kinetic, 0.0)); // T⁰ sets the energies' scale (its derivative is in ρ)
        out.push(e);
    }
    out
}

#[test]
fn f64_dual_tangents_are_within_the_conditioning_bound() {
    let mut worst: f64 = 0.0;
    for (text, key, points) in cases() {
        for at in points {
            let scene = seeded_at(text, key, at);
            let exact = run::<Dual<Exact>>(&scene, None).unwrap().report;
            let float = run::<Dual<f64>>(&scene, None).unwrap().report;
            assert_eq!(float.scalar, "dual");
            let kinetic = assemble::<Exact>(&scene)
                .unwrap()
                .impact
                .kinetic_before()
                .to_f64();
            let bound = f64_bound(&scene);
            for (e, f) in groups(&exact, kinetic).iter().zip(groups(&float, kinetic)) {
                let values: Vec<f64> = e.iter().map(|x| x.0).collect();
                let derivatives: Vec<f64> = e.iter().map(|x| x.1).collect();
                let tolerance = bound(&values, &derivatives);
                for ((_, d), (_, df)) in e.iter().zip(&f) {
                    let error = (df - d).abs();
                    assert!(
                        error <= tolerance,
                        "{key} = {at}: derivative {df} against exact {d}: error {error:e} > {tolerance:e}"
                    );
                    if tolerance > 0.0 {
                        worst = worst.max(error / tolerance);
                    }
                }
            }
        }
    }
    eprintln!("largest error / bound of the f64 derivatives: {worst:.3}");
}

/// The rod striking a rough floor (`derivations/friction-rod.md`), cos θ = 3/5: with μ = 1/2
/// its slip stops in compression and sticks, with μ = 1/4 it stops and reverses.
fn rod(mu: &str) -> String {
    format!(
        r#"
name = "rod on a rough floor"
[body]
mass = 1
inertia = ["1/300", "1/3", "1/3"]
velocity = ["-13/20", "-4/5", 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [-1, 0, 0]
normal = ["-4/5", "-3/5", 0]
tangent = ["3/5", "-4/5", 0]
k = 0.5
mu = {mu}
[solve]
models = ["newton", "poisson"]
"#
    )
}

/// A frictional law's outputs, named: the normal, compression and tangential impulses, the
/// contact velocity and the twist after impact, E_p, ΔE_c, the friction dissipation.
fn friction_outputs(report: &Report, law: Restitution) -> (Vec<(String, Value)>, String) {
    let f = report.friction.iter().find(|f| f.law == law).unwrap();
    let mut v = Vec::new();
    for (i, c) in f.contacts.iter().enumerate() {
        v.push((format!("P{}", i + 1), c.normal_impulse.clone()));
        v.push((format!("Pc{}", i + 1), c.compression_impulse.clone()));
        for (a, x) in c.tangential_impulse.iter().enumerate() {
            v.push((format!("Pt{}[{a}]", i + 1), x.clone()));
        }
        for (a, x) in c.velocity.iter().enumerate() {
            v.push((format!("v{}[{a}]", i + 1), x.clone()));
        }
    }
    for (a, x) in f.angular_velocity.iter().chain(&f.velocity).enumerate() {
        v.push((format!("twist[{a}]"), x.clone()));
    }
    v.push(("Ep".into(), f.lost_velocity_energy.clone()));
    v.push(("dEc".into(), f.kinetic_energy_loss.clone()));
    v.push(("Ef".into(), f.friction_dissipation.clone()));
    let history = f
        .contacts
        .iter()
        .map(|c| format!("{:?}", c.history))
        .collect::<Vec<_>>()
        .join(" ");
    (v, history)
}

fn rational(v: &Value) -> BigRational {
    q(v.exact.as_ref().unwrap())
}

#[test]
fn planar_friction_tangents_are_the_limit_of_exact_central_differences() {
    // Exact central differences D(h) = (y(x + h) − y(x − h))/2h have no rounding error, so h
    // can be tiny, and a truncation error c·h² + O(h⁴) with c = y‴/6 on a branch where y is
    // smooth (the same events in the same modes on [x − h, x + h], checked). If the dual
    // tangent t is y′, then |D(h/2) − t| ≈ |D(h) − t|/4 (asserted ≤ 0.3×) and |D(h) − t| ≤ h
    // relative to 1 + |t| (so long as |y‴| ≤ 6/h); a t off by δ would leave both errors near
    // δ, so it passes only if δ ≲ |c|h²/16 ≈ 10⁻¹³|c|.
    let h = BigRational::new(1.into(), (1i64 << 20).into());
    let mut converged = 0;
    for mu in ["0.5", "0.25"] {
        let text = rod(mu);
        for key in [
            "contact[0].mu",
            "body.velocity[0]",
            "body.angular_velocity[2]",
            "contact[0].k",
            "body.inertia[2]",
            "contact[0].point[1]",
        ] {
            let x = q(&scene_value(&text, key));
            let base = scene_with(&text, key, &format!("\"{x}\""));
            let at = |dx: &BigRational| {
                let s = scene_with(&text, key, &format!("\"{}\"", &x + dx));
                run::<Exact>(&s, None).unwrap().report
            };
            let dual = run::<Dual<Exact>>(&seeded(&base, key).unwrap(), None)
                .unwrap()
                .report;
            let h2 = &h / BigRational::from_integer(2.into());
            let reports = [at(&-h.clone()), at(&h), at(&-h2.clone()), at(&h2)];
            for law in [Restitution::Newton, Restitution::Poisson] {
                let what = format!("μ = {mu}, {key}, {law}");
                let (tangents, history) = friction_outputs(&dual, law);
                let sides: Vec<(Vec<(String, Value)>, String)> =
                    reports.iter().map(|r| friction_outputs(r, law)).collect();
                for (_, hist) in &sides {
                    assert_eq!(*hist, history, "{what}: the same modes at x ± h");
                }
                for (k, (name, t)) in tangents.iter().enumerate() {
                    let t = q(t.derivative.as_ref().unwrap().exact.as_ref().unwrap());
                    let diff = |a: usize, b: usize, step: &BigRational| {
                        (rational(&sides[b].0[k].1) - rational(&sides[a].0[k].1))
                            / (step * BigRational::from_integer(2.into()))
                    };
                    let e1 = (diff(0, 1, &h) - &t).abs();
                    let e2 = (diff(2, 3, &h2) - &t).abs();
                    let scale = BigRational::from_integer(1.into()) + t.abs();
                    assert!(
                        e1 <= &h * &scale,
                        "{what}: d{name}: central difference {e1} from the tangent {t}"
                    );
                    if !e1.is_zero() {
                        assert!(
                            e2.clone() * BigRational::from_integer(10.into())
                                <= e1.clone() * BigRational::from_integer(3.into()),
                            "{what}: d{name}: the central differences do not converge to {t} at the rate h² ({e1} → {e2})"
                        );
                        converged += 1;
                    }
                }
            }
        }
    }
    assert!(converged > 50, "{converged} derivatives seen converging");
}

/// The text of the number at `key` in `text`.
fn scene_value(text: &str, key: &str) -> String {
    let scene = Scene::parse(text, "scene.toml").unwrap();
    let key = match key.strip_suffix(".k") {
        Some(c) => format!("{c}.k_newton"),
        None => key.to_string(),
    };
    let (_, n) = scene.numbers().find(|(k, _)| *k == key).unwrap();
    n.text.clone()
}

#[test]
fn energetic_friction_tangents_match_f64_central_differences() {
    // The energetic law stops where a quadratic vanishes (√ in the stop), so it runs in
    // Dual<f64> only. Central differences in f64 with h = 10⁻⁵: truncation h²|y‴|/6 and
    // rounding ≈ ε|y|/h ≈ 2·10⁻¹¹|y|; for these O(1) scenes |y‴| ≲ 10⁴ (the closed forms of
    // friction-rod.md are rational functions with O(1) coefficients), so the difference is
    // within 10⁻⁶ of the scale 1 + |y| + |y′|.
    let hf = 1e-5;
    for mu in ["0.5", "0.25"] {
        let text = rod(mu).replace(
            "models = [\"newton\", \"poisson\"]",
            "restitution = \"energetic\"",
        );
        for key in ["contact[0].mu", "body.velocity[0]", "contact[0].k"] {
            let x = parse_number(&scene_value(&text, key)).unwrap().approx;
            let at = |v: f64| {
                let s = scene_with(&text, key, &format!("{v:?}"));
                run::<f64>(&s, None).unwrap().report
            };
            let base = scene_with(&text, key, &format!("{x:?}"));
            let dual = run::<Dual<f64>>(&seeded(&base, key).unwrap(), None)
                .unwrap()
                .report;
            let (tangents, _) = friction_outputs(&dual, Restitution::Energetic);
            let (lo, _) = friction_outputs(&at(x - hf), Restitution::Energetic);
            let (hi, _) = friction_outputs(&at(x + hf), Restitution::Energetic);
            for (k, (name, t)) in tangents.iter().enumerate() {
                let d = t.derivative.as_ref().unwrap().f64;
                let fd = (hi[k].1.f64 - lo[k].1.f64) / (2.0 * hf);
                let scale = 1.0 + t.f64.abs() + d.abs();
                assert!(
                    (fd - d).abs() <= 1e-6 * scale,
                    "μ = {mu}, {key}: d{name} = {d} against central difference {fd}"
                );
            }
        }
    }
}

/// Two contacts at the centre of mass, the second normal tilting by x: singular at x = 0
/// (the same point and normal), compressive (`ok`) for x ∈ [0.05, 0.2] — by hand,
/// P_2 = (1 + k)v_x⁰/x·|n_2|, P_1 = (1 + k)(−v_y⁰) − (1 + k)v_x⁰/x.
const TILTING: &str = r#"
name = "two contacts at one point, the second normal tilting"
[body]
mass = 1
inertia = [1, 1, 1]
velocity = [0.05, -2, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [0, 0, 0]
normal = [0, -1, 0]
k = 0.5
[[contact]]
point = [0, 0, 0]
normal = [0, -1, 0]
k = 0.5
"#;

/// A scratch directory, removed when the test ends.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!(
            "inertance-sensitivity-{}-{name}",
            std::process::id()
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Scratch(dir)
    }

    fn file(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn inertance(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .unwrap()
}

/// The CSV as a header and rows.
fn read_csv(path: &std::path::Path) -> (Vec<String>, Vec<Vec<String>>) {
    let mut r = csv::Reader::from_path(path).unwrap();
    let header = r.headers().unwrap().iter().map(String::from).collect();
    let rows = r
        .records()
        .map(|rec| rec.unwrap().iter().map(String::from).collect())
        .collect();
    (header, rows)
}

/// The report's outputs of one model in the sweep's column order (P1 … PN, vC, ω, Ep, dEc).
fn sweep_order(report: &Report, model: usize) -> Vec<Value> {
    let m = &report.models[model];
    let mut v: Vec<Value> = m.impulses.clone();
    v.extend(m.velocity.iter().cloned());
    v.extend(m.angular_velocity.iter().cloned());
    v.push(m.lost_velocity_energy.clone());
    v.push(m.kinetic_energy_loss.clone());
    v
}

#[test]
fn sweep_writes_derivative_columns_equal_to_the_library_run() {
    let dir = Scratch::new("cli");
    let scene = dir.file("tilting.toml", TILTING);
    let key = "contact[1].normal[0]";
    let vary = format!("{key}=0:0.2:5");
    let names = [
        "P1", "P2", "vCx", "vCy", "vCz", "wx", "wy", "wz", "Ep", "dEc",
    ];
    for exact in [false, true] {
        let out = dir.0.join(format!("out-{exact}.csv"));
        let plot = dir.0.join(format!("out-{exact}.svg"));
        let mut args = vec![
            "sweep",
            scene.to_str().unwrap(),
            "--vary",
            &vary,
            "--sensitivity",
            "--out",
            out.to_str().unwrap(),
            "--plot",
            plot.to_str().unwrap(),
        ];
        if exact {
            args.push("--exact");
        }
        let run_cli = inertance(&args);
        assert!(
            run_cli.status.success(),
            "{}",
            String::from_utf8_lossy(&run_cli.stderr)
        );
        let (header, rows) = read_csv(&out);
        let col = |name: &str| {
            header
                .iter()
                .position(|h| h == name)
                .unwrap_or_else(|| panic!("no column {name} in {header:?}"))
        };
        assert_eq!(header.last().unwrap(), "status");
        let derivative_columns = header.iter().filter(|h| h.starts_with("d(")).count();
        assert_eq!(
            derivative_columns,
            2 * (names.len() + if exact { 4 } else { 0 })
        );
        // x = 0: singular — no outputs, no derivatives.
        assert_eq!(rows[0][col("status")], "singular");
        for (h, cell) in header.iter().zip(&rows[0]) {
            if h.starts_with("d(") || h.starts_with("newton_") || h.starts_with("poisson_") {
                assert!(cell.is_empty(), "{h} at the singular point: {cell}");
            }
        }
        for (p, row) in rows.iter().enumerate().skip(1) {
            assert_eq!(row[col("status")], "ok", "point {p}");
            let x = format!("{}/20", p);
            let seeded = seeded_at(TILTING, key, &x);
            let library = if exact {
                run::<Dual<Exact>>(&seeded, None)
            } else {
                run::<Dual<f64>>(&seeded, None)
            }
            .unwrap()
            .report;
            for (m, model) in ["newton", "poisson"].iter().enumerate() {
                let values = sweep_order(&library, m);
                for (name, v) in names.iter().zip(&values) {
                    let d = v.derivative.as_ref().unwrap();
                    let cell = &row[col(&format!("d({model}_{name})/d({key})"))];
                    assert_eq!(
                        cell.parse::<f64>().unwrap(),
                        d.f64,
                        "point {p}: {model} {name}"
                    );
                    if exact && ["P1", "P2", "Ep", "dEc"].contains(name) {
                        let cell = &row[col(&format!("d({model}_{name})/d({key})_exact"))];
                        assert_eq!(cell, d.exact.as_ref().unwrap(), "point {p}: {model} {name}");
                    }
                }
            }
            // By hand: P_1 = 3 − 0.075/x and P_2 = 0.075·√(1 + x²)/x, so dP_1/dx = 0.075/x²
            // and dP_2/dx = 0.075·(1/√(1 + x²) − √(1 + x²)/x²).
            let x = p as f64 / 20.0;
            let cell = |name: &str| -> f64 {
                row[col(&format!("d(newton_{name})/d({key})"))]
                    .parse()
                    .unwrap()
            };
            let w = (1.0 + x * x).sqrt();
            for (got, want) in [
                (cell("P1"), 0.075 / (x * x)),
                (cell("P2"), 0.075 * (1.0 / w - w / (x * x))),
            ] {
                assert!(
                    (got - want).abs() <= 1e-9 * want.abs(),
                    "point {p}: {got} ≠ {want}"
                );
            }
        }
        let svg = std::fs::read_to_string(&plot).unwrap();
        assert!(
            svg.contains(&format!("newton d(P1)/d({key})")),
            "the plot draws the derivatives"
        );
    }

    // Without the flag the columns are those of an ordinary sweep.
    let plain = dir.0.join("plain.csv");
    let status = inertance(&[
        "sweep",
        scene.to_str().unwrap(),
        "--vary",
        &vary,
        "--out",
        plain.to_str().unwrap(),
    ]);
    assert!(status.status.success());
    let (header, _) = read_csv(&plain);
    assert!(header.iter().all(|h| !h.starts_with("d(")), "{header:?}");
    assert_eq!(header.len(), 2 + 2 * names.len() + 1);
}

#[test]
fn a_spatial_frictional_scene_is_refused_before_the_sweep() {
    let dir = Scratch::new("spatial");
    // Example 3 with friction and a spin about x: the motion leaves the plane.
    let text = EXAMPLE_3
        .replace(
            "angular_velocity = [0, 0, 0.4]",
            "angular_velocity = [0.3, 0, 0.4]",
        )
        .replace("k = 0.2", "k = 0.2\nmu = 0.5");
    let scene = dir.file("spatial.toml", &text);
    let out = dir.0.join("out.csv");
    let args = [
        "sweep",
        scene.to_str().unwrap(),
        "--vary",
        "contact[1].mu=0.1:0.5:3",
        "--out",
        out.to_str().unwrap(),
    ];
    assert!(inertance(&args).status.success(), "the f64 sweep runs");
    let mut with = args.to_vec();
    with.push("--sensitivity");
    let refused = inertance(&with);
    assert_eq!(refused.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&refused.stderr);
    assert!(
        stderr.contains("not planar") && stderr.contains("finite differences"),
        "{stderr}"
    );
    assert!(!out.with_extension("csv.tmp").exists());
}
