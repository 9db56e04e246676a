//! The accuracy contract (`analysis::accuracy`, its systems paragraph) on systems of bodies,
//! per output — impulses, twist, contact velocities, E_p, ΔE_c — in f32, f64 and
//! double-double against the exact solve of the same scene in the units float solves use
//! (`scene::scale::system`):
//!
//! - the system examples (cradles, the double pendulum, the leg; box-on-box has a singular G
//!   and is not measured);
//! - 60 seeded random systems (`tools::accuracy::system_scenes`): free systems of 2–4 bodies
//!   with 1–4 contacts, and trees of revolute and spherical joints struck at 1–3 contacts,
//!   masses over 10^±6, one in three nearly singular (two contacts 10⁻³…10⁻⁷ m apart with
//!   normals 10⁻³ apart).
//!
//! Asserted: every output of every solve within its bound (error/bound ≤ 1); a type declares G
//! singular only where κ·ε ≥ 10⁻³; and the corpus is not vacuous. The test prints the largest
//! ratio per type and output.

mod common;

use common::assert_contract;
use inertance::tools::accuracy::{system_examples, system_rows, system_scenes};

#[test]
fn every_output_meets_its_bound_on_the_system_examples() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let scenes = system_examples(&dir);
    assert!(scenes.len() >= 5, "the examples with [[body]]");
    let solved = assert_contract("system examples", &system_rows(&scenes));
    assert!(solved.iter().all(|&n| n >= 6), "{solved:?}");
}

#[test]
fn every_output_meets_its_bound_on_random_systems() {
    let scenes = system_scenes(60, 24);
    assert_eq!(scenes.len(), 60, "the generator writes valid systems");
    let jointed = scenes
        .iter()
        .filter(|s| s.system.as_ref().is_some_and(|s| !s.joints.is_empty()))
        .count();
    assert!(jointed >= 20, "{jointed} systems with joints");
    let solved = assert_contract("random systems", &system_rows(&scenes));
    assert!(solved.iter().all(|&n| n >= 40), "{solved:?}");
}
