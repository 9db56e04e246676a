//! One impact of the sequence, solved by the impact layer: the contacts at the event brought to
//! a [`Problem`] (world axes, origin at C, each contact's outward normal −N), solved under the
//! scene's law, and the twist after it returned with what the log reports.
//!
//! | law | solved by |
//! |---|---|
//! | simultaneous, frictionless | [`Impact::solve`] (the paper's eq. 12–15, 20–23); verdicts from [`verdicts`] |
//! | unilateral, frictionless | [`Impact::solve_unilateral`] (the complementarity law) |
//! | either, with friction, or the energetic restitution law | [`solve_frictional_under`] (§14, impulse space) |
//! | LZB | [`solve_lzb`] |
//!
//! **A singular G under the simultaneous law** (a block landing flat on both corners of an edge
//! and both of the other: more contacts than the motions they constrain) has a family of
//! impulses. The law is then solved on a basis of the contacts — the first ones, in the log's
//! order, whose wrenches are independent — and every contact left out is checked to meet its
//! law too (Newton's v⁺ = −k v⁻ to 10⁻⁹ of the speeds); the log says so (`basis`). If one does
//! not, the impact has no answer under that law and the run stops, naming it.

use crate::impact::admissibility::{energy_gain, verdicts};
use crate::impact::friction::{
    Hypothesis, Restitution, Verdict as FrictionVerdict, solve_frictional_under,
};
use crate::impact::mechanism::Mechanism;
use crate::impact::multiple::{ContactLaw as LzbLaw, solve_lzb};
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::body::RigidBody;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};

use super::body::{Body, State, V3};
use super::world::Plane;

/// The impact law of a simulation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// The paper's simultaneous law under a restitution law.
    Simultaneous(Restitution),
    /// The unilateral law under a restitution law (Newton's or Poisson's).
    Unilateral(Restitution),
    /// The LZB multiple-impact law.
    Lzb,
}

impl Law {
    /// Its name in the log: `simultaneous (newton)`.
    pub fn name(&self) -> String {
        match self {
            Law::Simultaneous(r) => format!("simultaneous ({})", r.name()),
            Law::Unilateral(r) => format!("unilateral ({})", r.name()),
            Law::Lzb => "lzb".to_string(),
        }
    }

    /// The scene's law replaced by the one named `name` (`"simultaneous"`, `"unilateral"` or
    /// `"lzb"`, as `simulate --law`), keeping the scene's restitution law; an error saying why
    /// when the combination is not integrated (the unilateral law with energetic restitution)
    /// or the name is unknown.
    pub fn chosen(self, name: &str) -> Result<Law, String> {
        let r = match self {
            Law::Simultaneous(r) | Law::Unilateral(r) => r,
            Law::Lzb => Restitution::Newton,
        };
        match name {
            "simultaneous" => Ok(Law::Simultaneous(r)),
            "unilateral" if r == Restitution::Energetic => Err(
                "the unilateral law is integrated with Newton's and Poisson's restitution, and \
                 [simulate] restitution is \"energetic\""
                    .to_string(),
            ),
            "unilateral" => Ok(Law::Unilateral(r)),
            "lzb" => Ok(Law::Lzb),
            other => Err(format!(
                "unknown law `{other}`: \"simultaneous\", \"unilateral\" or \"lzb\""
            )),
        }
    }
}

/// A contact of an impact: a feature's point on a plane.
#[derive(Clone, Debug, PartialEq)]
pub struct At {
    /// The feature.
    pub feature: usize,
    /// The plane.
    pub plane: usize,
    /// The point (world).
    pub point: V3,
}

/// What an impact gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Rebound {
    /// v after (world).
    pub v: V3,
    /// ω after (world).
    pub w: V3,
    /// The normal impulse of each contact (N s).
    pub impulses: Vec<f64>,
    /// Why the answer is not physical (tensile, separating, …), empty when it is.
    pub verdicts: Vec<String>,
    /// A note on how it was solved (a basis of a singular G), if any.
    pub note: Option<String>,
}

/// Why an impact has no answer.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ImpactError {
    /// The problem could not be built (a contact point at C with no moment arm is fine; this is
    /// an input the impact layer refuses).
    #[error("the impact problem is invalid: {0}")]
    Invalid(String),
    /// The law has no answer (singular G with an inconsistent contact, jammed, no consistent
    /// stick/slip, an LZB integration that did not end).
    #[error("{0}")]
    NoAnswer(String),
}

/// Solve the impact of `body` at `s` on the contacts `at` under `law`, to the relative
/// `tolerance` of the integrated laws.
///
/// # Errors
/// [`ImpactError`].
pub fn solve(
    body: &Body,
    planes: &[Plane],
    s: &State,
    at: &[At],
    law: Law,
    tolerance: f64,
) -> Result<Rebound, ImpactError> {
    let problem = problem(body, planes, s, at)?;
    let rough = at.iter().any(|c| planes[c.plane].law.mu > 0.0);
    match law {
        Law::Lzb => {
            let laws: Vec<LzbLaw> = at
                .iter()
                .map(|c| {
                    let l = &planes[c.plane].law;
                    LzbLaw {
                        stiffness: l.stiffness,
                        exponent: l.exponent,
                        restitution: l.k_energetic,
                    }
                })
                .collect();
            let out = solve_lzb(&problem, &laws, tolerance)
                .map_err(|e| ImpactError::NoAnswer(e.to_string()))?;
            Ok(Rebound {
                w: to_v3(&out.velocity.top()),
                v: to_v3(&out.velocity.bottom()),
                impulses: out.impulses.clone(),
                verdicts: Vec::new(),
                note: None,
            })
        }
        Law::Simultaneous(r) | Law::Unilateral(r) if rough || r == Restitution::Energetic => {
            let (velocity, impulses, faults, notes) = frictional(&problem, law, r, tolerance)?;
            Ok(Rebound {
                w: to_v3(&velocity.top()),
                v: to_v3(&velocity.bottom()),
                impulses,
                verdicts: faults,
                note: notes,
            })
        }
        Law::Simultaneous(r) => simultaneous(body, planes, s, at, problem, model(r)),
        Law::Unilateral(r) => {
            let mut impact = Impact::assemble(&problem).map_err(no_answer)?;
            let mut out = Outcome::default();
            impact
                .solve_unilateral(model(r), &mut out)
                .map_err(|e| ImpactError::NoAnswer(e.to_string()))?;
            let verdicts = energy_gain(&impact, &out)
                .into_iter()
                .map(|v| v.name().to_string())
                .collect();
            Ok(outcome(&out, verdicts, None))
        }
    }
}

/// What [`frictional`] gives: the twist after, each contact's normal impulse, the verdicts
/// that make the answer not physical, and the notes on one that is.
pub(super) type Frictioned<S> = (S, Vec<f64>, Vec<String>, Option<String>);

/// The frictional impact of `mechanism` (one body's problem, or a system) under `law`'s
/// hypothesis (the unilateral law's, or the simultaneous one) and restitution `r`: the twist
/// after, each contact's normal impulse, and the verdicts split as [`frictional_verdicts`]
/// splits them.
///
/// # Errors
/// [`ImpactError::NoAnswer`] when the frictional law has none.
pub(super) fn frictional<M: Mechanism<f64>>(
    mechanism: &M,
    law: Law,
    r: Restitution,
    tolerance: f64,
) -> Result<Frictioned<M::Screw>, ImpactError> {
    let hypothesis = match law {
        Law::Unilateral(_) => Hypothesis::Unilateral,
        _ => Hypothesis::Simultaneous,
    };
    let out = solve_frictional_under::<f64, _>(mechanism, r, hypothesis, tolerance)
        .map_err(|e| ImpactError::NoAnswer(e.to_string()))?;
    let b = &out.blocks;
    let impulses = (0..b.contacts())
        .map(|i| out.impulses[b.offset[i]] * b.directions[b.offset[i]].norm())
        .collect();
    let (faults, notes) = frictional_verdicts(&out.verdicts);
    Ok((out.velocity, impulses, faults, notes))
}

/// A frictional impact's verdicts split into what makes the answer not physical (a pulling
/// rate, a contact still approaching, energy gained) and notes on an answer that is (a split of
/// sticking impulses that only their sum determines, several consistent stick/slip assignments,
/// an unstable slip), each kind named once per impact: the twist after is the law's either way.
fn frictional_verdicts(verdicts: &[FrictionVerdict]) -> (Vec<String>, Option<String>) {
    let mut faults = Vec::new();
    let mut notes: Vec<String> = Vec::new();
    for v in verdicts {
        match v {
            FrictionVerdict::TensileRate { .. }
            | FrictionVerdict::StillApproaching { .. }
            | FrictionVerdict::EnergyGain => faults.push(v.to_string()),
            FrictionVerdict::SplitNotUnique { .. } => {
                let note = "sticking contacts on one line share a tangential impulse only its \
                            sum determines (the twist after is unique)"
                    .to_string();
                if !notes.contains(&note) {
                    notes.push(note);
                }
            }
            FrictionVerdict::NormalSplitNotUnique {
                decided, friction, ..
            } => {
                let note = if *friction {
                    "contacts of one face share a normal impulse only its resultant determines, \
                     and their sliding friction follows the split: the rigid model does not \
                     decide the twist after (the least-norm member, the split of equal \
                     compliances, was taken)"
                } else if *decided {
                    "contacts of one face share a normal impulse only its resultant determines \
                     (the least-norm member was taken; the twist after is unique)"
                } else {
                    "contacts of one face share a normal impulse only its resultant determines \
                     (the least-norm member was taken; under this restitution law the twist \
                     after may depend on it)"
                }
                .to_string();
                if !notes.contains(&note) {
                    notes.push(note);
                }
            }
            FrictionVerdict::Ambiguous { .. } | FrictionVerdict::UnstableSlip { .. } => {
                notes.push(v.to_string());
            }
        }
    }
    (faults, (!notes.is_empty()).then(|| notes.join("; ")))
}

fn model(r: Restitution) -> Model {
    match r {
        Restitution::Poisson => Model::Poisson,
        _ => Model::Newton,
    }
}

fn no_answer(e: SolveError) -> ImpactError {
    ImpactError::NoAnswer(e.to_string())
}

fn to_v3(v: &Vec3<f64>) -> V3 {
    V3::new(v[0], v[1], v[2])
}

fn outcome(out: &Outcome<f64>, verdicts: Vec<String>, note: Option<String>) -> Rebound {
    Rebound {
        w: to_v3(&out.velocity.top()),
        v: to_v3(&out.velocity.bottom()),
        // the normals are unit: P = P̂
        impulses: out.impulses_hat.clone(),
        verdicts,
        note,
    }
}

/// The impact problem: world axes, origin at C.
fn problem(
    body: &Body,
    planes: &[Plane],
    s: &State,
    at: &[At],
) -> Result<Problem<f64>, ImpactError> {
    let r = s.rotation();
    let j = body.world_inertia(&r);
    // symmetrise the rounding of R J Rᵀ
    let tensor: [[f64; 3]; 3] =
        std::array::from_fn(|p| std::array::from_fn(|q| 0.5 * (j[(p, q)] + j[(q, p)])));
    let rigid = RigidBody::with_tensor(body.mass, tensor);
    let twist = Screw::new(
        Vec3::new(s.w.x, s.w.y, s.w.z),
        Vec3::new(s.v.x, s.v.y, s.v.z),
    );
    let contacts = at
        .iter()
        .map(|c| {
            let plane = &planes[c.plane];
            // the feature's point moved onto the plane (by its gap, within the gap tolerance):
            // contacts on one face then have exactly alike rows, so a family of stick splits is
            // recognised as one (the rounding of the flight would otherwise make it a family
            // that moves the body)
            let on_plane = c.point - plane.normal * plane.normal.dot(&(c.point - plane.point));
            let d = on_plane - s.x;
            let n = -plane.normal;
            Contact::new(
                Vec3::new(d.x, d.y, d.z),
                Vec3::new(n.x, n.y, n.z),
                plane.law.k,
            )
            .with_friction(plane.law.mu)
            .with_energetic(plane.law.k_energetic)
        })
        .collect();
    Problem::new(rigid, twist, contacts).map_err(|e| ImpactError::Invalid(e.to_string()))
}

/// The simultaneous law, on a basis of the contacts when G is singular.
fn simultaneous(
    body: &Body,
    planes: &[Plane],
    s: &State,
    at: &[At],
    whole: Problem<f64>,
    model: Model,
) -> Result<Rebound, ImpactError> {
    let mut impact = Impact::assemble(&whole).map_err(no_answer)?;
    if !impact.singular() {
        let mut out = Outcome::default();
        impact.solve(model, &mut out).map_err(no_answer)?;
        let v = verdicts(&impact, model, &out)
            .iter()
            .map(|v| verdict_name(v, |c| c + 1))
            .collect();
        return Ok(outcome(&out, v, None));
    }
    // A basis: add the contacts in order, keeping those that leave G regular.
    let mut basis: Vec<usize> = Vec::new();
    for i in 0..at.len() {
        let mut trial = basis.clone();
        trial.push(i);
        let sub: Vec<At> = trial.iter().map(|&k| at[k].clone()).collect();
        let p = problem(body, planes, s, &sub)?;
        if !Impact::assemble(&p).map_err(no_answer)?.singular() {
            basis = trial;
        }
    }
    let sub: Vec<At> = basis.iter().map(|&k| at[k].clone()).collect();
    let p = problem(body, planes, s, &sub)?;
    let mut reduced = Impact::assemble(&p).map_err(no_answer)?;
    let mut out = Outcome::default();
    reduced.solve(model, &mut out).map_err(no_answer)?;
    let v_after = to_v3(&out.velocity.bottom());
    let w_after = to_v3(&out.velocity.top());
    // Every contact left out must meet Newton's law with the basis' answer.
    let scale = at
        .iter()
        .map(|c| {
            planes[c.plane]
                .normal
                .dot(&(s.v + s.w.cross(&(c.point - s.x))))
                .abs()
        })
        .fold(f64::MIN_POSITIVE, f64::max);
    let mut impulses = vec![0.0; at.len()];
    for (k, &i) in basis.iter().enumerate() {
        impulses[i] = out.impulses_hat[k];
    }
    for (i, c) in at.iter().enumerate() {
        if basis.contains(&i) {
            continue;
        }
        let n = planes[c.plane].normal;
        let d = c.point - s.x;
        let before = n.dot(&(s.v + s.w.cross(&d)));
        let after = n.dot(&(v_after + w_after.cross(&d)));
        left_out_meets_law(i, &basis, before, after, planes[c.plane].law.k, scale)?;
    }
    let v = verdicts(&reduced, model, &out)
        .iter()
        .map(|v| match v.contact() {
            Some(c) => format!("{} at contact {}", v.name(), basis[c] + 1),
            None => v.name().to_string(),
        })
        .collect();
    let mut result = outcome(&out, v, None);
    result.impulses = impulses;
    result.note = Some(format!(
        "G singular: solved on the basis {} (the split among dependent contacts is not \
         determined by the law; the others meet it)",
        list(&basis)
    ));
    Ok(result)
}

/// A verdict as the log names it: `tensile at contact 2`, the contact numbered by `number`.
pub(super) fn verdict_name(
    v: &crate::impact::admissibility::Inadmissible,
    number: impl Fn(usize) -> usize,
) -> String {
    match v.contact() {
        Some(c) => format!("{} at contact {}", v.name(), number(c)),
        None => v.name().to_string(),
    }
}

/// Whether contact `i`, left out of the `basis` of a singular G, meets Newton's law
/// v⁺ = −k v⁻ with the basis' answer (its normal rates `before` and `after`), to 10⁻⁹ of the
/// speeds' `scale`: else the simultaneous law has no answer at this impact.
pub(super) fn left_out_meets_law(
    i: usize,
    basis: &[usize],
    before: f64,
    after: f64,
    k: f64,
    scale: f64,
) -> Result<(), ImpactError> {
    if (after + k * before).abs() > 1e-9 * scale {
        return Err(ImpactError::NoAnswer(format!(
            "G is singular and contact {} (left out of the basis {}) does not meet the \
             simultaneous law with the basis' answer: the law has no answer here (solve it \
             under the unilateral law)",
            i + 1,
            list(basis)
        )));
    }
    Ok(())
}

/// A basis of contacts as the note names it: `{1, 2, 4}`.
pub(super) fn list(basis: &[usize]) -> String {
    let v: Vec<String> = basis.iter().map(|i| (i + 1).to_string()).collect();
    format!("{{{}}}", v.join(", "))
}
