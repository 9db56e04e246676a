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
//! Measured 2026-11-28 20:57 UTC (guide/sweeps.md; one thread, release, a shared 2-core VM,
//! load 1.5–1.7): Example 3 over `contact[1].k`, 35 → 6.4 µs a point, the tilted box over
//! `contact[1].k` 28 → 6.5 µs. Under callgrind a point of Example 3 was 357 k instructions:
//! 46 % scaling the scene, 11 % reading it into f64, 12 % copying it, 10 % writing the row,
//! about 2 % assembling and solving; preparing once removes the first three (with the row
//! written into one buffer and the grid value formed as one fraction, 66 k remain, a third of
//! them the report the answer is read from).

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
    Float(Box<Prepared<f64>>),
    /// Exact rationals, as written (the exact path is not scaled).
    Exact(Box<Problem<Exact>>),
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
            Template::Exact(Box::new(prepare::<Exact>(&scene).ok()?))
        } else {
            Template::Float(Box::new(prepare_scaled::<f64>(&scene).ok()?))
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
            slot.set_restitution(&mut contacts, &self.scene, q)?;
        }
        let problem = Problem::new(body, velocity, contacts).ok()?;
        match constraints {
            None => Some(problem),
            Some(c) => problem.with_constrained(c).ok(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::outputs::written_outputs;
    use super::super::text::toml_text;
    use super::*;
    use crate::scene::{parse_document, set_value};
    use crate::tools::sweep::q;

    /// The scene of `text` with the numbers at `paths` set to `values` by re-reading the
    /// document, asking for the sweep's outputs: what a point costs without a prepared problem.
    fn reread(text: &str, paths: &[&str], values: &[BigRational]) -> Scene {
        let mut doc = parse_document(text, "s.toml").unwrap();
        for (path, x) in paths.iter().zip(values) {
            set_value(&mut doc, path, &toml_text(x)).unwrap();
        }
        let mut scene = Scene::from_document(&doc, "s.toml").unwrap();
        scene.outputs = written_outputs();
        scene
    }

    fn report(answer: Option<Answer>) -> Option<crate::report::Report> {
        match answer? {
            Answer::Body(r) => Some(r),
            Answer::System(_) => panic!("one body"),
        }
    }

    /// A prepared problem with its coefficients set gives the report of the scene re-read with
    /// them — bit for bit, in f64 (scaled units) and exactly — on a body in its own axes, a
    /// posed box, a pinned rod and a rough bar; a singular point gives none (it is solved the
    /// usual way).
    #[test]
    fn a_prepared_problem_answers_as_the_scene_reread() {
        let scenes = [
            include_str!("../../../examples/planar-bar.toml"),
            include_str!("../../../examples/tilted-box.toml"),
            include_str!("../../../examples/pinned-rod.toml"),
            include_str!("../../../examples/rough-bar.toml"),
        ];
        let grids: [&[&str]; 3] = [
            &["contact[0].k"],
            &["contact[0].k_newton", "contact[0].k_poisson"],
            &["contact[0].k_poisson"],
        ];
        let values = [q(0, 1), q(1, 3), q(7, 10), q(1, 1), q(1, 1000)];
        for text in scenes {
            for paths in grids {
                let first = reread(text, paths, &vec![q(1, 2); paths.len()]);
                let slots: Vec<Slot> = paths
                    .iter()
                    .map(|p| Slot::find(p, &first).unwrap())
                    .collect();
                for exact in [false, true] {
                    let Some(c) = Coefficients::new(first.clone(), &slots, exact) else {
                        // Only a scene that does not prepare (a box posed at 30° has
                        // irrational entries: no exact problem) is left to the usual path.
                        assert!(exact && Answer::solve::<Exact>(&first).is_err());
                        continue;
                    };
                    for (a, b) in values.iter().zip(values.iter().rev()) {
                        let at = [a.clone(), b.clone()];
                        let at = &at[..paths.len()];
                        let scene = reread(text, paths, at);
                        let want = if exact {
                            Answer::solve::<Exact>(&scene)
                        } else {
                            Answer::solve::<f64>(&scene)
                        };
                        let want = report(want.ok()).unwrap();
                        let got = report(c.solve(at)).unwrap();
                        assert_eq!(got, want, "{paths:?} = {at:?}, exact = {exact}");
                    }
                }
            }
        }
        // A k that f64 rounds to zero is out of its range, as the reader says: no answer here.
        let text = include_str!("../../../examples/planar-bar.toml");
        let first = reread(text, &["contact[1].k"], &[q(1, 2)]);
        let slots = [Slot::find("contact[1].k", &first).unwrap()];
        let c = Coefficients::new(first.clone(), &slots, false).unwrap();
        let tiny = BigRational::new(1.into(), num_bigint::BigInt::from(10).pow(400));
        assert!(c.solve(std::slice::from_ref(&tiny)).is_none());
        assert!(
            Answer::solve::<f64>(&reread(
                text,
                &["contact[1].k"],
                std::slice::from_ref(&tiny)
            ))
            .is_err()
        );
        let c = Coefficients::new(first, &slots, true).unwrap();
        assert!(
            c.solve(&[tiny]).is_some(),
            "exactly, 10⁻⁴⁰⁰ is a coefficient like any other"
        );
        // Two contacts at one point: G is singular at every k.
        let text = include_str!("../../../examples/planar-bar.toml")
            .replace("point = [0, 4, 0]", "point = [0, -2, 0]");
        let first = reread(&text, &["contact[1].k"], &[q(1, 2)]);
        let slots = [Slot::find("contact[1].k", &first).unwrap()];
        for exact in [false, true] {
            let c = Coefficients::new(first.clone(), &slots, exact).unwrap();
            assert!(c.solve(&[q(1, 3)]).is_none(), "exact = {exact}");
        }
    }

    /// Only coefficients of restitution are set in a prepared problem.
    #[test]
    fn other_numbers_are_not_prepared() {
        let text = include_str!("../../../examples/planar-bar.toml");
        let scene = reread(text, &[], &[]);
        for path in [
            "body.mass",
            "contact[0].mu",
            "contact[1].point[1]",
            "body.velocity[0]",
        ] {
            let slot = Slot::find(path, &scene).unwrap();
            assert!(
                Coefficients::new(scene.clone(), &[slot], false).is_none(),
                "{path}"
            );
        }
    }
}
