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
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/modelled").join(name)
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
        .map(|i| {
            r[i][0].clone() * &v[0] + r[i][1].clone() * &v[1] + r[i][2].clone() * &v[2]
        })
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
    assert_eq!(in_world.problem().contacts().len(), in_body.problem().contacts().len());
    for model in [Model::Newton, Model::Poisson] {
        let (w, _) = in_world.solve(model).expect("solves");
        let (b, _) = in_body.solve(model).expect("solves");
        assert_eq!(w.impulses_hat, b.impulses_hat, "{pair} {model:?}: impulses");
        assert_eq!(w.compression_hat, b.compression_hat, "{pair} {model:?}");
        assert_eq!(w.lost_velocity_energy, b.lost_velocity_energy, "{pair} {model:?}: E_p");
        assert_eq!(w.kinetic_energy_loss, b.kinetic_energy_loss, "{pair} {model:?}: ΔE_c");
        let bs = b.velocity.as_slice();
        let (top, bottom) = (rotate(&r, &bs[0..3]), rotate(&r, &bs[3..6]));
        let expected = Screw::new(Vec3::from_column_slice(&top), Vec3::from_column_slice(&bottom));
        assert_eq!(w.velocity, expected, "{pair} {model:?}: twist after = R · body twist");
    }
}

#[test]
fn the_planar_bar_in_the_world_equals_example_3_in_rationals() {
    same_physics::<Exact>("planar-bar", [["0", "1", "0"], ["0", "0", "-1"], ["-1", "0", "0"]]);
}

#[test]
fn the_ball_in_the_corner_against_two_walls_equals_example_8() {
    let id = [["1", "0", "0"], ["0", "1", "0"], ["0", "0", "1"]];
    same_physics::<Exact>("ball-in-corner", id);
}

#[test]
fn the_tilted_box_on_a_floor_equals_its_hand_rotated_scene_in_exact_radicals() {
    let c = "cos(30 deg)";
    same_physics::<RatFun>("tilted-box", [[c, "0", "1/2"], ["0", "1", "0"], ["-1/2", "0", c]]);
}
