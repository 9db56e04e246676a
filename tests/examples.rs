//! The programs in `examples/` run and print what they promise. Each example's `run` is
//! compiled into this test from its source file and called with a buffer for stdout, so the
//! test needs no example binary built beforehand.

use std::process::Command;

#[allow(dead_code)]
#[path = "../examples/coefficient_sweep.rs"]
mod coefficient_sweep;
#[allow(dead_code)] // its `main` is the program's, not the test's
#[path = "../examples/planar_bar.rs"]
mod planar_bar;
#[allow(dead_code)]
#[path = "../examples/scene_report.rs"]
mod scene_report;

/// The text an example's `run` prints.
fn printed(run: impl FnOnce(&mut Vec<u8>) -> Result<(), Box<dyn std::error::Error>>) -> String {
    let mut out = Vec::new();
    run(&mut out).expect("the example runs");
    String::from_utf8(out).expect("UTF-8 output")
}

#[test]
fn planar_bar_prints_the_papers_example_3_exactly() {
    let out = printed(planar_bar::run);
    // §7, Example 3: P₁ = 3.6556, P₂ = 0.1978 (Newton); P₁ = 3.64, P₂ = 0.24 (Poisson).
    for want in [
        "P1 = 3.655555556 N s   (exact 329/90)",
        "P2 = 0.197777778 N s   (exact 89/450)",
        "P1 = 3.640000000 N s   (exact 91/25)",
        "E_p = 413791/45000 J",
        "Δ = det G = 3",
    ] {
        assert!(out.contains(want), "missing {want:?} in\n{out}");
    }
}

#[test]
fn coefficient_sweep_has_newton_equal_poisson_where_the_coefficients_are_equal() {
    let out = printed(coefficient_sweep::run);
    let rows: Vec<Vec<f64>> = out
        .lines()
        .skip(1)
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 11);
    for r in &rows {
        // eq. 55: Newton = Poisson exactly when k₂ = k₁ = 0.3, and only then (g₁₂ ≠ 0).
        let equal = (r[1] - r[2]).abs() < 1e-9;
        assert_eq!(equal, (r[0] - 0.3).abs() < 1e-9, "row {r:?}");
    }
}

#[test]
fn scene_report_prints_the_json_report_of_the_cli() {
    let out = printed(|o| scene_report::run(&["--exact".to_string()], o));
    let json: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    let cli = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["solve", "examples/planar-bar.toml", "--exact", "--json"])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let cli: serde_json::Value = serde_json::from_slice(&cli.stdout).expect("CLI JSON");
    assert_eq!(json, cli);
    assert_eq!(json["models"]["newton"]["impulses"][0], "329/90");
}
