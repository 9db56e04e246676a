//! Regression (issue 28, item 15: every stage of `analyze` bounded): the coincident points.
//!
//! `analyze` lists every pair of contacts at one point with its single-impulse reduction
//! (eq. 69–72). For k contacts at one point that is k(k − 1)/2 pairs: 3000 contacts made 4.5
//! million — 97 s, 10 GB of memory and 900 MB of JSON in a release build — while the rest of
//! the analysis is linear in N. Now at most `MAX_COINCIDENT` = 1000 pairs are listed, of at most
//! `MAX_COINCIDENT_CANDIDATES` examined, and `coincident_truncated` says when more may exist.
//!
//! And the reduction P = (1 + k_i) v_ix⁰ / g_ii divided by g_ii = 0 where constraints absorb
//! the normal's impulse (a fuzz finding of the long run: `analyze --exact` panicked, f64 wrote
//! `null`). For such a contact every free screw D_a is reciprocal to its axis, D_aᵀ η E_i = 0,
//! so W E_i = D M_red⁻¹ Dᵀ η E_i = 0 and g_ii = 0 exactly; the body cannot move along the
//! normal (v_ix⁰ = 0 too) and 0·P = 0 fixes no P. The pair is listed without a reduction.

use std::path::PathBuf;
use std::process::Command;

use inertance::analysis::{MAX_COINCIDENT, analyze};
use inertance::impact::solve::Impact;
use inertance::mechanics::screw::Screw;
use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::pipeline::prepare;
use inertance::tools::analyze::analyze_scene;
use num_traits::Zero;

fn finding() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus/coincident-absorbed-by-constraints.toml")
}

/// `n` contacts at one point under a falling box.
fn cluster(n: usize) -> String {
    let mut text = String::from(
        "[body]\nmass = 1\ninertia = [1, 2, 3]\nvelocity = [0, 0, -1]\nangular_velocity = [0.1, 0.2, 0]\n",
    );
    for _ in 0..n {
        text += "[[contact]]\npoint = [0.5, 0.25, -1]\nnormal = [0, 0, -1]\nk = 0.5\n";
    }
    text
}

#[test]
fn a_cluster_of_3000_contacts_lists_a_bounded_number_of_pairs() {
    let dir = std::env::temp_dir().join(format!("inertance-cluster-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("cluster.toml");
    std::fs::write(&path, cluster(3000)).unwrap();
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
    let pairs = json["coincident"].as_array().unwrap();
    assert_eq!(pairs.len(), MAX_COINCIDENT);
    assert_eq!(json["coincident_truncated"], true);
    // The first pairs in order: contact 1 with 2, 3, …; each the same axis, P = (1 + k)·1/g.
    assert_eq!(pairs[0]["contacts"], serde_json::json!([1, 2]));
    assert_eq!(pairs[1]["contacts"], serde_json::json!([1, 3]));
    assert!(pairs.iter().all(|p| p["same_axis"] == true));
}

#[test]
fn below_the_cap_every_pair_is_listed_and_nothing_is_truncated() {
    // 45 contacts at one point: 990 pairs, all listed, on the wrench route (N > 24).
    let scene = Scene::parse(&cluster(45), "cluster.toml").unwrap();
    let report = analyze_scene::<f64>(&scene, None).expect("analysed");
    assert_eq!(report.coincident.len(), 45 * 44 / 2);
    assert!(!report.coincident_truncated);
}

#[test]
fn a_normal_the_constraints_absorb_has_no_single_impulse() {
    let scene = Scene::load(&finding()).unwrap();
    // The closed form: each free screw is reciprocal to contact 1's axis, so g_11 = 0.
    let problem = prepare::<Exact>(&scene).unwrap();
    let c = &problem.contacts()[0];
    let axis = Screw::axis(&c.point, &c.normal);
    let constraints = problem.constraints().expect("constrained");
    for d in &constraints.free {
        assert!(d.reciprocal(&axis).is_zero());
    }
    let mut impact = Impact::assemble(&problem).unwrap();
    assert!(impact.g_hat()[0].is_zero());
    let analysis = analyze(&mut impact, &scene.models);
    assert_eq!(analysis.coincident.len(), 1);
    assert_eq!(analysis.coincident[0].pair, (0, 1));
    assert!(analysis.coincident[0].single_impulse.is_none());
    // Both arithmetics answer, without a reduction for the pair.
    let exact = analyze_scene::<Exact>(&scene, None).expect("exact");
    let float = analyze_scene::<f64>(&scene, None).expect("f64");
    for report in [&exact, &float] {
        assert_eq!(report.coincident.len(), 1);
        assert!(report.coincident[0].2.is_none());
        assert!(report.to_text().contains("no single-impulse reduction"));
        assert!(report.to_json()["coincident"][0]["single_impulse"].is_null());
    }
}
