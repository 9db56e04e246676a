//! Hertz's stiffness from the shapes and materials that touch (`stiffness = "hertz"`,
//! `src/scene/model/hertz.rs`): the chain of balls of Siconos' tutorial reproduces its stiffness
//! formula and the answer of the same scene with the stiffness written out; a sphere on an
//! obstacle plane takes R* = R; every case where Hertz's law cannot apply is refused with the
//! key and the value.

mod common;

use common::SceneFile;
use inertance::scene::Scene;
use inertance::scene::lzb::run_lzb;
use std::path::Path;

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

/// Siconos' stiffness of two steel balls of radius r: √(r/2) · (2/3) E/(1 − ν²).
fn siconos_stiffness(r: f64) -> f64 {
    (r / 2.0).sqrt() * (2.0 / 3.0) * (203.0e9 / (1.0 - 0.3_f64.powi(2)))
}

#[test]
fn the_chain_of_balls_takes_siconos_stiffness_and_its_answer() {
    let path = example("chain-of-balls-hertz.toml");
    let scene = Scene::load(&path).expect("loads");
    let k = siconos_stiffness(0.01);
    for c in &scene.contacts {
        let given = c.stiffness.as_ref().expect("set from the shapes").approx;
        assert!(
            (given - k).abs() <= 4.0 * f64::EPSILON * k,
            "{given} vs {k}"
        );
        assert_eq!(c.exponent.as_ref().expect("3/2").approx, 1.5);
    }
    let hertz = run_lzb(&scene).expect("solves");
    // The same scene with the stiffness written as a number: the same answer, bit for bit
    // (every contact has the same K either way, and only the ratios enter).
    let text = std::fs::read_to_string(&path).unwrap();
    let written = SceneFile::new(
        "lzb-hertz-written",
        &text.replace("stiffness = \"hertz\"", &format!("stiffness = {k:e}")),
    );
    let numeric = run_lzb(&Scene::load(&written.path).expect("loads")).expect("solves");
    assert_eq!(hertz.twists, numeric.twists);
}

#[test]
fn a_sphere_on_a_floor_takes_its_own_radius() {
    let scene = SceneFile::new(
        "lzb-hertz-sphere-floor",
        r#"name = "ball on a floor"
[body]
shape = { sphere = 0.02 }
mass = 1
material = { young = 2e11, poisson = 0.25 }
velocity = [0, 0, -1]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
material = { young = 7e10, poisson = 0.35 }
[[contact]]
obstacle = "floor"
k = 1
stiffness = "hertz"
[solve]
law = "lzb"
"#,
    );
    let loaded = Scene::load(&scene.path).expect("loads");
    let k = loaded.contacts[0].stiffness.as_ref().expect("set").approx;
    let e_star = 1.0 / ((1.0 - 0.0625) / 2e11 + (1.0 - 0.1225) / 7e10);
    let expected = 4.0 / 3.0 * e_star * 0.02_f64.sqrt();
    assert!(
        (k - expected).abs() <= 8.0 * f64::EPSILON * expected,
        "{k} vs {expected}"
    );
    // One contact: Newton's law, whatever K.
    let out = run_lzb(&loaded).expect("solves");
    assert!((out.after[0] + 1.0).abs() <= 1e-8, "{:?}", out.after);
}

/// Each refusal names the contact's `stiffness` (or the key at fault) and exits with status 2.
#[test]
fn where_hertz_does_not_apply_the_scene_is_refused() {
    let flat_box = std::fs::read_to_string(example("flat-box.toml")).unwrap();
    let box_corner = flat_box.replacen("k = 0.5", "k = 0.5\nstiffness = \"hertz\"", 1);
    let ball = |extra_body: &str, extra_floor: &str, contact: &str| {
        format!(
            "name = \"ball\"\n[body]\nshape = {{ sphere = 0.02 }}\nmass = 1\n{extra_body}\n\
             velocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n[[obstacle]]\nname = \"floor\"\n\
             normal = [0, 0, 1]\n{extra_floor}\n[[contact]]\nobstacle = \"floor\"\nk = 1\n\
             {contact}\n[solve]\nlaw = \"lzb\"\n"
        )
    };
    let steel = "material = { young = 2e11, poisson = 0.3 }";
    let cases: Vec<(&str, String, &str, &str)> = vec![
        (
            "corner",
            box_corner,
            "contact[0].stiffness",
            "an edge or a corner",
        ),
        (
            "no-floor-material",
            ball(steel, "", "stiffness = \"hertz\""),
            "contact[0].stiffness",
            "the material of obstacle \"floor\"",
        ),
        (
            "no-body-material",
            ball("", steel, "stiffness = \"hertz\""),
            "contact[0].stiffness",
            "the material of the body",
        ),
        (
            "exponent",
            ball(steel, steel, "stiffness = \"hertz\"\nexponent = 1"),
            "contact[0].exponent",
            "exponent 3/2",
        ),
        (
            "word",
            ball(steel, steel, "stiffness = \"soft\""),
            "contact[0].stiffness",
            "or \"hertz\"",
        ),
        (
            "poisson",
            ball(
                "material = { young = 2e11, poisson = 0.7 }",
                steel,
                "stiffness = \"hertz\"",
            ),
            "body.material.poisson",
            "(−1, 1/2]",
        ),
        (
            "paper-form",
            "name = \"paper\"\n[body]\nmass = 1\ninertia = [1, 1, 1]\nvelocity = [0, 0, -1]\n\
             angular_velocity = [0, 0, 0]\n[[contact]]\npoint = [0, 0, -1]\nnormal = [0, 0, -1]\n\
             k = 1\nstiffness = \"hertz\"\n[solve]\nlaw = \"lzb\"\n"
                .to_string(),
            "contact[0].stiffness",
            "world frame",
        ),
    ];
    for (name, text, key, says) in cases {
        let scene = SceneFile::new(&format!("lzb-hertz-{name}"), &text);
        let out = scene.run(&["solve"]);
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{name}: {stderr}");
        assert!(
            stderr.contains(&format!("key `{key}`")) && stderr.contains(says),
            "{name}: {stderr}"
        );
        assert!(!stderr.contains("panicked"), "{name}: {stderr}");
    }
}
