//! The LZB law end to end through the binary: `[solve] law = "lzb"` and `--law lzb` print the
//! library's numbers ([`inertance::scene::lzb::run_lzb`], whose physics `tests/lzb.rs` checks
//! against closed forms and an independent integration), and what the law does not support is
//! refused with the file, the key and the value (status 2), never answered under another name.

mod common;

use common::SceneFile as Scene;
use inertance::scene::Scene as Loaded;
use std::path::Path;

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

fn run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .unwrap()
}

/// The number printed after `v_C = [` on the line of `body`.
fn printed_vx(stdout: &str, body: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{body}:")))
        .unwrap_or_else(|| panic!("no line for {body} in\n{stdout}"));
    let at = line.find("v_C = [").expect("v_C") + "v_C = [".len();
    line[at..]
        .split(',')
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn the_cradle_scene_prints_the_librarys_lzb_answer() {
    let path = example("cradle-3-lzb.toml");
    let out = run(&["solve", path.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("— f64 (lzb)"), "{stdout}");
    assert!(
        stdout.contains("events; contacts ended in the order A1, A2"),
        "{stdout}"
    );
    let scene = Loaded::load(&path).expect("loads");
    let report = inertance::scene::lzb::run_lzb(&scene).expect("solves");
    for (name, _, v) in &report.twists {
        // Printed to 6 decimals.
        assert!(
            (printed_vx(&stdout, name) - v[0]).abs() <= 5e-7,
            "{name}: {stdout}"
        );
    }
    // The same scene under the simultaneous law, for contrast: the striker bounces back.
    let simultaneous = run(&["solve", path.to_str().unwrap(), "--law", "simultaneous"]);
    assert_eq!(simultaneous.status.code(), Some(0));
}

#[test]
fn law_lzb_on_the_command_line_solves_a_frictionless_one_body_scene() {
    let path = example("pitching-bar.toml");
    let out = run(&["solve", path.to_str().unwrap(), "--law", "lzb"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("(lzb)") && stdout.contains("ΔE_c [J]"),
        "{stdout}"
    );
}

#[test]
fn what_the_lzb_law_does_not_support_is_refused_by_key_and_value() {
    let cradle = example("cradle-3-lzb.toml");
    let cradle = cradle.to_str().unwrap();
    let exact = run(&["solve", cradle, "--exact"]);
    let err = String::from_utf8_lossy(&exact.stderr);
    assert_eq!(exact.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--exact") && err.contains("never exact"),
        "{err}"
    );
    assert!(exact.stdout.is_empty(), "nothing printed as exact");

    // Friction is integrated (it was refused before LZB's Part II): the tangential columns.
    let rough = example("rough-bar.toml");
    let out = run(&["solve", rough.to_str().unwrap(), "--law", "lzb"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("τ [N s]") && stdout.contains("by friction"),
        "{stdout}"
    );

    // A command that does not run the law refuses it rather than answer under another law.
    let csv = std::env::temp_dir().join(format!("inertance-lzb-sweep-{}.csv", std::process::id()));
    let sweep = run(&[
        "sweep",
        cradle,
        "--vary",
        "contact[0].k=0:1:3",
        "--out",
        csv.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&sweep.stderr);
    assert_eq!(sweep.status.code(), Some(2), "{err}");
    assert!(err.contains("solve.law") && err.contains("lzb"), "{err}");
}

#[test]
fn meaningless_lzb_parameters_name_their_key_and_value() {
    let text = std::fs::read_to_string(example("cradle-3-lzb.toml")).unwrap();
    for (from, to, key, value) in [
        (
            "stiffness = 1\nexponent",
            "stiffness = -2\nexponent",
            "contact[0].stiffness",
            "-2",
        ),
        (
            "exponent = 1.5\n[[contact]]",
            "exponent = 0\n[[contact]]",
            "contact[0].exponent",
            "0",
        ),
    ] {
        let s = Scene::new("lzb-bad-parameter", &text.replacen(from, to, 1));
        let out = s.run(&["solve"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(key) && err.contains(value), "{key}: {err}");
    }
    let s = Scene::new(
        "lzb-restitution-law",
        &text.replace(
            "law = \"lzb\"",
            "law = \"lzb\"\nrestitution = \"energetic\"",
        ),
    );
    let out = s.run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("solve.restitution"), "{err}");
}
