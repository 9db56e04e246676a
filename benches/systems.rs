//! The cost of a system's impact against its number of bodies: the planar chain of
//! `inertance::tools::chain` (N revolute links, the first pinned to the ground, tip and middle link
//! striking the ground: two contacts) in f64, N = 1, 10, 100, 1000.
//!
//! * `chain/tree/N`: everything from the data — [`System::new`] (checks, the joints' screws
//!   and their articulated-body factorization along the tree, `mechanics::system::articulated`),
//!   [`Impact::assemble`], Newton and
//!   Poisson, every output; throughput in bodies, so criterion prints bodies per second;
//! * `chain/newton/N`: the same with Newton's law only (what Pinocchio's `impulseDynamics`
//!   computes; `benches/peers/chains.py`);
//! * `chain/dense/N` (N ≤ 100): the same through the dense pivoted factorization of K (the path
//!   closed loops take, and every system took before the tree): O(rows³).
//!
//! * `examples/{cradle-3,box-on-box}`: the examples of several bodies from their data under
//!   their laws; throughput in contacts, so criterion prints contacts per second.
//!
//! At the end it prints ns per body and per contact for each N and the log–log slope of the
//! tree's N-curve between consecutive N, measured in this run.
//!
//! `cargo bench --bench systems`

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, Throughput};
use inertance::impact::lean_system::LeanSystem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::impact::unilateral::Law;
use inertance::mechanics::system::{System, SystemScrew};
use inertance::scene::Scene;
use inertance::tools::chain::Chain;

const SIZES: [usize; 4] = [1, 10, 100, 1000];

fn tree(chain: &Chain<f64>, models: &[Model], out: &mut Outcome<f64, SystemScrew<f64>>) {
    chain.solve(models, out).expect("solves");
}

fn dense(chain: &Chain<f64>, out: &mut Outcome<f64, SystemScrew<f64>>) {
    let system = chain.system().with_dense_joints().expect("factors");
    let mut impact = Impact::assemble(black_box(&system)).expect("assembles");
    for m in [Model::Newton, Model::Poisson] {
        impact.solve(m, out).expect("solves");
    }
}

/// One solve of a system scene from its data: `System::new`, assemble, its models under its law.
fn example(scene: &Scene, system: &System<f64>, out: &mut Outcome<f64, SystemScrew<f64>>) {
    let system = System::new(
        system.bodies().to_vec(),
        system.velocity().clone(),
        system.contacts().to_vec(),
        system.pairs().to_vec(),
        system.joints().to_vec(),
    )
    .expect("valid");
    let mut impact = Impact::assemble(black_box(&system)).expect("assembles");
    for &m in &scene.models {
        match scene.law {
            Law::Simultaneous => impact.solve(m, out).expect("solves"),
            Law::Unilateral => {
                impact.solve_unilateral(m, out).expect("solves");
            }
            // The LZB law is integrated, not assembled and solved (impact::multiple); the
            // examples timed here are under the other two.
            Law::Lzb => unreachable!(
                "{}: the examples timed here are not under the LZB law",
                scene.name
            ),
        }
    }
}

/// The median time of one call of `f` over 7 runs of at least 20 ms each.
fn median(mut f: impl FnMut()) -> Duration {
    let mut runs = Vec::new();
    for _ in 0..7 {
        let (mut n, start) = (0u32, Instant::now());
        while start.elapsed() < Duration::from_millis(20) || n == 0 {
            f();
            n += 1;
        }
        runs.push(start.elapsed() / n);
    }
    runs.sort();
    runs[3]
}

fn main() {
    let mut c = Criterion::default()
        .configure_from_args()
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .sample_size(20);
    let both = [Model::Newton, Model::Poisson];
    let mut out = Outcome::default();
    {
        let mut g = c.benchmark_group("chain");
        for n in SIZES {
            let chain = Chain::<f64>::new(n);
            g.throughput(Throughput::Elements(n as u64));
            g.bench_function(format!("tree/{n}"), |b| {
                b.iter(|| tree(&chain, &both, &mut out))
            });
            g.bench_function(format!("newton/{n}"), |b| {
                b.iter(|| tree(&chain, &[Model::Newton], &mut out))
            });
            if n <= 100 {
                g.bench_function(format!("dense/{n}"), |b| b.iter(|| dense(&chain, &mut out)));
            }
            // The lean path: the system built once, per solve its factorization, responses,
            // basis and Newton's law (impulses and twist only; impact::lean_system).
            let system = chain.system();
            let mut lean = LeanSystem::new(&system).expect("a chain is a tree");
            g.bench_function(format!("lean/{n}"), |b| {
                b.iter(|| {
                    lean.solve(black_box(&system), Model::Newton)
                        .expect("solves")
                })
            });
        }
        g.finish();
    }
    {
        // Example scenes of several bodies, throughput in contacts (criterion prints contacts
        // per second): `examples/{name}`, everything from the data under the scene's law.
        let mut g = c.benchmark_group("examples");
        for (name, text) in [
            ("cradle-3", include_str!("../examples/cradle-3.toml")),
            ("box-on-box", include_str!("../examples/box-on-box.toml")),
        ] {
            let scene = Scene::parse(text, name).expect("an example");
            let system = scene.system::<f64>().expect("a system");
            g.throughput(Throughput::Elements(system.contacts().len() as u64));
            g.bench_function(name, |b| b.iter(|| example(&scene, &system, &mut out)));
        }
        g.finish();
    }
    c.final_summary();
    // Ratios in one run: ns per body, the slope of log t against log N, tree against dense.
    println!("\nchain (f64, in this run; median of 7 runs ≥ 20 ms each)");
    println!(
        "{:>6} {:>12} {:>12} {:>12} {:>12} {:>8} {:>12}",
        "N", "tree+both", "ns/body", "ns/contact", "newton", "slope", "dense/tree"
    );
    let mut last: Option<(usize, f64)> = None;
    for n in SIZES {
        let chain = Chain::<f64>::new(n);
        let t = median(|| tree(&chain, &both, &mut out)).as_nanos() as f64;
        let newton = median(|| tree(&chain, &[Model::Newton], &mut out)).as_nanos() as f64;
        let slope = last.map_or(String::from("—"), |(m, s)| {
            format!("{:.2}", (t / s).ln() / (n as f64 / m as f64).ln())
        });
        let ratio = if n <= 100 {
            let d = median(|| dense(&chain, &mut out)).as_nanos() as f64;
            format!("{:.1}×", d / t)
        } else {
            String::from("—")
        };
        println!(
            "{n:>6} {:>10.1} µs {:>12.0} {:>12.0} {:>9.1} µs {slope:>8} {ratio:>12}",
            t / 1e3,
            t / n as f64,
            t / chain.contacts.len() as f64,
            newton / 1e3
        );
        last = Some((n, t));
    }
}
