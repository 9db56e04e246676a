//! Issue 28, item 14 (first part): a slip along +tangent was reported as `slide-`.
//!
//! **What broke.** A planar scene is solved along t_i = e × n_i (e the plane's normal), whose
//! sense has nothing to do with the tangent y_i the user gave (or the one §12 chooses, along
//! the slip before impact, when none is given) — the y_i the report prints under `frames`. The
//! labels `slide+` and `slide-` followed t_i: a rod slipping along its given tangent
//! y = (−1, 0, 0) was reported `slide- → slide+`. They now follow y_i: `slide+` is slip along
//! +y_i. Checked exactly on the rod of `tests/friction_spatial.rs` (slip −1/5 along x that
//! reverses at μ = 3/10), whose senses are read off the velocities the report prints, not off
//! the solver's axes.

mod common;

use common::SceneFile;
use serde_json::Value;

/// The rod (contact at (3/5, −4/5, 0), floor normal −y, slip −1/5 along x, Poisson, μ = 3/10:
/// the slip stops and reverses), with the `tangent` line given.
fn rod(tangent: &str) -> String {
    format!(
        r#"name = "rod"
[body]
mass = 1
inertia = ["3/10", "3/10", "3/10"]
velocity = ["-1/5", -1, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = ["3/5", "-4/5", 0]
normal = [0, -1, 0]
{tangent}
k = "1/2"
mu = "3/10"
[solve]
restitution = "poisson"
"#
    )
}

fn solve(name: &str, text: &str) -> Value {
    let s = SceneFile::new(name, text);
    let out = s.run(&["solve", "--exact", "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

fn number(v: &Value) -> f64 {
    let text = v.as_str().unwrap();
    match text.split_once('/') {
        Some((p, q)) => p.parse::<f64>().unwrap() / q.parse::<f64>().unwrap(),
        None => text.parse().unwrap(),
    }
}

/// The contact's tangent y (as the report prints it) and its velocity after impact.
fn tangent_and_after(j: &Value) -> ([f64; 3], [f64; 3]) {
    let y = &j["frames"][0]["y"];
    let v = &j["friction"]["poisson"]["contacts"][0]["velocity_after"];
    (
        std::array::from_fn(|k| number(&y[k])),
        std::array::from_fn(|k| number(&v[k])),
    )
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn modes(j: &Value) -> Value {
    j["friction"]["poisson"]["contacts"][0]["modes"].clone()
}

/// The slip before impact is (−1/5, 0, 0) (the rod does not turn before impact) and it
/// reverses: the first label is the sense of the slip before along y, the last the sense of
/// the velocity after along y.
#[test]
fn slide_plus_is_slip_along_the_tangent_given() {
    for (name, line) in [
        ("mode-sign-minus-x", "tangent = [-1, 0, 0]"),
        ("mode-sign-plus-x", "tangent = [1, 0, 0]"),
        ("mode-sign-none", ""),
    ] {
        let j = solve(name, &rod(line));
        let (y, after) = tangent_and_after(&j);
        let before = dot(y, [-0.2, 0.0, 0.0]);
        let label = |x: f64| if x > 0.0 { "slide+" } else { "slide-" };
        assert_eq!(
            modes(&j),
            serde_json::json!([label(before), label(dot(y, after))]),
            "{name}: y = {y:?}"
        );
    }
}

/// With the tangent along the slip (given, or chosen by §12 when none is given) the slip
/// starts `slide+`; against it, `slide-`.
#[test]
fn the_sense_follows_the_tangent_not_the_solvers_axis() {
    assert_eq!(
        modes(&solve("mode-sign-along", &rod("tangent = [-1, 0, 0]"))),
        serde_json::json!(["slide+", "slide-"])
    );
    assert_eq!(
        modes(&solve("mode-sign-against", &rod("tangent = [1, 0, 0]"))),
        serde_json::json!(["slide-", "slide+"])
    );
    assert_eq!(
        modes(&solve("mode-sign-default", &rod(""))),
        serde_json::json!(["slide+", "slide-"])
    );
}

/// `free`: a contact without friction carries no tangential impulse.
#[test]
fn a_contact_without_friction_is_free() {
    let text = rod("").replace("mu = \"3/10\"", "mu = 0")
        + "[[contact]]\npoint = [\"-3/5\", \"-4/5\", 0]\nnormal = [0, -1, 0]\nk = \"1/2\"\nmu = \"3/10\"\n";
    let j = solve("mode-free", &text);
    assert_eq!(
        j["friction"]["poisson"]["contacts"][0]["modes"],
        serde_json::json!(["free"])
    );
}
