//! `analyze` and `sweep` on scenes of several bodies, against closed forms derived by hand
//! (not by the code under test):
//!
//! * **Newton's cradle of three equal balls** (mass m, radius 1, the striker at v, one
//!   coefficient k at both contacts). Each contact's axis acts on its two balls only, so with
//!   unit normals along x, G = [[2, −1], [−1, 2]]/m and v⁰ = (v, 0). Newton's law
//!   G P = (1 + k) v⁰ (eq. 19) gives P = (1 + k) m v (2/3, 1/3), and the balls' velocities
//!   after are v − P₁/m, (P₁ − P₂)/m, P₂/m = ((1 − 2k)/3, (1 + k)/3, (1 + k)/3) v. So
//!   ∂P₁/∂v = (2/3)(1 + k) m, exactly, for the sweep's sensitivities.
//! * `analyze` reports the same answer as `solve` on a system held by joints, body by body.

mod common;

use common::SceneFile;
use serde_json::Value as Json;

fn cradle(k: &str, v: &str) -> String {
    let ball = |name: &str, x: i64, v: &str| {
        format!(
            "[[body]]\nname = \"{name}\"\nshape = {{ sphere = 1 }}\nmass = 2\n\
             position = [{x}, 0, 0]\nvelocity = [{v}, 0, 0]\nangular_velocity = [0, 0, 0]\n"
        )
    };
    format!(
        "name = \"cradle\"\n{}{}{}\
         [[contact]]\nbodies = [\"striker\", \"middle\"]\npoint = [1, 0, 0]\nnormal = [1, 0, 0]\nk = \"{k}\"\n\
         [[contact]]\nbodies = [\"middle\", \"last\"]\npoint = [3, 0, 0]\nnormal = [1, 0, 0]\nk = \"{k}\"\n",
        ball("striker", 0, v),
        ball("middle", 2, "0"),
        ball("last", 4, "0")
    )
}

/// Two bars (mass 1, moment 1/3 about every axis through C), the upper pinned at (0, 1, 0), the
/// lower joined to it at (2, 1, 0), the lower's tip striking the floor at (4, 9/10, 0).
const BARS: &str = r#"
name = "two bars"
[[body]]
name = "upper"
mass = 1
inertia = ["1/3", "1/3", "1/3"]
position = [1, 1, 0]
velocity = [0, -1, 0]
angular_velocity = [0, 0, -1]
[[body]]
name = "lower"
mass = 1
inertia = ["1/3", "1/3", "1/3"]
position = [3, 1, 0]
velocity = [0, -3, 0]
angular_velocity = [0, 0, -1]
[[joint]]
kind = "revolute"
bodies = ["upper"]
anchor = [0, 1, 0]
axis = [0, 0, 1]
[[joint]]
kind = "revolute"
bodies = ["upper", "lower"]
anchor = [2, 1, 0]
axis = [0, 0, 1]
[[obstacle]]
name = "floor"
normal = [0, 1, 0]
[[contact]]
body = "lower"
obstacle = "floor"
point = [4, "9/10", 0]
k = "1/2"
"#;

fn json(out: &std::process::Output) -> Json {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

fn strings(v: &Json) -> Vec<String> {
    v.as_array()
        .expect("an array")
        .iter()
        .map(|x| x.as_str().expect("an exact value").to_string())
        .collect()
}

#[test]
fn analyze_gives_the_cradle_by_hand_and_says_the_last_contact_is_not_approaching() {
    // k = 1/2, m = 2, v = 1: P = (3/2)·2·(2/3, 1/3) = (2, 1); velocities (0, 1/2, 1/2).
    let scene = SceneFile::new("sys-analyze-cradle", &cradle("1/2", "1"));
    let a = json(&scene.run(&["analyze", "--exact", "--json"]));
    assert_eq!(
        a["bodies"],
        serde_json::json!(["striker", "middle", "last"])
    );
    assert_eq!(a["det"], "3/4");
    for model in ["newton", "poisson"] {
        let m = &a["models"][model];
        assert_eq!(strings(&m["impulses"]), ["2", "1"]);
        let twist = m["twist_after"].as_array().unwrap();
        let vx: Vec<String> = twist
            .iter()
            .map(|b| b["velocity"][0].as_str().unwrap().to_string())
            .collect();
        assert_eq!(vx, ["0", "1/2", "1/2"]);
        assert_eq!(twist[2]["name"], "last");
        // The second contact does not approach (v_2x⁰ = 0): the verdict says so.
        assert_eq!(m["admissible"][1]["approaching"], false);
        assert!(
            m["verdicts"]
                .as_array()
                .unwrap()
                .iter()
                .any(|v| v.as_str().unwrap().contains("A2 is not approaching")),
            "{m}"
        );
    }
}

#[test]
fn analyze_and_solve_agree_body_by_body_on_a_system_with_joints() {
    let scene = SceneFile::new("sys-analyze-bars", BARS);
    let a = json(&scene.run(&["analyze", "--exact", "--json"]));
    let s = json(&scene.run(&["solve", "--exact", "--json"]));
    for model in ["newton", "poisson"] {
        let from_analyze = a["models"][model]["twist_after"]
            .as_array()
            .unwrap()
            .clone();
        let from_solve = s["models"][model]["bodies"].as_array().unwrap();
        assert_eq!(from_analyze.len(), 2);
        for (x, y) in from_analyze.iter().zip(from_solve) {
            assert_eq!(x["name"], y["name"]);
            assert_eq!(x["velocity"], y["velocity"]);
            assert_eq!(x["angular_velocity"], y["angular_velocity"]);
        }
        assert_eq!(
            a["models"][model]["impulses"],
            s["models"][model]["impulses"]
        );
        assert_eq!(
            a["models"][model]["lost_velocity_energy"],
            s["models"][model]["lost_velocity_energy"]
        );
    }
    // Newton's law at the tip: v_x after = −k v_x⁰ = −(1/2)·4.
    assert_eq!(s["models"]["newton"]["contacts"][0]["velocity"][0], "-2");
}

#[test]
fn a_sweep_of_the_cradle_gives_the_closed_form_and_its_derivative_at_every_point() {
    // k = 1/2, m = 2, the striker's speed v varied: P = (2v, v), the last ball at v/2.
    let scene = SceneFile::new("sys-sweep-cradle", &cradle("1/2", "1"));
    let csv = scene.sweep(&[
        "--vary",
        "body[0].velocity[0]=1:3:5",
        "--exact",
        "--sensitivity",
    ]);
    for (r, v) in ["1", "3/2", "2", "5/2", "3"].iter().enumerate() {
        let v: num_rational::BigRational = v.parse().unwrap();
        let two = num_rational::BigRational::from_integer(2.into());
        let half = |x: num_rational::BigRational| x / &two;
        assert_eq!(
            csv.cell(r, "newton_P1_exact"),
            (two.clone() * &v).to_string()
        );
        assert_eq!(csv.cell(r, "newton_P2_exact"), v.to_string());
        let last: f64 = csv.cell(r, "newton_last.vCx").parse().unwrap();
        let expected = half(v.clone());
        assert_eq!(last, num_traits::ToPrimitive::to_f64(&expected).unwrap());
        // ∂P₁/∂v = (2/3)(1 + k) m = 2, exactly.
        assert_eq!(
            csv.cell(r, "d(newton_P1)/d(body[0].velocity[0])_exact"),
            "2"
        );
        assert_eq!(csv.cell(r, "status"), "ok");
    }
}

#[test]
fn a_sweep_names_a_body_that_does_not_exist() {
    let scene = SceneFile::new("sys-sweep-unknown", &cradle("1", "1"));
    let out = scene.run(&[
        "sweep",
        "--vary",
        "body[7].mass=1:2:2",
        "--out",
        scene.dir().join("x.csv").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("body[7]"), "{err}");
    assert!(!scene.dir().join("x.csv").exists());
}

#[test]
fn a_batch_of_the_cradle_gives_the_closed_form() {
    // Both coefficients k at each point: P = (1 + k) m v (2/3, 1/3), the balls after at
    // ((1 − 2k)/3, (1 + k)/3, (1 + k)/3) v (module docs), m = 2, v = 1.
    let doc: toml_edit::DocumentMut = cradle("1", "1").parse().unwrap();
    let ks = vec![0.0, 0.5, 1.0];
    let varied = ["contact[0].k", "contact[1].k"].map(|path| inertance::tools::sweep::Varied {
        path: path.into(),
        values: ks.clone(),
    });
    let b = inertance::tools::sweep::solve_batch(&doc, "cradle.toml", &varied, None).unwrap();
    assert_eq!(b.bodies, ["striker", "middle", "last"]);
    let w = b.outputs.len();
    let col = |name: &str| b.outputs.iter().position(|o| o == name).unwrap();
    for column in &b.values {
        for (p, k) in ks.iter().enumerate() {
            let row = &column[p * w..(p + 1) * w];
            let near = |x: f64, y: f64| (x - y).abs() <= 1e-14;
            assert!(near(row[col("P1")], (1.0 + k) * 2.0 * 2.0 / 3.0), "{row:?}");
            assert!(near(row[col("P2")], (1.0 + k) * 2.0 / 3.0), "{row:?}");
            assert!(
                near(row[col("striker.vCx")], (1.0 - 2.0 * k) / 3.0),
                "{row:?}"
            );
            assert!(near(row[col("last.vCx")], (1.0 + k) / 3.0), "{row:?}");
        }
    }
}

/// The cradle with its mass, speed and coefficient as symbols.
fn symbolic_cradle() -> String {
    cradle("k", "v")
        .replace("mass = 2", "mass = \"m\"")
        .replace("k = \"k\"", "k = \"k\"")
        .replacen(
            "name = \"cradle\"\n",
            "name = \"cradle\"\n[params]\nm = 2\nv = 1\nk = \"1/2\"\n",
            1,
        )
        .replace("velocity = [v, 0, 0]", "velocity = [\"v\", 0, 0]")
}

#[test]
fn derive_gives_the_cradle_in_closed_form_with_no_condition_on_the_speed() {
    let scene = SceneFile::new("sys-derive-cradle", &symbolic_cradle());
    let out = scene.run(&["derive", "--model", "newton"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // The closed forms of the module docs: P = (1 + k) m v (2/3, 1/3), the striker at
    // (1 − 2k)/3 v and the others at (1 + k)/3 v; E_p = (1 + k)² m v²/3 (eq. 28:
    // ½ Σ P_i (1 + k) v_ix⁰ / (1 + k) … written out: ½ (1 + k) P₁ v).
    for line in [
        "det = 3/m^2",
        "g12xx = -1/m",
        "newton.P1 = 2/3*m*v*(k + 1)",
        "newton.P2 = 1/3*m*v*(k + 1)",
        "newton.striker.vC[0] = -1/3*v*(2*k - 1)",
        "newton.middle.vC[0] = 1/3*v*(k + 1)",
        "newton.last.vC[0] = 1/3*v*(k + 1)",
        "newton.v1x = -k*v",
        "newton.Ep = 1/3*m*v^2*(k + 1)^2",
        "newton: energy identity ΔE_c = −E_p + Σ P_i v_ix⁰ (eq. 34) holds identically",
    ] {
        assert!(
            text.lines().any(|l| l.trim() == line),
            "no `{line}` in\n{text}"
        );
    }
    // A sign of v is never assumed: the formulas hold for a striker moving either way.
    assert!(!text.contains("v > 0"), "{text}");
}

#[test]
fn a_symbolic_twist_that_violates_a_joint_is_refused_naming_it() {
    // The upper bar's centre moves at −2w while it turns at −w about its pin one length away.
    let scene = SceneFile::new(
        "sys-derive-violated",
        &BARS
            .replace(
                "name = \"two bars\"",
                "name = \"two bars\"\n[params]\nw = 1",
            )
            .replace("velocity = [0, -1, 0]", "velocity = [0, \"-2*w\", 0]")
            .replace(
                "angular_velocity = [0, 0, -1]",
                "angular_velocity = [0, 0, \"-w\"]",
            ),
    );
    let out = scene.run(&["derive"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    // The pin's speed on the upper bar, v_C + ω × (P − C) = (0, −2w) + (−w e_z) × (−1, 0, 0)
    // = (0, −w), shown as an expression in w, never as NaN.
    assert!(
        err.contains("joint[0]") && err.contains("moves at (0, -w, 0) m/s") && !err.contains("NaN"),
        "{err}"
    );
}

#[test]
fn derive_refuses_a_system_under_the_unilateral_law_rather_than_derive_another() {
    let scene = SceneFile::new(
        "sys-derive-unilateral",
        &symbolic_cradle().replacen("[params]", "[solve]\nlaw = \"unilateral\"\n[params]", 1),
    );
    let out = scene.run(&["derive"]);
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        err.contains("solve.law") && err.contains("unilateral"),
        "{err}"
    );
}

/// `examples/box-on-box.toml` under the simultaneous law with k a symbol: the base's four
/// floor contacts act on three of its motions, so G (6 × 6) has rank 5 for every k and derive
/// gives the family, as for one body (§8). By hand (the example's comment and
/// derivations/systems.md): the base stays at rest and the top box rebounds as off a fixed
/// table, P = (1 + k) v / (2/m + 2d²/J_y) at each of its corners (v = 1, m = 2, d = 89/500,
/// J_y = 17/600), leaving at v_z = −1 + 2P/m, ω_y = −2Pd/J_y; the floor's impulses form a
/// one-parameter set along z = (0, 0, 1, −1, −1, 1) (the base's four corners, a couple that
/// moves nothing), and the twist is the same for every member.
#[test]
fn derive_gives_the_family_of_a_singular_system() {
    use num_rational::Rational64 as Q;
    let text = std::fs::read_to_string(format!(
        "{}/examples/box-on-box.toml",
        env!("CARGO_MANIFEST_DIR")
    ))
    .expect("the example")
    .replace("law = \"unilateral\"", "law = \"simultaneous\"")
    .replace("\nk = 0.5", "\nk = \"k\"")
    .replace("[solve]", "[params]\nk = \"1/2\"\n[solve]");
    let scene = SceneFile::new("sys-derive-singular", &text);
    let out = scene.run(&["derive"]);
    let printed = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let (m, d, j) = (Q::from(2), Q::new(89, 500), Q::new(17, 600));
    let p = Q::from(1) / (Q::from(2) / m + Q::from(2) * d * d / j); // per unit (1 + k)
    let omega = Q::from(2) * p * d / j;
    // v_z = −1 + 2P/m = (p₀ k + p₀ − 1) with p₀ = 2P/(m(1 + k)) = P/(1 + k) for m = 2, printed
    // over p₀'s denominator: (numer(p₀) k − c)/denom(p₀).
    let at_k0 = (Q::from(2) * p / m - Q::from(1)) * Q::from(*p.denom());
    let frac = |q: Q| format!("{}/{}", q.numer(), q.denom());
    for line in [
        "det = 0 identically: rank G = 5 of 6 for every value of the symbols (§8, eq. 61–68, 98–102)".to_string(),
        format!("newton.P1/|n1| = {}*(k + 1)", frac(p)),
        format!("newton.P2/|n2| = {}*(k + 1)", frac(p)),
        "z1 = [0, 0, 1, -1, -1, 1]".into(),
        "newton: the twist after impact and both energies are the same for every member of the family".into(),
        format!(
            "newton.top.twist (particular solution) = [0, -{}*(k + 1), 0, 1/2, 0, 1/{}*({}*k - {})]",
            frac(omega),
            p.denom(),
            p.numer(),
            -at_k0.to_integer()
        ),
        "newton.base.twist (particular solution) = [0, 0, 0, 0, 0, 0]".into(),
    ] {
        assert!(
            printed.lines().any(|l| l.trim() == line),
            "no `{line}` in\n{printed}"
        );
    }
    let json = scene.run(&["derive", "--json"]);
    let j: Json = serde_json::from_slice(&json.stdout).expect("JSON");
    assert_eq!(j["singular"]["rank"], 5);
    assert_eq!(j["singular"]["models"][0]["compatible_identically"], true);
}
