//! What a point of a sweep answers: one body's report, or a system's
//! ([`crate::mechanics::system`]). Both give the same outputs in the same order: the
//! impulses, each body's v_C and ω (a system's by body name), E_p and ΔE_c.

use crate::impact::restitution::Model;
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

    /// A system's outputs for `model` in the sweep's order (`None`: not solved).
    pub(super) fn system_outputs(
        r: &SystemReport,
        model: Model,
    ) -> Option<Vec<crate::report::Value>> {
        let m = r.models.iter().find(|m| m.model == model)?;
        let mut v = m.impulses.clone();
        for (w, vc) in &m.twists {
            v.extend(vc.iter().cloned());
            v.extend(w.iter().cloned());
        }
        v.push(m.lost_velocity_energy.clone());
        v.push(m.kinetic_energy_loss.clone());
        Some(v)
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
