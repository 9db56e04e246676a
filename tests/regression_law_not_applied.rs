//! Issue 28, item 4: `--law unilateral` with friction was ignored.
//!
//! With μ > 0 the frictional integration (§14) imposes the simultaneous hypothesis on every
//! contact. A rocking block landing on its new edge, with friction, got P = −19/15 N s — a
//! pulling impulse — at the old edge, exit 0, while the header and the JSON `effects` said
//! "unilateral". The combination was then refused; since issue 25, item 3, the unilateral law
//! is integrated with friction (the old edge is released, the block turns about the new one:
//! Housner's ω⁺/ω⁻ = 1 − (3/2) sin²α = 7/10 here), from the scene file, from `--law`, from
//! `sweep` and from the library alike — and, since it was applied with Stronge's energetic
//! restitution too, that combination, once refused, is solved from every path.

mod common;

use common::SceneFile;
use inertance::impact::unilateral::Law;
use inertance::scene::Scene;
use inertance::scene::pipeline::run;

/// Housner's block (a × c = 1 × 2 m, 1 kg) rocking about its edge x = −a/2 at ω = 1 rad/s,
/// landing flat: the new edge x = +a/2 approaches at ω a = 1 m/s, the old one is at rest. One
/// contact per edge (the planar block; `partial = true` says the other corners are left out on
/// purpose), plastic, μ = 0.8. The simultaneous law with friction pulls at the old edge
/// (P₂ = −17/30 N s, with a warning): exactly what the unilateral law would not do.
const ROCKING: &str = r#"
name = "rocking block landing on its new edge"
[body]
shape = { box = [1, 0.5, 2] }
mass = 1
velocity = [1, 0, -0.5]
angular_velocity = [0, 1, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
partial = true
[[contact]]
obstacle = "floor"
body_point = [0.5, 0, -1]
k = 0
mu = 0.8
[[contact]]
obstacle = "floor"
body_point = [-0.5, 0, -1]
k = 0
mu = 0.8
"#;

fn refused(out: &std::process::Output) -> String {
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        out.stdout.is_empty(),
        "printed: {}",
        String::from_utf8_lossy(&out.stdout)
    );
    err
}

#[test]
fn the_unilateral_law_with_friction_is_applied_from_the_command_line() {
    let s = SceneFile::new("law-cli", ROCKING);
    for args in [
        &["solve", "--law", "unilateral"][..],
        &["solve", "--law", "unilateral", "--exact"],
    ] {
        let out = s.run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{err}");
        assert!(!err.contains("negative normal impulse rate"), "{err}");
        let text = String::from_utf8_lossy(&out.stdout);
        assert!(text.contains("(unilateral, friction"), "{text}");
        assert!(text.contains("modes released"), "{text}");
    }
    let out = s.run(&["solve", "--law", "unilateral", "--exact", "--json"]);
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(j["effects"][0], "unilateral");
    // Housner: b/h = 1/2, sin²α = 1/5, ω⁺ = (1 − 3/10) ω⁻.
    let newton = &j["friction"]["newton"];
    assert_eq!(newton["angular_velocity"][1], "7/10");
    assert_eq!(newton["contacts"][1]["normal_impulse"], "0");
    let csv = s.dir().join("sweep.csv");
    let out = s.run(&[
        "sweep",
        "--vary",
        "contact[0].k=0:1:3",
        "--law",
        "unilateral",
        "--out",
        csv.to_str().expect("utf-8"),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(0), "{err}");
    assert!(csv.exists(), "the sweep wrote its CSV");
    // The simultaneous law with friction is still answered, its pull named on stderr.
    let out = s.run(&["solve", "--json"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        err.contains("contact 2: negative normal impulse rate"),
        "{err}"
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(j["effects"][0], "friction");
}

#[test]
fn the_energetic_law_runs_with_it_from_the_file_and_the_command_line() {
    // Plastic (k = 0): the energetic restitution has no work to give back, so the block turns
    // about its new edge as under Newton's law: Housner's ω⁺/ω⁻ = 7/10, exactly.
    let energetic = ROCKING.to_string() + "[solve]\nrestitution = \"energetic\"\n";
    let from_flag = SceneFile::new("law-energetic", &energetic);
    let from_file = SceneFile::new(
        "law-file-energetic",
        &format!("{ROCKING}[solve]\nlaw = \"unilateral\"\nrestitution = \"energetic\"\n"),
    );
    for out in [
        from_flag.run(&["solve", "--exact", "--json", "--law", "unilateral"]),
        from_file.run(&["solve", "--exact", "--json"]),
    ] {
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(out.status.success(), "{err}");
        let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
        assert_eq!(j["effects"][0], "unilateral");
        let f = &j["friction"]["energetic"];
        assert_eq!(f["angular_velocity"][1], "7/10", "{f}");
        assert_eq!(f["contacts"][1]["normal_impulse"], "0", "{f}");
        assert_eq!(f["contacts"][1]["modes"][0], "released", "{f}");
    }
}

#[test]
fn no_library_path_applies_another_law_under_its_name() {
    // The energetic law under the unilateral law: set, solved, and said so.
    let energetic = ROCKING.to_string() + "[solve]\nrestitution = \"energetic\"\n";
    let mut scene = Scene::parse(&energetic, "rocking.toml").expect("a scene");
    scene
        .set_law(Law::Unilateral, "the unilateral law")
        .expect("allowed");
    assert_eq!(scene.law, Law::Unilateral);
    for solved in [
        run::<f64>(&scene, None).map(|s| s.report.effects),
        run::<inertance::scalar::Exact>(&scene, None).map(|s| s.report.effects),
    ] {
        let effects = solved.expect("solves");
        assert_eq!(effects.first().map(String::as_str), Some("unilateral"));
    }
    // With friction and Newton's or Poisson's law, the unilateral law is applied, and says so.
    let mut scene = Scene::parse(ROCKING, "rocking.toml").expect("a scene");
    scene
        .set_law(Law::Unilateral, "the unilateral law")
        .expect("allowed");
    let solved = run::<inertance::scalar::Exact>(&scene, None).expect("solves");
    assert_eq!(
        solved.report.effects.first().map(String::as_str),
        Some("unilateral")
    );
    // Frictionless, the unilateral law is applied, and says so.
    let smooth = ROCKING.replace("mu = 0.8", "mu = 0");
    let mut scene = Scene::parse(&smooth, "smooth.toml").expect("a scene");
    scene
        .set_law(Law::Unilateral, "the unilateral law")
        .expect("allowed");
    let solved = run::<inertance::scalar::Exact>(&scene, None).expect("solves");
    assert_eq!(
        solved.report.effects.first().map(String::as_str),
        Some("unilateral")
    );
}

/// `derive` on one body whose scene names the unilateral law printed the simultaneous law's
/// closed forms under the header "effects: unilateral, poisson", exit 0 (found this session on
/// `examples/symbolic-bar.toml` with `law = "unilateral"`). It is refused now, naming
/// `solve.law`, as it is for a system (`tests/system_tools.rs`).
#[test]
fn derive_refuses_a_one_body_scene_under_the_unilateral_law() {
    let text = std::fs::read_to_string(format!(
        "{}/examples/symbolic-bar.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("the example")
    .replace("[solve]", "[solve]\nlaw = \"unilateral\"");
    let scene = SceneFile::new("derive-unilateral-one-body", &text);
    let out = scene.run(&["derive", "--symbols", "m,Jx,Jy,Jz,vx,vy,omega,y1,y2,k1,k2"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("solve.law") && err.contains("unilateral"),
        "{err}"
    );
    assert!(out.stdout.is_empty(), "nothing printed");
}

/// `derive` on a scene under the LZB law printed the simultaneous law's closed forms
/// ("effects: newton, poisson"), exit 0, and `analyze` the simultaneous and unilateral
/// analyses without a word on the scene's law (found this session on
/// `examples/cradle-3-lzb.toml`). `derive` refuses it now, naming `solve.law`; `analyze`, whose
/// every section names its law, adds the simultaneous law against the LZB law over stiffness
/// ratios (it first warned that the LZB law was not analysed).
#[test]
fn derive_refuses_and_analyze_compares_on_a_scene_under_the_lzb_law() {
    let text = std::fs::read_to_string(format!(
        "{}/examples/cradle-3-lzb.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("the example");
    let scene = SceneFile::new("derive-lzb", &text);
    let err = refused(&scene.run(&["derive", "--symbols", "k"]));
    assert!(err.contains("solve.law") && err.contains("lzb"), "{err}");

    let out = scene.run(&["analyze"]);
    assert_eq!(out.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("The simultaneous law against the LZB law"),
        "{stdout}"
    );
}
