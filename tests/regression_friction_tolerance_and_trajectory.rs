//! Issue 28, item 13: a spatial frictional solve had no tolerance setting (`solve.tolerance`
//! was an unknown key) and no way to see its path, so a sensitive case could be neither
//! checked at a tighter tolerance nor plotted.
//!
//! Now `[solve] tolerance` and `--tolerance` set the integration's relative tolerance (a number
//! in (0, 1), refused otherwise with status 2 naming the key or flag and the value), the report
//! says which tolerance it was integrated to, and `--trajectory FILE.csv|FILE.json` writes the
//! path: per sample s, the phase and, per contact, P_i, the tangential impulse, the slip and
//! the mode — never half a file. The path is checked against what the report does not compute
//! from it: the slips before impact by hand, Coulomb's cone along the whole path, and a planar
//! scene's impulses at its events derived by hand (derivations/friction-example-8.md).

mod common;

use common::SceneFile;
use serde_json::Value;

/// The ball in the corner of issue 28 (derivations/friction-stick-exit.md), Newton, spatial.
const CORNER: &str = include_str!("../examples/ball-in-corner.toml");

/// Example 8 with μ = 1/5 and ω⁰ = (0, 0, 4): planar, exact (derivations/friction-example-8.md).
const CORNER_ROUGH: &str = r#"name = "Example 8 with friction"
[body]
mass = 2
inertia = ["1/5", "1/5", "1/5"]
velocity = [3, 6, 0]
angular_velocity = [0, 0, 4]
[[contact]]
point = ["1/2", 0, 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = "1/2"
mu = "1/5"
[[contact]]
point = [0, "1/2", 0]
normal = [0, 1, 0]
tangent = [-1, 0, 0]
k = "3/10"
mu = "1/5"
[solve]
models = ["newton"]
"#;

fn ok(out: &std::process::Output) -> String {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout.clone()).unwrap()
}

fn refused(out: &std::process::Output) -> String {
    assert_eq!(
        out.status.code(),
        Some(2),
        "{}",
        String::from_utf8_lossy(&out.stdout)
    );
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The same f64, printed by one program and read back by serde_json, whose default parser is
/// not correctly rounded (it may miss the last bit; CSV cells are read by Rust's, which is).
fn same(a: f64, b: f64) -> bool {
    (a - b).abs() <= f64::EPSILON * a.abs().max(b.abs())
}

fn json(out: &std::process::Output) -> Value {
    serde_json::from_str(&ok(out)).unwrap()
}

fn with_solve_line(line: &str) -> String {
    CORNER.replace(
        "models = [\"newton\"]",
        &format!("models = [\"newton\"]\n{line}"),
    )
}

/// The files in `dir` other than the scene.
fn others(dir: &std::path::Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != "scene.toml")
        .collect()
}

#[test]
fn the_scene_sets_the_tolerance_and_a_tighter_run_agrees_within_the_estimate() {
    let default = json(&SceneFile::new("tol-default", CORNER).run(&["solve", "--json"]));
    let tight = json(
        &SceneFile::new("tol-scene", &with_solve_line("tolerance = 1e-12"))
            .run(&["solve", "--json"]),
    );
    let (d, t) = (&default["friction"]["newton"], &tight["friction"]["newton"]);
    assert_eq!(t["tolerance"], 1e-12);
    // The default is ε^(2/3) in f64.
    let eps23 = f64::EPSILON.powf(2.0 / 3.0);
    assert_eq!(d["tolerance"].as_f64().unwrap(), eps23);
    let est = d["error_estimate"].as_f64().unwrap();
    assert!(t["error_estimate"].as_f64().unwrap() < est);
    for (a, b) in [
        (&d["angular_velocity"], &t["angular_velocity"]),
        (&d["velocity"], &t["velocity"]),
    ] {
        for k in 0..3 {
            let (x, y) = (a[k].as_f64().unwrap(), b[k].as_f64().unwrap());
            assert!((x - y).abs() <= est, "{x} against {y}, estimate {est:e}");
        }
    }
    // The flag overrides the scene.
    let flag = json(
        &SceneFile::new("tol-flag", &with_solve_line("tolerance = 1e-12")).run(&[
            "solve",
            "--json",
            "--tolerance",
            "1e-9",
        ]),
    );
    assert_eq!(flag["friction"]["newton"]["tolerance"], 1e-9);
}

#[test]
fn a_tolerance_outside_zero_to_one_is_refused_naming_the_key_and_value() {
    for value in ["0", "1", "2", "-1e-3", "\"abc\"", "nan", "inf"] {
        let s = SceneFile::new(
            &format!("tol-bad-{}", value.replace('"', "")),
            &with_solve_line(&format!("tolerance = {value}")),
        );
        let err = refused(&s.run(&["solve"]));
        assert!(
            err.contains("scene.toml")
                && err.contains("`solve.tolerance`")
                && err.contains(&format!("= {value}"))
                && err.contains("between 0 and 1"),
            "{err}"
        );
    }
    let s = SceneFile::new("tol-bad-flag", CORNER);
    for value in ["0", "1", "-1", "abc", "NaN"] {
        let err = refused(&s.run(&["solve", &format!("--tolerance={value}")]));
        assert!(
            err.contains(&format!("--tolerance = {value}")) && err.contains("between 0 and 1"),
            "{err}"
        );
    }
}

/// f64 resolves no tolerance below 4ε: the integration is run there, and says so.
#[test]
fn a_tolerance_below_the_scalars_reach_is_raised_with_a_warning() {
    let out = SceneFile::new("tol-floor", CORNER).run(&["solve", "--json", "--tolerance", "1e-20"]);
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    let j = json(&out);
    assert_eq!(
        j["friction"]["newton"]["tolerance"].as_f64(),
        Some(4.0 * f64::EPSILON)
    );
    assert!(
        stderr.contains("warning") && stderr.contains("1e-20") && stderr.contains("f64"),
        "{stderr}"
    );
}

/// A CSV table: the header and the rows, by column name.
struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    fn read(path: &std::path::Path) -> Table {
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let header = lines
            .next()
            .unwrap()
            .split(',')
            .map(str::to_string)
            .collect();
        let rows = lines
            .map(|l| l.split(',').map(str::to_string).collect())
            .collect();
        Table { header, rows }
    }

    fn col(&self, name: &str) -> usize {
        self.header.iter().position(|h| h == name).unwrap()
    }

    fn f(&self, row: &[String], name: &str) -> f64 {
        row[self.col(name)].parse().unwrap()
    }

    fn s(&self, row: &[String], name: &str) -> String {
        row[self.col(name)].clone()
    }
}

fn norm(x: [f64; 3]) -> f64 {
    x.iter().map(|a| a * a).sum::<f64>().sqrt()
}

#[test]
fn the_trajectory_csv_holds_the_path_from_the_slips_before_to_the_report_after() {
    let s = SceneFile::new("traj-csv", CORNER);
    let file = s.dir().join("path.csv");
    let report = json(&s.run(&["solve", "--json", "--trajectory", file.to_str().unwrap()]));
    let f = &report["friction"]["newton"];
    let t = Table::read(&file);
    let mut want = vec!["law", "s", "phase"]
        .into_iter()
        .map(String::from)
        .collect::<Vec<_>>();
    for i in 1..=2 {
        for c in [
            "P", "tau_x", "tau_y", "tau_z", "slip_x", "slip_y", "slip_z", "mode",
        ] {
            let (a, b) = c.split_at(c.find('_').unwrap_or(c.len()));
            want.push(format!("{a}{i}{b}"));
        }
    }
    assert_eq!(t.header, want);
    assert!(t.rows.len() > 10);
    // s runs from 0 to the end, never back; the phase turns once, at s = 1.
    let s_of: Vec<f64> = t.rows.iter().map(|r| t.f(r, "s")).collect();
    assert_eq!(s_of[0], 0.0);
    assert!(same(*s_of.last().unwrap(), f["end"].as_f64().unwrap()));
    assert!(s_of.windows(2).all(|w| w[0] <= w[1]));
    for r in &t.rows {
        let phase = t.s(r, "phase");
        let s = t.f(r, "s");
        assert!(
            (phase == "compression" && s <= 1.0) || (phase == "restitution" && s >= 1.0),
            "{phase} at s = {s}"
        );
        assert_eq!(t.s(r, "law"), "newton");
    }
    // At s = 0: no impulse, and the slips before impact, by hand: floor (v_x − rω_y,
    // v_y + rω_x, 0) = (2.4, 1.3, 0), wall (0, v_y + rω_z, v_z − rω_y) = (0, 2, −2.6).
    let first = &t.rows[0];
    for (i, slip) in [(1, [2.4, 1.3, 0.0]), (2, [0.0, 2.0, -2.6])] {
        assert_eq!(t.f(first, &format!("P{i}")), 0.0);
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let got = t.f(first, &format!("slip{i}_{axis}"));
            assert!((got - slip[k]).abs() <= 1e-12, "slip{i}_{axis} = {got}");
        }
    }
    // At the end: the report's impulses, and its contact velocities less their normal parts.
    let last = t.rows.last().unwrap();
    let normals = [[0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]];
    for i in 1..=2 {
        let c = &f["contacts"][i - 1];
        assert!(same(
            t.f(last, &format!("P{i}")),
            c["normal_impulse"].as_f64().unwrap()
        ));
        let v: Vec<f64> = (0..3)
            .map(|k| c["velocity_after"][k].as_f64().unwrap())
            .collect();
        let n = normals[i - 1];
        let vn: f64 = (0..3).map(|k| v[k] * n[k]).sum();
        for (k, axis) in ["x", "y", "z"].iter().enumerate() {
            let tau = t.f(last, &format!("tau{i}_{axis}"));
            assert!(same(tau, c["tangential_impulse"][k].as_f64().unwrap()));
            let slip = t.f(last, &format!("slip{i}_{axis}"));
            assert!((slip - (v[k] - vn * n[k])).abs() <= 1e-12);
        }
    }
    // The modes along the path, repeats merged, are the report's histories.
    for i in 1..=2 {
        let mut h: Vec<String> = Vec::new();
        for r in &t.rows {
            let m = t.s(r, &format!("mode{i}"));
            if h.last() != Some(&m) {
                h.push(m);
            }
        }
        let want: Vec<String> = f["contacts"][i - 1]["modes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m.as_str().unwrap().to_string())
            .collect();
        assert_eq!(h, want);
    }
    // Coulomb's cone along the whole path: |τ_i| ≤ μ P_i, to the estimate.
    let est = f["error_estimate"].as_f64().unwrap();
    for r in &t.rows {
        for i in 1..=2 {
            let tau = [
                t.f(r, &format!("tau{i}_x")),
                t.f(r, &format!("tau{i}_y")),
                t.f(r, &format!("tau{i}_z")),
            ];
            let p = t.f(r, &format!("P{i}"));
            assert!(
                norm(tau) <= 0.3 * p + est,
                "|τ{i}| = {} > μP = {}",
                norm(tau),
                0.3 * p
            );
        }
    }
    assert_eq!(others(s.dir()), ["path.csv"]);
}

#[test]
fn the_trajectory_json_holds_the_same_path_as_the_csv() {
    let s = SceneFile::new("traj-json", CORNER);
    let (csv, js) = (s.dir().join("p.csv"), s.dir().join("p.json"));
    ok(&s.run(&["solve", "--trajectory", csv.to_str().unwrap()]));
    ok(&s.run(&["solve", "--trajectory", js.to_str().unwrap()]));
    let t = Table::read(&csv);
    let j: Value = serde_json::from_str(&std::fs::read_to_string(&js).unwrap()).unwrap();
    let points = j["newton"].as_array().unwrap();
    assert_eq!(points.len(), t.rows.len());
    for (p, r) in points.iter().zip(&t.rows) {
        assert!(same(p["s"].as_f64().unwrap(), t.f(r, "s")));
        assert_eq!(p["phase"], t.s(r, "phase").as_str());
        for i in 1..=2 {
            let c = &p["contacts"][i - 1];
            assert!(same(
                c["normal_impulse"].as_f64().unwrap(),
                t.f(r, &format!("P{i}"))
            ));
            assert_eq!(c["mode"], t.s(r, &format!("mode{i}")).as_str());
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                assert!(same(
                    c["tangential_impulse"][k].as_f64().unwrap(),
                    t.f(r, &format!("tau{i}_{axis}"))
                ));
                assert!(same(
                    c["slip"][k].as_f64().unwrap(),
                    t.f(r, &format!("slip{i}_{axis}"))
                ));
            }
        }
    }
}

/// derivations/friction-example-8.md by hand: A₂'s slip stops at s = 8/39 and it sticks; at
/// s = 1, p = p^c = (19/3, 161/15) and τ = (19/15, 1/3), so the tangential impulses on the body
/// are −τ₁t₁ = (0, −19/15, 0) and −τ₂t₂ = (1/3, 0, 0); A₂ is at rest, A₁ slips at
/// v₁ₙ + v₂ₙ = 0 there (the corner's identity).
#[test]
fn a_planar_trajectory_passes_through_the_events_derived_by_hand() {
    let s = SceneFile::new("traj-planar", CORNER_ROUGH);
    let file = s.dir().join("path.csv");
    ok(&s.run(&["solve", "--exact", "--trajectory", file.to_str().unwrap()]));
    let t = Table::read(&file);
    let at = |s: f64, phase: &str| {
        t.rows
            .iter()
            .find(|r| (t.f(r, "s") - s).abs() < 1e-15 && t.s(r, "phase") == phase)
            .unwrap_or_else(|| panic!("no sample at s = {s} ({phase})"))
    };
    let one = at(1.0, "compression");
    let close = |got: f64, want: f64| assert!((got - want).abs() <= 1e-13, "{got} ≠ {want}");
    close(t.f(one, "P1"), 19.0 / 3.0);
    close(t.f(one, "P2"), 161.0 / 15.0);
    close(t.f(one, "tau1_y"), -19.0 / 15.0);
    close(t.f(one, "tau2_x"), 1.0 / 3.0);
    for axis in ["x", "y", "z"] {
        close(t.f(one, &format!("slip1_{axis}")), 0.0);
        close(t.f(one, &format!("slip2_{axis}")), 0.0);
    }
    let stop = at(8.0 / 39.0, "compression");
    close(t.f(stop, "slip2_x"), 0.0);
    // The sample that ends the first segment slides; the one that starts the next sticks.
    let modes: Vec<String> = t
        .rows
        .iter()
        .filter(|r| (t.f(r, "s") - 8.0 / 39.0).abs() < 1e-15)
        .map(|r| t.s(r, "mode2"))
        .collect();
    assert_eq!(modes, ["slide-", "stick"]);
}

#[test]
fn no_trajectory_is_written_when_it_cannot_be_whole() {
    // An extension that is neither .csv nor .json: refused before solving.
    let s = SceneFile::new("traj-ext", CORNER);
    let err = refused(&s.run(&[
        "solve",
        "--trajectory",
        s.dir().join("p.txt").to_str().unwrap(),
    ]));
    assert!(
        err.contains("p.txt") && err.contains(".csv or .json"),
        "{err}"
    );
    // A frictionless scene has no path.
    let frictionless = CORNER.replace("mu = 0.3", "mu = 0");
    let s2 = SceneFile::new("traj-frictionless", &frictionless);
    let err = refused(&s2.run(&[
        "solve",
        "--trajectory",
        s2.dir().join("p.csv").to_str().unwrap(),
    ]));
    assert!(err.contains("no friction"), "{err}");
    // A directory that does not exist: status 2, nothing left behind.
    let err = refused(&s.run(&[
        "solve",
        "--trajectory",
        s.dir().join("missing/p.csv").to_str().unwrap(),
    ]));
    assert!(
        err.contains("missing/p.csv") && err.contains("cannot write"),
        "{err}"
    );
    // No answer (status 3): Painlevé's rod under the unilateral law — sliding, friction asks
    // the floor for a pull (μ K_nt < −K_nn along the slip) and no rule continues
    // (tests/unilateral_friction.rs). (Example 3 with μ = 1 under Newton served here until
    // 2026-11-28, when its pulling contact was freed of friction and it got an answer.)
    let none = SceneFile::new(
        "traj-none",
        r#"[body]
mass = 1
inertia = ["3/10", "3/10", "3/10"]
velocity = ["1/2", -1, 0]
angular_velocity = [0, 0, 0]
[[contact]]
point = ["3/5", "-4/5", 0]
normal = [0, -1, 0]
k = 0.5
mu = 2
[solve]
restitution = "energetic"
"#,
    );
    let out = none.run(&[
        "solve",
        "--law",
        "unilateral",
        "--trajectory",
        none.dir().join("p.csv").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(3));
    for dir in [s.dir(), s2.dir(), none.dir()] {
        assert!(others(dir).is_empty(), "{:?}", others(dir));
    }
}

/// A planar path is rebuilt from its segments' constant rates: exactly, it ends at the
/// impulses the solve reports (Example 8 in rationals, Newton and Poisson).
#[test]
fn a_planar_path_ends_exactly_at_the_impulses() {
    use inertance::impact::friction::{Restitution, solve_frictional};
    use inertance::scalar::Exact;
    use inertance::scene::Scene;
    let scene = Scene::parse(CORNER_ROUGH, "corner-rough").unwrap();
    let problem = scene.problem::<Exact>().unwrap();
    for law in [Restitution::Newton, Restitution::Poisson] {
        let out = solve_frictional(&problem, law, 0.0).unwrap();
        let last = out.samples.last().unwrap();
        assert_eq!(last.impulses, out.impulses, "{law}");
        assert_eq!(last.s, out.end, "{law}");
        assert!(out.samples.windows(2).all(|w| w[0].s <= w[1].s), "{law}");
    }
}
