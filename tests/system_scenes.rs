//! Scenes of several bodies with bad input get the usual treatment — status 2, and a message
//! that names the file, the key and the value and says what to do — and a scene of one body
//! written as `[[body]]` reads as the same scene written as `[body]`.
//!
//! Each case writes a scene, runs `inertance solve` on it and checks the exit status and
//! stderr: a contact between a body and itself, a contact or joint naming an unknown body, a
//! joint between a body and itself, a twist that breaks a joint, a contact point off one
//! body's surface (spheres, boxes), a normal that is not the surfaces' (crossing bodies), a box
//! resting on another at fewer named corners than touch, `[[joint]]` in a one-body scene.

mod common;

use common::SceneFile;
use serde_json::Value;

/// Two spheres of radius 1/2 touching at (1/2, 0, 0), the first moving into the second; the
/// contact and extra tables are the case's.
fn two_spheres(contact: &str, extra: &str) -> String {
    format!(
        r#"
name = "two spheres"
[[body]]
name = "a"
shape = {{ sphere = 0.5 }}
mass = 1
velocity = [1, 0, 0]
angular_velocity = [0, 0, 0]
[[body]]
name = "b"
shape = {{ sphere = 0.5 }}
mass = 1
position = [1, 0, 0]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
{contact}
normal = [1, 0, 0]
k = 1
{extra}
"#
    )
}

/// Run `inertance solve FILE --exact` on `text`: (status, stderr).
fn solve(name: &str, text: &str) -> (i32, String) {
    let scene = SceneFile::new(name, text);
    let out = scene.run(&["solve", "--exact"]);
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The scene is refused as bad input (status 2) with a message naming `key` with its `value`
/// (as `key `KEY` = VALUE`, the value as written or its start) and saying each of `says`.
fn refused(name: &str, text: &str, key: &str, value: Option<&str>, says: &[&str]) {
    let (status, stderr) = solve(name, text);
    assert_eq!(status, 2, "{name}: {stderr}");
    assert!(
        stderr.contains("scene.toml"),
        "{name}: the file is named: {stderr}"
    );
    let named = match value {
        Some(v) => format!("key `{key}` = {v}"),
        None => format!("key `{key}`:"),
    };
    assert!(
        stderr.contains(&named),
        "{name}: expected {named:?} in {stderr}"
    );
    for s in says {
        assert!(stderr.contains(s), "{name}: expected {s:?} in {stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
}

#[test]
fn a_contact_between_a_body_and_itself_is_refused() {
    refused(
        "self-contact",
        &two_spheres("bodies = [\"a\", \"a\"]\npoint = [0.5, 0, 0]", ""),
        "contact[0].bodies",
        Some("[\"a\", \"a\"]"),
        &["joins a body to itself", "name two different bodies"],
    );
}

#[test]
fn a_contact_naming_an_unknown_body_is_refused() {
    refused(
        "unknown-contact-body",
        &two_spheres("bodies = [\"a\", \"c\"]\npoint = [0.5, 0, 0]", ""),
        "contact[0].bodies[1]",
        Some("\"c\""),
        &["no such body", "the scene has: a, b"],
    );
    // The obstacle form names its body with `body`.
    let text = two_spheres(
        "bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]",
        "[[obstacle]]\nname = \"floor\"\nnormal = [0, 0, 1]\npoint = [0, 0, -0.5]\n[[contact]]\nbody = \"ghost\"\nobstacle = \"floor\"\npoint = [0, 0, -0.5]\nk = 0",
    );
    refused(
        "unknown-obstacle-body",
        &text,
        "contact[1].body",
        Some("\"ghost\""),
        &["no such body", "the scene has: a, b"],
    );
}

#[test]
fn a_joint_naming_an_unknown_body_is_refused() {
    let joint = "[[joint]]\nkind = \"spherical\"\nbodies = [\"a\", \"zz\"]\nanchor = [0.5, 0, 0]";
    refused(
        "unknown-joint-body",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", joint),
        "joint[0].bodies[1]",
        Some("\"zz\""),
        &["no such body", "the scene has: a, b"],
    );
}

#[test]
fn a_joint_between_a_body_and_itself_is_refused() {
    let joint = "[[joint]]\nkind = \"spherical\"\nbodies = [\"b\", \"b\"]\nanchor = [0.5, 0, 0]";
    refused(
        "self-joint",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", joint),
        "joint[0].bodies",
        Some("[\"b\", \"b\"]"),
        &["joins a body to itself"],
    );
}

/// A ball joint at the contact point between a moving and a resting sphere: their twists
/// separate the joint. The message says how each body moves at the anchor and which keys to
/// change; a hinge to the ground whose anchor moves, likewise.
#[test]
fn a_twist_that_breaks_a_joint_is_refused_saying_how_the_bodies_move() {
    let joint = "[[joint]]\nkind = \"spherical\"\nbodies = [\"a\", \"b\"]\nanchor = [0.5, 0, 0]";
    refused(
        "twist-breaks-joint",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", joint),
        "joint[0]",
        Some("{ kind = \"spherical\", bodies = [\"a\", \"b\"] }"),
        &[
            "break this spherical joint",
            "at its anchor (1/2, 0, 0), \"a\" moves at (1, 0, 0) m/s and \"b\" at (0, 0, 0) m/s",
            "`body[0].velocity`",
            "`body[1].velocity`",
        ],
    );
    let hinge =
        "[[joint]]\nkind = \"revolute\"\nbodies = [\"a\"]\nanchor = [0, 0, 1]\naxis = [0, 0, 1]";
    refused(
        "twist-breaks-hinge",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", hinge),
        "joint[0]",
        Some("{ kind = \"revolute\", bodies = [\"a\"] }"),
        &[
            "break this revolute joint",
            "\"a\" moves at (1, 0, 0) m/s and the ground at (0, 0, 0) m/s",
            "`body[0].angular_velocity`",
        ],
    );
}

#[test]
fn a_contact_point_off_a_spheres_surface_is_refused() {
    // Inside the first sphere (0.4 from its centre).
    refused(
        "inside-sphere",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.4, 0, 0]", ""),
        "contact[0].point",
        Some("[0.4, 0, 0]"),
        &[
            "not on the surface of body \"a\"",
            "0.400000 m from the sphere's centre, whose radius is 1/2 m",
            "`body[0].position`",
        ],
    );
    // On the first sphere but off the second: a's surface at (0, 0.5, 0), 1.118 m from b's centre.
    refused(
        "off-second-sphere",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0, 0.5, 0]", ""),
        "contact[0].point",
        Some("[0, 0.5, 0]"),
        &[
            "not on the surface of body \"b\"",
            "1.118034 m",
            "`body[1].position`",
        ],
    );
}

/// Two spheres of radius 1/2 whose centres are 0.8 apart cross each other: (0.4, 0.3, 0) lies
/// on both surfaces (their circle of intersection), but their surface normals there differ, so
/// no normal fits both; and a normal that is not the spheres' common normal at their touching
/// point is refused too.
#[test]
fn a_contact_normal_off_the_surface_normal_is_refused() {
    let crossing = two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.4, 0.3, 0]", "")
        .replace("position = [1, 0, 0]", "position = [0.8, 0, 0]");
    refused(
        "crossing-spheres",
        &crossing,
        "contact[0].normal",
        Some("[1, 0, 0]"),
        &[
            "not the surface normal of body \"a\"",
            "faces (2/5, 3/10, 0)",
            "cross each other",
        ],
    );
    // The normal along a's surface normal there: b's differs.
    refused(
        "crossing-spheres-b",
        &crossing.replace("normal = [1, 0, 0]", "normal = [0.8, 0.6, 0]"),
        "contact[0].normal",
        Some("[0.8, 0.6, 0]"),
        &[
            "not the surface normal of body \"b\"",
            "faces (-2/5, 3/10, 0)",
        ],
    );
    refused(
        "tilted-normal",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", "")
            .replace("normal = [1, 0, 0]", "normal = [1, 1, 0]"),
        "contact[0].normal",
        Some("[1, 1, 0]"),
        &["not the surface normal of body \"a\""],
    );
    // Pointing into the first body.
    refused(
        "reversed-normal",
        &two_spheres("bodies = [\"a\", \"b\"]\npoint = [0.5, 0, 0]", "")
            .replace("normal = [1, 0, 0]", "normal = [-1, 0, 0]"),
        "contact[0].normal",
        Some("[-1, 0, 0]"),
        &["points out of the first body into the second"],
    );
}

/// A box above a larger slab, the box placed at `z` (its bottom face at z − 0.1; the slab's
/// top face at 0.1), with a contact at each of `corners` of the box.
fn box_on_slab(z: &str, corners: &[&str]) -> String {
    let mut text = format!(
        r#"
name = "box on a slab"
[[body]]
name = "box"
shape = {{ box = [0.4, 0.2, 0.2] }}
mass = 1
position = [0, 0, {z}]
velocity = [0, 0, -1]
angular_velocity = [0, 0, 0]
[[body]]
name = "slab"
shape = {{ box = [1, 1, 0.2] }}
mass = 1
velocity = [0, 0, 0]
angular_velocity = [0, 0, 0]
"#
    );
    for c in corners {
        text.push_str(&format!(
            "[[contact]]\nbodies = [\"box\", \"slab\"]\ncorner = {c}\nnormal = [0, 0, -1]\nk = 1\n"
        ));
    }
    text
}

#[test]
fn a_contact_point_off_a_boxs_surface_is_refused() {
    refused(
        "inside-box",
        &box_on_slab("0.15", &["[1, 1, -1]"]),
        "contact[0].corner",
        Some("[1, 1, -1]"),
        &[
            "not on the surface of body \"slab\"",
            "it is at (1/5, 1/10, 1/20), inside, between the faces at ±(1/2, 1/2, 1/10)",
            "`body[1].position`",
        ],
    );
    refused(
        "outside-box",
        &box_on_slab("0.25", &["[1, 1, -1]"]),
        "contact[0].corner",
        Some("[1, 1, -1]"),
        &["not on the surface of body \"slab\"", "outside the faces"],
    );
}

/// A box resting flat on another body touches it at four corners, as it would an obstacle:
/// naming fewer is refused, naming the missing ones; naming all four is read and solved (under
/// the unilateral law: four contacts on three relative motions make G singular).
#[test]
fn a_box_resting_on_a_box_must_name_every_touching_corner() {
    refused(
        "one-corner-of-four",
        &box_on_slab("0.2", &["[1, 1, -1]"]),
        "contact[0]",
        None,
        &[
            "the box \"box\" touches \"slab\" at 4 corners in this pose",
            "name 1 of them",
            "at the others ([-1, -1, -1], [-1, 1, -1], [1, -1, -1]) it would pass through \"slab\"",
            "`corner = [-1, -1, -1]`",
        ],
    );
    let all = ["[1, 1, -1]", "[1, -1, -1]", "[-1, 1, -1]", "[-1, -1, -1]"];
    let scene = SceneFile::new("four-corners", &box_on_slab("0.2", &all));
    let out = scene.run(&["solve", "--exact", "--law", "unilateral"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn joint_tables_in_a_one_body_scene_are_refused() {
    let text = r#"
name = "one ball"
[body]
shape = { sphere = 0.5 }
mass = 1
velocity = [0, 0, -1]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
[[contact]]
obstacle = "floor"
point = [0, 0, -0.5]
k = 1
[[joint]]
kind = "revolute"
bodies = ["ball"]
anchor = [0, 0, 0]
axis = [0, 0, 1]
"#;
    refused(
        "joint-one-body",
        text,
        "joint",
        Some("[{ kind = \"revolute\", bodies = [\"ball\"]"),
        &[
            "[[joint]] tables join the bodies of a scene of several [[body]] tables",
            "[[constraints.joint]]",
        ],
    );
}

// ------------------------------------------------------------------------------------------
// One body as [[body]] is the [body] scene.

/// A box tilted about y by the rational rotation of the quaternion (7, 0, 1, 0), spinning,
/// landing on two corners with different coefficients: `[body]` or `[[body]]` (with `body =`
/// on each contact).
fn tilted_box(system: bool) -> String {
    box_at(system, "[0.1, 0.2, 0.3]", "[7, 0, 1, 0]", "0.3 - 13/125")
}

/// The box of [`tilted_box`] with its centre at `position`, its `pose` quaternion, and the
/// floor at height `floor` under the two corners (`partial` when the box is flat: it would
/// touch at four, and the scene names two deliberately).
fn box_at(system: bool, position: &str, quaternion: &str, floor: &str) -> String {
    let partial = if quaternion == "[1, 0, 0, 0]" {
        "partial = true"
    } else {
        ""
    };
    let (header, on) = if system {
        ("[[body]]\nname = \"box\"", "body = \"box\"\n")
    } else {
        ("[body]", "")
    };
    format!(
        r#"
name = "tilted box"
{header}
shape = {{ box = [0.4, 0.2, 0.1] }}
mass = 2
pose = {{ quaternion = {quaternion} }}
position = {position}
velocity = [0.5, 0.25, -1]
angular_velocity = [1, -2, 0.5]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
point = [0, 0, "{floor}"]
{partial}
[[contact]]
{on}obstacle = "floor"
corner = [1, 1, -1]
k = 0.5
[[contact]]
{on}obstacle = "floor"
corner = [1, -1, -1]
k = 0.25
"#
    )
}

fn report(name: &str, text: &str, args: &[&str]) -> Value {
    let scene = SceneFile::new(name, text);
    let mut all = vec!["solve"];
    all.extend(args);
    all.push("--json");
    let out = scene.run(&all);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

/// The numbers of the two reports that mean the same thing, side by side: (what, single,
/// system).
fn pairs<'a>(single: &'a Value, system: &'a Value) -> Vec<(String, &'a Value, &'a Value)> {
    let mut v = vec![
        (
            "inertance".to_string(),
            &single["inertance"],
            &system["inertance"],
        ),
        ("det".to_string(), &single["det"], &system["det"]),
    ];
    for model in ["newton", "poisson"] {
        let (a, b) = (&single["models"][model], &system["models"][model]);
        let body = &b["bodies"][0];
        for (what, x, y) in [
            ("impulses", &a["impulses"], &b["impulses"]),
            ("velocity", &a["velocity"], &body["velocity"]),
            (
                "angular_velocity",
                &a["angular_velocity"],
                &body["angular_velocity"],
            ),
            (
                "lost_velocity_energy",
                &a["lost_velocity_energy"],
                &b["lost_velocity_energy"],
            ),
            (
                "kinetic_energy_loss",
                &a["kinetic_energy_loss"],
                &b["kinetic_energy_loss"],
            ),
            ("admissible", &a["admissible"], &b["admissible"]),
        ] {
            v.push((format!("{model}.{what}"), x, y));
        }
        for i in 0..2 {
            v.push((
                format!("{model}.contact[{i}].velocity_after"),
                &a["contacts"][i]["velocity_after"],
                &b["contacts"][i]["velocity"],
            ));
        }
    }
    v
}

#[test]
fn one_body_written_as_a_system_reads_exactly_as_the_one_body_scene() {
    for law in ["simultaneous", "unilateral"] {
        let args = ["--exact", "--law", law];
        let single = report("one-body-single", &tilted_box(false), &args);
        let system = report("one-body-system", &tilted_box(true), &args);
        assert_eq!(single["axes"], "world");
        for (what, a, b) in pairs(&single, &system) {
            assert!(!a.is_null(), "{what} missing in the one-body report");
            assert_eq!(a, b, "{law}: {what}");
        }
    }
}

/// The same in f64, bit for bit, for a body whose centre is the world origin, posed (a full
/// inertia tensor in world axes: both take the general code) or not (both take the small-N
/// float lane, `Mechanism::lane_body`; before a one-body system did, Δ differed in the last
/// bits).
#[test]
fn one_body_at_the_origin_written_as_a_system_reads_as_the_one_body_scene_bit_for_bit_in_f64() {
    for (quaternion, floor) in [("[1, 0, 0, 0]", "-1/20"), ("[7, 0, 1, 0]", "-13/125")] {
        let (single, system) = (
            box_at(false, "[0, 0, 0]", quaternion, floor),
            box_at(true, "[0, 0, 0]", quaternion, floor),
        );
        let single = report("origin-single-f64", &single, &[]);
        let system = report("origin-system-f64", &system, &[]);
        for (what, a, b) in pairs(&single, &system) {
            assert!(!a.is_null(), "{what} missing in the one-body report");
            assert_eq!(a, b, "pose {quaternion}: {what}");
        }
    }
}

/// And away from the origin, posed or not: both scenes form each lever arm A_i − C exactly
/// from the scene's numbers and round it once (`SystemSpec::levers`,
/// `System::with_lever_arms`). Before, a system formed it in f64 from its rounded world point
/// and centre, one more rounding, and Ĝ's g₁₁ read 2.7476988235294124 against the one-body
/// scene's 2.747698823529412.
#[test]
fn one_body_away_from_the_origin_written_as_a_system_reads_as_the_one_body_scene_bit_for_bit_in_f64()
 {
    let cases = [
        ("[0.1, 0.2, 0.3]", "[7, 0, 1, 0]", "0.3 - 13/125"),
        ("[0.1, 0.2, 0.3]", "[1, 0, 0, 0]", "0.3 - 1/20"),
        ("[-1.7, 3.1, 0.7]", "[7, 0, 1, 0]", "0.7 - 13/125"),
        (r#"[1e3, -2.5e2, "1/3"]"#, "[7, 0, 1, 0]", "1/3 - 13/125"),
    ];
    for (position, quaternion, floor) in cases {
        let single = report(
            "away-single-f64",
            &box_at(false, position, quaternion, floor),
            &[],
        );
        let system = report(
            "away-system-f64",
            &box_at(true, position, quaternion, floor),
            &[],
        );
        for (what, a, b) in pairs(&single, &system) {
            assert!(!a.is_null(), "{what} missing in the one-body report");
            assert_eq!(a, b, "at {position}, pose {quaternion}: {what}");
        }
    }
}
