//! Regression: `analyze` on many contacts ran for minutes (a fuzz finding, formerly pending):
//! on 220 contacts `analyze --exact` took 100 s in a release build — the family of N − 6
//! solutions was projected to least norm through a dense (N − 6)×(N − 6) system in rationals,
//! and Lemke's method ran on an N-contact tableau in rationals; in f64, 2000 contacts took over
//! two minutes, and 60,000 aborted on a 2 GiB allocation (G, N×N). It was then refused beyond
//! 48 contacts (exact) and 1000 (f64).
//!
//! Now, beyond `DENSE_CONTACTS` = 24, `analyze` works in the space of the contact wrenches
//! (`analysis::wrench_space`, cost linear in N; tests/linear_n.rs checks it against the N×N
//! analysis): 220 exact contacts answer in milliseconds, 60,000 in f64 in seconds (mostly
//! reading the scene). The unilateral law (Lemke on the N×N tableau) is reported up to its own
//! limit and says why beyond it; `solve --law unilateral` refuses beyond that limit at once
//! (issue 16: 2000 contacts ran over two minutes). What remains limited is named: more than
//! `MAX_EXACT_CONTACTS` = 1000 exact contacts are refused at once, status 2, key `contact`.

use std::path::PathBuf;
use std::process::Command;

use inertance::impact::unilateral::max_unilateral_contacts;
use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::Scene;
use inertance::scene::pipeline::RunError;
use inertance::tools::analyze::{MAX_EXACT_CONTACTS, analyze_scene};

fn finding() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus/large/analyze-220-contacts.toml")
}

/// The refusal's key and message, or a panic naming what came instead.
fn refusal(r: Result<inertance::tools::analyze::AnalysisReport, RunError>) -> (String, String) {
    match r {
        Err(RunError::Scene(e)) => (e.key.clone(), e.to_string()),
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(_) => panic!("analysed"),
    }
}

/// A table of `n` contacts under a falling box (the plane z = −1, normal −z).
fn table(n: usize) -> String {
    let mut text = String::from(
        "[body]\nmass = 1\ninertia = [1, 2, 3]\nvelocity = [0, 0, -1]\nangular_velocity = [0.1, 0.2, 0]\n",
    );
    for i in 0..n {
        let x = (i % 300) as f64 / 100.0 - 1.5;
        let y = (i / 300) as f64 / 1000.0 - 0.2;
        text += &format!("[[contact]]\npoint = [{x}, {y}, -1]\nnormal = [0, 0, -1]\nk = 0.5\n");
    }
    text
}

#[test]
fn exact_analysis_of_220_contacts_answers() {
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["analyze", finding().to_str().unwrap(), "--exact", "--json"])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["contacts"], 220);
    assert_eq!(json["rank"], 6);
    assert_eq!(json["det"], "0");
    for (_, m) in json["models"].as_object().unwrap() {
        let why = m["unilateral"]["reason"].as_str().unwrap_or_default();
        assert!(
            why.contains(&format!("at most {}", max_unilateral_contacts::<Exact>())),
            "{m}"
        );
        if m["classification"] == "singular-compatible" {
            assert_eq!(m["family"]["null_space_dimension"], 214);
            assert!(m["family"]["null_space"].is_null());
        }
    }
    let scene = Scene::load(&finding()).unwrap();
    let report = analyze_scene::<RatFun>(&scene, None).expect("analysed");
    assert_eq!((report.contacts, report.rank), (220, 6));
}

/// Below `DENSE_CONTACTS` the report is as before: the first 24 contacts of the finding list
/// the family's basis (G singular, rank 6).
#[test]
fn below_the_dense_limit_the_family_basis_is_listed() {
    let text = std::fs::read_to_string(finding()).unwrap();
    let mut parts = text.split("[[contact]]");
    let mut cut = parts.next().unwrap().to_string();
    for c in parts.take(24) {
        cut += "[[contact]]";
        cut += c;
    }
    let scene = Scene::parse(&cut, "first-24").unwrap();
    let report = analyze_scene::<Exact>(&scene, None).expect("analysed");
    assert_eq!((report.contacts, report.rank), (24, 6));
    for m in &report.models {
        assert_eq!(m.family.len(), m.nullity);
    }
}

/// Beyond `MAX_EXACT_CONTACTS` the exact analysis is refused before anything is assembled.
#[test]
fn exact_analysis_beyond_its_limit_is_refused_naming_it() {
    let scene = Scene::parse(&table(MAX_EXACT_CONTACTS + 1), "many").unwrap();
    let (key, message) = refusal(analyze_scene::<Exact>(&scene, None));
    assert_eq!(key, "contact");
    assert!(
        message.contains(&format!("{} contacts", MAX_EXACT_CONTACTS + 1))
            && message.contains(&format!(
                "`analyze --exact` takes at most {MAX_EXACT_CONTACTS}"
            )),
        "{message}"
    );
}

/// 60,000 contacts in f64 aborted on a 2 GiB allocation: now the CLI answers (rank 3: a
/// plane's contacts), with Δ = 0, the family's dimension and the unilateral law's limit.
#[test]
fn float_analysis_of_60000_contacts_answers() {
    let dir = std::env::temp_dir().join(format!("inertance-60000-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("table.toml");
    std::fs::write(&path, table(60_000)).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["analyze", path.to_str().unwrap(), "--json"])
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["contacts"], 60_000);
    assert_eq!(json["rank"], 3);
    assert_eq!(json["condition_number"], "inf");
    let newton = &json["models"]["newton"];
    assert_eq!(newton["classification"], "singular-compatible");
    assert_eq!(newton["family"]["null_space_dimension"], 60_000 - 3);
    assert_eq!(newton["family"]["velocities_fixed"], true);
}

/// Issue 16: `solve --law unilateral` on 2000 contacts ran over two minutes; now it is refused
/// at once, status 2, naming the limit.
#[test]
fn unilateral_solve_beyond_its_limit_is_refused_at_once() {
    let dir = std::env::temp_dir().join(format!("inertance-u2000-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("table.toml");
    std::fs::write(&path, table(2000)).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["solve", path.to_str().unwrap(), "--law", "unilateral"])
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains(&format!(
            "at most {} contacts",
            max_unilateral_contacts::<f64>()
        )) && err.contains("(2000 given)"),
        "{err}"
    );
}
