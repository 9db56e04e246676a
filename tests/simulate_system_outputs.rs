//! `simulate --json` and `--trajectory FILE.svg` on a system of spheres: the JSON read back
//! carries the library's own numbers (every impact's time, contacts, rates and impulses, bit
//! for bit: serde_json round-trips f64), the plot is well-formed SVG with the energies and one
//! line per sphere, and files with another extension are refused before anything runs.

use inertance::scene::AnySimulation;
use inertance::simulate::system::{SystemSetup, simulate_system};
use serde_json::Value;

fn setup(path: &str) -> (String, SystemSetup) {
    match AnySimulation::load(std::path::Path::new(path)).expect("scene") {
        AnySimulation::System(s) => (s.name, s.setup),
        AnySimulation::Body(_) => panic!("{path}: not a system"),
    }
}

fn inertance(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .arg("simulate")
        .args(args)
        .output()
        .expect("runs")
}

fn number(v: &Value) -> f64 {
    v.as_f64().unwrap_or_else(|| panic!("a number: {v}"))
}

/// The column of beads: 138 impacts of up to ten contacts, each in the JSON as the library
/// computed it.
#[test]
fn json_carries_every_impact_of_the_library_run() {
    let path = "examples/simulate/column-of-beads.toml";
    let (name, s) = setup(path);
    let sim = simulate_system(&s);
    let out = inertance(&[path, "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let j: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(j["name"], name.as_str());
    assert_eq!(j["law"], s.law.name());
    assert_eq!(j["end"], "duration");
    assert_eq!(number(&j["t_end"]), sim.t_end);
    let bodies = j["bodies"].as_array().expect("bodies");
    assert_eq!(bodies.len(), s.members.len());
    for (b, sphere) in bodies.iter().zip(&s.members) {
        assert_eq!(b["name"], sphere.name.as_str());
        assert_eq!(number(&b["mass"]), sphere.mass());
        assert_eq!(Some(number(&b["radius"])), sphere.radius());
    }
    let impacts = j["impacts"].as_array().expect("impacts");
    assert_eq!(impacts.len(), sim.impacts.len());
    assert!(impacts.len() > 100, "the column's sequence");
    for (i, r) in impacts.iter().zip(&sim.impacts) {
        assert_eq!(i["index"], r.index);
        assert_eq!(number(&i["t"]), r.t);
        assert_eq!(number(&i["kinetic_before"]), r.kinetic_before);
        assert_eq!(number(&i["kinetic_after"]), r.kinetic_after);
        let contacts = i["contacts"].as_array().expect("contacts");
        assert_eq!(contacts.len(), r.contacts.len());
        for (c, k) in contacts.iter().zip(&r.contacts) {
            assert_eq!(c["feature"], k.feature.as_str());
            assert_eq!(c["obstacle"], k.plane.as_str());
            assert_eq!(number(&c["before"]), k.before);
            assert_eq!(number(&c["after"]), k.after);
            assert_eq!(number(&c["impulse"]), k.impulse);
            assert_eq!(c["closed"], k.persisting);
        }
    }
    // the first impact strikes the wall and all nine closed contacts
    assert_eq!(impacts[0]["contacts"].as_array().map(Vec::len), Some(10));
    assert_eq!(impacts[0]["contacts"][0]["obstacle"], "wall");
    let events = j["events"].as_array().expect("events");
    assert_eq!(events.len(), sim.events.len());
    for (e, k) in events.iter().zip(&sim.events) {
        assert_eq!(number(&e["t"]), k.t);
        assert_eq!(e["what"], k.what.as_str());
    }
    // the final state, one [x, y, z] per sphere
    let x = j["state"]["x"].as_array().expect("x");
    assert_eq!(x.len(), s.members.len());
    for (p, want) in x.iter().zip(&sim.state.x) {
        let got: Vec<f64> = p.as_array().expect("xyz").iter().map(number).collect();
        assert_eq!(got, vec![want.x, want.y, want.z]);
    }
}

/// A system's accumulation of impacts in the JSON: `examples/simulate/box-dropped-on-box.toml`
/// (the top bouncing flat on the base, k = ½) sums its impacts after the third, and `zeno`
/// carries the library's t∞, the impact after which it was taken and the ratio, bit for bit
/// (the closed form, t∞ = 0.3 s, is checked in tests/simulate_bodies.rs).
#[test]
fn json_carries_a_systems_accumulation() {
    let path = "examples/simulate/box-dropped-on-box.toml";
    let (_, s) = setup(path);
    let sim = simulate_system(&s);
    let zeno = sim.zeno.as_ref().expect("the accumulation");
    let out = inertance(&[path, "--json"]);
    assert_eq!(out.status.code(), Some(0));
    let j: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(number(&j["zeno"]["t_inf"]), zeno.t_inf);
    assert_eq!(j["zeno"]["after"], zeno.after);
    assert_eq!(number(&j["zeno"]["ratio"]), zeno.ratio);
    assert_eq!(j["end"], "rest");
    // a run without one says null
    let out = inertance(&["examples/simulate/cradle-3.toml", "--json"]);
    let j: Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert!(j["zeno"].is_null(), "{}", j["zeno"]);
}

/// The cradle's plot: the three energies and one line per ball, every line through every
/// sample; the impact marked and the balls named in the legend.
#[test]
fn the_plot_draws_the_energies_and_every_sphere() {
    let path = "examples/simulate/cradle-3.toml";
    let (_, s) = setup(path);
    let sim = simulate_system(&s);
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let file = dir.join("cradle-plot.svg");
    let out = inertance(&[path, "--trajectory", file.to_str().expect("utf-8")]);
    assert_eq!(out.status.code(), Some(0), "{out:?}");
    let svg = std::fs::read_to_string(&file).expect("written");
    let doc = roxmltree::Document::parse(&svg).expect("well-formed XML");
    let texts: Vec<&str> = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "text")
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for want in [
        "kinetic",
        "potential",
        "total",
        "impact",
        "striker",
        "ball 2",
        "ball 3",
    ] {
        assert!(texts.contains(&want), "{want} in the legend: {texts:?}");
    }
    let lines = doc
        .descendants()
        .filter(|n| n.tag_name().name() == "polyline")
        .filter(|n| {
            n.attribute("points")
                .is_some_and(|p| p.split_whitespace().count() == sim.samples.len())
        })
        .count();
    assert_eq!(
        lines,
        3 + s.members.len(),
        "three energies and a line per ball"
    );
}

/// Every file `simulate` writes for a system, and what it refuses: another extension (status
/// 2, nothing written, the log not printed), `--exact` (a system has no exact run).
#[test]
fn statuses_of_the_system_outputs() {
    let path = "examples/simulate/cradle-3.toml";
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"));
    let csv = dir.join("cradle-out.csv");
    let anim = dir.join("cradle-out.svg");
    let out = inertance(&[
        path,
        "--json",
        "--trajectory",
        csv.to_str().expect("utf-8"),
        "--animation",
        anim.to_str().expect("utf-8"),
    ]);
    assert_eq!(out.status.code(), Some(0));
    serde_json::from_slice::<Value>(&out.stdout).expect("JSON");
    assert!(
        std::fs::read_to_string(&csv)
            .expect("csv")
            .starts_with("t,")
    );
    roxmltree::Document::parse(&std::fs::read_to_string(&anim).expect("svg")).expect("XML");
    for (flag, file) in [
        ("--trajectory", "cradle.png"),
        ("--animation", "cradle.gif"),
    ] {
        let f = dir.join(file);
        let out = inertance(&[path, flag, f.to_str().expect("utf-8")]);
        assert_eq!(out.status.code(), Some(2), "{flag} {file}");
        assert!(String::from_utf8_lossy(&out.stderr).contains(flag));
        assert!(out.stdout.is_empty(), "refused before the run");
        assert!(!f.exists(), "nothing written");
    }
    let out = inertance(&[path, "--exact"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("system"));
}
