//! Issue 28, items 3 and 7: half the touching corners, and a top corner blamed on the normal.
//!
//! A box lying flat on a floor with only two of its four touching corners named solved with
//! status 0 (ω_x = −22.6 rad/s while the centre kept going down into the floor); the README's own
//! sweep of the tilted box hit it at θ = 0. Whenever a box touches an obstacle along an edge or
//! a face, every touching corner must now be a contact, or the obstacle says `partial = true`;
//! the refusal lists the missing ones by their `corner` key. And a top corner of a resting box
//! was reported as "the body is on the wrong side of obstacle … flip its sign" though the
//! normal was right: the message now says which corners can touch first.
//!
//! Checked against the closed form of a box dropped flat on its four corners (symmetric: it
//! rises at k v without turning, the impulses summing to (1 + k) m v), exactly.

mod common;

use common::SceneFile;

/// A 0.4 × 0.2 × 0.1 m box of 2 kg lying flat, dropped at 1 m/s, k = 1/2; `{contacts}` and
/// `{partial}` filled in by each test.
fn flat_box(contacts: &[[i64; 3]], extra_obstacle_keys: &str) -> String {
    let mut s = format!(
        "name = \"flat box\"\n[params]\ntheta = \"0 deg\"\n[body]\nshape = {{ box = [0.4, 0.2, 0.1] }}\nmass = 2\n\
         pose = {{ axis = [0, 1, 0], angle = \"theta\" }}\nvelocity = [0, 0, -1]\n\
         angular_velocity = [0, 0, 0]\n[[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\n{extra_obstacle_keys}\n"
    );
    for c in contacts {
        s += &format!(
            "[[contact]]\nobstacle = \"floor\"\ncorner = [{}, {}, {}]\nk = 0.5\n",
            c[0], c[1], c[2]
        );
    }
    s
}

const BOTTOM: [[i64; 3]; 4] = [[1, -1, -1], [1, 1, -1], [-1, -1, -1], [-1, 1, -1]];

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

#[test]
fn a_flat_box_with_two_of_four_corners_named_is_refused_naming_the_missing_ones() {
    let s = SceneFile::new("corners-half", &flat_box(&BOTTOM[..2], ""));
    for args in [&["solve"][..], &["solve", "--exact"], &["analyze"]] {
        let out = s.run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(out.stdout.is_empty());
        assert!(
            err.contains("obstacle[0]")
                && err.contains("at 4 corners")
                && err.contains("name 2 of them")
                && err.contains("`corner = [-1, -1, -1]`, `corner = [-1, 1, -1]`")
                && err.contains("partial = true"),
            "{err}"
        );
    }
}

/// The four corners of a flat box: G has rank 3 (three motions, z, ωx, ωy, for four
/// contacts), so the simultaneous law is singular and the unilateral law answers: the box rises
/// at k v = 1/2 m/s without turning, the impulses summing to (1 + k) m v = 3 N s (their split
/// is one of a family).
fn assert_symmetric_rebound(j: &serde_json::Value) {
    for model in ["newton", "poisson"] {
        let m = &j["models"][model];
        assert_eq!(
            m["angular_velocity"],
            serde_json::json!(["0", "0", "0"]),
            "{model}"
        );
        assert_eq!(
            m["velocity"],
            serde_json::json!(["0", "0", "1/2"]),
            "{model}"
        );
        let sum: num_rational::BigRational = m["impulses"]
            .as_array()
            .expect("impulses")
            .iter()
            .map(|p| {
                p.as_str()
                    .expect("exact")
                    .parse::<num_rational::BigRational>()
                    .expect("a fraction")
            })
            .sum();
        assert_eq!(
            sum,
            num_rational::BigRational::from_integer(3.into()),
            "{model}"
        );
    }
}

#[test]
fn every_touching_corner_named_gives_the_symmetric_closed_form() {
    let s = SceneFile::new("corners-all", &flat_box(&BOTTOM, ""));
    assert_symmetric_rebound(&json(&s.run(&[
        "solve",
        "--exact",
        "--json",
        "--law",
        "unilateral",
    ])));
    // The simultaneous law says why it cannot answer (Δ = 0), not a wrong number.
    assert_eq!(s.run(&["solve", "--exact"]).status.code(), Some(3));
}

#[test]
fn partial_true_says_the_omission_is_deliberate() {
    let s = SceneFile::new("corners-partial", &flat_box(&BOTTOM[..2], "partial = true"));
    let j = json(&s.run(&["solve", "--exact", "--json"]));
    assert_eq!(
        j["models"]["newton"]["impulses"].as_array().map(Vec::len),
        Some(2)
    );
    let bad = SceneFile::new(
        "corners-partial-bad",
        &flat_box(&BOTTOM[..2], "partial = \"yes\""),
    );
    let out = bad.run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.contains("obstacle[0].partial") && err.contains("true or false"),
        "{err}"
    );
}

#[test]
fn an_edge_landing_with_one_of_its_two_corners_named_is_refused() {
    // Tilted by 30° about y the box stands on its edge x = +a/2, z = −c/2: two corners touch.
    let s = SceneFile::new("corners-edge", &flat_box(&BOTTOM[..1], ""));
    let out = s.run(&["solve", "--param", "theta=30"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("at 2 corners") && err.contains("`corner = [1, 1, -1]`"),
        "{err}"
    );
    // Both named: the edge landing solves.
    let both = SceneFile::new("corners-edge-both", &flat_box(&BOTTOM[..2], ""));
    json(&both.run(&["solve", "--json", "--param", "theta=30"]));
}

#[test]
fn the_readme_tilted_box_at_zero_degrees_is_refused() {
    let s = SceneFile::new(
        "corners-readme",
        include_str!("../examples/tilted-box.toml"),
    );
    let out = s.run(&["solve", "--param", "theta=0"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("at 4 corners"), "{err}");
}

#[test]
fn a_corner_given_by_its_world_point_counts_as_named() {
    // The two far corners as world points (+/-0.2, +/-0.1, -0.05) instead of `corner`.
    let mut text = flat_box(&BOTTOM[..2], "");
    for y in ["-0.1", "0.1"] {
        text +=
            &format!("[[contact]]\nobstacle = \"floor\"\npoint = [-0.2, {y}, -0.05]\nk = 0.5\n");
    }
    let s = SceneFile::new("corners-world-points", &text);
    assert_symmetric_rebound(&json(&s.run(&[
        "solve",
        "--exact",
        "--json",
        "--law",
        "unilateral",
    ])));
}

#[test]
fn a_top_corner_is_named_as_the_corner_that_cannot_touch() {
    let mut corners = BOTTOM.to_vec();
    corners.push([1, 1, 1]);
    let s = SceneFile::new("corners-top", &flat_box(&corners, ""));
    let out = s.run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    // The corners that can touch come first; the flipped normal is the second explanation.
    let can = err
        .find("the corners that can touch it in this pose are")
        .expect("listed");
    let flip = err.find("flip its sign").expect("the other explanation");
    assert!(can < flip, "{err}");
    assert!(
        err.contains("contact[4].obstacle")
            && err.contains("[-1, -1, -1], [-1, 1, -1], [1, -1, -1], [1, 1, -1]"),
        "{err}"
    );
}
