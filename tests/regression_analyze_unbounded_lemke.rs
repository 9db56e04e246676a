//! Regression (issue 28, item 15): `analyze` of 200 random contacts in f64 with k = 0
//! (`tests/fuzz_corpus/large/analyze-200-contacts-k0.toml`) ran past two minutes. The stage
//! that was not bounded: Lemke's method for the unilateral law's part of the report. On a
//! singular G (rank 6 of 200) rounding made its lexicographic path cycle, and the pivot budget
//! that should end it was 64(N + 1)² pivots of O(N²) each, O(N⁴) work. Now the budget is
//! `PIVOTS_PER_ROW`·(N + 1) = 10(N + 1) pivots, O(N³), the f64 unilateral law is limited to
//! 300 contacts (0.8 s at the limit in a release build), and a float path that runs out says
//! so and points to `--exact`.
//!
//! The same floats also ended paths on false rays: 10 random contacts with k = 0 were called
//! "jammed", a verdict with status 3, while exact arithmetic solves them. With every k_i = 0
//! no scene can be jammed (`impact::unilateral`: jammed iff some y ≥ 0 in ker G has y_i > 0
//! at an approaching contact with k_i > 0), so here the theorem is the reference; a float ray
//! is now reported as decided in floating point, `--exact` decides.

use std::path::PathBuf;
use std::process::Command;

use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::impact::unilateral::{UnilateralError, max_unilateral_contacts};
use inertance::linalg::lcp::PIVOTS_PER_ROW;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::scene::pipeline::prepare;
use inertance::tools::analyze::analyze_scene;

fn finding() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus/large/analyze-200-contacts-k0.toml")
}

/// `n` random contacts (integer points in [−9, 9]³, integer normals in [−3, 3]³) with k = `k`
/// (one of {0, 3/10, 1/2, 9/10} at random when `None`): a seeded SplitMix64.
fn random(n: usize, seed: u64, k: Option<&str>) -> Scene {
    Scene::parse(&random_text(n, seed, k), "random.toml").unwrap()
}

/// The text of [`random`]'s scene.
fn random_text(n: usize, seed: u64, k: Option<&str>) -> String {
    let mut state = seed;
    let mut next = |lo: i64, hi: i64| {
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        lo + ((z ^ (z >> 31)) % (hi - lo + 1) as u64) as i64
    };
    let mut text = String::from(
        "[body]\nmass = 2\ninertia = [1, 2, 3]\nvelocity = [0.3, -0.2, -1]\nangular_velocity = [0.1, 0.2, -0.3]\n",
    );
    for _ in 0..n {
        let p = [next(-9, 9), next(-9, 9), next(-9, 9)];
        let mut m = [next(-3, 3), next(-3, 3), next(-3, 3)];
        if m == [0, 0, 0] {
            m = [0, 0, -1];
        }
        let k = k.unwrap_or(["0", "0.3", "0.5", "0.9"][next(0, 3) as usize]);
        text += &format!(
            "[[contact]]\npoint = [{}, {}, {}]\nnormal = [{}, {}, {}]\nk = {k}\n",
            p[0], p[1], p[2], m[0], m[1], m[2]
        );
    }
    text
}

/// Each model's unilateral solve in `T`: the pivots made, or the error.
fn unilateral<T: Scalar>(scene: &Scene) -> Vec<Result<usize, UnilateralError>> {
    let mut impact = Impact::assemble(&prepare::<T>(scene).unwrap()).unwrap();
    [Model::Newton, Model::Poisson]
        .into_iter()
        .map(|m| {
            let mut out = Outcome::default();
            impact.solve_unilateral(m, &mut out).map(|a| a.pivots)
        })
        .collect()
}

/// The finding answers, and the unilateral part is either solved or says that the budget
/// ran out; every path stays within it (Poisson: two phases, and the least-norm step's own
/// path, each within its budget).
#[test]
fn the_finding_is_analysed_within_the_budget() {
    let scene = Scene::load(&finding()).unwrap();
    let n = scene.contacts.len();
    assert!(n <= max_unilateral_contacts::<f64>());
    let report = analyze_scene::<f64>(&scene, None).expect("analysed");
    assert_eq!((report.contacts, report.rank), (200, 6));
    let budget = PIVOTS_PER_ROW * (n + 1);
    for m in &report.models {
        if let Err(why) = &m.unilateral {
            assert!(
                why.contains(&format!("within {budget} pivots")) && why.contains("--exact"),
                "{why}"
            );
        }
    }
    for r in unilateral::<f64>(&scene) {
        match r {
            Ok(pivots) => assert!(pivots <= 3 * budget),
            Err(UnilateralError::IterationLimit { pivots, .. }) => assert_eq!(pivots, budget),
            Err(e) => panic!("{e}"),
        }
    }
}

/// With every k_i = 0 the theorem says no body is jammed: exact arithmetic always solves
/// (7 to 40 contacts, singular G); f64, where its path ends on a ray, says the verdict is
/// rounding's — never a plain "jammed", in the library and through the CLI.
#[test]
fn with_k_zero_nothing_is_jammed_and_a_float_ray_says_so() {
    let mut ray = None;
    for seed in 0..12u64 {
        let n = 7 + (seed as usize * 3) % 34;
        let scene = random(n, seed, Some("0"));
        for r in unilateral::<Exact>(&scene) {
            assert!(r.is_ok(), "seed {seed}, N = {n}: exact: {r:?}");
        }
        for r in unilateral::<f64>(&scene) {
            match r {
                Err(e @ UnilateralError::Jammed { rounded, .. }) => {
                    assert!(rounded, "seed {seed}: {e}");
                    assert!(e.to_string().contains("`--exact` decides"), "{e}");
                    ray.get_or_insert((n, seed));
                }
                Err(e @ UnilateralError::IterationLimit { .. }) => {
                    assert!(e.to_string().contains("--exact"), "{e}")
                }
                Err(e) => panic!("seed {seed}: {e}"),
                Ok(_) => {}
            }
        }
    }
    let (n, seed) = ray.expect("no float ray met: the test checks nothing");
    let dir = std::env::temp_dir().join(format!("inertance-jam-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, random_text(n, seed, Some("0"))).unwrap();
    let run = |exact: bool| {
        let mut args = vec!["solve", path.to_str().unwrap(), "--law", "unilateral"];
        if exact {
            args.push("--exact");
        }
        Command::new(env!("CARGO_BIN_EXE_inertance"))
            .args(&args)
            .output()
            .unwrap()
    };
    let (float, exact) = (run(false), run(true));
    std::fs::remove_dir_all(&dir).ok();
    let err = String::from_utf8_lossy(&float.stderr);
    assert_eq!(float.status.code(), Some(3), "{err}");
    assert!(
        err.contains("`--exact` decides") && !err.contains("a verdict, not a number"),
        "{err}"
    );
    assert_eq!(exact.status.code(), Some(0));
}

/// The budget is not what ends an exact path: on random scenes of 7 to 40 contacts with
/// random k (every classification of G's rank 6), exact paths are at most about 2.5 N pivots
/// long per phase, a quarter of the budget.
#[test]
fn exact_paths_stay_well_within_the_budget() {
    for seed in 100..112u64 {
        let n = 7 + (seed as usize * 7) % 34;
        let scene = random(n, seed, None);
        for r in unilateral::<Exact>(&scene) {
            match r {
                Ok(pivots) => assert!(
                    pivots <= 3 * PIVOTS_PER_ROW * (n + 1) / 4,
                    "seed {seed}, N = {n}: {pivots} pivots"
                ),
                Err(UnilateralError::Jammed { rounded: false, .. }) => {}
                Err(e) => panic!("seed {seed}, N = {n}: {e}"),
            }
        }
    }
}
