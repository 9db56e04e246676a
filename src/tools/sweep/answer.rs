//! What a point of a sweep answers: one body's report, or a system's
//! ([`crate::mechanics::system`]). Both give the same outputs in the same order: the
//! impulses, each body's v_C and ω (a system's by body name), E_p and ΔE_c.

use crate::report::Report;
use crate::report::system::SystemReport;
use crate::scalar::Scalar;
use crate::scene::Scene;
use crate::scene::pipeline::{RunError, run};
use crate::scene::system_pipeline::run_system;

/// A solved point's readout.
pub(super) enum Answer {
    /// One body.
    Body(Report),
    /// A system of bodies.
    System(SystemReport),
}

impl Answer {
    /// Solve `scene` in `T` with its own models and law.
    pub(super) fn solve<T: Scalar>(scene: &Scene) -> Result<Answer, RunError> {
        if scene.system.is_some() {
            run_system::<T>(scene, None).map(|s| Answer::System(s.report))
        } else {
            run::<T>(scene, None).map(|s| Answer::Body(s.report))
        }
    }
}

/// The names a system's bodies give the sweep's columns (empty for one body).
pub(super) fn body_names(scene: &Scene) -> Vec<String> {
    scene
        .system
        .as_ref()
        .map(|s| s.bodies.iter().map(|b| b.name.clone()).collect())
        .unwrap_or_default()
}
