//! Regression: exact scaling (`scene::scale`) covered only rational free-body scenes without a
//! `[surface]`, and refused what it could not hold after scaling back even when that was only
//! Δ = det G. Example 3 with a body of 10⁻³⁰⁰ kg was refused ("the scene's numbers span more
//! than f64 can hold") although its impulses, twist and energies are representable — only
//! Δ ~ m⁻² = 10⁶⁰⁰ is not; the same scene with a point at −√2, and Example 2's ellipsoid from
//! its surface with a tiny mass, were not scaled at all and refused.
//!
//! Now Δ and the inertances beyond f64 are reported from their scaled value and power of two
//! (decimal text; a JSON string), irrational numbers are scaled as expressions and surfaces
//! as f(2^b x′, 2^b y′, 2^b z′); only a physical output beyond f64 is refused, by name.

mod common;

use common::SceneFile;
use inertance::analysis::accuracy::{Bounds, Conditioning};
use inertance::impact::solve::{Impact, Outcome};
use inertance::report::{Report, Value};
use inertance::scalar::dd::DoubleDouble;
use inertance::scene::Scene;
use inertance::scene::pipeline::run;
use inertance::{Exact, Model, Scalar};
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

/// Example 3 (`derivations/`) with its body's mass and moments given as `mass` and `j`.
fn example_3(mass: &str, j: [&str; 3], point: &str) -> String {
    format!(
        r#"
[body]
mass = "{mass}"
inertia = ["{}", "{}", "{}"]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, "{point}", 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
"#,
        j[0], j[1], j[2]
    )
}

fn tiny() -> Scene {
    let text = example_3("1e-300", ["12e-300", "1.6e-300", "12e-300"], "-2");
    Scene::parse(&text, "tiny.toml").unwrap()
}

/// A reported value as an exact rational: its exact text, or its f64.
fn exact(v: &Value) -> BigRational {
    match &v.exact {
        Some(t) => inertance::number::parse_number(t).unwrap().exact.unwrap(),
        None => BigRational::from_float(v.f64).unwrap(),
    }
}

fn f(q: &BigRational) -> f64 {
    ToPrimitive::to_f64(q).unwrap()
}

/// ‖a − b‖₂ of two lists of reported values, exactly then rounded.
fn distance(a: &[Value], b: &[Value]) -> f64 {
    let mut s = BigRational::zero();
    for (x, y) in a.iter().zip(b) {
        let d = exact(x) - exact(y);
        s += &d * &d;
    }
    f(&s).sqrt()
}

/// ‖(δω, δv_C)‖_M = (m|δv_C|² + Σ J_k δω_k²)^½ for a body in principal axes.
fn energy_norm(scene: &Scene, a: &Report, b: &Report, model: usize) -> f64 {
    let m = scene.mass.exact.clone().unwrap();
    let (ra, rb) = (&a.models[model], &b.models[model]);
    let mut s = BigRational::zero();
    for k in 0..3 {
        let dv = exact(&ra.velocity[k]) - exact(&rb.velocity[k]);
        let dw = exact(&ra.angular_velocity[k]) - exact(&rb.angular_velocity[k]);
        let j = scene.inertia[k].exact.clone().unwrap();
        s += &m * &dv * &dv + &j * &dw * &dw;
    }
    f(&s).sqrt()
}

/// The tiny body solved in `T` meets the accuracy contract (`analysis::accuracy`, bounds in
/// the scene's own units by [`Bounds::of`]) against the exact solve; `report_rounding` is
/// the relative rounding of the report's f64 values (0 unless `T` is wider than f64).
fn meets_the_contract<T: Scalar>(report_rounding: f64) {
    let scene = tiny();
    let problem = scene.problem::<Exact>().unwrap();
    let mut impact = Impact::assemble(&problem).unwrap();
    let cond = Conditioning::of(&mut impact).unwrap();
    let exact_report = run::<Exact>(&scene, None).unwrap().report;
    let float = run::<T>(&scene, None)
        .unwrap_or_else(|e| panic!("{}: {e}", T::NAME))
        .report;
    let n = 2.0;
    for (i, model) in [Model::Newton, Model::Poisson].into_iter().enumerate() {
        let mut out = Outcome::default();
        impact.solve(model, &mut out).unwrap();
        let b = Bounds::of(&impact, &cond, model, &out, T::epsilon_f64());
        let (e, x) = (&exact_report.models[i], &float.models[i]);
        let size = |v: &[Value]| v.iter().map(|x| x.f64 * x.f64).sum::<f64>().sqrt();
        let what = format!("{} {model}", T::NAME);
        let dp = distance(&x.impulses, &e.impulses);
        assert!(
            dp <= b.impulses + report_rounding * size(&e.impulses),
            "{what}: ‖δP‖ = {dp:e} > {:e}",
            b.impulses
        );
        let dv = energy_norm(&scene, &float, &exact_report, i);
        // The report's v_C and ω rounded to f64: at most report_rounding·V in the M-norm.
        let speed = b.v0 + b.dv;
        assert!(
            dv <= b.twist + 2.0 * report_rounding * speed,
            "{what}: ‖δv‖_M = {dv:e} > {:e}",
            b.twist
        );
        let e_p = f(&exact(&e.lost_velocity_energy));
        let d_ep = f(&(exact(&x.lost_velocity_energy) - exact(&e.lost_velocity_energy)).abs());
        let eps = T::epsilon_f64();
        assert!(
            d_ep <= b.dv * b.twist + n * eps * e_p + report_rounding * e_p,
            "{what}: |δE_p| = {d_ep:e}"
        );
        let d_ec = f(&(exact(&x.kinetic_energy_loss) - exact(&e.kinetic_energy_loss)).abs());
        let loss = f(&exact(&e.kinetic_energy_loss));
        assert!(
            d_ec <= 3.0 * speed * b.twist + n * eps * speed * speed + report_rounding * loss,
            "{what}: |δΔE_c| = {d_ec:e}"
        );
    }
}

#[test]
fn a_tiny_body_is_solved_in_every_float_type_within_the_contract() {
    meets_the_contract::<f32>(0.0);
    meets_the_contract::<f64>(0.0);
    // A double-double report holds each value rounded to f64 (half an ulp, 2⁻⁵³ relative).
    meets_the_contract::<DoubleDouble>(f64::EPSILON / 2.0);
}

#[test]
fn delta_beyond_f64_is_printed_from_its_scaled_value() {
    let scene = tiny();
    let exact_det = exact(&run::<Exact>(&scene, None).unwrap().report.det);
    let float = run::<f64>(&scene, None).unwrap().report;
    let w = float.det.wide.expect("Δ ≈ 3·10⁶⁰⁰ is beyond f64");
    assert_eq!(float.det.f64, f64::INFINITY, "what f64 holds of it");
    // The bound on Δ: Δ = det G and the contract's G is exact for wrenches perturbed by
    // ‖δE_j‖ ≤ η_E ‖E_j‖, η_E = (3ℓ + 16N) ε ≤ c ε/(2√N), so |δg_ij| ≤ 2η_E (g_ii g_jj)^½,
    // ‖δG‖₂ ≤ 2η_E Σ g_ii ≤ 2N η_E λ_max and |δΔ/Δ| = |tr(G⁻¹ δG)| ≤ N κ ‖δG‖₂/λ_max
    // ≤ N^{3/2} κ c ε; plus N ε for the product of the pivots and the division by the |n_i|².
    let problem = scene.problem::<Exact>().unwrap();
    let mut impact = Impact::assemble(&problem).unwrap();
    let cond = Conditioning::of(&mut impact).unwrap();
    let n: f64 = 2.0;
    let bound = n.powf(1.5) * cond.cond * cond.constant() * f64::EPSILON + 2.0 * n * f64::EPSILON;
    // The JSON's 17 significant digits add at most 5·10⁻¹⁷ relative.
    let json = float.to_json();
    let text = json["det"]
        .as_str()
        .expect("a string: no JSON number holds 10⁶⁰⁰");
    assert_eq!(text, w.decimal(17));
    let printed = inertance::number::parse_number(text)
        .unwrap()
        .exact
        .unwrap();
    let relative = f(&((printed - &exact_det) / &exact_det).abs());
    assert!(relative <= bound + 5e-17, "{relative:e} > {bound:e}");
    // Example 3's Δ = 3 kg⁻² with m = 1 kg; with m = 10⁻³⁰⁰ kg, G = G₁·10³⁰⁰: Δ = 3·10⁶⁰⁰.
    assert_eq!(
        exact_det,
        BigRational::from_integer(3.into())
            * num_traits::pow(BigRational::from_integer(10.into()), 600)
    );
    assert!(float.to_table().contains("Δ = det G = 3.000000e600\n"));
}

#[test]
fn the_cli_reports_delta_as_a_string_and_refuses_only_physical_outputs() {
    let text = example_3("1e-300", ["12e-300", "1.6e-300", "12e-300"], "-2");
    let out = SceneFile::new("tiny-mass", &text).run(&["solve", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let stdout = String::from_utf8(out.stdout).unwrap();
    let json: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert!(json["det"].as_str().is_some_and(|s| s.ends_with("e600")));
    for bad in ["null", "NaN", "Infinity", "\"inf\""] {
        assert!(!stdout.contains(bad), "{bad} in {stdout}");
    }
    assert!(
        json["inertance"][0][0].is_number(),
        "1.3·10³⁰⁰ kg⁻¹ is an f64"
    );
    // `analyze` (in the scene's units) takes Δ from the scaled scene.
    let out = SceneFile::new("tiny-mass-analyze", &text).run(&["analyze", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let det = json["det"].as_str().unwrap().parse::<f64>().unwrap();
    assert_eq!(det, f64::INFINITY, "beyond f64: a string");
    let det = inertance::number::parse_number(json["det"].as_str().unwrap()).unwrap();
    let three = BigRational::from_integer(3.into());
    let relative = f(&(det.exact.unwrap()
        / num_traits::pow(BigRational::from_integer(10.into()), 600)
        / &three
        - BigRational::from_integer(1.into()))
    .abs());
    assert!(relative < 1e-14, "Δ = 3·10⁶⁰⁰ to {relative:e}");
    // The same body moving at 10³⁰⁰ m/s: its energies (10³⁰⁰ J) are held, Δ is not.
    let fast = text.replace(
        "velocity = [3, 2, 0]",
        "velocity = [\"3e300\", \"2e300\", 0]",
    );
    let out = SceneFile::new("tiny-mass-fast", &fast).run(&["solve"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // A body of 1 kg at 10³⁰⁰ m/s: its energies (10⁶⁰⁰ J) are not: refused, by name.
    let heavy = fast.replace("\"1e-300\"", "1").replace("e-300", "");
    let out = SceneFile::new("heavy-fast", &heavy).run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("energies are beyond the range of f64") && err.contains("body.velocity["),
        "{err}"
    );
}

/// `scene` at scale 1 and with its mass scaled by 2^a and lengths by 2^b (exact powers of
/// two), solved in `T`: every output is the scale-1 output times 2 to its dimension, exactly.
fn scales_exactly<T: Scalar>(one: &str, scaled: &str, a: i64, b: i64) {
    let solve = |text: &str| {
        let scene = Scene::parse(text, "scaled.toml").unwrap();
        run::<T>(&scene, None)
            .unwrap_or_else(|e| panic!("{}: {e}", T::NAME))
            .report
    };
    let (r1, r2) = (solve(one), solve(scaled));
    let value = |v: &Value| match v.wide {
        Some(w) => (w.mantissa, w.exponent),
        None => (v.f64, 0),
    };
    let times = |x: &Value, k: i64, y: &Value| {
        let what = format!("{}: {} · 2^{k} ≠ {}", T::NAME, x.f64, y.f64);
        if x.wide.is_none() && y.wide.is_none() {
            // What the report does: one multiplication by 2^k (exact unless subnormal).
            assert_eq!(y.f64, ldexp(x.f64, k), "{what}");
            return;
        }
        // m2·2^e2 = m1·2^(e1 + k), compared as exact rationals.
        let q = |(m, e): (f64, i64)| {
            let p = num_traits::pow(
                BigRational::from_integer(2.into()),
                e.unsigned_abs() as usize,
            );
            let m = BigRational::from_float(m).unwrap();
            if e >= 0 { m * p } else { m / p }
        };
        let (m1, e1) = value(x);
        assert_eq!(q(value(y)), q((m1, e1 + k)), "{what}");
    };
    let n = r1.inertance.len() as i64;
    times(&r1.det, -a * n, &r2.det);
    for (x, y) in r1
        .inertance
        .iter()
        .flatten()
        .zip(r2.inertance.iter().flatten())
    {
        times(x, -a, y);
    }
    for (m1, m2) in r1.models.iter().zip(&r2.models) {
        for (x, y) in m1.impulses.iter().zip(&m2.impulses) {
            times(x, a + b, y);
        }
        for (x, y) in m1.velocity.iter().zip(&m2.velocity) {
            times(x, b, y);
        }
        for (x, y) in m1.angular_velocity.iter().zip(&m2.angular_velocity) {
            times(x, 0, y);
        }
        times(
            &m1.lost_velocity_energy,
            a + 2 * b,
            &m2.lost_velocity_energy,
        );
        times(&m1.kinetic_energy_loss, a + 2 * b, &m2.kinetic_energy_loss);
    }
}

/// x·2^k in f64, by steps that are exact until the last.
fn ldexp(x: f64, k: i64) -> f64 {
    let (mut y, mut k) = (x, k);
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        y *= 2f64.powi(step as i32);
        k -= step;
    }
    y
}

/// `2^k` times `x`, as scene text.
fn p2(k: i64, x: &str) -> String {
    format!("2^({k})*{x}")
}

#[test]
fn an_irrational_scene_scales_by_powers_of_two_exactly() {
    let one = example_3("1", ["12", "1.6", "12"], "-sqrt(2)");
    for a in [-1000, 1000] {
        let scaled = example_3(
            &p2(a, "1"),
            [&p2(a, "12"), &p2(a, "1.6"), &p2(a, "12")],
            "-sqrt(2)",
        );
        scales_exactly::<f32>(&one, &scaled, a, 0);
        scales_exactly::<f64>(&one, &scaled, a, 0);
        scales_exactly::<DoubleDouble>(&one, &scaled, a, 0);
    }
}

/// Example 2's ellipsoid from its surface (`derivations/example-2-ellipsoid.md`), with mass
/// 10·2^a and lengths 2^b: semi-axes 2^b·(1, 2, 3), moments 2^(a+2b)·(26, 20, 10), v_C
/// 2^b·(5, 7, 4).
fn ellipsoid(a: i64, b: i64) -> String {
    let l = |x: &str| p2(b, x);
    let axis2 = |k: &str| format!("({k}*2^({}))", 2 * b);
    format!(
        r#"
[surface]
f = "x^2/{} + y^2/{} + z^2/{} - 1"
[body]
mass = "{}"
inertia = ["{}", "{}", "{}"]
velocity = ["{}", "{}", "{}"]
angular_velocity = [3, 1, 2]
[[contact]]
point = ["{}", "{}", 0]
tangent = [-1, 4, 0]
k = 1
[[contact]]
point = [0, "{}", "{}"]
tangent = [-1, 0, 0]
k = 1
[solve]
models = ["newton", "poisson"]
"#,
        axis2("1"),
        axis2("4"),
        axis2("9"),
        p2(a, "10"),
        p2(a + 2 * b, "26"),
        p2(a + 2 * b, "20"),
        p2(a + 2 * b, "10"),
        l("5"),
        l("7"),
        l("4"),
        l("2/sqrt(5)"),
        l("2/sqrt(5)"),
        l("6*sqrt(3/31)"),
        l("6/sqrt(31)"),
    )
}

#[test]
fn a_surface_scene_scales_by_powers_of_two_exactly() {
    let one = ellipsoid(0, 0);
    // (a, b) = (−1000, 0): the issue's tiny ellipsoid; (∓1000, ±1000): semi-axes of 10^±301 m
    // whose surface's coefficients (2^∓2000) no f64 holds in metres.
    for (a, b) in [(-1000, 0), (1000, 0), (-1000, 1000), (1000, -1000)] {
        let scaled = ellipsoid(a, b);
        // Not f32: its rounding of 2/√5 misses the surface by more than the on-surface test's
        // 10⁻⁹ (as at scale 1).
        scales_exactly::<f64>(&one, &scaled, a, b);
        scales_exactly::<DoubleDouble>(&one, &scaled, a, b);
    }
}

#[test]
fn a_point_off_a_scaled_surface_is_refused_as_written() {
    // The on-surface test runs in the scaled units: the message still shows the point as written.
    let text = ellipsoid(-1000, 0).replace("\"2^(0)*2/sqrt(5)\", \"2^(0)*2/sqrt(5)\"", "1, 1");
    let out = SceneFile::new("off-surface", &text).run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("contact[0].point` = [1, 1, 0]: not on the surface"),
        "{err}"
    );
}
