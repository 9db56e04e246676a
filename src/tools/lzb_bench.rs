//! The LZB law's time per solve (`inertance bench --scene` on a scene under the LZB law, and
//! the LZB examples of the report's scene table): the mechanism prepared once, each solve the
//! whole integration ([`crate::impact::multiple::solve_lzb`]: G, the adaptive Runge–Kutta steps,
//! the events, every output). The law is integrated in f64 and double-double (each to its
//! default tolerance ε^(2/3), unless the scene sets one); f32 and exact say why not.

use std::time::Duration;

use crate::impact::mechanism::Mechanism;
use crate::impact::multiple::{ContactLaw, LzbError, solve_lzb};
use crate::scalar::Real;
use crate::scalar::dd::DoubleDouble;
use crate::scene::Scene;
use crate::scene::lzb::contact_laws;
use crate::scene::pipeline::{RunError, friction_tolerance, prepare};
use crate::tools::bench::time_three;
use crate::tools::system_bench::{NotTimed, SceneTiming};

/// What one timed solve is.
pub const SOLVE: &str =
    "solve_lzb on the prepared mechanism (G, adaptive RK5(4) steps, events), every output";

/// Time `scene` under the LZB law, each solve within `budget`: f64 and double-double, the
/// other types not applicable.
pub fn time_lzb_scene(scene: &Scene, budget: Duration) -> SceneTiming {
    let floats_only = || {
        Err(NotTimed::NotApplicable(
            "the LZB law is integrated in f64 and double-double only".into(),
        ))
    };
    SceneTiming {
        scene: scene.name.clone(),
        bodies: scene.system.as_ref().map_or(1, |s| s.bodies.len()),
        contacts: scene.contacts.len(),
        law: "lzb".into(),
        solve: SOLVE.into(),
        rows: vec![
            ("f32", floats_only()),
            ("f64", time_lzb::<f64>(scene, budget)),
            ("double-double", time_lzb::<DoubleDouble>(scene, budget)),
            ("exact", floats_only()),
        ],
    }
}

fn not_timed(e: RunError) -> NotTimed {
    match e {
        RunError::Lzb(LzbError::Runaway { .. }) => NotTimed::NoAnswer("runaway"),
        RunError::Scene(s) => NotTimed::NotApplicable(format!("{}: {}", s.key, s.message)),
        other => NotTimed::NotApplicable(other.to_string()),
    }
}

/// ns per LZB solve of `scene` in `T`.
fn time_lzb<T: Real>(scene: &Scene, budget: Duration) -> Result<f64, NotTimed> {
    let laws = contact_laws(scene).map_err(|e| not_timed(e.into()))?;
    let tolerance = scene.tolerance.unwrap_or_else(friction_tolerance::<T>);
    if scene.system.is_some() {
        let system = scene.system::<T>().map_err(|e| not_timed(e.into()))?;
        time_on(&system, &laws, tolerance, budget)
    } else {
        let problem = prepare::<T>(scene).map_err(not_timed)?;
        time_on(&problem, &laws, tolerance, budget)
    }
}

fn time_on<T: Real, M: Mechanism<T>>(
    mechanism: &M,
    laws: &[ContactLaw],
    tolerance: f64,
    budget: Duration,
) -> Result<f64, NotTimed> {
    solve_lzb(mechanism, laws, tolerance).map_err(|e| not_timed(e.into()))?;
    time_three(budget, || {
        solve_lzb(std::hint::black_box(mechanism), laws, tolerance)
            .map(|out| {
                std::hint::black_box(out);
            })
            .map_err(|e| not_timed(e.into()))
    })
}
