//! Sweeps over a scene's `[params]` write, byte for byte, the CSVs `main` wrote before the
//! reader remembered the names in the texts it reads back at every point
//! (`src/scene/model/params.rs`): over the tilted box's θ (in degrees, with and without
//! `--sensitivity`), a box's length and mass, a θ × length grid, a rational rotation with
//! `--exact` (and `--sensitivity`); and a point where the scene is invalid fails as it did.
//! The CSVs are in `tests/data/sweep-params/` (its README says where they come from).

use std::path::{Path, PathBuf};

use inertance::tools::sweep::{SweepOptions, Vary, sweep};

/// The directory of the scenes and CSVs.
fn data() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/sweep-params")
}

/// A scene: the tilted box of `examples/`, or one of the data directory's.
fn scene(name: &str) -> PathBuf {
    match name {
        "tilted-box.toml" => Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/tilted-box.toml"),
        _ => data().join(name),
    }
}

/// The CSV a sweep of `name` over `vary` writes (one thread, so that one thread reads every
/// point, each after the last).
fn swept(name: &str, vary: &[&str], exact: bool, sensitivity: bool, out: &str) -> Vec<u8> {
    let dir = std::env::temp_dir().join(format!("inertance-sweep-params-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join(out);
    let opts = SweepOptions {
        scene: scene(name),
        vary: vary.iter().map(|v| Vary::parse(v).unwrap()).collect(),
        out: out.clone(),
        exact,
        sensitivity,
        threads: Some(1),
        ..SweepOptions::default()
    };
    sweep(&opts).unwrap_or_else(|e| panic!("{name} {vary:?}: {e}"));
    let csv = std::fs::read(&out).unwrap();
    let _ = std::fs::remove_file(&out);
    csv
}

/// The sweep writes the CSV `main` wrote.
fn same_as_main(name: &str, vary: &[&str], exact: bool, sensitivity: bool, csv: &str) {
    let written = swept(name, vary, exact, sensitivity, csv);
    let expected = std::fs::read(data().join(csv)).unwrap();
    assert!(
        written == expected,
        "{name} {vary:?}: the CSV differs from tests/data/sweep-params/{csv}:\n{}",
        String::from_utf8_lossy(&written)
    );
}

#[test]
fn the_tilted_box_over_theta_in_degrees_writes_mains_csv() {
    same_as_main(
        "tilted-box.toml",
        &["theta=1:80:21"],
        false,
        false,
        "theta.csv",
    );
}

#[test]
fn the_tilted_box_over_theta_with_sensitivities_writes_mains_csv() {
    same_as_main(
        "tilted-box.toml",
        &["theta=1:80:9"],
        false,
        true,
        "theta-sens.csv",
    );
}

#[test]
fn a_parameter_of_the_shape_and_one_of_the_mass_write_mains_csvs() {
    same_as_main(
        "sized-box.toml",
        &["a=0.2:0.6:11"],
        false,
        false,
        "length.csv",
    );
    same_as_main("sized-box.toml", &["m=1:3:5"], false, true, "mass.csv");
}

#[test]
fn two_varied_parameters_write_mains_csv() {
    same_as_main(
        "sized-box.toml",
        &["theta=10:70:4", "a=0.2:0.6:3"],
        false,
        false,
        "grid.csv",
    );
}

#[test]
fn a_rational_rotation_swept_exactly_writes_mains_csvs() {
    same_as_main(
        "quaternion-box.toml",
        &["t=0.3:0.7:5"],
        true,
        false,
        "quat-exact.csv",
    );
    same_as_main(
        "quaternion-box.toml",
        &["t=0.3:0.7:3"],
        true,
        true,
        "quat-exact-sens.csv",
    );
}

/// u = 1/2 lays the box flat on four corners, two of them unnamed: the sweep stops at that
/// point with the message `main` gave, after the points on either side read as they did.
#[test]
fn a_point_where_the_scene_is_invalid_fails_as_it_did() {
    same_as_main("valley-box.toml", &["u=0:1:4"], false, false, "valley2.csv");
    let out = std::env::temp_dir().join(format!("inertance-valley-{}.csv", std::process::id()));
    let opts = SweepOptions {
        scene: scene("valley-box.toml"),
        vary: vec![Vary::parse("u=0:1:5").unwrap()],
        out: out.clone(),
        threads: Some(1),
        ..SweepOptions::default()
    };
    let e = sweep(&opts).expect_err("u = 1/2 lays the box flat");
    assert_eq!(e.exit_code(), 2, "{e}");
    let _ = std::fs::remove_file(&out);
    let file = scene("valley-box.toml").display().to_string();
    assert_eq!(
        e.to_string(),
        format!(
            "point 2 (u = 0.5): {file}: key `obstacle[0]`: the box touches obstacle \"floor\" at 4 \
             corners in this pose ([-1, -1, -1], [-1, 1, -1], [1, -1, -1], [1, 1, -1]), but the \
             contacts name 2 of them: the others would pass through the plane. Add a contact for \
             each missing corner (`corner = [-1, -1, -1]`, `corner = [-1, 1, -1]`), or set \
             `partial = true` on the obstacle if leaving them out is deliberate"
        )
    );
}
