//! The unilateral law and the admissibility of simultaneous answers, end to end through the
//! binary: no inadmissible number is printed without a warning; `--law unilateral` gives the
//! physical answer, checked against values derived by hand; a jammed body is a verdict.

mod common;

use common::SceneFile as Scene;
use std::process::{Command, Output};

/// The paper's Example 3 with the bar pitching at ω_z = 0.7 rad/s: v_1x⁰ = 3 + 2·0.7 = 4.4,
/// v_2x⁰ = 3 − 4·0.7 = 0.2 — both approach, yet the simultaneous Newton answer pulls at A₂.
const PITCHING: &str = r#"
name = "bar pitching on two supports"
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.7]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
k = 0.2
"#;

/// A body squeezed at one point between two walls with opposite normals, driven into the
/// first: with k > 0 the law asks it to bounce back into the second wall, which no P ≥ 0 can
/// do (w₁ + w₂ = −k v⁰ < 0 for every P: the LCP is infeasible).
const JAMMED: &str = r#"
name = "jammed"
[body]
mass = 1
inertia = [1, 1, 1]
velocity = [1, 0, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = [0, 0, 0]
normal = [1, 0, 0]
k = 0.5
[[contact]]
point = [0, 0, 0]
normal = [-1, 0, 0]
k = 0.5
"#;

fn stdout_json(out: &Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

#[test]
fn a_tensile_simultaneous_answer_is_never_silent() {
    let s = Scene::new("unilateral-tensile", PITCHING);
    for exact in [false, true] {
        let args: &[&str] = if exact {
            &["solve", "--exact", "--json"]
        } else {
            &["solve", "--json"]
        };
        let out = s.run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(0), "documented: warnings, status 0");
        assert!(
            err.contains("warning") && err.contains("contact 2 takes a tensile impulse"),
            "{err}"
        );
        assert!(err.contains("--law unilateral"), "{err}");
        let j = stdout_json(&out);
        let newton = &j["models"]["newton"];
        assert_eq!(newton["law"], "simultaneous");
        assert_eq!(newton["admissible"], false);
        assert_eq!(newton["inadmissible"][0]["reason"], "tensile");
        assert_eq!(newton["inadmissible"][0]["contact"], 1);
        if exact {
            // eq. 20 by hand: G = [[4/3, 1/3], [1/3, 7/3]], b = (1.3·4.4, 1.2·0.2) = (5.72, 0.24);
            // P₂ = (4/3·0.24 − 1/3·5.72)/3 = −119/225.
            assert_eq!(newton["impulses"][1], "-119/225");
        }
    }
    // The admissible Example 3 (ω_z = 0.4) has no warning.
    let ok = Scene::new("unilateral-ok", &PITCHING.replace("0.7]", "0.4]"));
    let out = ok.run(&["solve"]);
    assert!(
        out.status.success() && out.stderr.is_empty(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

#[test]
fn the_unilateral_law_gives_the_physical_answer() {
    let s = Scene::new("unilateral-unilateral", PITCHING);
    let j = stdout_json(&s.run(&["solve", "--exact", "--json", "--law", "unilateral"]));
    assert!(
        j["effects"]
            .as_array()
            .unwrap()
            .contains(&"unilateral".into())
    );
    for model in ["newton", "poisson"] {
        let m = &j["models"][model];
        assert_eq!(m["law"], "unilateral");
        assert_eq!(m["active"], serde_json::json!([true, false]), "{model}");
        assert_eq!(m["impulses_unique"], true);
        // Only A₁ acts: Newton P₁ = (1 + k₁) v_1x⁰ / g₁₁ = 1.3·4.4·3/4 = 429/100; Poisson
        // P₁ = (1 + k₁) P₁ᶜ with P₁ᶜ = v_1x⁰ / g₁₁ = 33/10 — the same here (one contact).
        assert_eq!(
            m["impulses"],
            serde_json::json!(["429/100", "0"]),
            "{model}"
        );
        // A₂ leaves: v_2x = v_2x⁰ − g₂₁ P₁ = 1/5 − 429/300 = −123/100 < 0.
        assert_eq!(m["contacts"][1]["velocity_after"][0], "-123/100");
        assert_eq!(m["admissible"], true);
    }
    // The scene key does the same as the flag, and the table says who separates.
    let keyed = Scene::new(
        "keyed",
        &format!("{PITCHING}[solve]\nlaw = \"unilateral\"\n"),
    );
    let out = keyed.run(&["solve"]);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success() && out.stderr.is_empty());
    assert!(
        table.contains("separates") && table.contains("active"),
        "{table}"
    );
}

#[test]
fn a_jammed_body_is_a_verdict_not_a_number() {
    let s = Scene::new("unilateral-jammed", JAMMED);
    for args in [
        &["solve", "--law", "unilateral", "--model", "newton"][..],
        &[
            "solve",
            "--law",
            "unilateral",
            "--model",
            "newton",
            "--exact",
        ],
    ] {
        let out = s.run(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(3), "{err}");
        assert!(out.stdout.is_empty());
        assert!(
            err.contains("no admissible impulses") && err.contains("jam"),
            "{err}"
        );
    }
    // With both models, Poisson (never jammed) answers and Newton's jam is named beside it:
    // status 4 (tests/regression_jam_hides_other_model.rs).
    let out = s.run(&["solve", "--law", "unilateral"]);
    assert_eq!(out.status.code(), Some(4));
    assert!(String::from_utf8_lossy(&out.stdout).contains("newton: no answer"));
    // Simultaneously it is singular (coincident points, opposite normals): exit 3 pointing to
    // analyze and to the unilateral law.
    let out = s.run(&["solve"]);
    assert_eq!(out.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--law unilateral"));
}

#[test]
fn the_obstacles_normal_given_by_mistake_gets_a_hint() {
    // Example 3 with both normals reversed: every contact separates before impact.
    let s = Scene::new(
        "reversed",
        &PITCHING
            .replace("0.7]", "0.4]")
            .replace("normal = [1, 0, 0]", "normal = [-1, 0, 0]"),
    );
    let out = s.run(&["solve", "--law", "unilateral"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success());
    assert!(
        err.contains("every contact is separating") && err.contains("outward normal"),
        "{err}"
    );
}

#[test]
fn analyze_shows_the_unilateral_resolution_and_exits_2_on_bad_input() {
    let s = Scene::new("unilateral-analyze", PITCHING);
    let out = s.run(&["analyze", "--exact"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(out.status.success());
    assert!(
        text.contains("unilateral newton") && text.contains("A2: separates, P2 = 0"),
        "{text}"
    );
    let j = stdout_json(&s.run(&["analyze", "--exact", "--json"]));
    assert_eq!(
        j["models"]["newton"]["unilateral"]["impulses"],
        serde_json::json!(["429/100", "0"])
    );
    // A tangent not perpendicular to its normal is bad input (2), naming the key.
    let skew = Scene::new(
        "skew",
        &PITCHING.replacen("k = 0.2", "tangent = [1, 1, 0]\nk = 0.2", 1),
    );
    let out = skew.run(&["analyze"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("contact[1].tangent"));
}

#[test]
fn analyze_prints_the_fixed_velocities_of_a_singular_family() {
    // Example 5's hinge (tests/hard_cases): Δ = 0, compatible; the twist is fixed.
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/hard_cases/constrained-singular-compatible.toml"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["analyze", path, "--exact"])
        .output()
        .unwrap();
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("velocities after impact (the same for the whole family): ω = (0, 0, -1/5"),
        "{text}"
    );
}

#[test]
fn sweep_status_names_the_inadmissible_points() {
    let s = Scene::new("unilateral-sweep", PITCHING);
    let csv = s.dir().join("s.csv");
    // ω_z from 0.4 to 0.7: v_2x⁰ = 3 − 4ω > 0 throughout; by eq. 20 the Newton impulse
    // P₂ = (4/3·1.2(3 − 4ω) − 1/3·1.3(3 + 2ω))/3 vanishes where 4.8(3 − 4ω) = 1.3(3 + 2ω),
    // ω = 10.5/21.8 = 105/218 ≈ 0.482.
    let out = s.run(&[
        "sweep",
        "--vary",
        "body.angular_velocity[2]=0.4:0.7:4",
        "--out",
        csv.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&csv).unwrap();
    let status: Vec<&str> = text
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    // ω = 0.4 < 105/218: ok; 0.5, 0.6, 0.7 > 105/218: tensile.
    assert_eq!(status[0], "ok");
    assert!(
        status[1..].iter().all(|s| s.starts_with("tensile")),
        "{status:?}"
    );
    let out = s.run(&[
        "sweep",
        "--vary",
        "body.angular_velocity[2]=0.4:0.7:4",
        "--out",
        csv.to_str().unwrap(),
        "--law",
        "unilateral",
    ]);
    assert!(out.status.success());
    let text = std::fs::read_to_string(&csv).unwrap();
    assert!(text.lines().skip(1).all(|l| l.ends_with(",ok")), "{text}");
}

/// A 2 × 1 × 3 box (m = 12) landing flat on its four bottom corners at 2 m/s: G is singular
/// (rank 3 of 4).
fn box_scene(k: [&str; 4]) -> String {
    let mut s = String::from(
        "name = \"box\"\n[body]\nmass = 12\ninertia = [10, 13, 5]\nvelocity = [0, 0, -2]\nangular_velocity = [0, 0, 0]\n",
    );
    for (i, (x, y)) in [(1, "0.5"), (-1, "0.5"), (-1, "-0.5"), (1, "-0.5")]
        .iter()
        .enumerate()
    {
        s += &format!(
            "[[contact]]\npoint = [{x}, {y}, -1.5]\nnormal = [0, 0, -1]\nk = {}\n",
            k[i]
        );
    }
    s
}

#[test]
fn a_box_landing_flat_has_unique_velocities_and_least_norm_impulses() {
    let s = Scene::new("unilateral-box", &box_scene(["0.5"; 4]));
    let j = stdout_json(&s.run(&[
        "solve",
        "--exact",
        "--json",
        "--law",
        "unilateral",
        "--model",
        "newton",
    ]));
    let m = &j["models"]["newton"];
    // By hand: a pure translation stays one (no moment about C from a symmetric set), so
    // v_Cz = −k·(−2) = 1; the total impulse is m(1 + k)·2 = 36, and the least-norm split of a
    // symmetric set is the equal one: 9 N s per corner.
    assert_eq!(m["velocity"], serde_json::json!(["0", "0", "1"]));
    assert_eq!(m["impulses"], serde_json::json!(["9", "9", "9", "9"]));
    assert_eq!(m["impulses_unique"], false);
    assert_eq!(m["outcome_decided"], true);
    // Unequal k under Poisson: the law does not decide; never one number as the answer.
    let s = Scene::new(
        "unilateral-box-poisson",
        &box_scene(["0.7", "0.3", "0.7", "0.3"]),
    );
    let out = s.run(&[
        "solve",
        "--exact",
        "--law",
        "unilateral",
        "--model",
        "poisson",
    ]);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("the law does not decide the outcome"),
        "{table}"
    );
    let j = stdout_json(&s.run(&[
        "solve",
        "--exact",
        "--json",
        "--law",
        "unilateral",
        "--model",
        "poisson",
    ]));
    assert_eq!(j["models"]["poisson"]["outcome_decided"], false);
    // By hand: compression stops the box (ΣPᶜ = m·2 = 24) with Pᶜ anywhere on the set; all of it
    // on the k = 0.3 corners gives ΣP = 1.3·24, v_Cz = −2 + 31.2/12 = 3/5; all on the k = 0.7
    // corners, 7/5 (no expansion impulse X is needed: every corner then leaves).
    let range = &j["models"]["poisson"]["outcome_range"];
    assert_eq!(range["twist_min"][5], "3/5");
    assert_eq!(range["twist_max"][5], "7/5");
    assert!(table.contains("vCz ∈ [3/5 ≈ 0.6, 7/5 ≈ 1.4]"), "{table}");
}

/// Every scene of the unilateral derivations (`derivations/unilateral-*.md`) has a physical
/// answer in f64 and exactly, and they agree: impulses and twist to 10⁻¹² of their scale (small
/// integer data, O(N) pivots; the exact values are the hand-checked ones of `check`).
#[test]
fn the_unilateral_scenes_agree_in_f64_and_exactly() {
    use inertance::scalar::symbolic::RatFun;
    use inertance::scene::{Scene as S, pipeline::run};
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/derivations");
    let mut scenes = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if !path
            .file_name()
            .unwrap()
            .to_str()
            .unwrap()
            .starts_with("unilateral-")
        {
            continue;
        }
        let d = inertance::tools::check::Derivation::load(&path).unwrap();
        for (name, (_, text)) in &d.scenes {
            let Ok(mut scene) = S::parse(text, name) else {
                continue;
            };
            if scene.numbers().any(|(_, n)| !n.symbols.is_empty()) {
                continue;
            }
            scene.law = inertance::impact::unilateral::Law::Unilateral;
            let exact = if scene.is_rational() {
                run::<inertance::Exact>(&scene, None)
            } else {
                run::<RatFun>(&scene, None)
            };
            let float = run::<f64>(&scene, None);
            let (Ok(e), Ok(f)) = (exact, float) else {
                panic!("{}#{name}: no answer in one of the modes", path.display());
            };
            scenes += 1;
            for (me, mf) in e.report.models.iter().zip(&f.report.models) {
                let values = |m: &inertance::report::ModelReport| -> Vec<f64> {
                    m.impulses
                        .iter()
                        .chain(&m.angular_velocity)
                        .chain(&m.velocity)
                        .map(|v| v.f64)
                        .collect()
                };
                let (a, b) = (values(me), values(mf));
                let scale = a.iter().fold(1.0f64, |s, x| s.max(x.abs()));
                for (x, y) in a.iter().zip(&b) {
                    assert!(
                        (x - y).abs() <= 1e-12 * scale,
                        "{}#{name} {}: {x} vs {y}",
                        path.display(),
                        me.model
                    );
                }
                assert_eq!(me.active, mf.active);
            }
        }
    }
    assert!(scenes >= 5, "found {scenes} scenes");
}

#[test]
fn jamming_needs_restitution_at_an_approaching_contact() {
    // The characterisation (docs of impact::unilateral): infeasible iff some y ≥ 0 in ker G has
    // y_i > 0 at an approaching contact with k_i > 0. Here ker G = span(1, 1) and contact 1
    // approaches: with k = 0 the body just stops (no jam), with k = 1/2 it jams.
    let plastic = Scene::new("unilateral-plastic", &JAMMED.replace("k = 0.5", "k = 0"));
    let j = stdout_json(&plastic.run(&[
        "solve",
        "--exact",
        "--json",
        "--law",
        "unilateral",
        "--model",
        "newton",
    ]));
    assert_eq!(
        j["models"]["newton"]["velocity"],
        serde_json::json!(["0", "0", "0"])
    );
    // Poisson is never jammed (its right-hand sides are orthogonal to ker G).
    let s = Scene::new("unilateral-poisson-jam", JAMMED);
    let out = s.run(&[
        "solve",
        "--exact",
        "--law",
        "unilateral",
        "--model",
        "poisson",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
}
