//! Issue 28, item 10: under the unilateral law with both models, Newton's jam hid Poisson's
//! answer.
//!
//! A rod fitting exactly between two walls, driven into one at 2 m/s: Newton's law asks it to
//! bounce back into the other wall, which no P ≥ 0 can do (a jam, a verdict), while Poisson's
//! stops it — the solve exited 3 with no output at all. Each model's verdict is now reported on
//! its own, as the frictional solve does for its laws: the answering model is printed, the
//! other is named with its reason on stderr, in the table and in the JSON
//! (`models.newton = {"error", "status": "jammed"}`), and the exit status is 4 (some model has
//! no answer; guide/solving.md, "Exit status"). With one model, or when no model answers, it stays 3.
//!
//! Poisson's answer by hand (m = 1, v⁰ = 2 into wall 1, k = 1/2): compression stops the rod,
//! P1c = m v⁰ = 2, P2c = 0; expansion gives k P1c = 1 at wall 1, which drives the rod into
//! wall 2, whose impulse 1 keeps it at rest: P = (3, 1), v = 0, ΔE_c = ½ m v⁰² = 2 — the
//! momentum balance P1 − P2 = m v⁰ holds.

mod common;

use common::SceneFile;

const RODS_BETWEEN_WALLS: &str = include_str!("../examples/rod-between-walls.toml");

#[test]
fn poisson_answers_while_newton_is_jammed() {
    let s = SceneFile::new("jam-both", RODS_BETWEEN_WALLS);
    for exact in [false, true] {
        let mut args = vec!["solve", "--json"];
        if exact {
            args.push("--exact");
        }
        let out = s.run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(4), "{err}");
        assert!(
            err.contains("newton under the unilateral law has no answer") && err.contains("jam"),
            "{err}"
        );
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        assert_eq!(j["effects"], serde_json::json!(["unilateral", "poisson"]));
        assert_eq!(j["models"]["newton"]["status"], "jammed");
        assert!(
            j["models"]["newton"]["error"]
                .as_str()
                .is_some_and(|e| e.contains("jam"))
        );
        let p = &j["models"]["poisson"];
        let num = |v: &serde_json::Value| -> f64 {
            match v {
                serde_json::Value::String(s) => s.parse().expect("an integer"),
                v => v.as_f64().expect("a number"),
            }
        };
        let impulses: Vec<f64> = p["impulses"]
            .as_array()
            .expect("list")
            .iter()
            .map(num)
            .collect();
        assert_eq!(impulses, [3.0, 1.0], "exact = {exact}");
        let velocity: Vec<f64> = p["velocity"]
            .as_array()
            .expect("list")
            .iter()
            .map(num)
            .collect();
        assert_eq!(velocity, [0.0, 0.0, 0.0]);
        assert_eq!(num(&p["kinetic_energy_loss"]), 2.0);
    }
    // The table says it too.
    let out = s.run(&["solve"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(4));
    assert!(
        text.contains("newton: no answer: no admissible impulses"),
        "{text}"
    );
    assert!(text.contains("poisson"), "{text}");
}

#[test]
fn one_model_or_none_answering_is_still_status_3() {
    let s = SceneFile::new("jam-newton", RODS_BETWEEN_WALLS);
    let out = s.run(&["solve", "--model", "newton"]);
    assert_eq!(out.status.code(), Some(3));
    assert!(out.stdout.is_empty());
    let out = s.run(&["solve", "--model", "poisson", "--exact"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn a_sweep_fills_the_answering_model_and_marks_the_jammed_one() {
    let s = SceneFile::new("jam-sweep", RODS_BETWEEN_WALLS);
    let csv = s.sweep(&["--vary", "contact[0].k=0:0.5:2"]);
    // k₁ = 1/2: Newton jams, Poisson stops the rod with (3, 1).
    assert_eq!(csv.cell(1, "status"), "jammed");
    assert!(csv.cell(1, "newton_P1").is_empty());
    assert_eq!(csv.cell(1, "poisson_P1").parse::<f64>().ok(), Some(3.0));
    assert_eq!(csv.cell(1, "poisson_P2").parse::<f64>().ok(), Some(1.0));
}
