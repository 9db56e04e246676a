//! Regression: `analyze` on many contacts ran for minutes (a fuzz finding, formerly pending):
//! on 220 contacts `analyze --exact` took 100 s in a release build and over a minute in a debug
//! one — the family of N − 6 solutions was projected to least norm through a dense
//! (N − 6)×(N − 6) system in rationals, and Lemke's method ran on an N-contact tableau in
//! rationals; in f64, 2000 contacts took over two minutes.
//!
//! Now the least-norm member of the family is found from an r×r system (r = rank G ≤ 6, the
//! family's structure Πᵀ[−M; I]; 102 s → 28 s on that scene), and `analyze` takes at most
//! `MAX_EXACT_CONTACTS` = 48 contacts in exact arithmetic (1.3 s on 48 of the scene's contacts,
//! release) and `MAX_FLOAT_CONTACTS` = 1000 in floats (0.7 s on 1000), refusing more at once:
//! status 2, the key `contact`, the count and the limit, nothing on stdout.

use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

use inertance::scalar::Exact;
use inertance::scalar::symbolic::RatFun;
use inertance::scene::Scene;
use inertance::scene::pipeline::RunError;
use inertance::tools::analyze::{MAX_EXACT_CONTACTS, MAX_FLOAT_CONTACTS, analyze_scene};

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

#[test]
fn exact_analysis_of_220_contacts_is_refused_at_once_naming_the_limit() {
    let start = Instant::now();
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["analyze", finding().to_str().unwrap(), "--exact"])
        .output()
        .unwrap();
    assert!(
        start.elapsed() < Duration::from_secs(10),
        "{:?}",
        start.elapsed()
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(out.stdout.is_empty());
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("key `contact` = 220 contacts")
            && err.contains("`analyze --exact` takes at most 48 contacts")
            && err.contains("without --exact takes up to 1000"),
        "{err}"
    );
    let scene = Scene::load(&finding()).unwrap();
    for (key, message) in [
        refusal(analyze_scene::<Exact>(&scene, None)),
        refusal(analyze_scene::<RatFun>(&scene, None)),
    ] {
        assert_eq!(key, "contact");
        assert!(
            message.contains(&format!("at most {MAX_EXACT_CONTACTS}")),
            "{message}"
        );
    }
}

/// Below the limit the exact analysis answers, in a bounded time: the scene's first 24
/// contacts (G singular, rank 6; 1.7 s in a debug build).
#[test]
fn below_the_limit_the_exact_analysis_answers() {
    let text = std::fs::read_to_string(finding()).unwrap();
    let mut parts = text.split("[[contact]]");
    let mut cut = parts.next().unwrap().to_string();
    for c in parts.take(24) {
        cut += "[[contact]]";
        cut += c;
    }
    let scene = Scene::parse(&cut, "first-24").unwrap();
    assert_eq!(scene.contacts.len(), 24);
    let start = Instant::now();
    let report = analyze_scene::<Exact>(&scene, None).expect("analysed");
    assert!(
        start.elapsed() < Duration::from_secs(30),
        "{:?}",
        start.elapsed()
    );
    assert_eq!((report.contacts, report.rank), (24, 6));
}

/// In floats the limit is 1000 contacts: 1001 are refused before anything is assembled.
#[test]
fn float_analysis_beyond_its_limit_is_refused_at_once() {
    let mut text = String::from(
        "[body]\nmass = 1\ninertia = [1, 2, 3]\nvelocity = [0, 0, -1]\nangular_velocity = [0, 0, 0]\n",
    );
    for i in 0..=MAX_FLOAT_CONTACTS {
        let x = (i % 40) as f64 / 10.0 - 2.0;
        let y = (i / 40) as f64 / 10.0 - 1.0;
        text += &format!("[[contact]]\npoint = [{x}, {y}, -1]\nnormal = [0, 0, -1]\nk = 0.5\n");
    }
    let scene = Scene::parse(&text, "many").unwrap();
    let start = Instant::now();
    let (key, message) = refusal(analyze_scene::<f64>(&scene, None));
    assert!(start.elapsed() < Duration::from_secs(1));
    assert_eq!(key, "contact");
    assert!(
        message.contains("1001 contacts") && message.contains("`analyze` takes at most 1000"),
        "{message}"
    );
}
