//! Scenes written as a user thinks of them — world frame, pose, shapes, obstacles, parameters —
//! against the same scenes rotated into body axes by hand (`tests/modelled/*.body.toml`).
//!
//! Exact first: in rationals (a pose with rational entries) or with exact radicals (`30 deg`),
//! the modelled scene solved in body axes (`[solve] axes = "body"`) gives the very same report
//! as the hand-rotated one, value for value; solved in world axes it gives the same impulses
//! and energies, and a twist after impact that is R times the body-axes twist, exactly.

use std::path::{Path, PathBuf};

use inertance::impact::restitution::Model;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::number::parse_number;
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::pipeline::{assemble, run};
use inertance::scene::{Scene, parse_document};

fn path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/modelled")
        .join(name)
}

fn text(name: &str) -> String {
    std::fs::read_to_string(path(name)).expect("scene file")
}

/// The scene `name` with `[solve] axes` set.
fn with_axes(name: &str, axes: &str) -> Scene {
    let mut doc = parse_document(&text(name), name).expect("toml");
    if doc.get("solve").is_none() {
        doc.insert("solve", toml_edit::table());
    }
    doc["solve"]["axes"] = toml_edit::value(axes);
    Scene::from_document(&doc, name).expect("a valid scene")
}

fn scene(name: &str) -> Scene {
    Scene::parse(&text(name), name).expect("a valid scene")
}

/// The report as JSON without the keys that name the scene and its axes.
fn report_json<T: Scalar>(scene: &Scene) -> serde_json::Value {
    let mut v = run::<T>(scene, None).expect("solves").report.to_json();
    let o = v.as_object_mut().expect("an object");
    o.remove("scene");
    o.remove("axes");
    v
}

fn matrix<T: Scalar>(rows: [[&str; 3]; 3]) -> [[T; 3]; 3] {
    rows.map(|r| r.map(|e| T::from_number(&parse_number(e).expect("a number")).expect("exact")))
}

fn rotate<T: Scalar>(r: &[[T; 3]; 3], v: &[T]) -> Vec<T> {
    (0..3)
        .map(|i| r[i][0].clone() * &v[0] + r[i][1].clone() * &v[1] + r[i][2].clone() * &v[2])
        .collect()
}

/// The modelled scene in body axes reports exactly what the hand-rotated one does; in world
/// axes its impulses and energies are equal and its twist is R times the body twist.
fn same_physics<T: Scalar>(pair: &str, r: [[&str; 3]; 3]) {
    let world = format!("{pair}.world.toml");
    let body = format!("{pair}.body.toml");
    assert_eq!(
        report_json::<T>(&with_axes(&world, "body")),
        report_json::<T>(&scene(&body)),
        "{pair}: body-axes reports differ"
    );
    let r = matrix::<T>(r);
    let mut in_world = assemble::<T>(&scene(&world)).expect("assembles");
    let mut in_body = assemble::<T>(&scene(&body)).expect("assembles");
    assert_eq!(
        in_world.problem().contacts().len(),
        in_body.problem().contacts().len()
    );
    for model in [Model::Newton, Model::Poisson] {
        let (w, _) = in_world.solve(model).expect("solves");
        let (b, _) = in_body.solve(model).expect("solves");
        assert_eq!(w.impulses_hat, b.impulses_hat, "{pair} {model:?}: impulses");
        assert_eq!(w.compression_hat, b.compression_hat, "{pair} {model:?}");
        assert_eq!(
            w.lost_velocity_energy, b.lost_velocity_energy,
            "{pair} {model:?}: E_p"
        );
        assert_eq!(
            w.kinetic_energy_loss, b.kinetic_energy_loss,
            "{pair} {model:?}: ΔE_c"
        );
        let bs = b.velocity.as_slice();
        let (top, bottom) = (rotate(&r, &bs[0..3]), rotate(&r, &bs[3..6]));
        let expected = Screw::new(
            Vec3::from_column_slice(&top),
            Vec3::from_column_slice(&bottom),
        );
        assert_eq!(
            w.velocity, expected,
            "{pair} {model:?}: twist after = R · body twist"
        );
    }
}

#[test]
fn the_planar_bar_in_the_world_equals_example_3_in_rationals() {
    same_physics::<Exact>(
        "planar-bar",
        [["0", "1", "0"], ["0", "0", "-1"], ["-1", "0", "0"]],
    );
}

#[test]
fn the_ball_in_the_corner_against_two_walls_equals_example_8() {
    let id = [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]];
    same_physics::<Exact>("ball-in-corner", id);
}

#[test]
fn the_tilted_box_on_a_floor_equals_its_hand_rotated_scene_in_exact_radicals() {
    let c = "cos(30 deg)";
    same_physics::<RatFun>(
        "tilted-box",
        [[c, "0", "1/2"], ["0", "1", "0"], ["-1/2", "0", c]],
    );
}

/// The report of a scene text in exact rationals, as JSON without its name and axes.
fn exact_json(text: &str) -> serde_json::Value {
    report_json::<Exact>(&Scene::parse(text, "inline.toml").expect("a valid scene"))
}

fn error(text: &str) -> inertance::scene::SceneError {
    Scene::parse(text, "inline.toml").expect_err("refused")
}

const CONTACTS_ON_A_FLOOR: &str = r#"
velocity = [1, 0, -2]
angular_velocity = [0, 0, 1]
[[obstacle]]
normal = [0, 0, 1]
[[contact]]
obstacle = 0
body_point = [1, 0, -1]
k = 0.5
[[contact]]
obstacle = 0
body_point = [-1, 1, -1]
k = 0.25
"#;

#[test]
fn a_rational_quaternion_and_its_rotation_matrix_give_the_same_impact() {
    // q = (2, 0, 0, 1)/√5: a turn about z with cos = 3/5, sin = 4/5.
    let by = |pose: &str| {
        exact_json(&format!(
            "[body]\nmass = 3\ninertia = [1, 2, 3]\npose = {pose}\n{CONTACTS_ON_A_FLOOR}"
        ))
    };
    let q = by("{ quaternion = [2, 0, 0, 1] }");
    assert_eq!(
        q,
        by("{ matrix = [[0.6, -0.8, 0], [0.8, 0.6, 0], [0, 0, 1]] }")
    );
    // Two quarter turns in a list are a half turn.
    assert_eq!(
        by("[{ axis = [0, 0, 1], angle = \"90 deg\" }, { axis = [0, 0, 2], angle = \"pi/2\" }]"),
        by("{ axis = [0, 0, 1], angle = \"180 deg\" }")
    );
}

#[test]
fn shapes_give_their_textbook_mass_properties_exactly() {
    let solve = |body: &str| exact_json(&format!("[body]\n{body}\n{CONTACTS_ON_A_FLOOR}"));
    // A 0.1 m steel-like cube of density 1000 has m = 1 and J = m a²/6 = 1/600.
    assert_eq!(
        solve("shape = { box = [0.1, 0.1, 0.1] }\ndensity = 1000"),
        solve("mass = 1\ninertia = [\"1/600\", \"1/600\", \"1/600\"]")
    );
    // Point masses: 1 at (±1, 0, 0), 2 at (0, 3, 0): m = 4, c = (0, 3/2, 0), J_C = diag(9, 2, 11).
    assert_eq!(
        solve(
            "shape = { points = [{ mass = 1, at = [1, 0, 0] }, { mass = 1, at = [-1, 0, 0] }, \
             { mass = 2, at = [0, 3, 0] }] }"
        ),
        solve("mass = 4\ninertia = [9, 2, 11]\ncentre_of_mass = [0, 1.5, 0]")
    );
    // The parallel-axis theorem: the tensor about a corner A = (1, 1, 0) of a body with
    // J_C = diag(1, 2, 3), m = 2: J_A = J_C + m (|d|² I − d dᵀ), d = (1, 1, 0).
    assert_eq!(
        solve("mass = 2\ninertia = [[3, -2, 0], [-2, 4, 0], [0, 0, 7]]\ninertia_about = [1, 1, 0]"),
        solve("mass = 2\ninertia = [1, 2, 3]")
    );
    // A cylinder r = 1, h = 2, m = 6: J = diag(m(3r² + h²)/12, same, m r²/2) = diag(7/2, 7/2, 3).
    assert_eq!(
        solve("shape = { cylinder = [1, 2] }\nmass = 6"),
        solve("mass = 6\ninertia = [3.5, 3.5, 3]")
    );
    // A sphere r = 1/2, m = 2: J = 2/5 m r² = 1/5.
    assert_eq!(
        solve("shape = { sphere = 0.5 }\nmass = 2"),
        solve("mass = 2\ninertia = [0.2, 0.2, 0.2]")
    );
}

#[test]
fn parameters_reach_every_value_and_chain() {
    let with = |params: &str, body: &str| {
        exact_json(&format!(
            "[params]\n{params}\n[body]\n{body}\n{CONTACTS_ON_A_FLOOR}"
        ))
    };
    assert_eq!(
        with(
            "a = 2\nhalf = \"a/4\"\nturn = \"90 deg\"",
            "shape = { box = [\"a\", \"a/2\", \"half\"] }\nmass = \"a + 1\"\npose = { axis = [0, 0, 1], angle = \"turn\" }"
        ),
        exact_json(&format!(
            "[body]\nshape = {{ box = [2, 1, 0.5] }}\nmass = 3\npose = {{ axis = [0, 0, 1], angle = \"90 deg\" }}\n{CONTACTS_ON_A_FLOOR}"
        ))
    );
}

#[test]
fn obstacle_mistakes_are_named_with_the_fix() {
    let box_on = |normal: &str, corner: &str| {
        format!(
            "[body]\nshape = {{ box = [2, 1, 1] }}\nmass = 1\npose = {{ axis = [0, 1, 0], angle = \"30 deg\" }}\n\
             velocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n[[obstacle]]\nname = \"floor\"\nnormal = {normal}\n\
             [[contact]]\nobstacle = \"floor\"\n{corner}\nk = 0.5\n"
        )
    };
    // A floor whose normal points down, into the floor: the centre of mass is below it.
    let e = error(&box_on("[0, 0, -1]", "corner = [1, 1, -1]"));
    assert_eq!(e.key, "contact[0].obstacle");
    assert!(e.message.contains("flip its sign"), "{e}");
    // A corner that is not the lowest: the box would pass through the floor.
    let e = error(&box_on("[0, 0, 1]", "corner = [-1, 1, -1]"));
    assert_eq!(e.key, "contact[0]");
    assert!(e.message.contains("above the box's lowest corner"), "{e}");
    assert!(e.message.contains("[1, -1, -1], [1, 1, -1]"), "{e}");
    // No corner named while an edge touches: the two corners are listed.
    let e = error(&box_on("[0, 0, 1]", ""));
    assert_eq!(e.key, "contact[0].corner");
    assert!(
        e.message
            .contains("2 corners of the box touch obstacle \"floor\""),
        "{e}"
    );
    // A normal given beside the obstacle's.
    let e = error(&box_on(
        "[0, 0, 1]",
        "corner = [1, 1, -1]\nnormal = [0, 0, -1]",
    ));
    assert_eq!(e.key, "contact[0].normal");
    // An obstacle with a point the contact misses, with the distance.
    let e = error(
        "[body]\nshape = { sphere = 1 }\nmass = 1\nposition = [0, 0, 2]\nvelocity = [0, 0, -1]\n\
         angular_velocity = [0, 0, 0]\n[[obstacle]]\nnormal = [0, 0, 1]\npoint = [0, 0, 0]\n\
         [[contact]]\nobstacle = 0\nk = 1\n",
    );
    assert!(
        e.message.contains("(A − P)·N = 1 (above it: no contact)"),
        "{e}"
    );
    // An unknown obstacle name lists the ones there are.
    let e = error(&box_on("[0, 0, 1]", "corner = [1, 1, -1]").replace(
        "obstacle = \"floor\"\ncorner",
        "obstacle = \"flor\"\ncorner",
    ));
    assert_eq!(e.key, "contact[0].obstacle");
    assert!(e.message.contains("\"floor\""), "{e}");
}

#[test]
fn poses_and_parameters_that_are_wrong_are_named() {
    let body = |extra: &str| {
        format!(
            "{extra}\n[body]\nmass = 1\ninertia = [1, 1, 1]\n{}\n{CONTACTS_ON_A_FLOOR}",
            ""
        )
    };
    // A rotation matrix typed to three digits is not a rotation; the fix is named.
    let e = error(&format!(
        "[body]\nmass = 1\ninertia = [1, 1, 1]\npose = {{ matrix = [[0.866, -0.5, 0], [0.5, 0.866, 0], [0, 0, 1]] }}\n{CONTACTS_ON_A_FLOOR}"
    ));
    assert_eq!(e.key, "body.pose.matrix");
    assert!(e.message.contains("not a rotation"), "{e}");
    assert!(e.message.contains("cos(30 deg)"), "{e}");
    // A reflection.
    let e = error(&format!(
        "[body]\nmass = 1\ninertia = [1, 1, 1]\npose = {{ matrix = [[1, 0, 0], [0, 1, 0], [0, 0, -1]] }}\n{CONTACTS_ON_A_FLOOR}"
    ));
    assert!(e.message.contains("reflection"), "{e}");
    // A parameter used before it is defined, and one named like a function.
    let e = error(&body("[params]\nh = \"2*L\"\nL = 1"));
    assert_eq!(e.key, "params.h");
    assert!(e.message.contains("only the parameters above it"), "{e}");
    let e = error(&body("[params]\nsin = 1"));
    assert_eq!(e.key, "params.sin");
    // A parameter in degrees written with °: the usual hint.
    let e = error(&body("[params]\ntheta = \"3°\""));
    assert!(e.message.contains("did you mean `3 deg`"), "{e}");
}

fn inertance(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .expect("runs")
}

fn stdout_json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("json")
}

#[test]
fn the_cli_sets_parameters_and_axes_and_derives_in_the_parameters() {
    let world = path("tilted-box.world.toml");
    let world = world.to_str().expect("utf-8");
    // --param overrides [params]: at 45° the impulses are 51/61 (derived below as
    // 51/(2(45 cos²θ − 24 cos θ sin θ + 20)) = 51/(2·61/2)).
    let at45 = stdout_json(&inertance(&[
        "solve",
        world,
        "--exact",
        "--json",
        "--param",
        "theta=45 deg",
    ]));
    assert_eq!(at45["axes"], "world");
    assert_eq!(at45["models"]["newton"]["impulses"][0], "51/61");
    // --axes body gives the hand-rotated scene's twist.
    let body = path("tilted-box.body.toml");
    let in_body = stdout_json(&inertance(&[
        "solve", world, "--exact", "--json", "--axes", "body",
    ]));
    let hand = stdout_json(&inertance(&[
        "solve",
        body.to_str().expect("utf-8"),
        "--exact",
        "--json",
    ]));
    assert_eq!(in_body["axes"], "body");
    for key in ["velocity", "angular_velocity"] {
        assert_eq!(
            in_body["models"]["newton"][key],
            hand["models"]["newton"][key]
        );
    }
    // An unknown parameter is named with the ones there are (status 2).
    let out = inertance(&["solve", world, "--param", "phi=2"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("has: theta"));
    // derive takes the parameters as symbols by default.
    let out = inertance(&["derive", world, "--model", "newton"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("symbols: theta"), "{text}");
    // A rational function of cos θ and sin θ (not always in lowest terms: there is no
    // multivariate gcd); derivations/modelled-tilted-box.md proves it equal to
    // 51/(2(45 cos²θ − 24 cos θ sin θ + 20)).
    assert!(text.contains("newton.P1 = 51"), "{text}");
    assert!(
        text.contains("cos(theta)") && text.contains("sin(theta)"),
        "{text}"
    );
}

mod posed {
    //! Any scene, posed by a random rational rotation: its world vectors are computed here, in
    //! the test (R from the quaternion formula, in rationals), independently of the reader's
    //! lowering; solved in body axes it must report exactly what the unposed scene reports.

    use super::*;
    use num_bigint::BigInt;
    use num_rational::BigRational;
    use proptest::prelude::*;

    fn q(n: i64) -> BigRational {
        BigRational::from_integer(BigInt::from(n))
    }

    /// R of the quaternion (w, x, y, z), rational.
    fn rotation(w: i64, x: i64, y: i64, z: i64) -> [[BigRational; 3]; 3] {
        let n2 = q(w * w + x * x + y * y + z * z);
        let m = [
            [
                w * w + x * x - y * y - z * z,
                2 * (x * y - w * z),
                2 * (x * z + w * y),
            ],
            [
                2 * (x * y + w * z),
                w * w - x * x + y * y - z * z,
                2 * (y * z - w * x),
            ],
            [
                2 * (x * z - w * y),
                2 * (y * z + w * x),
                w * w - x * x - y * y + z * z,
            ],
        ];
        m.map(|row| row.map(|e| q(e) / &n2))
    }

    fn vector(r: &[[BigRational; 3]; 3], v: [i64; 3]) -> String {
        let w: Vec<String> = (0..3)
            .map(|i| {
                let x = &r[i][0] * q(v[0]) + &r[i][1] * q(v[1]) + &r[i][2] * q(v[2]);
                format!("\"{x}\"")
            })
            .collect();
        format!("[{}]", w.join(", "))
    }

    fn triple() -> impl Strategy<Value = [i64; 3]> {
        [-3i64..=3, -3i64..=3, -3i64..=3]
    }

    fn direction() -> impl Strategy<Value = [i64; 3]> {
        triple().prop_filter("nonzero", |v| v.iter().any(|&x| x != 0))
    }

    /// The scene with every vector mapped by `r`; `pose` is added when given.
    #[allow(clippy::too_many_arguments)]
    fn scene_text(
        r: &[[BigRational; 3]; 3],
        pose: Option<[i64; 4]>,
        inertia: [i64; 3],
        v: [i64; 3],
        w: [i64; 3],
        contacts: &[([i64; 3], [i64; 3])],
        hinge: Option<([i64; 3], [i64; 3])>,
    ) -> String {
        let mut s = String::from("[body]\nmass = 2\n");
        s += &format!(
            "inertia = [{}, {}, {}]\n",
            inertia[0], inertia[1], inertia[2]
        );
        if let Some([a, b, c, d]) = pose {
            s += &format!("pose = {{ quaternion = [{a}, {b}, {c}, {d}] }}\n");
        }
        s += &format!(
            "velocity = {}\nangular_velocity = {}\n",
            vector(r, v),
            vector(r, w)
        );
        for (i, (p, n)) in contacts.iter().enumerate() {
            s += &format!(
                "[[contact]]\npoint = {}\nnormal = {}\nk = \"{}/4\"\n",
                vector(r, *p),
                vector(r, *n),
                i % 5
            );
        }
        if let Some((p, a)) = hinge {
            s += &format!(
                "[[constraints.joint]]\nkind = \"revolute\"\npoint = {}\naxis = {}\n",
                vector(r, p),
                vector(r, a)
            );
        }
        s
    }

    fn report(text: &str) -> Result<serde_json::Value, String> {
        let scene = Scene::parse(text, "posed.toml").map_err(|e| e.to_string())?;
        let mut v = run::<Exact>(&scene, None)
            .map_err(|e| format!("{e:?}"))?
            .report
            .to_json();
        let o = v.as_object_mut().expect("an object");
        o.remove("scene");
        o.remove("axes");
        Ok(v)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 40, .. ProptestConfig::default() })]

        #[test]
        fn a_posed_scene_in_body_axes_is_the_unposed_scene(
            quat in [-2i64..=2, -2i64..=2, -2i64..=2, -2i64..=2]
                .prop_filter("nonzero", |q| q.iter().any(|&x| x != 0)),
            inertia in [1i64..=5, 1i64..=5, 1i64..=5],
            v in direction(),
            w in triple(),
            contacts in prop::collection::vec((triple(), direction()), 1..=3),
            hinge in prop::option::of((triple(), direction())),
        ) {
            let id = rotation(1, 0, 0, 0);
            let r = rotation(quat[0], quat[1], quat[2], quat[3]);
            let plain = report(&scene_text(&id, None, inertia, v, w, &contacts, hinge));
            let mut posed = scene_text(&r, Some(quat), inertia, v, w, &contacts, hinge);
            posed += "[solve]\naxes = \"body\"\n";
            let posed = report(&posed);
            match (plain, posed) {
                (Ok(a), Ok(b)) => prop_assert_eq!(a, b),
                // The same failure (a singular G, a dependent joint), whatever the pose.
                (Err(a), Err(b)) => prop_assert_eq!(
                    a.replace("posed.toml", ""),
                    b.replace("posed.toml", "")
                ),
                (a, b) => prop_assert!(false, "unposed {:?} but posed {:?}", a.is_ok(), b.is_ok()),
            }
        }
    }
}

mod sensitivity {
    //! A parameter's sensitivity through a modelled scene — a box edge L that sets the shape's
    //! moments and the corners' positions — against the exact derivative of `derive`'s closed
    //! form (the same scene with L a symbol), at rational points.

    use super::*;
    use inertance::scalar::dual::Dual;
    use inertance::scene::pipeline::assemble;
    use std::collections::HashMap;

    const BOX: &str = r#"
[params]
L = 0.4
[body]
shape = { box = ["L", 0.2, 0.1] }
mass = 2
pose = { quaternion = [2, 0, 1, 0] }       # about y: cos = 3/5, sin = 4/5
velocity = [0.5, 0, -1]
angular_velocity = [0, 1, 0]
[[obstacle]]
normal = [0, 0, 1]
[[contact]]
obstacle = 0
corner = [1, -1, -1]
k = 0.5
[[contact]]
obstacle = 0
corner = [1, 1, -1]
k = 0.25
"#;

    #[test]
    fn a_parameter_sensitivity_equals_the_derivative_of_the_closed_form() {
        let symbolic = Scene::parse_with(BOX, "box.toml", &["L".to_string()]).expect("reads");
        let mut formulas = assemble::<RatFun>(&symbolic).expect("assembles");
        for at in ["2/5", "1/2", "3/4", "1"] {
            let mut doc = parse_document(BOX, "box.toml").expect("toml");
            inertance::scene::set_param(&mut doc, "L", at).expect("a parameter");
            let seeded = Scene::from_document_seeded(&doc, "box.toml", &[], "L").expect("reads");
            let mut dual = assemble::<Dual<f64>>(&seeded).expect("assembles");
            let point = HashMap::from([(
                "L".to_string(),
                parse_number(at).expect("n").exact.expect("rational"),
            )]);
            for model in [Model::Newton, Model::Poisson] {
                let (f, _) = formulas.solve(model).expect("solves");
                let (d, _) = dual.solve(model).expect("solves");
                let pairs = f
                    .impulses_hat
                    .iter()
                    .zip(&d.impulses_hat)
                    .chain(f.velocity.as_slice().iter().zip(d.velocity.as_slice()))
                    .chain([
                        (&f.lost_velocity_energy, &d.lost_velocity_energy),
                        (&f.kinetic_energy_loss, &d.kinetic_energy_loss),
                    ]);
                for (formula, dual) in pairs {
                    let exact = formula
                        .derivative("L")
                        .expect("differentiable")
                        .eval(&point)
                        .expect("a value");
                    let exact = inertance::number::rational_to_f64(&exact);
                    // The inputs' tangents are computed in f64 (a few roundings each) and the
                    // solve propagates them as it does values, within c·cond(G)·ε; G here has
                    // cond₂ < 10 and the outputs are of order 1, so 10⁻¹³ leaves a factor ~50.
                    let err = (dual.tangent - exact).abs();
                    assert!(
                        err <= 1e-13 * exact.abs().max(1.0),
                        "L = {at}, {model:?}: d/dL {} against {exact}",
                        dual.tangent
                    );
                }
            }
        }
    }

    #[test]
    fn sweeping_an_angle_parameter_in_degrees_gives_derivatives_per_degree() {
        let dir = std::env::temp_dir().join(format!("inertance-modelled-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("dir");
        let out = dir.join("theta.csv");
        let scene = path("tilted-box.world.toml");
        let run = inertance(&[
            "sweep",
            scene.to_str().expect("utf-8"),
            "--vary",
            "theta=10:60:6",
            "--sensitivity",
            "--out",
            out.to_str().expect("utf-8"),
        ]);
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let text = std::fs::read_to_string(&out).expect("csv");
        let _ = std::fs::remove_dir_all(&dir);
        let mut lines = text.lines();
        let header: Vec<&str> = lines.next().expect("header").split(',').collect();
        let col = |name: &str| header.iter().position(|h| *h == name).expect(name);
        let (th, p1, dp1) = (col("theta"), col("newton_P1"), col("d(newton_P1)/d(theta)"));
        for line in lines {
            let cells: Vec<&str> = line.split(',').collect();
            let num = |i: usize| cells[i].parse::<f64>().expect("a number");
            // The hand-derived closed form (derivations/modelled-tilted-box.md):
            // P1 = 51/(2D), D = 45c² − 24cs + 20, dP1/dθ = −51 D′/(2D²), D′ = −90cs − 24(c² − s²),
            // per degree: × π/180.
            let t = num(th).to_radians();
            let (c, s) = (t.cos(), t.sin());
            let d = 45.0 * c * c - 24.0 * c * s + 20.0;
            let dd = -90.0 * c * s - 24.0 * (c * c - s * s);
            assert!((num(p1) - 51.0 / (2.0 * d)).abs() < 1e-14);
            let per_degree = -51.0 * dd / (2.0 * d * d) * std::f64::consts::PI / 180.0;
            assert!((num(dp1) - per_degree).abs() < 1e-15, "{line}");
        }
    }
}

#[test]
fn a_thin_rod_needs_no_moment_about_its_axis() {
    // A rod of length 2 and mass 3 (J = mL²/12 = 1 across it), at 60° from the vertical, lands
    // on its lower end at 1 m/s, k = 1/2. By hand: the end is r = (−√3/2, 0, −1/2) from C, a unit
    // upward impulse changes its upward velocity by 1/m + r_x²/J = 1/3 + 3/4 = 13/12, so
    // P = (1 + k)·1/(13/12) = 18/13, and ω_y = −r_x P/J = 9√3/13.
    let rod = |point: &str| {
        format!(
            "[body]\nshape = {{ rod = 2 }}\nmass = 3\npose = {{ axis = [0, 1, 0], angle = \"60 deg\" }}\n\
             velocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n[[obstacle]]\nnormal = [0, 0, 1]\n\
             [[contact]]\nobstacle = 0\nbody_point = {point}\nk = 0.5\n"
        )
    };
    let scene = Scene::parse(&rod("[0, 0, -1]"), "rod.toml").expect("a valid scene");
    let mut a = assemble::<RatFun>(&scene).expect("assembles");
    let (o, _) = a.solve(Model::Newton).expect("solves");
    let q = |t: &str| RatFun::from_number(&parse_number(t).expect("n")).expect("exact");
    assert_eq!(o.impulses_hat[0], q("18/13"));
    assert_eq!(o.velocity.as_slice()[1], q("9*sqrt(3)/13"));
    // A contact with a moment about the axis cannot be taken by a body without one.
    let e = error(&rod("[0, 0.1, -1]"));
    assert_eq!(e.key, "contact[0]");
    assert!(
        e.message
            .contains("no moment of inertia about its own axis"),
        "{e}"
    );
    // Point masses on a line are the same: a dumbbell landing on its lower mass takes
    // P = (1 + k) m v = 2·3·1.
    let dumbbell = exact_json(
        "[body]\nshape = { points = [{ mass = 1, at = [0, 0, 1] }, { mass = 2, at = [0, 0, -2] }] }\n\
         velocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n[[obstacle]]\nnormal = [0, 0, 1]\n\
         [[contact]]\nobstacle = 0\nbody_point = [0, 0, -2]\nk = 1\n",
    );
    assert_eq!(dumbbell["models"]["newton"]["impulses"][0], "6");
}
