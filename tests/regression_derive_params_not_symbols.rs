//! Regression: `derive` takes a scene's `[params]` as its symbols when none are named (guide/solving.md:
//! "default symbols: the scene's [params]"), but only the CLI did, and by reading the scene
//! file a second time: a scene piped to `inertance derive -` was refused ("give --symbols"),
//! and Python's `derive(scene)` evaluated the parameters and silently returned numbers
//! (`python/tests/test_regression_derive_params_as_numbers.py`). The default is now one library
//! function, `tools::derive::default_symbols`, applied to the document as read, by both.

use std::io::Write;
use std::process::{Command, Output, Stdio};

use inertance::scene::parse_document;
use inertance::tools::derive::default_symbols;

const TILTED_BOX: &str = include_str!("../examples/tilted-box.toml");

/// A bar on two supports whose mass and one support's position are parameters.
const TWO_PARAMS: &str = r#"
name = "bar with parameters"
[params]
m = 2
b = 4
[body]
mass = "m"
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, "b", 0]
normal = [1, 0, 0]
k = 0.2
[solve]
models = ["newton"]
"#;

/// `inertance ARGS`, with `stdin` on its standard input.
fn inertance(args: &[&str], stdin: &str) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    child
        .stdin
        .take()
        .unwrap()
        .write_all(stdin.as_bytes())
        .unwrap();
    child.wait_with_output().unwrap()
}

/// The JSON of a successful `derive`.
fn json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn the_default_symbols_are_the_params_not_set() {
    let doc = parse_document(TWO_PARAMS, "bar").unwrap();
    assert_eq!(default_symbols(&doc, &[]), ["m", "b"]);
    assert_eq!(default_symbols(&doc, &["m"]), ["b"]);
    let doc = parse_document(TILTED_BOX, "box").unwrap();
    assert_eq!(default_symbols(&doc, &[]), ["theta"]);
}

/// From a file and from standard input alike, `derive` without `--symbols` derives in the
/// parameters: P₁ is an expression in θ, not the number of θ = 30°.
#[test]
fn derive_takes_the_params_as_symbols_from_a_file_and_from_stdin() {
    let file = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/tilted-box.toml");
    let args = |scene: &'static str| ["derive", scene, "--model", "newton", "--json"];
    for out in [
        inertance(&args(file), ""),
        inertance(&args("-"), TILTED_BOX),
    ] {
        let j = json(&out);
        assert_eq!(j["symbols"], serde_json::json!(["theta"]));
        let p1 = j["models"]["newton"]["impulses"][0].as_str().unwrap();
        assert!(p1.contains("cos(theta)"), "{p1}");
    }
}

/// `--param NAME=VALUE` gives a parameter a value, so it is not a symbol; with no parameter
/// left and no `--symbols`, status 2 and what to do.
#[test]
fn a_param_given_a_value_is_not_a_symbol() {
    let j = json(&inertance(
        &["derive", "-", "--param", "m=3", "--json"],
        TWO_PARAMS,
    ));
    assert_eq!(j["symbols"], serde_json::json!(["b"]));
    let out = inertance(
        &["derive", "-", "--param", "m=3", "--param", "b=4"],
        TWO_PARAMS,
    );
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("<stdin>") && err.contains("--symbols") && err.contains("[params]"),
        "{err}"
    );
}
