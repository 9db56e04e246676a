//! A sweep over coefficients of restitution solves one problem prepared once.
//!
//! Reading a scene into a problem costs far more than solving it: in f64 the scene is first put
//! in units of mass, length and time chosen from its own numbers ([`crate::scene::scale`]:
//! exact products for the speeds of approach, every number shifted and written again), then
//! each number is read into the scalar and validated. A coefficient of restitution k_i is
//! dimensionless — the units neither change it nor depend on it — and the solve reads it from
//! its contact only, so the problem at k is the problem prepared at any other k with k_i^N,
//! k_i^P (and k_i^E where it follows k_i^P) replaced by `T::from_rational(k)`, exactly what the
//! reader would give. A point then costs a copy of the prepared problem, its validation
//! (k ∈ [0, 1] among the rest) and the solve.
//!
//! Only answers come this way: a point where the prepared problem is refused or the solve
//! gives no answer (singular, jammed, a refusal) is solved again the usual way, so its status
//! or its error is the one the scene itself gives.
//!
//! Measured 2026-11-28 (see guide/sweeps.md): Example 3 over `contact[1].k`, one thread, the
//! profile of a point was 46 % scaling the scene, 11 % reading it into f64, 12 % copying it,
//! 10 % writing the row, 3 % solving; preparing once removes the first three.

use num_rational::BigRational;

use super::answer::Answer;
use super::slot::Slot;
use crate::impact::problem::Problem;
use crate::scalar::{Exact, Scalar};
use crate::scene::Scene;
use crate::scene::pipeline::{
    Prepared, prepare, prepare_scaled, run_prepared, run_prepared_scaled,
};

/// The problem prepared once, in the sweep's scalar.
enum Template {
    /// f64, in the units [`prepare_scaled`] picks (the same at every k).
    Float(Prepared<f64>),
    /// Exact rationals, as written (the exact path is not scaled).
    Exact(Problem<Exact>),
}

/// A scene whose varied numbers are all coefficients of restitution, prepared once.
pub(super) struct Coefficients {
    /// The scene at one point of the sweep (its law and outputs those the sweep solves).
    scene: Scene,
    template: Template,
    slots: Vec<Slot>,
}

impl Coefficients {
    /// Prepare `scene` (the scene at a point of the sweep) when every slot is a coefficient of
    /// restitution ([`Slot::restitution`]) and the scene is one body; `None` otherwise, or
    /// when the scene does not prepare (its points are then solved the usual way, which
    /// reports why).
    pub(super) fn new(scene: Scene, slots: &[Slot], exact: bool) -> Option<Coefficients> {
        if scene.system.is_some() || !slots.iter().all(|s| s.restitution()) {
            return None;
        }
        let template = if exact {
            Template::Exact(prepare::<Exact>(&scene).ok()?)
        } else {
            Template::Float(prepare_scaled::<f64>(&scene).ok()?)
        };
        Some(Coefficients {
            scene,
            template,
            slots: slots.to_vec(),
        })
    }

    /// The answer at the varied `values` (outer first), or `None` when the prepared problem
    /// gives none there (then the point is solved the usual way).
    pub(super) fn solve(&self, values: &[BigRational]) -> Option<Answer> {
        let report = match &self.template {
            Template::Float(p) => {
                let prepared = Prepared {
                    problem: self.at(&p.problem, values)?,
                    units: p.units.clone(),
                };
                // As `run_with` gives it: named after the scene.
                let mut report = run_prepared_scaled(&self.scene, &prepared, None)
                    .ok()?
                    .report;
                report.scene.clone_from(&self.scene.name);
                report
            }
            Template::Exact(p) => {
                run_prepared(&self.scene, &self.at(p, values)?, None)
                    .ok()?
                    .report
            }
        };
        Some(Answer::Body(report))
    }

    /// The prepared `problem` with the coefficients set to `values`, validated again.
    fn at<T: Scalar>(&self, problem: &Problem<T>, values: &[BigRational]) -> Option<Problem<T>> {
        let constraints = problem.constraints().cloned();
        let (body, velocity, mut contacts) = problem.clone().into_parts();
        for (slot, q) in self.slots.iter().zip(values) {
            slot.set_restitution(&mut contacts, &self.scene, q);
        }
        let problem = Problem::new(body, velocity, contacts).ok()?;
        match constraints {
            None => Some(problem),
            Some(c) => problem.with_constrained(c).ok(),
        }
    }
}
