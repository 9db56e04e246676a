//! The `inertance` binary end to end: reports, and bad input that names the file, the key
//! and the value, exits with status 2, and never panics.

use std::path::PathBuf;
use std::process::{Command, Output};

const GOOD: &str = r#"
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
[solve]
models = ["newton", "poisson"]
"#;

/// A scene file in a fresh temporary directory (removed when the test ends).
struct Scene {
    dir: PathBuf,
    path: PathBuf,
}

impl Scene {
    fn new(name: &str, text: &str) -> Scene {
        let dir = std::env::temp_dir().join(format!("inertance-cli-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.toml");
        std::fs::write(&path, text).unwrap();
        Scene { dir, path }
    }
}

impl Drop for Scene {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

fn inertance(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .unwrap()
}

fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Run `solve` on `GOOD` with `from` replaced by `to`; expect status 2 and a message that
/// contains each of `needles` (the key, the value, what is wrong).
fn rejects(name: &str, from: &str, to: &str, needles: &[&str]) {
    assert!(GOOD.contains(from), "bad test: {from}");
    let scene = Scene::new(name, &GOOD.replacen(from, to, 1));
    for exact in [false, true] {
        let path = scene.path.to_str().unwrap();
        let out = if exact {
            inertance(&["solve", path, "--exact"])
        } else {
            inertance(&["solve", path])
        };
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        assert!(out.stdout.is_empty(), "{name}: nothing on stdout");
        assert!(err.contains(path), "{name}: names the file: {err}");
        for n in needles {
            assert!(err.contains(n), "{name}: expected `{n}` in: {err}");
        }
        assert!(!err.contains("panicked"), "{name}: {err}");
    }
}

#[test]
fn exact_json_report_has_the_contract_keys_and_exact_values() {
    let scene = Scene::new("json", GOOD);
    let v = json(&inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--exact",
        "--json",
    ]));
    assert_eq!(v["scalar"], "exact");
    assert_eq!(v["effects"], serde_json::json!(["newton", "poisson"]));
    assert_eq!(
        v["inertance"],
        serde_json::json!([["4/3", "1/3"], ["1/3", "7/3"]])
    );
    assert_eq!(v["det"], "3");
    let p = &v["models"]["poisson"];
    // Poisson: P^c solves G P^c = v⁰_x = (19/5, 7/5): P^c = (14/5, 1/5), P = (1.3, 1.2)·P^c.
    assert_eq!(
        p["compression_impulses"],
        serde_json::json!(["14/5", "1/5"])
    );
    assert_eq!(p["impulses"], serde_json::json!(["91/25", "6/25"]));
    assert_eq!(p["velocity"], serde_json::json!(["-22/25", "2", "0"]));
    assert_eq!(
        p["angular_velocity"],
        serde_json::json!(["0", "0", "-19/150"])
    );
    let c = &p["contacts"][0];
    assert_eq!(c["velocity_before"], serde_json::json!(["19/5", "2", "0"]));
    assert_eq!(c["angle_before_deg"], 0.0);
    for key in ["lost_velocity_energy", "kinetic_energy_loss"] {
        assert!(p[key].is_string(), "{key}");
    }
    let n = &v["models"]["newton"];
    assert!(n.get("compression_impulses").is_none());
    // Newton: v_ix = −k_i v_ix⁰.
    assert_eq!(n["contacts"][0]["velocity_after"][0], "-57/50");
    assert_eq!(n["contacts"][1]["velocity_after"][0], "-7/25");
}

#[test]
fn f64_json_report_uses_numbers_and_model_flag_selects() {
    let scene = Scene::new("f64", GOOD);
    let v = json(&inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--json",
        "--model",
        "newton",
    ]));
    assert_eq!(v["scalar"], "f64");
    assert_eq!(v["effects"], serde_json::json!(["newton"]));
    assert!(v["models"].get("poisson").is_none());
    let e = v["models"]["newton"]["lost_velocity_energy"]
        .as_f64()
        .unwrap();
    assert!((e - 9.195356).abs() < 5e-7);
}

#[test]
fn table_output_names_models_and_units() {
    let scene = Scene::new("table", GOOD);
    let out = inertance(&["solve", scene.path.to_str().unwrap()]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    for s in [
        "newton",
        "poisson",
        "P1 [N s]",
        "E_p [J]",
        "ΔE_c [J]",
        "9.195356",
        "4.976533",
    ] {
        assert!(text.contains(s), "missing {s} in:\n{text}");
    }
}

#[test]
fn non_unit_normal_is_exact_with_surd_impulse() {
    // One contact, normal (4, 1, 0) through C: g = 17/m for the hatted axis, P = P̂·√17.
    let text = r#"
[body]
mass = 2
inertia = [1, 1, 1]
velocity = [1, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [0, 0, 0]
normal = [4, 1, 0]
k = 0.5
"#;
    let scene = Scene::new("surd", text);
    let v = json(&inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--exact",
        "--json",
        "--model",
        "newton",
    ]));
    let n = &v["models"]["newton"];
    // v_n⁰ = 4/√17 ⇒ P = m(1+k) v_n⁰ = 2·(3/2)·4/√17 = 12/√17 = 12/17·√17.
    assert_eq!(n["impulses"][0], "12/17*sqrt(17)");
    assert_eq!(n["impulses_per_normal"][0], "12/17");
    // v_C = v⁰ − P̂ n/m = (1,0,0) − (6/17)(4,1,0).
    assert_eq!(n["velocity"], serde_json::json!(["-7/17", "-6/17", "0"]));
    assert_eq!(n["contacts"][0]["velocity_before"][0], "4/17*sqrt(17)");
    // E_p = ½ m |Δv|² = (6/17)²·17 = 36/17; ΔE_c = 1 − (49 + 36)/289 = 12/17.
    assert_eq!(n["lost_velocity_energy"], "36/17");
    assert_eq!(n["kinetic_energy_loss"], "12/17");
}

#[test]
fn decimal_input_is_read_exactly() {
    let scene = Scene::new("decimal", &GOOD.replace("k = 0.3", "k = 0.1"));
    let v = json(&inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--exact",
        "--json",
    ]));
    // Newton: v_1x = −0.1 · 19/5 exactly.
    assert_eq!(
        v["models"]["newton"]["contacts"][0]["velocity_after"][0],
        "-19/50"
    );
}

#[test]
fn singular_scene_is_reported_not_divided() {
    let text = GOOD.replace("point = [0, 4, 0]", "point = [0, -2, 0]");
    let scene = Scene::new("singular", &text);
    for flag in ["--exact", "--json"] {
        let out = inertance(&["solve", scene.path.to_str().unwrap(), flag]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{err}");
        assert!(err.contains("singular") && err.contains("Δ = 0"), "{err}");
    }
}

#[test]
fn missing_key() {
    rejects("missing", "mass = 1\n", "", &["body.mass", "missing"]);
}

#[test]
fn unknown_key() {
    rejects(
        "unknown",
        "k = 0.3",
        "k = 0.3\nfriction = 0.5",
        &["contact[0].friction", "unknown key"],
    );
}

#[test]
fn wrong_type() {
    rejects(
        "type",
        "mass = 1",
        "mass = \"heavy\"",
        &["body.mass", "heavy"],
    );
    rejects(
        "triple",
        "velocity = [3, 2, 0]",
        "velocity = [3, 2]",
        &["body.velocity", "three numbers"],
    );
}

#[test]
fn non_positive_mass_and_inertia() {
    rejects(
        "mass0",
        "mass = 1",
        "mass = 0",
        &["body.mass", "= 0", "positive"],
    );
    rejects(
        "inertia",
        "inertia = [12, 1.6, 12]",
        "inertia = [12, -1.6, 12]",
        &["body.inertia[1]", "-1.6", "positive"],
    );
}

#[test]
fn zero_normal() {
    rejects(
        "normal",
        "normal = [1, 0, 0]",
        "normal = [0, 0.0, \"0/5\"]",
        &["contact[0].normal", "zero vector"],
    );
}

#[test]
fn nan_and_infinity() {
    rejects(
        "nan",
        "mass = 1",
        "mass = nan",
        &["body.mass", "nan", "not finite"],
    );
    rejects(
        "inf",
        "velocity = [3, 2, 0]",
        "velocity = [3, inf, 0]",
        &["body.velocity[1]", "inf"],
    );
    rejects("div0", "mass = 1", "mass = \"1/0\"", &["body.mass", "1/0"]);
}

#[test]
fn coefficient_out_of_range() {
    rejects(
        "k",
        "k = 0.2",
        "k = 1.5",
        &["contact[1].k", "1.5", "[0, 1]"],
    );
    rejects(
        "kn",
        "k = 0.2",
        "k_newton = -0.1\nk_poisson = 0.2",
        &["contact[1].k_newton", "-0.1"],
    );
    rejects(
        "khalf",
        "k = 0.2",
        "k_newton = 0.1",
        &["contact[1].k_poisson", "missing"],
    );
}

#[test]
fn bad_toml_and_bad_model() {
    rejects("toml", "mass = 1", "mass = = 1", &["not valid TOML"]);
    rejects(
        "model",
        "\"newton\", \"poisson\"",
        "\"newton\", \"energetic\"",
        &["solve.models", "energetic"],
    );
}

#[test]
fn skew_tangent() {
    rejects(
        "tangent",
        "tangent = [0, 1, 0]",
        "tangent = [1, 1, 0]",
        &["contact[1].tangent", "perpendicular"],
    );
}

#[test]
fn unreadable_file() {
    let out = inertance(&["solve", "/nonexistent/scene.toml"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("/nonexistent/scene.toml") && err.contains("cannot read"),
        "{err}"
    );
}

/// `--exact` runs radicals exactly (m = √2: P_i scale with m, so they carry √2), and refuses
/// a number with no exact form (cos 20° is no radical), naming the key and the value.
#[test]
fn exact_mode_takes_radicals_and_refuses_transcendental_input() {
    let scene = Scene::new("radical", &GOOD.replace("mass = 1", "mass = \"sqrt(2)\""));
    let path = scene.path.to_str().unwrap();
    let j = json(&inertance(&["solve", path, "--exact", "--json"]));
    assert_eq!(j["scalar"], "symbolic");
    let p1 = j["models"]["newton"]["impulses"][0].as_str().unwrap();
    assert!(p1.contains("sqrt(2)"), "{p1}");
    let floats = json(&inertance(&["solve", path, "--json"]));
    let exact_p1 = inertance::scalar::symbolic::symbolic(p1, &[]).unwrap();
    let f = floats["models"]["newton"]["impulses"][0].as_f64().unwrap();
    assert!((inertance::scalar::Scalar::to_f64(&exact_p1) - f).abs() <= 1e-12 * f.abs());

    let scene = Scene::new(
        "transcendental",
        &GOOD.replace("mass = 1", "mass = \"cos(20 deg)\""),
    );
    let path = scene.path.to_str().unwrap();
    let out = inertance(&["solve", path, "--exact"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("body.mass") && err.contains("cos(20 deg)") && err.contains("no exact"),
        "{err}"
    );
    assert!(inertance(&["solve", path]).status.success());
}

#[test]
fn bad_flag_is_status_2() {
    let out = inertance(&["solve"]);
    assert_eq!(out.status.code(), Some(2));
    let out = inertance(&["frobnicate"]);
    assert_eq!(out.status.code(), Some(2));
}

const CONSTRAINED: &str = r#"
[body]
mass = 10
inertia = ["10/3", "10/3", "10/3"]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 1]
[[contact]]
point = [0, "-1/3", 0]
normal = [1, 0, 0]
k = 0
[[contact]]
point = [0, "1/3", 0]
normal = [1, 0, 0]
k = 0
[constraints]
free = [[0, 0, 1, -1, 0, 0], [0, 0, 0, 1, 0, 0]]
blocked = [[0, 1, 0, 0, 0, 0], [0, 0, 1, -1, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0]]
"#;

/// Solve `CONSTRAINED` with `from` replaced by `to`; expect status 2 and every needle.
fn rejects_constrained(name: &str, from: &str, to: &str, needles: &[&str]) {
    assert!(CONSTRAINED.contains(from), "bad test: {from}");
    let scene = Scene::new(name, &CONSTRAINED.replacen(from, to, 1));
    let out = inertance(&["solve", scene.path.to_str().unwrap(), "--exact"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{name}: {err}");
    for n in needles {
        assert!(err.contains(n), "{name}: expected `{n}` in: {err}");
    }
}

#[test]
fn constrained_scene_reports_constraint_impulses() {
    let scene = Scene::new("constrained", CONSTRAINED);
    let v = json(&inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--exact",
        "--json",
    ]));
    assert_eq!(
        v["effects"],
        serde_json::json!(["constraints", "newton", "poisson"])
    );
    // Example 6, case (i): P1 = 5, P2 = −5, E_p = ΔE_c = 5/3; the paper's {q} = 0.
    let n = &v["models"]["newton"];
    assert_eq!(n["impulses"], serde_json::json!(["5", "-5"]));
    assert_eq!(
        n["constraint_impulses"],
        serde_json::json!(["0", "0", "0", "0"])
    );
    assert_eq!(n["lost_velocity_energy"], "5/3");
    assert_eq!(
        v["constraints"]["reduced_mass"],
        serde_json::json!([["40/3", "-10"], ["-10", "10"]])
    );
    assert_eq!(v["constraints"]["blocked_derived"], false);
}

#[test]
fn bad_constraints_name_the_offending_screw() {
    rejects_constrained(
        "dependent-free",
        "free = [[0, 0, 1, -1, 0, 0], [0, 0, 0, 1, 0, 0]]",
        "free = [[0, 0, 1, -1, 0, 0], [0, 0, 2, -2, 0, 0]]",
        &["constraints.free[1]", "combination"],
    );
    rejects_constrained(
        "reciprocal",
        "[0, 0, 0, 0, 1, 0]]",
        "[0, 0, 0, 0, 0, 1]]",
        &[
            "constraints.blocked[3]",
            "not reciprocal",
            "constraints.free",
        ],
    );
    rejects_constrained(
        "dimension",
        ", [0, 0, 0, 0, 1, 0]]",
        "]",
        &["constraints.blocked", "≠ 6"],
    );
    rejects_constrained(
        "velocity",
        "velocity = [0, 0, 0]",
        "velocity = [0, 1, 0]",
        &["body.velocity", "not allowed by the constraints"],
    );
    rejects_constrained(
        "zero-screw",
        "free = [[0, 0, 1, -1, 0, 0],",
        "free = [[0, 0, 0, 0, 0, 0],",
        &["constraints.free[0]", "must not be zero"],
    );
    rejects_constrained(
        "short-screw",
        "free = [[0, 0, 1, -1, 0, 0],",
        "free = [[0, 0, 1, -1, 0],",
        &["constraints.free[0]", "six numbers"],
    );
    rejects_constrained(
        "both-forms",
        "[constraints]\n",
        "[[constraints.joint]]\nkind = \"prismatic\"\naxis = [1, 0, 0]\n[constraints]\n",
        &["not both"],
    );
}

#[test]
fn bad_joints_are_named() {
    let joints = |body: &str| {
        CONSTRAINED
            .split("[constraints]")
            .next()
            .unwrap()
            .to_string()
            + body
    };
    let cases: [(&str, &str, &[&str]); 4] = [
        (
            "kind",
            "[[constraints.joint]]\nkind = \"hinge\"\naxis = [0, 0, 1]\n",
            &["constraints.joint[0].kind", "hinge", "revolute"],
        ),
        (
            "missing",
            "[[constraints.joint]]\nkind = \"revolute\"\naxis = [0, 0, 1]\n",
            &["constraints.joint[0].point", "missing"],
        ),
        (
            "zero-axis",
            "[[constraints.joint]]\nkind = \"prismatic\"\naxis = [0, 0, 0]\n",
            &["constraints.joint[0].axis", "zero"],
        ),
        (
            "repeated",
            "[[constraints.joint]]\nkind = \"prismatic\"\naxis = [1, 0, 0]\n[[constraints.joint]]\nkind = \"prismatic\"\naxis = [2, 0, 0]\n",
            &["constraints.joint[1]", "already given"],
        ),
    ];
    for (name, body, needles) in cases {
        let scene = Scene::new(&format!("joint-{name}"), &joints(body));
        let out = inertance(&["solve", scene.path.to_str().unwrap()]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {err}");
        for n in needles {
            assert!(err.contains(n), "{name}: expected `{n}` in: {err}");
        }
    }
}

#[test]
fn analyze_json_has_the_contract_keys() {
    let scene = Scene::new(
        "analyze",
        &CONSTRAINED.replace("k = 0\n[constraints]", "k = 0.5\n[constraints]"),
    );
    let v = json(&inertance(&[
        "analyze",
        scene.path.to_str().unwrap(),
        "--exact",
        "--json",
    ]));
    let n = &v["models"]["newton"];
    assert_eq!(n["det"], "1/75");
    assert_eq!(n["rank"], 2);
    assert_eq!(n["augmented_rank"], 2);
    assert_eq!(n["classification"], "unique");
    // Example 6: A2 separates (v_2x⁰ = −1/3) and takes a tensile impulse.
    assert_eq!(n["admissible"][0]["approaching"], true);
    assert_eq!(n["admissible"][0]["compressive"], true);
    assert_eq!(n["admissible"][1]["approaching"], false);
    assert_eq!(n["admissible"][1]["compressive"], false);
    assert_eq!(n["energy_gain"], false);
    assert!(
        n["verdicts"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s.as_str().unwrap().contains("tensile"))
    );
    // k1 = 0 ≠ k2 = 0.5 and g12 ≠ 0.
    assert_eq!(v["newton_equals_poisson"]["equal"], false);
    assert!(v["newton_equals_poisson"]["reason"].is_string());
    assert!((v["condition_number"].as_f64().unwrap() - 3.0).abs() < 1e-12);
}

#[test]
fn analyze_classifies_singular_scenes_in_both_modes() {
    let text = GOOD.replace("point = [0, 4, 0]", "point = [0, -2, 0]");
    let scene = Scene::new("analyze-singular", &text);
    for exact in [true, false] {
        let mut args = vec!["analyze", scene.path.to_str().unwrap(), "--json"];
        if exact {
            args.push("--exact");
        }
        let v = json(&inertance(&args));
        // Coincident points with k1 = 0.3 ≠ k2 = 0.2: Newton incompatible, Poisson compatible.
        assert_eq!(
            v["models"]["newton"]["classification"], "singular-incompatible",
            "exact: {exact}"
        );
        assert_eq!(
            v["models"]["poisson"]["classification"], "singular-compatible",
            "exact: {exact}"
        );
        assert_eq!(v["models"]["newton"]["rank"], 1);
        assert_eq!(v["models"]["newton"]["augmented_rank"], 2);
        assert_eq!(v["coincident"][0]["contacts"], serde_json::json!([1, 2]));
        assert_eq!(v["coincident"][0]["same_axis"], true);
        let family = &v["models"]["poisson"]["family"];
        assert_eq!(family["null_space"].as_array().unwrap().len(), 1);
        assert_eq!(exact, v.get("rank_tolerance").is_none());
    }
    // `solve` on it points to `analyze`.
    let out = inertance(&["solve", scene.path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&out.stderr).contains("inertance analyze"));
}

#[test]
fn bench_quick_json_and_plot() {
    let dir = std::env::temp_dir().join(format!("inertance-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let plot = dir.join("bench.svg");
    let tables = dir.join("bench.md");
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args([
            "bench",
            "--quick",
            "--json",
            "--plot",
            plot.to_str().unwrap(),
            "--out",
            tables.to_str().unwrap(),
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let v = json(&out);
    let rows = v["scalars"].as_array().unwrap();
    let names: Vec<&str> = rows.iter().map(|r| r["scalar"].as_str().unwrap()).collect();
    assert_eq!(names, ["f32", "f64", "double-double", "exact"]);
    // The ladder: each type at least as accurate as the one before, exact exactly.
    let err = |i: usize| rows[i]["max_relative_error"].as_f64().unwrap();
    assert!(
        err(0) < 1e-4 && err(1) < 1e-12 && err(2) < 1e-28 && err(3) == 0.0,
        "{rows:?}"
    );
    assert!(v["scenes"]["hard_cases"].as_u64().unwrap() > 0);
    assert!(
        v["scaling"]
            .as_array()
            .unwrap()
            .iter()
            .any(|s| s["contacts"] == 24)
    );
    // The unilateral law on the same scenes, measured like the simultaneous solve.
    let uerr = |i: usize| {
        rows[i]["unilateral"]["max_relative_error"]
            .as_f64()
            .unwrap()
    };
    assert!(
        uerr(0) < 1e-4 && uerr(1) < 1e-12 && uerr(2) < 1e-28 && uerr(3) == 0.0,
        "{rows:?}"
    );
    for r in rows {
        assert!(r["unilateral"]["median_ns_per_solve"].as_f64().unwrap() > 0.0);
    }
    // The accuracy contract, per float type and output: the largest error/bound is reported,
    // and it is at most 1.
    let contract = v["contract"]["scalars"].as_array().unwrap();
    assert_eq!(contract.len(), 3, "{contract:?}");
    for r in contract {
        assert!(r["solves"].as_u64().unwrap() > 0, "{r}");
        let ratios = r["max_error_over_bound"].as_object().unwrap();
        assert_eq!(ratios.len(), 5, "{r}");
        for (output, x) in ratios {
            let ratio = x["ratio"].as_f64().unwrap();
            assert!(
                (0.0..=1.0).contains(&ratio),
                "{} {output}: {ratio}",
                r["scalar"]
            );
        }
    }
    // Against N: a free body's G is singular beyond six contacts, so the simultaneous solve
    // is impossible there. The landing scenes never jam: their normals all have n_z = 1, so no
    // impulses y ≥ 0 but 0 have B y = 0 (Σ y_i n_iz = Σ y_i), which infeasibility of an LCP
    // in a semidefinite G = Bᵀ W B would need (Farkas: y ≥ 0, G y ≤ 0 ⇒ yᵀ G y = 0 ⇒ B y = 0);
    // so the unilateral one answers for every N.
    for s in v["scaling"].as_array().unwrap() {
        let n = s["contacts"].as_u64().unwrap();
        let (sim, uni) = (
            &s["ns_per_solve_simultaneous"],
            &s["ns_per_solve_unilateral"],
        );
        for t in ["f32", "f64", "double-double"] {
            if n > 6 {
                assert_eq!(sim[t], "singular", "N = {n}, {t}");
            }
            assert!(uni[t].as_f64().unwrap() > 0.0, "N = {n}, {t}: {uni}");
        }
        let active = s["unilateral_active"]["newton"].as_u64().unwrap();
        assert!(active <= n, "N = {n}: {active} active");
    }
    assert!(std::fs::read_to_string(&plot).unwrap().starts_with("<svg"));
    // Issue 29's goals, each measured in this run: a value (or why not), its bound and
    // whether it is met; the sweeps' points against the paper form and against k.
    let goals = v["goals"].as_array().unwrap();
    assert_eq!(goals.len(), 7, "{goals:?}");
    for g in goals {
        let measured = g["measured"].as_f64();
        assert!(
            measured.is_some_and(|x| x > 0.0) || !g["note"].as_str().unwrap().is_empty(),
            "{g}"
        );
        assert_eq!(g["met"].is_boolean(), measured.is_some(), "{g}");
        assert!(
            ["at_most", "at_least"].contains(&g["bound"].as_str().unwrap()),
            "{g}"
        );
    }
    assert!(
        goals[2]["what"].as_str().unwrap().contains("pose angle"),
        "{goals:?}"
    );
    // --out: the tables, headed by when and under what load they were measured.
    let text = std::fs::read_to_string(&tables).unwrap();
    assert!(text.starts_with("Measured 20"), "{text}");
    assert!(text.contains("`inertance bench --quick`"), "{text}");
    assert!(text.contains("Issue 29's goals"), "{text}");
    assert!(!dir.join("bench.md.tmp").exists());
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bench_one_scene_reports_every_scalar() {
    let scene = Scene::new("bench-scene", GOOD);
    let v = json(&inertance(&[
        "bench",
        "--quick",
        "--json",
        "--scene",
        scene.path.to_str().unwrap(),
    ]));
    for s in ["f32", "f64", "double-double", "exact", "f64/impulses,twist"] {
        assert!(v["ns_per_solve"][s].as_f64().unwrap() > 0.0, "{s}");
    }
}

#[test]
fn bench_batch_times_the_batch_api_per_point() {
    let scene = Scene::new("bench-batch", GOOD);
    let file = scene.path.to_str().unwrap();
    let v = json(&inertance(&[
        "bench",
        "--quick",
        "--json",
        "--scene",
        file,
        "--batch",
        "contact[1].k=0:1:50",
    ]));
    assert_eq!(v["batch"]["points"], 50, "{v}");
    assert_eq!(v["batch"]["runs"], 3, "{v}");
    assert!(v["batch"]["threads"].as_u64().unwrap() >= 1, "{v}");
    assert!(v["batch"]["ns_per_point"].as_f64().unwrap() > 0.0, "{v}");
    assert!(v.get("ns_per_solve").is_none(), "{v}");
    // a path the scene lacks, or a value that makes it invalid: status 2, naming it
    for spec in ["contact[9].k=0:1:5", "contact[1].k=0:1.5:5"] {
        let out = inertance(&["bench", "--quick", "--scene", file, "--batch", spec]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{spec}: {err}");
        assert!(err.contains("contact["), "{spec}: {err}");
    }
    // --batch needs --scene
    let out = inertance(&["bench", "--batch", "contact[1].k=0:1:5"]);
    assert_eq!(out.status.code(), Some(2));
}

/// Paper-cuts of issue 14: a scene from standard input, degree hints, a 3×3 inertia refused
/// with what to write, and `check` on a folder with no derivations.
#[test]
fn scenes_from_stdin_and_hints_for_degrees_and_inertia_tensors() {
    use std::io::Write;
    let bar = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/planar-bar.toml"),
    )
    .unwrap();
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["solve", "-", "--exact", "--json"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(bar.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(j["models"]["newton"]["impulses"][1], "89/450");

    let dir = std::env::temp_dir().join(format!("inertance-papercuts-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let run = |name: &str, text: &str, args: &[&str]| {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        let mut all = vec![args[0], path.to_str().unwrap()];
        all.extend(&args[1..]);
        std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
            .args(&all)
            .output()
            .unwrap()
    };
    // sin(3) beside an angle in `deg`: a note (radians were read), the solve goes on.
    let mixed = bar.replace("0.4]", "\"sin(3)\"]").replace(
        "velocity = [3, 2, 0]",
        "velocity = [\"3*cos(0 deg)\", 2, 0]",
    );
    let out = run("mixed.toml", &mixed, &["solve"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(String::from_utf8_lossy(&out.stderr).contains("write `3 deg` if degrees were meant"));
    let out = run("deg.toml", &bar.replace("0.4]", "\"3°\"]"), &["solve"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("did you mean `3 deg`"));
    // A 3×3 tensor is read: here the principal moments written as a diagonal tensor (the same
    // answer), then with J_yz = 1, which couples the spin about z to the bar's axis y — a
    // different body, other impulses.
    let out = run(
        "tensor.toml",
        &bar.replace(
            "inertia = [12, 1.6, 12]",
            "inertia = [[12, 0, 0], [0, 1.6, 0], [0, 0, 12]]",
        ),
        &["solve", "--exact", "--json"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(t["models"], j["models"]);
    let out = run(
        "products.toml",
        &bar.replace(
            "inertia = [12, 1.6, 12]",
            "inertia = [[12, 0, 0], [0, 1.6, 1], [0, 1, 12]]",
        ),
        &["solve", "--exact", "--json"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let t: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_ne!(
        t["models"]["newton"]["impulses"],
        j["models"]["newton"]["impulses"]
    );
    let empty = dir.join("empty");
    std::fs::create_dir_all(&empty).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["check", empty.to_str().unwrap()])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no derivation files"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--outputs` (and `[solve] outputs`): the JSON holds the outputs asked for, each equal to
/// the full report's, and not the others; the table prints only their rows.
#[test]
fn outputs_flag_prints_only_the_outputs_asked_for() {
    let scene = Scene::new("outputs", GOOD);
    let path = scene.path.to_str().unwrap();
    for exact in [false, true] {
        let run = |extra: &[&str]| {
            let mut args = vec!["solve", path, "--json"];
            if exact {
                args.push("--exact");
            }
            args.extend_from_slice(extra);
            json(&inertance(&args))
        };
        let all = run(&[]);
        let some = run(&["--outputs", "impulses,twist"]);
        assert_eq!(some["outputs"], "impulses,twist");
        assert!(all.get("outputs").is_none());
        assert!(some.get("inertance_yx").is_none() && some["frames"][0].get("y").is_none());
        assert_eq!(some["inertance"], all["inertance"]);
        for m in ["newton", "poisson"] {
            let (s, a) = (&some["models"][m], &all["models"][m]);
            for key in ["impulses", "velocity", "angular_velocity", "admissible"] {
                assert_eq!(s[key], a[key], "{m} {key}");
            }
            for key in ["contacts", "lost_velocity_energy", "kinetic_energy_loss"] {
                assert!(s.get(key).is_none(), "{m} {key}");
            }
        }
        let normal = run(&["--outputs", "normal-velocities,energies"]);
        let (s, a) = (&normal["models"]["newton"], &all["models"]["newton"]);
        assert!(s.get("impulses").is_none() && s.get("velocity").is_none());
        assert_eq!(s["kinetic_energy_loss"], a["kinetic_energy_loss"]);
        assert_eq!(
            s["contacts"][1]["normal_velocity_after"],
            a["contacts"][1]["velocity_after"][0]
        );
    }
    let table = inertance(&["solve", path, "--outputs", "twist"]);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(text.contains("ωz [rad/s]") && !text.contains("P1 [N s]") && !text.contains("E_p"));
    // The scene key does the same.
    let keyed = Scene::new(
        "outputs-key",
        &GOOD.replace("[solve]\n", "[solve]\noutputs = [\"impulses\"]\n"),
    );
    let v = json(&inertance(&[
        "solve",
        keyed.path.to_str().unwrap(),
        "--json",
    ]));
    assert_eq!(v["outputs"], "impulses");
    assert!(v["models"]["newton"].get("velocity").is_none());
}

#[test]
fn an_unknown_output_is_refused_naming_it() {
    rejects(
        "outputs-key-bad",
        "[solve]\n",
        "[solve]\noutputs = [\"impulses\", \"angles\"]\n",
        &["solve.outputs", "angles", "unknown output"],
    );
    let scene = Scene::new("outputs-flag-bad", GOOD);
    let out = inertance(&[
        "solve",
        scene.path.to_str().unwrap(),
        "--outputs",
        "twist,speed",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--outputs") && err.contains("speed"), "{err}");
}
