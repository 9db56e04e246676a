//! Outputs on demand (`impact::outputs`): for every subset of the outputs, a solve assembled
//! for that subset gives each requested output bit for bit as the solve of every output does,
//! and leaves the others out (their vectors empty) — in f64 and in exact rationals, by both
//! float routes, on the stored scenes (the hard cases, the examples, a constrained body) and
//! on random problems. "Bit for bit" is compared on the values' `Debug` text, which tells
//! −0 from 0 and every f64 from every other.

mod common;

use std::path::Path;

use inertance::impact::outputs::Outputs;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::scene::pipeline::prepare;
use inertance::tools::accuracy::hard_cases;
use inertance::{solve, solve_for};
use proptest::prelude::*;

fn bits<T: std::fmt::Debug + ?Sized>(x: &T) -> String {
    format!("{x:?}")
}

/// The solve of `problem` for every subset of the outputs against the solve of all of them,
/// both models; the number of solves compared (0 when G is singular).
fn compare<T: Scalar>(problem: &Problem<T>, name: &str) -> usize {
    let Ok(mut all) = Impact::assemble(problem) else {
        return 0;
    };
    let mut compared = 0;
    for model in Model::ALL {
        let mut every = Outcome::default();
        if all.solve(model, &mut every).is_err() {
            return 0;
        }
        for set in Outputs::subsets() {
            let mut some = Impact::assemble_for(problem, set).unwrap();
            assert_eq!(some.route(), all.route(), "{name}: the route");
            // A reused outcome full of another solve's numbers: what is not asked for must be
            // cleared or left alone, never half written.
            let mut out = every.clone();
            some.solve(model, &mut out).unwrap();
            let case = format!("{} {name} {model:?} {set}", T::NAME);
            let has = |o: Outputs| set.contains(o);
            if has(Outputs::IMPULSES) {
                assert_eq!(bits(&out.impulses_hat), bits(&every.impulses_hat), "{case}");
                assert_eq!(
                    bits(&out.compression_hat),
                    bits(&every.compression_hat),
                    "{case}"
                );
            } else {
                assert!(
                    out.impulses_hat.is_empty() && out.compression_hat.is_empty(),
                    "{case}"
                );
            }
            if has(Outputs::TWIST) {
                assert_eq!(bits(&out.velocity), bits(&every.velocity), "{case}");
            }
            let (normal, tangential) = (has(Outputs::NORMAL_VELOCITIES), has(Outputs::TANGENTIAL));
            if normal || tangential {
                assert_eq!(out.after_hat.len(), every.after_hat.len(), "{case}");
                for (a, b) in out.after_hat.iter().zip(&every.after_hat) {
                    if normal {
                        assert_eq!(bits(&a[0]), bits(&b[0]), "{case}");
                    }
                    if tangential {
                        assert_eq!(bits(&a[1..]), bits(&b[1..]), "{case}");
                    }
                }
            } else {
                assert!(out.after_hat.is_empty(), "{case}");
            }
            if has(Outputs::ENERGIES) {
                assert_eq!(
                    bits(&(&out.lost_velocity_energy, &out.kinetic_energy_loss)),
                    bits(&(&every.lost_velocity_energy, &every.kinetic_energy_loss)),
                    "{case}"
                );
                assert_eq!(bits(some.kinetic_before()), bits(all.kinetic_before()));
            }
            if has(Outputs::CONSTRAINT_IMPULSES) {
                assert_eq!(
                    bits(&out.constraint_impulses),
                    bits(&every.constraint_impulses),
                    "{case}"
                );
            } else {
                assert!(out.constraint_impulses.is_empty(), "{case}");
            }
            if tangential {
                assert_eq!(bits(some.frames()), bits(all.frames()), "{case}");
                assert_eq!(bits(some.g_yx_hat()), bits(all.g_yx_hat()), "{case}");
                assert_eq!(bits(some.g_zx_hat()), bits(all.g_zx_hat()), "{case}");
            } else {
                assert!(
                    some.g_yx_hat().is_empty() && some.g_zx_hat().is_empty(),
                    "{case}"
                );
            }
            compared += 1;
        }
    }
    compared
}

fn stored_scenes() -> Vec<Scene> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = hard_cases(&root.join("tests/hard_cases"));
    for file in ["examples/planar-bar.toml", "examples/tilted-box.toml"] {
        scenes.push(Scene::load(&root.join(file)).unwrap());
    }
    scenes
}

#[test]
fn every_subset_of_the_outputs_is_bit_for_bit_the_full_solve_on_the_stored_scenes() {
    let (mut f64s, mut exacts, mut routes) = (0, 0, Vec::new());
    for scene in stored_scenes() {
        if let Ok(p) = prepare::<f64>(&scene) {
            f64s += compare(&p, &scene.name);
            if let Ok(i) = Impact::assemble(&p) {
                routes.push(i.route());
            }
        }
        if scene.name.contains("mass-ratio") || scene.name.contains("contacts-12") {
            continue; // exact big-number arithmetic, slow and no different a path
        }
        if let Ok(p) = prepare::<Exact>(&scene) {
            exacts += compare(&p, &scene.name);
        }
    }
    eprintln!("compared {f64s} f64 and {exacts} exact solves");
    assert!(f64s >= 15 * 128 && exacts >= 15 * 128, "{f64s} {exacts}");
    use inertance::impact::route::Route;
    assert!(
        routes.contains(&Route::NormalEquations) && routes.contains(&Route::OrthogonalWrenches)
    );
}

/// The one-call API: `solve_for` gives the requested fields of `solve`'s `Solution`.
#[test]
fn solve_for_gives_the_requested_fields_of_solve() {
    let scene =
        Scene::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/planar-bar.toml"))
            .unwrap();
    let p = scene.problem::<Exact>().unwrap();
    let all = solve(&p, Model::Poisson).unwrap();
    let fast = solve_for(&p, Model::Poisson, Outputs::IMPULSES | Outputs::TWIST).unwrap();
    assert_eq!(fast.impulses, all.impulses);
    assert_eq!(fast.compression_impulses, all.compression_impulses);
    assert_eq!(fast.twist, all.twist);
    assert!(fast.contact_velocities.is_empty() && fast.constraint_impulses.is_empty());
    let v = solve_for(&p, Model::Poisson, Outputs::NORMAL_VELOCITIES).unwrap();
    for (a, b) in v.contact_velocities.iter().zip(&all.contact_velocities) {
        assert_eq!(a[0], b[0]);
    }
    assert!(v.impulses.is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// Random problems (one to four contacts, free bodies in principal axes): every subset,
    /// exact and f64.
    #[test]
    fn every_subset_is_bit_for_bit_the_full_solve_on_random_problems(p in common::problem(4)) {
        compare(&p, "random");
        compare(&common::convert::<f64>(&p), "random");
    }
}
