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

use inertance::impact::restitution::Model;
use inertance::impact::solve::Outcome;
use inertance::mechanics::system::SystemScrew;
use inertance::tools::chain::Chain;

fn solve(chain: &Chain<f64>, models: &[Model], out: &mut Outcome<f64, SystemScrew<f64>>) {
    chain.solve(models, out).expect("solves");
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
        .filter(|a| a != "--once")
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
            solve(&chain, &[Model::Newton], &mut out);
            continue;
        }
        let newton = median(|| solve(&chain, &[Model::Newton], &mut out));
        let both = median(|| solve(&chain, &[Model::Newton, Model::Poisson], &mut out));
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
             \"impulses\": [{}], \"omega_z\": [{}], \"v_centre\": [{}]}}",
            impulses.join(", "),
            omega.join(", "),
            centre.join(", ")
        );
    }
}
