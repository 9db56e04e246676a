//! The exact solve on the peer corpus (`benches/peers/corpus.txt`: 1000 random two-contact
//! scenes, the scenes `benches/peers/compare.py` times SymPy on): one iteration solves every
//! scene — assemble + Newton + Poisson, every output — in [`Exact`] (machine words, Henrici's
//! reductions) and in plain `BigRational`, the arithmetic `Exact` replaced. At the end it prints
//! the ratio BigRational / Exact measured in the same run.
//!
//! Group `radical`: posed scenes, whose numbers are radicals (cos 30° = √3/2), solved exactly in
//! the symbolic field as `solve --exact` does — the tilted box of `examples/tilted-box.toml` at
//! 30°, 45°, 60° and 15° (two contacts) and `tests/posed/box-floor-wall.toml` at 30° (four):
//! `solve/…` assembles and solves both laws, every output (the `exact/radicals` row of
//! `inertance bench --scene`); `report/…` is `scene::pipeline::run` — reading the numbers into
//! the field, the solve, its checks and the report with every value's exact text and decimal.
//!
//! `cargo bench --bench exact`

use std::hint::black_box;
use std::time::Instant;

use criterion::{Criterion, Throughput};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use num_rational::BigRational;

fn corpus() -> Vec<Scene> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/benches/peers/corpus.txt");
    let text = std::fs::read_to_string(path).expect("benches/peers/corpus.txt");
    inertance::tools::corpus::parse(&text).expect("a valid corpus")
}

/// Every scene's problem in `T`, built beforehand (the bench times the solve, not the reading).
fn problems<T: Scalar>(scenes: &[Scene]) -> Vec<Problem<T>> {
    scenes.iter().map(|s| s.problem::<T>().unwrap()).collect()
}

/// One pass over the corpus: assemble + Newton + Poisson per scene, buffers reused.
fn pass<T: Scalar>(
    problems: &[Problem<T>],
    impact: &mut Impact<T>,
    n: &mut Outcome<T>,
    q: &mut Outcome<T>,
) {
    for p in problems {
        impact.reassemble(black_box(p)).unwrap();
        impact.solve(Model::Newton, n).unwrap();
        impact.solve(Model::Poisson, q).unwrap();
    }
}

fn bench<T: Scalar>(c: &mut Criterion, name: &str, problems: &[Problem<T>]) {
    let mut impact = Impact::assemble(&problems[0]).unwrap();
    let (mut n, mut q) = (Outcome::default(), Outcome::default());
    let mut group = c.benchmark_group("peer-corpus");
    group.throughput(Throughput::Elements(problems.len() as u64));
    group.sample_size(10);
    group.bench_function(name, |b| {
        b.iter(|| pass(problems, &mut impact, &mut n, &mut q))
    });
    group.finish();
}

/// Seconds for one pass.
fn time_pass<T: Scalar>(problems: &[Problem<T>]) -> f64 {
    let mut impact = Impact::assemble(&problems[0]).unwrap();
    let (mut n, mut q) = (Outcome::default(), Outcome::default());
    let t = Instant::now();
    pass(problems, &mut impact, &mut n, &mut q);
    t.elapsed().as_secs_f64()
}

/// BigRational / Exact over the corpus: the median over 7 interleaved rounds of the per-round
/// ratio, so that a burst of load on a shared machine does not decide it.
fn ratio(exact: &[Problem<Exact>], big: &[Problem<BigRational>]) -> (f64, f64, f64) {
    let mut rounds = Vec::with_capacity(7);
    for _ in 0..7 {
        let e = time_pass(exact);
        let b = time_pass(big);
        rounds.push((b / e, e, b));
    }
    rounds.sort_by(|x, y| x.0.total_cmp(&y.0));
    rounds[rounds.len() / 2]
}

/// The posed scenes of the `radical` group: (name, scene).
fn posed() -> Vec<(String, Scene)> {
    let root = env!("CARGO_MANIFEST_DIR");
    let read = |path: &str| std::fs::read_to_string(format!("{root}/{path}")).expect(path);
    let (tilted, corner) = (
        read("examples/tilted-box.toml"),
        read("tests/posed/box-floor-wall.toml"),
    );
    let at = |text: &str, deg: u32| text.replace("\"30 deg\"", &format!("\"{deg} deg\""));
    let mut out: Vec<(String, Scene)> = [30, 45, 60, 15]
        .into_iter()
        .map(|deg| {
            let scene = Scene::parse(&at(&tilted, deg), "tilted-box.toml").unwrap();
            (format!("tilted-box-{deg}"), scene)
        })
        .collect();
    let scene = Scene::parse(&corner, "box-floor-wall.toml").unwrap();
    out.push(("box-floor-wall-30".into(), scene));
    out
}

fn radical(c: &mut Criterion) {
    let mut group = c.benchmark_group("radical");
    group.sample_size(20);
    for (name, scene) in posed() {
        let problem = scene.problem::<RatFun>().unwrap();
        let mut impact = Impact::assemble(&problem).unwrap();
        let (mut n, mut q) = (Outcome::default(), Outcome::default());
        group.bench_function(format!("solve/{name}"), |b| {
            b.iter(|| {
                impact.reassemble(black_box(&problem)).unwrap();
                impact.solve(Model::Newton, &mut n).unwrap();
                impact.solve(Model::Poisson, &mut q).unwrap();
            })
        });
        group.bench_function(format!("report/{name}"), |b| {
            b.iter(|| inertance::scene::pipeline::run::<RatFun>(black_box(&scene), None).unwrap())
        });
    }
    group.finish();
}

fn main() {
    let scenes = corpus();
    let exact = problems::<Exact>(&scenes);
    let big = problems::<BigRational>(&scenes);
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c, "exact", &exact);
    bench(&mut c, "bigrational", &big);
    radical(&mut c);
    c.final_summary();
    // `cargo test` runs this binary too (criterion's test mode, unoptimised): measure only
    // under `cargo bench`, which passes `--bench`.
    if std::env::args().any(|a| a == "--bench") {
        let (r, e, b) = ratio(&exact, &big);
        let per = |s: f64| s / scenes.len() as f64 * 1e6;
        println!(
            "\nexact solve of the peer corpus ({} scenes, assemble + Newton + Poisson, every \
             output): Exact {:.1} µs, BigRational {:.1} µs per scene: BigRational / Exact = {r:.1}×",
            scenes.len(),
            per(e),
            per(b),
        );
    }
}
