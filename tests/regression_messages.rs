//! Regressions from a fuzz of the CLI (issue 16): messages that named no key, no value, a wrong
//! reason, or a wrong line.

mod common;

use common::SceneFile;
use std::process::{Command, Output};

const SCENE: &str = include_str!("../examples/planar-bar.toml");

/// Run `inertance args[0] FILE args[1..]` on `text` written to a scratch file.
fn run(args: &[&str], text: &str, name: &str) -> Output {
    SceneFile::new(&format!("msg-{name}"), text).run(args)
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn an_empty_key_is_named() {
    let out = run(&["solve"], &format!("\"\" = -1\n{SCENE}"), "empty-key");
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("key `\"\"` = -1: unknown key"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_skew_tangent_shows_its_value_in_solve_and_analyze() {
    let text = SCENE.replace("tangent = [0, 1, 0]", "tangent = [1, 1, 0]");
    for cmd in ["solve", "analyze"] {
        let out = run(&[cmd], &text, cmd);
        assert_eq!(out.status.code(), Some(2), "{cmd}");
        assert!(
            stderr(&out).contains("contact[1].tangent` = [1, 1, 0]"),
            "{cmd}: {}",
            stderr(&out)
        );
    }
}

#[test]
fn a_400_digit_mass_is_exact_in_exact_mode_and_out_of_range_in_f64() {
    let big = "9".repeat(400);
    let text = SCENE.replace("mass = 1", &format!("mass = \"{big}\""));
    let out = run(&["solve", "--exact"], &text, "big-exact");
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        !String::from_utf8_lossy(&out.stdout).contains("inf"),
        "never ≈ inf for an exact value"
    );
    // In f64 the body's G — 1/m = 10⁻⁴⁰⁰ beside lever terms of order 1, cond₂ ≈ 10⁴⁰⁰ — is
    // singular to working precision (status 3, `--exact` decides); before the mass unit took
    // the moments into account (`scene::scale`), the moments left f64 and the scene was refused
    // as out of range (status 2).
    let out = run(&["solve"], &text, "big-f64");
    assert_eq!(out.status.code(), Some(3), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("singular to working precision") && stderr(&out).contains("--exact"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_number_too_small_to_read_is_not_called_non_positive() {
    let text = SCENE.replace("mass = 1", "mass = \"2^-99999999\"");
    let out = run(&["solve", "--exact"], &text, "tiny");
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("cannot be read") && !err.contains("must be positive"),
        "{err}"
    );
}

#[test]
fn check_names_the_line_of_a_case_whose_scene_is_missing() {
    let dir = std::env::temp_dir().join(format!("inertance-msg-{}-check", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("a.md"),
        "# t\n\n```expect c1 nosuch\nnewton.P1 = 1\n```\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["check", dir.to_str().unwrap()])
        .output()
        .unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(
        stderr(&out).contains("a.md:3: case `c1` runs scene `nosuch`"),
        "{}",
        stderr(&out)
    );
}
