//! A kept `PlanarFrictionWork` gives `solve_frictional_under`'s report, entry for entry: the
//! workspace refills the blocks, state and report of the previous solve in place, and none of
//! that may leak into the next one. The friction bench's seeded planar scenes, solved one after
//! the other on one workspace under every restitution law and both hypotheses, in f64 and in
//! exact rationals.

use inertance::Problem;
use inertance::impact::friction::{
    Frictional, Hypothesis, PlanarFrictionWork, Restitution, solve_frictional_under,
};
use inertance::scalar::{Exact, Scalar};
use inertance::tools::friction_bench::planar_scenes;

/// Every output of two reports is equal (f64: bit for bit, up to the sign of a zero).
fn same<T: Scalar>(a: &Frictional<T>, b: &Frictional<T>) {
    assert_eq!(a.impulses, b.impulses);
    assert_eq!(a.compression, b.compression);
    assert_eq!(a.after, b.after);
    assert_eq!(a.velocity, b.velocity);
    assert_eq!(a.work_compression, b.work_compression);
    assert_eq!(a.work_restitution, b.work_restitution);
    assert_eq!(a.friction_dissipation, b.friction_dissipation);
    assert_eq!(a.kinetic_energy_loss, b.kinetic_energy_loss);
    assert_eq!(a.lost_velocity_energy, b.lost_velocity_energy);
    assert_eq!(a.energy_residual, b.energy_residual);
    assert_eq!(a.segments, b.segments);
    assert_eq!(a.samples, b.samples);
    assert_eq!(a.verdicts, b.verdicts);
    assert_eq!(a.end, b.end);
    assert_eq!(a.law, b.law);
    assert_eq!(a.hypothesis, b.hypothesis);
    assert_eq!(a.blocks.k, b.blocks.k);
    assert_eq!(a.blocks.v0, b.blocks.v0);
    assert_eq!(a.blocks.offset, b.blocks.offset);
    assert_eq!(a.blocks.plane, b.blocks.plane);
}

fn kept_matches_one_off<T: Scalar>(problems: &[Problem<T>]) {
    let mut work = PlanarFrictionWork::new();
    for law in Restitution::ALL {
        for hypothesis in [Hypothesis::Simultaneous, Hypothesis::Unilateral] {
            for p in problems {
                let fresh = solve_frictional_under(p, law, hypothesis, 1e-10);
                let kept = work.solve_into(p, law, hypothesis, 1e-10);
                match (kept, fresh) {
                    (Ok(k), Ok(f)) => same(k, &f),
                    (Err(k), Err(f)) => assert_eq!(k, f),
                    (k, f) => panic!("kept {:?} against one-off {:?}", k.err(), f.err()),
                }
            }
        }
    }
}

#[test]
fn a_kept_workspace_solves_as_a_fresh_one_in_f64() {
    let problems: Vec<Problem<f64>> = planar_scenes(12)
        .iter()
        .map(|s| s.problem().expect("valid"))
        .collect();
    kept_matches_one_off(&problems);
}

#[test]
fn a_kept_workspace_solves_as_a_fresh_one_exactly() {
    let problems: Vec<Problem<Exact>> = planar_scenes(6)
        .iter()
        .map(|s| s.problem().expect("valid"))
        .collect();
    kept_matches_one_off(&problems);
}
