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

use inertance::analysis::accuracy::Output;
use inertance::tools::accuracy::{ContractRow, system_examples, system_rows, system_scenes};

fn epsilon(scalar: &str) -> f64 {
    match scalar {
        "f32" => f32::EPSILON as f64,
        "f64" => f64::EPSILON,
        _ => 2f64.powi(-104),
    }
}

/// Every bound holds, and G is declared singular only beyond the type's precision; the
/// number of solves measured per type.
fn assert_contract(corpus: &str, rows: &[ContractRow]) -> Vec<usize> {
    let mut solved = Vec::new();
    let mut failures = Vec::new();
    for r in rows {
        let eps = epsilon(r.scalar);
        let mut count = 0;
        for m in &r.measurements {
            match m.checks {
                Some(checks) => {
                    count += 1;
                    for (o, c) in Output::ALL.iter().zip(checks) {
                        if c.error > c.bound {
                            failures.push(format!(
                                "{corpus}, {} {}: {} error {:e} > bound {:e} ({}; cond {:e})",
                                r.scalar,
                                m.case,
                                o.name(),
                                c.error,
                                c.bound,
                                o.bound_text(),
                                m.cond
                            ));
                        }
                    }
                }
                None if m.cond * eps < 1e-3 => failures.push(format!(
                    "{corpus}, {} {}: declared singular at cond {:e}",
                    r.scalar, m.case, m.cond
                )),
                None => {}
            }
        }
        eprintln!("{corpus}, {}: {count} solves measured", r.scalar);
        for o in Output::ALL {
            let (ratio, case) = r.worst(o);
            eprintln!("  {:20} largest error/bound {ratio:.1e} ({case})", o.name());
        }
        solved.push(count);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    solved
}

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
