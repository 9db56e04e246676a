//! inertance's side of `benches/peers/chains.py`: the planar chains of
//! `inertance::tools::chain` in f64, timed in-process, with their answers.
//!
//! For each N on the command line (default 1 10 100 1000) it prints one JSON object per line:
//! `{"links": N, "ns_per_solve": t, "ns_per_solve_both": t2, "impulses": [P_1, P_2],
//! "omega_z": [ω_z of each link after impact], "v_centre": [[v_x, v_y] of each link]}` where
//! one solve is everything from the chain's data: `System::new` (the joints' rows and their
//! tree factorization) + `Impact::assemble` + Newton's law (t) or Newton and Poisson (t2),
//! every output; the time is the median over 7 runs of the mean per call, each run at least
//! 20 ms (as `benches/peers/pinocchio_call.cpp` times Pinocchio). Impulses are P_i (newtons
//! times seconds, along −n_i = +y on the bar: the ground pushes up).
//!
//! `cargo run --release --example chain_timing -- 1 10 100 1000`; with `--once`, one solve per N
//! and nothing printed, for instruction counts:
//! `valgrind --tool=callgrind target/release/examples/chain_timing --once 1000`

use std::time::{Duration, Instant};

use inertance::impact::lean_system::LeanSystem;
use inertance::impact::outputs::Outputs;
use inertance::impact::restitution::Model;
use inertance::impact::solve::Outcome;
use inertance::mechanics::system::SystemScrew;
use inertance::tools::chain::Chain;

fn solve(chain: &Chain<f64>, models: &[Model], out: &mut Outcome<f64, SystemScrew<f64>>) {
    chain.solve(models, out).expect("solves");
}

/// One more lean solve, on buffers sized by a first (for callgrind: `--once --lean`, toggle
/// `chain_timing::lean_once`).
#[inline(never)]
fn lean_once(lean: &mut LeanSystem<f64>, system: &inertance::mechanics::system::System<f64>) {
    lean.solve(std::hint::black_box(system), Model::Newton)
        .expect("solves");
}

fn median(mut f: impl FnMut()) -> f64 {
    let mut runs = Vec::new();
    for _ in 0..7 {
        let (mut n, start) = (0u32, Instant::now());
        while start.elapsed() < Duration::from_millis(20) || n == 0 {
            f();
            n += 1;
        }
        runs.push(start.elapsed().as_nanos() as f64 / f64::from(n));
    }
    runs.sort_by(f64::total_cmp);
    runs[3]
}

fn main() {
    // `--once`: one solve per N and no timing (for callgrind).
    let once = std::env::args().any(|a| a == "--once");
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter(|a| a != "--once" && a != "--lean")
        .map(|a| a.parse().expect("a number of links"))
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1, 10, 100, 1000]
    } else {
        sizes
    };
    for n in sizes {
        let chain = Chain::<f64>::new(n);
        let mut out = Outcome::default();
        if once {
            if std::env::args().any(|a| a == "--lean") {
                let system = chain.system();
                let mut lean = LeanSystem::new(&system).expect("a chain is a tree");
                lean.solve(&system, Model::Newton).expect("solves");
                lean_once(&mut lean, &system);
            } else {
                solve(&chain, &[Model::Newton], &mut out);
            }
            continue;
        }
        let newton = median(|| solve(&chain, &[Model::Newton], &mut out));
        let both = median(|| solve(&chain, &[Model::Newton, Model::Poisson], &mut out));
        let few = median(|| {
            chain
                .solve_for(
                    &[Model::Newton],
                    Outputs::IMPULSES | Outputs::TWIST,
                    &mut out,
                )
                .expect("solves");
        });
        // The lean path: the system built once (as Pinocchio's model and data are), then per
        // call the factorization, the responses, the basis and Newton's law.
        let system = chain.system();
        let mut lean = LeanSystem::new(&system).expect("a chain is a tree");
        let lean_ns = median(|| {
            lean.solve(std::hint::black_box(&system), Model::Newton)
                .expect("solves");
        });
        lean.solve(&system, Model::Newton).expect("solves");
        let lean_impulses: Vec<String> = lean
            .impulses_hat()
            .iter()
            .map(|p| format!("{p:e}"))
            .collect();
        let lean_omega: Vec<String> = lean
            .velocity()
            .0
            .iter()
            .map(|s| format!("{:e}", s.0[2]))
            .collect();
        solve(&chain, &[Model::Newton], &mut out);
        // P_i = P̂_i |n_i|, |n_i| = 1 here.
        let impulses: Vec<String> = out.impulses_hat.iter().map(|p| format!("{p:e}")).collect();
        let omega: Vec<String> = out
            .velocity
            .0
            .iter()
            .map(|s| format!("{:e}", s.0[2]))
            .collect();
        let centre: Vec<String> = out
            .velocity
            .0
            .iter()
            .map(|s| format!("[{:e}, {:e}]", s.0[3], s.0[4]))
            .collect();
        println!(
            "{{\"links\": {n}, \"ns_per_solve\": {newton:.1}, \"ns_per_solve_both\": {both:.1}, \
             \"ns_per_solve_impulses_twist\": {few:.1}, \"ns_per_solve_lean\": {lean_ns:.1}, \
             \"impulses\": [{}], \"omega_z\": [{}], \"v_centre\": [{}], \
             \"lean_impulses\": [{}], \"lean_omega_z\": [{}]}}",
            impulses.join(", "),
            omega.join(", "),
            centre.join(", "),
            lean_impulses.join(", "),
            lean_omega.join(", ")
        );
    }
}
