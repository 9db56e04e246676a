//! Solve the exact peer corpus (`benches/peers/corpus.txt`) once in exact arithmetic —
//! assemble + Newton + Poisson, every output, per scene — and print a checksum: the driver for
//! instruction counts under callgrind (repeatable on a shared machine, unlike wall time).
//! `bigrational` as the argument solves in plain `BigRational` instead of [`Exact`] — the
//! arithmetic `Exact` replaced — for the count before.
//!
//! ```sh
//! cargo build --release --example exact_corpus
//! valgrind --tool=callgrind --toggle-collect='inertance::impact::solve::Impact<T>::assemble' \
//!     --toggle-collect='inertance::impact::solve::Impact<T>::solve' \
//!     target/release/examples/exact_corpus [bigrational]
//! ```
//!
//! (The toggles count the solve alone, not the reading of the corpus.)

use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use num_rational::BigRational;

fn solve_all<T: Scalar>(scenes: &[Scene]) -> f64 {
    let problems: Vec<_> = scenes
        .iter()
        .map(|s| s.problem::<T>().expect("a valid scene"))
        .collect();
    let (mut newton, mut poisson) = (Outcome::default(), Outcome::default());
    let mut checksum = 0.0;
    for p in &problems {
        let mut impact = Impact::assemble(p).expect("assembled");
        impact.solve(Model::Newton, &mut newton).expect("solved");
        impact.solve(Model::Poisson, &mut poisson).expect("solved");
        checksum += poisson.kinetic_energy_loss.to_f64() + newton.impulses_hat[0].to_f64();
    }
    checksum
}

fn main() {
    // INERTANCE_CORPUS names another corpus file (compare.py's doubles corpus, say)
    let path = std::env::var("INERTANCE_CORPUS").unwrap_or_else(|_| {
        concat!(env!("CARGO_MANIFEST_DIR"), "/benches/peers/corpus.txt").to_string()
    });
    let text = std::fs::read_to_string(&path).expect("the corpus file");
    let scenes = inertance::tools::corpus::parse(&text).expect("a valid corpus");
    let (name, checksum) = match std::env::args().nth(1).as_deref() {
        Some("bigrational") => ("BigRational", solve_all::<BigRational>(&scenes)),
        _ => ("Exact", solve_all::<Exact>(&scenes)),
    };
    println!(
        "{} scenes in {name}, checksum {checksum:.12e}",
        scenes.len()
    );
}
