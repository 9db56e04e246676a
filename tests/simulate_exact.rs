//! `simulate --exact`: the exact runs of a frictionless sphere among planes against closed
//! forms (equality, in radicals), and the f64 integration against the exact run.
//!
//! Tolerance of the f64 comparison: the f64 run locates each impact to the gap tolerance
//! 10⁻¹¹ L (L ≈ 5 m), a time error of 10⁻¹¹ L/|ġ| ≤ 10⁻¹⁰ s at the slowest impact compared;
//! each later time is a sum of a few such errors, 10⁻⁹ s allowed (tests/simulate.rs states the
//! same bound for the same ball).

use inertance::scalar::Scalar;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::SimulationScene;
use inertance::simulate::exact::{ExactEnd, ExactError, run_exact, run_exact_history};
use inertance::simulate::simulate;
use num_rational::BigRational;

fn q(n: i64, d: i64) -> RatFun {
    RatFun::from_rational(&BigRational::new(n.into(), d.into()))
}

fn write_scene(name: &str, text: &str) -> std::path::PathBuf {
    let path = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    std::fs::write(&path, text).expect("writes");
    path
}

#[test]
fn the_bouncing_ball_is_exact_impact_by_impact_and_accumulates_at_three_seconds() {
    // dropped 5 m with g = 10 and k = 1/2: t₁ = 1, then t_n = 3 − 2^(2−n), ġ⁻_n = −10/2^(n−1)
    let path = std::path::Path::new("examples/simulate/bouncing-ball.toml");
    let (scene, sphere) = SimulationScene::load_exact::<RatFun>(path).expect("reads exactly");
    let run = run_exact(&sphere).expect("exact");
    assert_eq!(run.impacts.len(), 20, "20 impacts listed by default");
    for (i, r) in run.impacts.iter().enumerate() {
        let n = i as i64 + 1;
        let t = if n == 1 {
            q(1, 1)
        } else {
            q(3, 1) - q(1, 1 << (n - 2))
        };
        assert_eq!(r.t, t, "impact {n}: t");
        assert_eq!(r.before, -(q(10, 1) / q(1 << (n - 1), 1)), "impact {n}: ġ⁻");
        assert_eq!(r.after, -(q(1, 2) * &r.before), "impact {n}: ġ⁺ = −k ġ⁻");
    }
    assert_eq!(
        run.zeno,
        Some(q(3, 1)),
        "t∞ = t₁ + 2u₁/(g(1 − k)) = 3 exactly"
    );
    assert_eq!(run.end, ExactEnd::Zeno { t_inf: q(3, 1) });
    // the f64 integration against the exact run
    let sim = simulate(&scene.setup).expect("runs");
    for (exact, float) in run.impacts.iter().zip(&sim.impacts) {
        assert!((exact.t.to_f64() - float.t).abs() < 1e-9);
        assert!((exact.before.to_f64() - float.contacts[0].before).abs() < 1e-9);
    }
}

#[test]
fn a_ball_dropped_from_a_rational_height_lives_in_one_radical_field() {
    // h = 1 m (lowest point), g = 981/100, k = 3/4: t₁ = √(2h/g), ġ⁻₁ = −√(2gh), and every
    // flight after lasts 2 k^n √(2gh)/g: all in ℚ(√(2gh)) = ℚ(√218) — no nested radical
    let text = std::fs::read_to_string("examples/simulate/bouncing-ball.toml")
        .expect("reads")
        .replace("position = [0, 0, 5.1]", "position = [0, 0, 1.1]")
        .replace("gravity = [0, 0, -10]", "gravity = [0, 0, -9.81]")
        .replace(
            "contact = { k = 0.5 }",
            "contact = { k = 0.75 }\nimpacts = 6",
        );
    let path = write_scene("ball-radical.toml", &text);
    let (_, sphere) = SimulationScene::load_exact::<RatFun>(&path).expect("reads");
    let run = run_exact(&sphere).expect("exact");
    let (g, h, k) = (q(981, 100), q(1, 1), q(3, 4));
    let t1 = &run.impacts[0].t;
    assert_eq!(t1.clone() * t1, q(2, 1) * &h / g.clone(), "t₁² = 2h/g");
    let v1 = &run.impacts[0].before;
    assert_eq!(v1.clone() * v1, q(2, 1) * &g * &h, "ġ₁² = 2gh");
    assert!(
        t1.exact_text().expect("text").contains("sqrt(218)"),
        "in ℚ(√218): {t1:?}"
    );
    for w in run.impacts.windows(2) {
        let flight = w[1].t.clone() - &w[0].t;
        assert_eq!(
            flight,
            q(2, 1) * &w[0].after / g.clone(),
            "a flight lasts 2u/g"
        );
        assert_eq!(w[0].after, -(k.clone() * &w[0].before));
    }
    // t∞ = t₁ + 2 k |ġ₁| / (g (1 − k))
    let t_inf = t1.clone() + q(2, 1) * &k * &(-v1.clone()) / (g.clone() * (q(1, 1) - &k));
    assert_eq!(run.zeno, Some(t_inf));
}

#[test]
fn a_ball_between_a_floor_and_a_wall_stays_rational() {
    // launched from the floor at (1, 0, 3) m/s toward a wall 1/2 m away (its surface), g = 10:
    // a flight from the floor is rational (τ = 2ġ/g), the wall is reached at a rational time
    // (gravity along it: τ = g/|ġ|), so every impact is rational; k = 1/2 at both
    let text = r#"
name = "ball between floor and wall"
[body]
shape = { sphere = 0.1 }
mass = 1
position = [0, 0, 0.1]
velocity = [1, 0, 3]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
point = [0, 0, 0]
[[obstacle]]
name = "wall"
normal = [-1, 0, 0]
point = [0.6, 0, 0]
[simulate]
gravity = [0, 0, -10]
duration = 2
impacts = 8
contact = { k = 0.5 }
"#;
    let path = write_scene("floor-wall.toml", text);
    let (scene, sphere) = SimulationScene::load_exact::<RatFun>(&path).expect("reads");
    let run = run_exact(&sphere).expect("exact");
    // the first flight: the wall at t = 1/2 (x: 0 → 1/2 at 1 m/s), before the floor at 3/5
    assert_eq!(run.impacts[0].t, q(1, 2));
    assert_eq!(sphere.planes[run.impacts[0].plane].name, "wall");
    assert_eq!(run.impacts[0].before, q(-1, 1));
    // then the floor: ż(1/2) = 3 − 5 = −2, z(1/2) = 0.1 + 3/2 − 5/4 = 0.35 → lands at 3/5
    assert_eq!(run.impacts[1].t, q(3, 5));
    assert_eq!(run.impacts[1].before, q(-3, 1));
    for r in &run.impacts {
        assert!(r.t.to_rational().is_some(), "rational: {:?}", r.t);
    }
    let sim = simulate(&scene.setup).expect("runs");
    for (exact, float) in run.impacts.iter().zip(&sim.impacts) {
        assert!(
            (exact.t.to_f64() - float.t).abs() < 1e-9,
            "{} vs {}",
            exact.t.to_f64(),
            float.t
        );
    }
}

#[test]
fn a_nested_radical_stops_the_exact_path_and_says_where() {
    // a ball dropped onto a plane tilted by 45°: its gap is in ℚ(√2) and the time of its next
    // landing on the floor needs √ of a radicand in ℚ(√2)
    let text = r#"
name = "ball on a tilted plane and a floor"
[body]
shape = { sphere = 1 }
mass = 1
position = [0, 0, 3]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "ramp"
normal = [1, 0, 1]
point = [-2, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
point = [0, 0, 0]
[simulate]
gravity = [0, 0, -10]
duration = 5
impacts = 5
"#;
    let path = write_scene("nested.toml", text);
    let (_, sphere) = SimulationScene::load_exact::<RatFun>(&path).expect("reads");
    let (run, error) = run_exact_history(&sphere);
    assert_eq!(run.end, ExactEnd::Stopped);
    assert!(
        matches!(error, Some(ExactError::NestedRadical { .. })),
        "{error:?}"
    );
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["simulate", "--exact"])
        .arg(&path)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(3));
    assert!(String::from_utf8_lossy(&out.stderr).contains("nested radical"));
}

#[test]
fn scenes_without_an_exact_form_are_refused_with_status_2() {
    for (file, key) in [
        ("examples/simulate/rocking-block.toml", "body.shape"),
        ("examples/simulate/tumbling-box.toml", "body.shape"),
    ] {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
            .args(["simulate", "--exact", file])
            .output()
            .expect("runs");
        assert_eq!(out.status.code(), Some(2), "{file}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(file) && err.contains(key), "{err}");
    }
    let rough = write_scene(
        "rough-ball.toml",
        &std::fs::read_to_string("examples/simulate/bouncing-ball.toml")
            .expect("reads")
            .replace("contact = { k = 0.5 }", "contact = { k = 0.5, mu = 0.3 }"),
    );
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["simulate", "--exact"])
        .arg(&rough)
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("frictionless"));
}
