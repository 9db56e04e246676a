//! Issue 28, item 2: one parameter, two units.
//!
//! A scene with `phi = "20 deg"` read `--param phi=45` (and Python's `Scene.with_values`) as 45
//! **radians** — P1 = 4.687785 with no note — while `sweep --vary phi=45:46:2` (and
//! `solve_batch`) read 45 **degrees**. One rule now holds wherever a parameter is set
//! ([`inertance::scene::set_value`] on `params.NAME`): a bare number given to a parameter
//! written in degrees is a number of degrees; a value that carries its unit is taken as
//! written; one in radians (it mentions `pi`) is refused with the fix. A parameter written in
//! radians keeps reading radians. (Python's entry points: `python/tests/test_units.py`.)
//!
//! The reference is the tilted box's closed form (derivations/modelled-tilted-box.md),
//! P1 = 51/(2(45 cos²θ − 24 cos θ sin θ + 20)): 51/61 at 45°, exactly.

mod common;

use common::SceneFile;
use inertance::scene::{Scene, parse_document, set_value};

const TILTED: &str = include_str!("../examples/tilted-box.toml");

fn p1(theta: f64) -> f64 {
    let (c, s) = (theta.cos(), theta.sin());
    51.0 / (2.0 * (45.0 * c * c - 24.0 * c * s + 20.0))
}

fn stdout(out: &std::process::Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

#[test]
fn a_bare_number_given_to_a_parameter_in_degrees_is_degrees_in_the_cli() {
    let s = SceneFile::new("units-cli", TILTED);
    let with_unit = stdout(&s.run(&["solve", "--json", "--param", "theta=45 deg"]));
    for bare in ["theta=45", "theta=45.0", "theta=90/2", "theta= 45 "] {
        assert_eq!(
            stdout(&s.run(&["solve", "--json", "--param", bare])),
            with_unit,
            "{bare}"
        );
    }
    let exact: serde_json::Value = serde_json::from_str(&stdout(
        &s.run(&["solve", "--exact", "--json", "--param", "theta=45"]),
    ))
    .expect("JSON");
    assert_eq!(exact["models"]["newton"]["impulses"][0], "51/61");
    // derive with the parameter set: the numbers of 45°, not of 45 rad.
    let j: serde_json::Value = serde_json::from_str(&with_unit).expect("JSON");
    let p = j["models"]["newton"]["impulses"][0]
        .as_f64()
        .expect("number");
    assert!((p - 51.0 / 61.0).abs() < 1e-15, "{p}");
}

#[test]
fn sweep_and_param_read_the_same_degrees() {
    let s = SceneFile::new("units-sweep", TILTED);
    let csv = s.sweep(&["--vary", "theta=45:46:2"]);
    for (r, degrees) in ["45", "46"].into_iter().enumerate() {
        let j: serde_json::Value = serde_json::from_str(&stdout(&s.run(&[
            "solve",
            "--json",
            "--param",
            &format!("theta={degrees}"),
        ])))
        .expect("JSON");
        let solve = j["models"]["newton"]["impulses"][0]
            .as_f64()
            .expect("number");
        let swept: f64 = csv.cell(r, "newton_P1").parse().expect("number");
        assert_eq!(swept, solve, "θ = {degrees}");
        let expected = p1(degrees.parse::<f64>().expect("number").to_radians());
        assert!(
            (swept - expected).abs() <= 1e-14 * expected,
            "{swept} vs {expected}"
        );
    }
}

#[test]
fn a_value_in_radians_for_a_parameter_in_degrees_is_refused_with_the_fix() {
    let s = SceneFile::new("units-radians", TILTED);
    let out = s.run(&["solve", "--param", "theta=pi/4"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("params.theta")
            && err.contains("`pi/4` is in radians")
            && err.contains("`45 deg`"),
        "{err}"
    );
}

#[test]
fn a_parameter_in_radians_keeps_reading_radians() {
    let radians = TILTED.replace("theta = \"30 deg\"", "theta = \"pi/6\"");
    let s = SceneFile::new("units-keep-radians", &radians);
    let j: serde_json::Value = serde_json::from_str(&stdout(&s.run(&[
        "solve",
        "--json",
        "--param",
        "theta=0.5",
    ])))
    .expect("JSON");
    let p = j["models"]["newton"]["impulses"][0]
        .as_f64()
        .expect("number");
    assert!((p - p1(0.5)).abs() <= 1e-14 * p1(0.5), "{p}");
}

#[test]
fn every_entry_point_shares_one_rule_in_the_library() {
    let read = |value: &str| {
        let mut doc = parse_document(TILTED, "tilted.toml").expect("TOML");
        set_value(&mut doc, "params.theta", value).expect("set");
        Scene::from_document(&doc, "tilted.toml").expect("a scene")
    };
    let values =
        |s: &Scene| -> Vec<(String, f64)> { s.numbers().map(|(k, n)| (k, n.approx)).collect() };
    let with_unit = values(&read("\"45 deg\""));
    assert_eq!(values(&read("45")), with_unit);
    assert_eq!(values(&read("\"90/2\"")), with_unit);
    // A parameter that names one in degrees is in degrees too.
    let chained = TILTED.replace(
        "theta = \"30 deg\"",
        "alpha = \"15 deg\"\ntheta = \"2*alpha\"",
    );
    let mut doc = parse_document(&chained, "chained.toml").expect("TOML");
    set_value(&mut doc, "params.theta", "45").expect("set");
    let chained = Scene::from_document(&doc, "chained.toml").expect("a scene");
    assert_eq!(values(&chained), with_unit);
}
