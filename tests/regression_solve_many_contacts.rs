//! Regression (issue 28, item 15): `solve` on many contacts. It assembled and factored the
//! N×N matrix G whatever N: on 60,000 contacts it aborted ("memory allocation of 28800000000
//! bytes failed", a backtrace, killed by a signal), and `solve --exact` on 2000 contacts with
//! non-unit normals factored G in rationals for 114 s before saying "singular".
//!
//! G = Eᵀ η W E has rank at most the body's degrees of freedom (6 when free), so with more
//! contacts G is singular whatever the numbers. `solve` now decides that before G exists, with
//! rank G from the contact wrenches in O(N) work and memory (`analysis::wrench_space`, the
//! route `analyze` takes), and exact solves beyond `MAX_EXACT_CONTACTS` = 1000 contacts are
//! refused at once (status 2, key `contact`, naming the limit and `solve` without --exact).
//! The other stages whose work grows faster than N have their limits too: the integration
//! with friction (3N×3N blocks) beyond `MAX_FRICTION_CONTACTS` = 500, `derive` beyond
//! `MAX_DERIVE_CONTACTS` = 64.

use std::alloc::{GlobalAlloc, Layout, System};
use std::path::PathBuf;
use std::process::Command;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use inertance::impact::solve::{Impact, SolveError};
use inertance::scalar::{Exact, Scalar};
use inertance::scene::limits::{MAX_DERIVE_CONTACTS, MAX_EXACT_CONTACTS, MAX_FRICTION_CONTACTS};
use inertance::scene::pipeline::{RunError, prepare, run};
use inertance::scene::{ContactSpec, Scene};
use inertance::tools::analyze::analyze_scene;

/// Counts the largest single allocation (bytes).
struct Largest;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Largest = Largest;

/// The tests run on threads of one process: one at a time, so that the allocation counted is
/// the solve's.
static ONE_AT_A_TIME: Mutex<()> = Mutex::new(());

fn one_at_a_time() -> std::sync::MutexGuard<'static, ()> {
    ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner())
}

/// A table of `n` contacts under a falling box (the plane z = −1, normal −z): rank G = 3.
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

/// `n` contacts at integer points in [−9, 9]³ with integer normals in [−3, 3]³ (non-unit),
/// k from {0, 3/10, 1/2, 9/10}, and `mu` when given: a seeded SplitMix64.
fn random(n: usize, seed: u64, mu: Option<&str>) -> String {
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
        let k = ["0", "0.3", "0.5", "0.9"][next(0, 3) as usize];
        text += &format!(
            "[[contact]]\npoint = [{}, {}, {}]\nnormal = [{}, {}, {}]\nk = {k}\n",
            p[0], p[1], p[2], m[0], m[1], m[2]
        );
        if let Some(mu) = mu {
            text += &format!("mu = {mu}\n");
        }
    }
    text
}

fn cli(args: &[&str], text: &str, tag: &str) -> std::process::Output {
    let dir = std::env::temp_dir().join(format!("inertance-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path: PathBuf = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let mut all = vec![args[0], path.to_str().unwrap()];
    all.extend_from_slice(&args[1..]);
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(&all)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    out
}

/// The rank `solve` reports for a singular G, or a panic naming what came instead.
fn singular_rank<T: Scalar>(scene: &Scene) -> usize {
    match run::<T>(scene, None) {
        Err(RunError::Solve(SolveError::Singular {
            rank,
            contacts,
            rounded: false,
        })) => {
            assert_eq!(contacts, scene.contacts.len());
            rank
        }
        Err(e) => panic!("{}: not singular: {e}", T::NAME),
        Ok(_) => panic!("{}: solved", T::NAME),
    }
}

#[test]
fn sixty_thousand_contacts_are_singular_without_g() {
    let _guard = one_at_a_time();
    let out = cli(&["solve"], &table(60_000), "solve-60000");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("singular (Δ = 0; rank 3 of 60000)") && !err.contains("memory allocation"),
        "{err}"
    );
}

/// The solve's largest single allocation is O(N): no larger than the scene's own list of
/// contacts (N · size_of::<ContactSpec>(), about 2 KB per contact, which scaling the scene
/// copies), on 10⁴ contacts in f64 and on `MAX_EXACT_CONTACTS` exactly — where G alone would
/// take 8N bytes per contact in f64 (80 KB at N = 10⁴) and more in rationals.
#[test]
fn the_solve_allocates_nothing_of_order_n_squared() {
    let _guard = one_at_a_time();
    for (n, exact) in [(10_000, false), (MAX_EXACT_CONTACTS, true)] {
        let scene = Scene::parse(&random(n, 7, None), "many.toml").unwrap();
        LARGEST.store(0, Ordering::Relaxed);
        let rank = if exact {
            singular_rank::<Exact>(&scene)
        } else {
            singular_rank::<f64>(&scene)
        };
        let largest = LARGEST.load(Ordering::Relaxed);
        assert_eq!(rank, 6);
        assert!(
            largest <= n * std::mem::size_of::<ContactSpec>().max(1024),
            "N = {n} (exact: {exact}): an allocation of {largest} bytes"
        );
    }
}

/// The rank `solve` decides from the wrenches is the rank of the N×N matrix G, factored
/// exactly (an independent formulation: LDLᵀ with exact pivots), on random scenes of 7 to 40
/// contacts — also when contacts repeat or lie on a plane, so that the rank is below 6.
#[test]
fn the_rank_from_the_wrenches_is_the_rank_of_g() {
    let _guard = one_at_a_time();
    for seed in 0..24u64 {
        let n = 7 + (seed as usize * 5) % 34;
        let text = if seed % 3 == 0 {
            table(n)
        } else {
            random(n, seed, None)
        };
        let scene = Scene::parse(&text, "random.toml").unwrap();
        let dense = Impact::assemble(&prepare::<Exact>(&scene).unwrap()).unwrap();
        assert_eq!(
            singular_rank::<Exact>(&scene),
            dense.rank(),
            "seed {seed}, N = {n}"
        );
        assert_eq!(singular_rank::<f64>(&scene), dense.rank(), "seed {seed}");
    }
}

#[test]
fn exact_solves_beyond_the_limit_are_refused_at_once() {
    let _guard = one_at_a_time();
    let text = random(2000, 11, None);
    let out = cli(&["solve", "--exact"], &text, "solve-exact-2000");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(out.stdout.is_empty());
    assert!(
        err.contains("key `contact` = 2000 contacts")
            && err.contains(&format!(
                "exact arithmetic (`--exact`) takes at most {MAX_EXACT_CONTACTS} contacts"
            ))
            && err.contains("without --exact, `solve` and `sweep` take any number"),
        "{err}"
    );
    // Without --exact the same scene is answered: singular, rank 6.
    let out = cli(&["solve"], &text, "solve-2000");
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{err}");
    assert!(err.contains("rank 6 of 2000"), "{err}");
}

#[test]
fn friction_beyond_its_limit_is_refused_at_once() {
    let _guard = one_at_a_time();
    let scene = Scene::parse(
        &random(MAX_FRICTION_CONTACTS + 1, 3, Some("0.3")),
        "friction.toml",
    )
    .unwrap();
    let limit = format!("takes at most {MAX_FRICTION_CONTACTS} contacts");
    match run::<f64>(&scene, None) {
        Err(RunError::Scene(e)) => {
            assert_eq!(e.key, "contact");
            assert!(e.message.contains(&limit), "{e}");
        }
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(_) => panic!("integrated"),
    }
    // `analyze` reports the rest, and says why the friction part is missing.
    let report = analyze_scene::<f64>(&scene, None).expect("analysed");
    let friction = report.friction.expect("a frictional scene");
    assert!(friction.readouts.is_empty());
    assert!(friction.failures.iter().any(|f| f.contains(&limit)));
}

#[test]
fn derive_beyond_its_limit_is_refused() {
    let _guard = one_at_a_time();
    let text = table(MAX_DERIVE_CONTACTS + 1).replace("mass = 1", "mass = \"m\"");
    let symbols = vec!["m".to_string()];
    let scene = Scene::parse_with(&text, "derive.toml", &symbols).unwrap();
    match inertance::tools::derive::derive(&scene, &symbols, None) {
        Err(RunError::Scene(e)) => {
            assert_eq!(e.key, "contact");
            assert!(
                e.message
                    .contains(&format!("`derive` takes at most {MAX_DERIVE_CONTACTS}")),
                "{e}"
            );
        }
        Err(e) => panic!("refused for another reason: {e}"),
        Ok(_) => panic!("derived"),
    }
}
