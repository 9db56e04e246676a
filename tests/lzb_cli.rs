//! The LZB law end to end through the binary: `[solve] law = "lzb"` and `--law lzb` print the
//! library's numbers ([`inertance::scene::lzb::run_lzb`], whose physics `tests/lzb.rs` checks
//! against closed forms and an independent integration), and what the law does not support is
//! refused with the file, the key and the value (status 2), never answered under another name.

mod common;

use common::SceneFile as Scene;
use inertance::scene::Scene as Loaded;
use std::path::Path;

fn example(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples")
        .join(name)
}

fn run(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(args)
        .output()
        .unwrap()
}

/// The number printed after `v_C = [` on the line of `body`.
fn printed_vx(stdout: &str, body: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with(&format!("{body}:")))
        .unwrap_or_else(|| panic!("no line for {body} in\n{stdout}"));
    let at = line.find("v_C = [").expect("v_C") + "v_C = [".len();
    line[at..]
        .split(',')
        .next()
        .unwrap()
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn the_cradle_scene_prints_the_librarys_lzb_answer() {
    let path = example("cradle-3-lzb.toml");
    let out = run(&["solve", path.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("— f64 (lzb)"), "{stdout}");
    assert!(
        stdout.contains("events; contacts ended in the order A1, A2"),
        "{stdout}"
    );
    let scene = Loaded::load(&path).expect("loads");
    let report = inertance::scene::lzb::run_lzb(&scene).expect("solves");
    for (name, _, v) in &report.twists {
        // Printed to 6 decimals.
        assert!(
            (printed_vx(&stdout, name) - v[0]).abs() <= 5e-7,
            "{name}: {stdout}"
        );
    }
    // The same scene under the simultaneous law, for contrast: the striker bounces back.
    let simultaneous = run(&["solve", path.to_str().unwrap(), "--law", "simultaneous"]);
    assert_eq!(simultaneous.status.code(), Some(0));
}

#[test]
fn law_lzb_on_the_command_line_solves_a_frictionless_one_body_scene() {
    let path = example("pitching-bar.toml");
    let out = run(&["solve", path.to_str().unwrap(), "--law", "lzb"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("(lzb)") && stdout.contains("ΔE_c [J]"),
        "{stdout}"
    );
}

#[test]
fn what_the_lzb_law_does_not_support_is_refused_by_key_and_value() {
    let cradle = example("cradle-3-lzb.toml");
    let cradle = cradle.to_str().unwrap();
    let exact = run(&["solve", cradle, "--exact"]);
    let err = String::from_utf8_lossy(&exact.stderr);
    assert_eq!(exact.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--exact") && err.contains("never exact"),
        "{err}"
    );
    assert!(exact.stdout.is_empty(), "nothing printed as exact");

    // Friction is integrated (it was refused before LZB's Part II): the tangential columns.
    let rough = example("rough-bar.toml");
    let out = run(&["solve", rough.to_str().unwrap(), "--law", "lzb"]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        stdout.contains("τ [N s]") && stdout.contains("by friction"),
        "{stdout}"
    );

    // `derive` gives the simultaneous law's closed forms: it refuses the LZB law rather than
    // answer under its name.
    let derive = run(&["derive", cradle, "--symbols", "m"]);
    let err = String::from_utf8_lossy(&derive.stderr);
    assert_eq!(derive.status.code(), Some(2), "{err}");
    assert!(err.contains("solve.law") && err.contains("lzb"), "{err}");
}

#[test]
fn meaningless_lzb_parameters_name_their_key_and_value() {
    let text = std::fs::read_to_string(example("cradle-3-lzb.toml")).unwrap();
    for (from, to, key, value) in [
        (
            "stiffness = 1\nexponent",
            "stiffness = -2\nexponent",
            "contact[0].stiffness",
            "-2",
        ),
        (
            "exponent = 1.5\n[[contact]]",
            "exponent = 0\n[[contact]]",
            "contact[0].exponent",
            "0",
        ),
    ] {
        let s = Scene::new("lzb-bad-parameter", &text.replacen(from, to, 1));
        let out = s.run(&["solve"]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(key) && err.contains(value), "{key}: {err}");
    }
    let s = Scene::new(
        "lzb-restitution-law",
        &text.replace(
            "law = \"lzb\"",
            "law = \"lzb\"\nrestitution = \"energetic\"",
        ),
    );
    let out = s.run(&["solve"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("solve.restitution"), "{err}");
}

/// The number in the table's row `A{i}` at column `col` (0-based after the label).
fn table_cell(stdout: &str, contact: usize, col: usize) -> f64 {
    let label = format!("A{contact}");
    let line = stdout
        .lines()
        .find(|l| l.split_whitespace().next() == Some(label.as_str()))
        .unwrap_or_else(|| panic!("no row {label} in\n{stdout}"));
    line.split_whitespace()
        .nth(col + 1)
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn the_json_report_carries_the_tables_numbers() {
    let path = example("cradle-3-lzb.toml");
    let path = path.to_str().unwrap();
    let table = run(&["solve", path]);
    let table = String::from_utf8_lossy(&table.stdout).into_owned();
    let out = run(&["solve", path, "--json"]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    assert_eq!(j["law"], "lzb");
    assert_eq!(j["scalar"], "f64");
    let contacts = j["contacts"].as_array().unwrap();
    assert_eq!(contacts.len(), 2);
    // Columns: K η e v⁰ P v E_max W_c W_r dissipated, printed to 6 decimals.
    let close = |a: f64, b: f64| (a - b).abs() <= 5e-7 * (1.0 + b.abs());
    for (i, c) in contacts.iter().enumerate() {
        assert_eq!(c["contact"], i + 1);
        let at = |k: &str| c[k].as_f64().unwrap_or_else(|| panic!("{k}: {c}"));
        assert_eq!(c["law"]["stiffness"], 1.0);
        assert_eq!(c["law"]["exponent"], 1.5);
        assert_eq!(c["law"]["restitution"], 1.0);
        for (col, key) in [
            (3, "velocity_before"),
            (4, "impulse"),
            (5, "velocity_after"),
            (6, "max_potential_energy"),
            (7, "work_compression"),
            (8, "work_expansion"),
        ] {
            let printed = table_cell(&table, i + 1, col);
            assert!(close(printed, at(key)), "{key}: {printed} vs {c}");
        }
        assert!(
            (at("dissipation") - (at("work_compression") - at("work_expansion"))).abs() < 1e-15
        );
    }
    // The twist after impact, per body, and the striker nearly stops (derivations/lzb.md).
    let twists = j["twist_after"].as_array().unwrap();
    assert_eq!(twists.len(), 3);
    for t in twists {
        let name = t["body"].as_str().unwrap();
        let vx = t["velocity"][0].as_f64().unwrap();
        assert!((printed_vx(&table, name) - vx).abs() <= 5e-7, "{name}");
    }
    // Momentum: the three balls of 0.5 kg carry the striker's 0.5 kg m/s.
    let p: f64 = twists
        .iter()
        .map(|t| 0.5 * t["velocity"][0].as_f64().unwrap())
        .sum();
    assert!((p - 0.5).abs() < 1e-9, "{p}");
    let loss = j["kinetic_energy_loss"].as_f64().unwrap();
    let residual = j["energy_residual"].as_f64().unwrap();
    let dissipation = j["dissipation"].as_f64().unwrap();
    assert!((loss - dissipation - residual).abs() < 1e-15);
    assert!(
        loss.abs() < 1e-8 && residual.abs() < 1e-8,
        "{loss} {residual}"
    );
    assert_eq!(j["ending_order"], serde_json::json!([1, 2]));
    let events = j["events"].as_array().unwrap();
    let integration = &j["integration"];
    assert_eq!(
        integration["events"].as_u64().unwrap() as usize,
        events.len()
    );
    assert!(table.contains(&format!(
        "{} steps ({} rejected), {} events",
        integration["accepted_steps"], integration["rejected_steps"], integration["events"]
    )));
    let mut last = 0.0;
    for e in events {
        let tau = e["tau"].as_f64().unwrap();
        assert!(tau >= last && tau <= integration["end"].as_f64().unwrap());
        last = tau;
        assert!([1, 2].contains(&e["contact"].as_u64().unwrap()));
        assert!(
            [
                "compression ends",
                "expansion ends",
                "compresses again",
                "engages",
                "becomes primary"
            ]
            .contains(&e["kind"].as_str().unwrap()),
            "{e}"
        );
    }
    assert!(integration["error_estimate"].as_f64().unwrap() < 1e-6);
    assert!(integration["tolerance"].as_f64().unwrap() > 0.0);
}

#[test]
fn the_impulse_history_starts_at_rest_and_ends_at_the_reports_impulses() {
    let path = example("cradle-3-lzb.toml");
    let path = path.to_str().unwrap();
    let dir = std::env::temp_dir().join(format!("inertance-lzb-history-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("history.csv");
    let out = run(&[
        "solve",
        path,
        "--json",
        "--trajectory",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("tau,primary,P1,v1,E1,P2,v2,E2"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().expect(x)).collect())
        .collect();
    assert!(rows.len() > 10);
    assert!(rows.iter().all(|r| r.len() == 8));
    let first = &rows[0];
    assert_eq!(first[0], 0.0);
    assert_eq!((first[2], first[5]), (0.0, 0.0), "no impulse at τ = 0");
    assert_eq!((first[3], first[6]), (1.0, 0.0), "v⁰");
    let last = rows.last().unwrap();
    for (i, col) in [(0, 2), (1, 5)] {
        assert_eq!(
            last[col],
            j["contacts"][i]["impulse"].as_f64().unwrap(),
            "P{}",
            i + 1
        );
        assert_eq!(
            last[col + 1],
            j["contacts"][i]["velocity_after"].as_f64().unwrap()
        );
    }
    assert_eq!(last[0], j["integration"]["end"].as_f64().unwrap());
    // τ and the impulses never decrease; the energies are never negative.
    for w in rows.windows(2) {
        assert!(w[1][0] >= w[0][0] && w[1][2] >= w[0][2] && w[1][5] >= w[0][5]);
        assert!(w[1][4] >= 0.0 && w[1][7] >= 0.0);
    }

    let svg = dir.join("history.svg");
    let out = run(&["solve", path, "--trajectory", svg.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    // Every element opened is closed: as many `<tag` as `</tag>` or `/>`.
    let opened = svg.matches('<').count() - svg.matches("</").count();
    assert_eq!(
        opened,
        svg.matches("</").count() + svg.matches("/>").count()
    );
    // One line per contact in each panel (impulse above, velocity below), in its colour.
    for colour in ["#1F77B4", "#FF7F0E"] {
        let lines = svg
            .matches("<polyline")
            .zip(svg.split("<polyline").skip(1))
            .filter(|(_, rest)| rest.split('>').next().unwrap().contains(colour))
            .count();
        assert_eq!(lines, 2, "{colour}");
    }

    let json = dir.join("history.json");
    let out = run(&["solve", path, "--trajectory", json.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(0));
    let h: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(h["samples"].as_array().unwrap().len(), rows.len());

    let bad = dir.join("history.txt");
    let out = run(&["solve", path, "--trajectory", bad.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("history.txt") && err.contains(".csv, .json or .svg"),
        "{err}"
    );
    assert!(out.stdout.is_empty() && !bad.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// The CSV of an LZB sweep, as rows of named cells.
fn sweep_rows(args: &[&str], csv: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let out = run(args);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|l| {
            header
                .iter()
                .cloned()
                .zip(l.split(',').map(String::from))
                .collect()
        })
        .collect()
}

#[test]
fn a_sweep_of_the_stiffness_ratio_runs_the_lzb_law_per_point() {
    let bar = example("bar-two-supports-lzb.toml");
    let bar = bar.to_str().unwrap();
    let dir = std::env::temp_dir().join(format!("inertance-lzb-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("ratio.csv");
    let svg = dir.join("ratio.svg");
    // K₂/K₁ = 1/4, 1/2, 1, 2, 4 (K₁ = 1): written as a grid of K₂ in two sweeps, since the
    // grid is linear.
    let rows = sweep_rows(
        &[
            "sweep",
            bar,
            "--vary",
            "contact[1].stiffness=0.25:4:16",
            "--out",
            csv.to_str().unwrap(),
            "--plot",
            svg.to_str().unwrap(),
        ],
        &csv,
    );
    assert_eq!(rows.len(), 16);
    let f = |r: &std::collections::HashMap<String, String>, k: &str| -> f64 {
        r[k].parse().unwrap_or_else(|_| panic!("{k}: {r:?}"))
    };
    for r in &rows {
        assert_eq!(r["status"], "ok");
        let ratio = f(r, "contact[1].stiffness");
        let (p1, p2) = (f(r, "P1"), f(r, "P2"));
        // The energy balance closes; the momentum of the body is what the impulses gave it.
        assert!(f(r, "residual").abs() < 1e-8, "{r:?}");
        assert!((f(r, "vCy") - (-1.0 + p1 + p2)).abs() < 1e-9, "{r:?}");
        // At K₂ = K₁ the symmetric bar takes the simultaneous Newton impulses (1 + e) v⁰/(g11
        // + g12) = 1.5/2 = 0.75 each (tests/lzb.rs); the stiffer contact takes less.
        if ratio == 1.0 {
            assert!(
                (p1 - 0.75).abs() < 1e-8 && (p2 - 0.75).abs() < 1e-8,
                "{r:?}"
            );
        } else if ratio > 1.0 {
            assert!(p2 < p1, "{r:?}");
        } else {
            assert!(p1 < p2, "{r:?}");
        }
    }
    // Mirror symmetry: swapping the stiffnesses swaps the contacts' outcomes.
    let (quarter, four) = (&rows[0], &rows[15]);
    let mirrored = sweep_rows(
        &[
            "sweep",
            bar,
            "--vary",
            "contact[0].stiffness=0.25:4:2",
            "--out",
            csv.to_str().unwrap(),
        ],
        &csv,
    );
    // (K₁, K₂) = (1, 1/4) is (1/4, 1) swapped, and (1, 4) is (4, 1) swapped.
    for (a, b) in [(quarter, &mirrored[0]), (four, &mirrored[1])] {
        assert!((f(a, "P1") - f(b, "P2")).abs() < 1e-8 && (f(a, "P2") - f(b, "P1")).abs() < 1e-8);
    }
    // Very unequal stiffnesses: the stiff contact ends nearly at rest on its support.
    let far = sweep_rows(
        &[
            "sweep",
            bar,
            "--vary",
            "contact[1].stiffness=100000:1000000:2",
            "--out",
            csv.to_str().unwrap(),
        ],
        &csv,
    );
    for r in &far {
        assert!(f(r, "v2").abs() < 1e-3, "{r:?}");
    }
    let svg = std::fs::read_to_string(&svg).unwrap();
    assert!(svg.starts_with("<svg") && svg.contains("P1") && svg.contains("dEc"));

    // What the LZB sweep does not do is refused, naming the flag or the key.
    for (extra, needle) in [
        (vec!["--exact"], "--exact"),
        (vec!["--sensitivity"], "--sensitivity"),
    ] {
        let mut args = vec![
            "sweep",
            bar,
            "--vary",
            "contact[1].stiffness=1:2:3",
            "--out",
            csv.to_str().unwrap(),
        ];
        args.extend(extra);
        let out = run(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(needle), "{err}");
    }
    let out = run(&[
        "sweep",
        bar,
        "--vary",
        "contact[1].stiffness=-1:2:3",
        "--out",
        csv.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("contact[1].stiffness") && err.contains("-1"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn analyze_says_how_far_the_simultaneous_answer_is_from_the_lzb_one() {
    let bar = example("bar-two-supports-lzb.toml");
    let bar = bar.to_str().unwrap();
    let out = run(&[
        "analyze",
        bar,
        "--model",
        "newton",
        "--lzb-ratios",
        "0.1,1,10",
        "--json",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let lzb = &j["lzb"];
    assert_eq!(lzb["varied"], "contact[0].stiffness");
    let rows = lzb["ratios"].as_array().unwrap();
    assert_eq!(rows.len(), 3);
    let gap = |r: &serde_json::Value| r["gaps"]["newton"]["twist_gap"].as_f64().unwrap();
    // Equal stiffnesses: the symmetric bar takes the simultaneous impulses, no gap; r and 1/r
    // are the same bar mirrored, the same gap.
    assert!(gap(&rows[1]) < 1e-8, "{}", rows[1]);
    assert!(gap(&rows[0]) > 0.05 && (gap(&rows[0]) - gap(&rows[2])).abs() < 1e-8);
    assert!(
        rows[1]["gaps"]["newton"]["energy_gap"]
            .as_f64()
            .unwrap()
            .abs()
            < 1e-8
    );
    assert!(
        rows.iter().all(|r| r["gaps"].get("poisson").is_none()),
        "--model newton only"
    );

    // The cradle under its own law: the section by default, and the simultaneous answer far
    // from the LZB one at equal stiffnesses (the striker bounces back instead of stopping).
    let cradle = example("cradle-3-lzb.toml");
    let out = run(&["analyze", cradle.to_str().unwrap(), "--model", "newton"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        text.contains("The simultaneous law against the LZB law"),
        "{text}"
    );
    assert!(
        text.contains("depends on the contacts' stiffnesses"),
        "{text}"
    );

    // Bad ratios and a rough scene are refused, naming the value and the key.
    let out = run(&["analyze", bar, "--lzb-ratios", "1,-2"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("--lzb-ratios -2"), "{err}");
    let rough = example("rough-bar.toml");
    let out = run(&["analyze", rough.to_str().unwrap(), "--lzb-ratios", "1"]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("contact[0].mu"), "{err}");
    assert!(out.stdout.is_empty());
}

#[test]
fn bench_times_the_lzb_solve_in_f64_and_double_double() {
    let cradle = example("cradle-3-lzb.toml");
    let out = run(&[
        "bench",
        "--scene",
        cradle.to_str().unwrap(),
        "--quick",
        "--json",
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let text = j.to_string();
    assert!(j["ns_per_solve"]["f64"].as_f64().unwrap() > 0.0, "{text}");
    assert!(
        j["ns_per_solve"]["double-double"].as_f64().unwrap() > 0.0,
        "{text}"
    );
    assert!(j["ns_per_solve"]["exact"].is_null(), "{text}");
    assert!(
        text.contains("integrated in f64 and double-double only"),
        "{text}"
    );
}

/// With friction the impulse history adds, per rough contact, its tangential impulse and its
/// slip velocity (`tau{i}`, `vt{i}` in a plane): zero impulse at τ = 0, the report's
/// tangential impulse at the end, and the same numbers in the JSON history.
#[test]
fn the_impulse_history_of_a_rough_impact_has_tangential_columns() {
    let path = example("rough-bar.toml");
    let path = path.to_str().unwrap();
    let dir = std::env::temp_dir().join(format!("inertance-lzb-rough-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let csv = dir.join("history.csv");
    let json = dir.join("history.json");
    let out = run(&[
        "solve",
        path,
        "--law",
        "lzb",
        "--json",
        "--trajectory",
        csv.to_str().unwrap(),
    ]);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let j: serde_json::Value = serde_json::from_slice(&out.stdout).expect("JSON");
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next(),
        Some("tau,primary,P1,v1,E1,tau1,vt1,P2,v2,E2,tau2,vt2")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse::<f64>().expect(x)).collect())
        .collect();
    assert!(rows.iter().all(|r| r.len() == 12));
    let (first, last) = (&rows[0], rows.last().unwrap());
    for (i, col) in [(0, 5), (1, 10)] {
        assert_eq!(first[col], 0.0, "no tangential impulse at τ = 0");
        let reported = j["contacts"][i]["tangential_impulse"][0].as_f64().unwrap();
        assert_eq!(last[col], reported, "τ{}", i + 1);
        assert!(reported != 0.0, "contact {} takes friction", i + 1);
    }
    let out = run(&[
        "solve",
        path,
        "--law",
        "lzb",
        "--trajectory",
        json.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0));
    let h: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let samples = h["samples"].as_array().unwrap();
    assert_eq!(samples.len(), rows.len());
    for (s, r) in samples.iter().zip(&rows) {
        for (i, col) in [(0, 5), (1, 10)] {
            assert_eq!(s["tangential"][i][0].as_f64().unwrap(), r[col]);
            assert_eq!(s["slips"][i][0].as_f64().unwrap(), r[col + 1]);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `--precision double-double` integrates the LZB law in double-double: the JSON says so, and
/// its impulses agree with the f64 run's within twice the f64 estimate plus the double-double
/// one (each side's distance from the exact outcome is within twice its own); the other laws
/// refuse it (status 2, naming the law).
#[test]
fn precision_double_double_runs_the_lzb_law_and_only_it() {
    let cradle = example("cradle-3-lzb.toml");
    let cradle = cradle.to_str().unwrap();
    let json = |extra: &[&str]| -> serde_json::Value {
        let mut args = vec!["solve", cradle, "--json"];
        args.extend_from_slice(extra);
        let out = run(&args);
        assert_eq!(
            out.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        serde_json::from_slice(&out.stdout).expect("JSON")
    };
    let f = json(&[]);
    let d = json(&["--precision", "double-double"]);
    assert_eq!(f["scalar"], "f64");
    assert_eq!(d["scalar"], "double-double");
    let est = |j: &serde_json::Value| j["integration"]["error_estimate"].as_f64().unwrap();
    assert!(d["integration"]["tolerance"].as_f64().unwrap() < 1e-20);
    let bound = 2.0 * (est(&f) + est(&d)) + 4.0 * f64::EPSILON;
    for i in 0..2 {
        let p = |j: &serde_json::Value| j["contacts"][i]["impulse"].as_f64().unwrap();
        assert!(
            (p(&f) - p(&d)).abs() <= bound,
            "P{}: {} vs {}",
            i + 1,
            p(&f),
            p(&d)
        );
    }
    let pitching = example("pitching-bar.toml");
    let out = run(&[
        "solve",
        pitching.to_str().unwrap(),
        "--precision",
        "double-double",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--precision double-double") && err.contains("--law lzb"),
        "{err}"
    );
    assert!(out.stdout.is_empty());
}
