//! `bench` and batches on scenes of several bodies.
//!
//! * Batches (`tools::sweep::solve_batch`, what Python's `solve_batch` calls): every point's
//!   numbers are those of `run_system` on the scene with the same values written in, bit for
//!   bit in f64; the columns are the sweep's (`BODY.vCx` …); a bad value names the point, the
//!   key and the value.
//! * `bench --scene` on a system: every type has a time, and the per-body and per-contact
//!   times are the time per solve divided by the counts; a type without an answer says why. No
//!   timing is asserted beyond being positive.

use inertance::report::Value;
use inertance::report::system::SystemReport;
use inertance::scene::system_pipeline::run_system;
use inertance::scene::{Scene, parse_document, set_value};
use inertance::tools::sweep::{Batch, SweepError, Varied, solve_batch};

const CRADLE: &str = include_str!("../examples/cradle-3.toml");
const ROUGH: &str = include_str!("../examples/rough-pendulum.toml");
const BOXES: &str = include_str!("../examples/box-on-box.toml");

/// The batch of `text` at the points of `vary`.
fn batch(text: &str, vary: &[(&str, &[f64])]) -> Result<Batch, SweepError> {
    let doc = parse_document(text, "scene.toml").unwrap();
    let vary: Vec<Varied> = vary
        .iter()
        .map(|(path, values)| Varied {
            path: path.to_string(),
            values: values.to_vec(),
        })
        .collect();
    solve_batch(&doc, "scene.toml", &vary, None)
}

/// The system's report at point `p` of `vary`, solved on its own.
fn solved_at(text: &str, vary: &[(&str, &[f64])], p: usize) -> SystemReport {
    let mut doc = parse_document(text, "scene.toml").unwrap();
    for (path, values) in vary {
        set_value(&mut doc, path, &values[p].to_string()).unwrap();
    }
    let scene = Scene::from_document(&doc, "scene.toml").unwrap();
    run_system::<f64>(&scene, None).unwrap().report
}

/// A report's outputs in the batch's column order, for the law named `law`: P_i, per body
/// v_C then ω, E_p, ΔE_c (and E_f with friction), read from the report's own fields.
fn expected(r: &SystemReport, law: &str, friction: bool) -> Vec<f64> {
    let f = |v: &Value| v.f64;
    let mut out = Vec::new();
    let twists = |t: &[([Value; 3], [Value; 3])], out: &mut Vec<f64>| {
        for (w, vc) in t {
            out.extend(vc.iter().map(f));
            out.extend(w.iter().map(f));
        }
    };
    if let Some(fr) = r.friction.iter().find(|x| x.law.name() == law) {
        out.extend(fr.contacts.iter().map(|c| c.normal_impulse.f64));
        twists(&fr.twists, &mut out);
        out.extend([
            fr.lost_velocity_energy.f64,
            fr.kinetic_energy_loss.f64,
            fr.friction_dissipation.f64,
        ]);
        return out;
    }
    let m = r.models.iter().find(|m| m.model.name() == law).unwrap();
    out.extend(m.impulses.iter().map(f));
    twists(&m.twists, &mut out);
    out.extend([m.lost_velocity_energy.f64, m.kinetic_energy_loss.f64]);
    if friction {
        out.push(0.0);
    }
    out
}

/// Every point of the batch equals its own solve, bit for bit.
fn check_points(text: &str, vary: &[(&str, &[f64])], b: &Batch) {
    let friction = b.outputs.last().is_some_and(|o| o == "Ef");
    let w = b.outputs.len();
    for p in 0..b.points {
        let r = solved_at(text, vary, p);
        assert_eq!(b.bodies, r.bodies);
        for (law, column) in b.models.iter().zip(&b.values) {
            let want = expected(&r, law.name(), friction);
            let got = &column[p * w..(p + 1) * w];
            assert_eq!(got.len(), want.len());
            for (k, (x, y)) in got.iter().zip(&want).enumerate() {
                assert_eq!(
                    x.to_bits(),
                    y.to_bits(),
                    "{law} {} at point {p}: {x} vs {y}",
                    b.outputs[k]
                );
            }
        }
    }
}

#[test]
fn a_system_batch_is_its_points_solved_one_by_one() {
    let ks: &[f64] = &[0.0, 0.25, 0.5, 0.9, 1.0];
    let masses: &[f64] = &[0.5, 0.1, 2.0, 0.3, 7.0];
    let vary = [("contact[1].k", ks), ("body[0].mass", masses)];
    let b = batch(CRADLE, &vary).unwrap();
    assert_eq!(b.points, 5);
    assert_eq!(b.bodies, ["striker", "ball 2", "ball 3"]);
    assert_eq!(
        b.outputs[..8],
        [
            "P1",
            "P2",
            "striker.vCx",
            "striker.vCy",
            "striker.vCz",
            "striker.wx",
            "striker.wy",
            "striker.wz"
        ]
    );
    assert_eq!(b.outputs.len(), 2 + 3 * 6 + 2);
    assert_eq!(b.outputs[b.outputs.len() - 2..], ["Ep", "dEc"]);
    check_points(CRADLE, &vary, &b);
    // At the scene's own values (m = 0.5, k = 1) the closed form: P = (2/3, 1/3) N s.
    let b = batch(CRADLE, &[("contact[1].k", &[1.0])]).unwrap();
    let w = b.outputs.len();
    for column in &b.values {
        assert!((column[0] - 2.0 / 3.0).abs() < 1e-15 && (column[1] - 1.0 / 3.0).abs() < 1e-15);
        assert_eq!(column.len(), w);
    }
    assert_eq!(b.status, ["ok"]);
}

#[test]
fn a_frictional_system_batch_gives_each_law_with_its_dissipation() {
    let ks: &[f64] = &[0.0, 0.5, 1.0];
    let vary = [("contact[0].k", ks)];
    let b = batch(ROUGH, &vary).unwrap();
    assert_eq!(b.outputs.last().map(String::as_str), Some("Ef"));
    assert_eq!(b.bodies, ["upper", "lower"]);
    check_points(ROUGH, &vary, &b);
    // The scene's Poisson answer (k = 1/2 there): P = 132/35 N s (tests/system_friction.rs).
    let w = b.outputs.len();
    assert!(
        (b.values[0][w] - 132.0 / 35.0).abs() < 1e-12,
        "{}",
        b.values[0][w]
    );
    assert!(b.values[0].iter().all(|x| x.is_finite()));
    // The status is the sweep's: the two consistent assignments at the stick event.
    assert!(b.status.iter().all(|s| s == "ambiguous"), "{:?}", b.status);
}

#[test]
fn a_unilateral_system_batch_and_its_statuses() {
    let ks: &[f64] = &[0.5, 0.2];
    let vary = [("contact[0].k", ks)];
    let b = batch(BOXES, &vary).unwrap();
    check_points(BOXES, &vary, &b);
    assert_eq!(b.status, ["ok", "ok"]);
    // Under the simultaneous law G (6 × 6, rank 5) is singular: a status, no numbers.
    let doc = parse_document(BOXES, "boxes.toml").unwrap();
    let s = solve_batch(
        &doc,
        "boxes.toml",
        &[Varied {
            path: "contact[0].k".into(),
            values: vec![0.5],
        }],
        Some(inertance::impact::unilateral::Law::Simultaneous),
    )
    .unwrap();
    assert_eq!(s.status, ["singular"]);
    assert!(s.values.iter().all(|c| c.iter().all(|x| x.is_nan())));
}

#[test]
fn a_bad_value_in_a_system_batch_names_the_point_the_key_and_the_value() {
    let e = batch(CRADLE, &[("contact[1].k", &[0.5, 0.7, 1.5])]).unwrap_err();
    match &e {
        SweepError::Point { point, at, .. } => {
            assert_eq!((*point, at.as_str()), (2, "contact[1].k = 1.5"), "{e}");
        }
        other => panic!("{other}"),
    }
    let e = batch(CRADLE, &[("body[1].mass", &[1.0, -2.0])]).unwrap_err();
    assert!(
        matches!(&e, SweepError::Point { point: 1, at, .. } if at == "body[1].mass = -2"),
        "{e}"
    );
    let e = batch(CRADLE, &[("body[7].mass", &[1.0])]).unwrap_err();
    assert!(matches!(e, SweepError::Vary { .. }), "{e}");
}

/// Run the binary from the crate's folder; it must succeed.
fn run(args: &[&str]) -> Vec<u8> {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{args:?}: {err}");
    out.stdout
}

/// Its JSON.
fn inertance(args: &[&str]) -> serde_json::Value {
    serde_json::from_slice(&run(args)).unwrap()
}

/// `ns_per_body` and `ns_per_contact` are `ns_per_solve` over the counts, for every type.
fn check_per_body_and_contact(v: &serde_json::Value, types: &[&str]) {
    let (bodies, contacts) = (
        v["bodies"].as_f64().unwrap(),
        v["contacts"].as_f64().unwrap(),
    );
    for t in types {
        let ns = v["ns_per_solve"][t]
            .as_f64()
            .unwrap_or_else(|| panic!("{t}: {v}"));
        assert!(ns > 0.0, "{t}: {v}");
        for (key, count) in [("ns_per_body", bodies), ("ns_per_contact", contacts)] {
            let x = v[key][t]
                .as_f64()
                .unwrap_or_else(|| panic!("{key} {t}: {v}"));
            assert!(
                (x - ns / count).abs() <= 1e-12 * ns,
                "{key} {t}: {x} vs {ns}/{count}"
            );
        }
    }
}

#[test]
fn bench_times_a_system_scene_per_solve_body_and_contact() {
    let v = inertance(&[
        "bench",
        "--scene",
        "examples/cradle-3.toml",
        "--quick",
        "--json",
    ]);
    assert_eq!(
        (v["bodies"].as_u64(), v["contacts"].as_u64()),
        (Some(3), Some(2)),
        "{v}"
    );
    let types = ["f32", "f64", "double-double", "exact"];
    assert_eq!(
        v["ns_per_solve"].as_object().unwrap().len(),
        types.len(),
        "{v}"
    );
    check_per_body_and_contact(&v, &types);
    assert_eq!(v["not_timed"], serde_json::json!({}), "{v}");
    assert!(
        v["solve"]
            .as_str()
            .unwrap()
            .starts_with("System::new + assemble"),
        "{v}"
    );
    // A frictional system: its restitution law integrated, in every type (planar: exact too).
    let v = inertance(&[
        "bench",
        "--scene",
        "examples/rough-pendulum.toml",
        "--quick",
        "--json",
    ]);
    assert_eq!(v["law"], "friction: poisson", "{v}");
    check_per_body_and_contact(&v, &types);
    // The batch of a system, per point.
    let v = inertance(&[
        "bench",
        "--quick",
        "--json",
        "--scene",
        "examples/cradle-3.toml",
        "--batch",
        "contact[1].k=0:1:20",
    ]);
    assert_eq!(v["batch"]["points"], 20, "{v}");
    assert!(v["batch"]["ns_per_point"].as_f64().unwrap() > 0.0, "{v}");
}

#[test]
fn a_type_without_an_answer_says_why() {
    use inertance::tools::system_bench::{NotTimed, time_system_scene};
    // Under the simultaneous law the boxes' G is singular in every type.
    let mut scene = Scene::parse(BOXES, "boxes.toml").unwrap();
    scene.law = inertance::impact::unilateral::Law::Simultaneous;
    let t = time_system_scene(&scene, std::time::Duration::from_micros(100));
    assert_eq!(t.rows.len(), 4);
    for (name, r) in &t.rows {
        assert_eq!(r, &Err(NotTimed::NoAnswer("singular")), "{name}");
    }
    let j = t.to_json();
    assert_eq!(j["not_timed"]["exact"], "singular", "{j}");
    assert!(j["ns_per_solve"]["f64"].is_null(), "{j}");
    assert!(
        t.to_text().contains("     exact: singular"),
        "{}",
        t.to_text()
    );
}

#[test]
fn the_reports_systems_section_has_the_chain_and_the_examples() {
    use inertance::tools::system_bench::chain_curve;
    let chain = chain_curve(&[1, 10, 30], std::time::Duration::from_micros(200));
    assert_eq!(
        chain
            .iter()
            .map(|p| (p.links, p.contacts))
            .collect::<Vec<_>>(),
        [(1, 1), (10, 2), (30, 2)]
    );
    assert!(chain[0].slope.is_none() && chain[1..].iter().all(|p| p.slope.is_some()));
    let report = inertance::tools::system_bench::SystemsBench {
        chain,
        scenes: vec![],
    };
    let j = report.to_json();
    for p in j["chain"].as_array().unwrap() {
        let (ns, per) = (
            p["ns_per_solve"].as_f64().unwrap(),
            p["ns_per_body"].as_f64().unwrap(),
        );
        assert!(
            (per - ns / p["bodies"].as_f64().unwrap()).abs() <= 1e-12 * ns,
            "{p}"
        );
    }
    assert!(
        report.to_text().contains("| 30 | 2 |"),
        "{}",
        report.to_text()
    );
}

/// The sweep's columns of a frictional system are the batch's (they were empty, status `ok`).
#[test]
fn a_frictional_system_sweep_writes_its_columns() {
    let dir = std::env::temp_dir().join(format!("system-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("rough.csv");
    run(&[
        "sweep",
        "examples/rough-pendulum.toml",
        "--vary",
        "contact[0].k=0:1:3",
        "--out",
        csv.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let b = batch(ROUGH, &[("contact[0].k", &[0.0, 0.5, 1.0])]).unwrap();
    let w = b.outputs.len();
    for (p, line) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').collect();
        for (k, name) in b.outputs.iter().enumerate() {
            let c = header
                .iter()
                .position(|h| *h == format!("poisson_{name}"))
                .unwrap();
            let x: f64 = cells[c]
                .parse()
                .unwrap_or_else(|_| panic!("{name} at {p}: {line}"));
            assert_eq!(x, b.values[0][p * w + k], "{name} at point {p}");
        }
        assert_eq!(*cells.last().unwrap(), b.status[p]);
    }
}
