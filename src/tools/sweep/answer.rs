//! What a point of a sweep answers: one body's report, or a system's
//! ([`crate::mechanics::system`]). Both give the same outputs in the same order: the
//! impulses, each body's v_C and ω (a system's by body name), E_p and ΔE_c.

use crate::impact::friction::Restitution;
use crate::impact::restitution::Model;
use crate::report::system::SystemReport;
use crate::report::{Report, Value};
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

    /// A system's outputs for `law` in the sweep's order (`None`: not solved): from its
    /// frictional readout of `law` when it has one (with E_f), else from the paper's model of
    /// that name (with E_f = 0 in a frictional sweep, as one body's: see
    /// [`super::outputs::law_outputs`]).
    pub(super) fn system_outputs(
        r: &SystemReport,
        law: Restitution,
        friction: bool,
    ) -> Option<Vec<Value>> {
        let twists = |twists: &[([Value; 3], [Value; 3])], v: &mut Vec<Value>| {
            for (w, vc) in twists {
                v.extend(vc.iter().cloned());
                v.extend(w.iter().cloned());
            }
        };
        if let Some(f) = r.friction.iter().find(|f| f.law == law) {
            let mut v: Vec<Value> = f
                .contacts
                .iter()
                .map(|c| c.normal_impulse.clone())
                .collect();
            twists(&f.twists, &mut v);
            v.push(f.lost_velocity_energy.clone());
            v.push(f.kinetic_energy_loss.clone());
            v.push(f.friction_dissipation.clone());
            return Some(v);
        }
        let model = match law {
            Restitution::Newton => Model::Newton,
            Restitution::Poisson => Model::Poisson,
            Restitution::Energetic => return None,
        };
        let m = r.models.iter().find(|m| m.model == model)?;
        let mut v = m.impulses.clone();
        twists(&m.twists, &mut v);
        v.push(m.lost_velocity_energy.clone());
        v.push(m.kinetic_energy_loss.clone());
        if friction {
            v.push(super::outputs::zero_like(&m.kinetic_energy_loss));
        }
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
