//! One impact of a system, solved by the impact layer: the contacts at the event brought to a
//! [`System`] ([`crate::mechanics::system`]: world axes, each member's screws about its centre,
//! the contact normal out of the pair's first member — a feature's −N on a plane, n from a to b
//! between two spheres, a feature's −n on a box's face) and solved by the scene's law through
//! the same functions as any system's impact:
//!
//! | law | solved by |
//! |---|---|
//! | simultaneous, frictionless (Newton, Poisson) | [`Impact::solve`] over the system (eq. 12–15, 20–23) |
//! | unilateral, frictionless (Newton, Poisson) | [`Impact::solve_unilateral`] |
//! | either, with friction, or the energetic restitution law | [`solve_frictional_under`] over the system (§14, impulse space) |
//! | LZB (with each contact's μ) | [`solve_lzb`] over the system ([`crate::impact::mechanism::Mechanism`]) |
//!
//! The system's joints are the impact problem's ([`super::joints::Link::at`]: the anchor and the
//! axis where the first member carries them), and the twist before impact is first projected
//! onto what they allow in the impact layer's own rows
//! ([`crate::mechanics::system::allowed`]: the simulation holds it on its rows only to
//! rounding, and the impact layer takes a blocked rate as zero only within the rounding of its
//! own); the joints' reactions enter every impulse. Every member of the system is a body of the
//! impact problem (one not touched takes no
//! impulse); the spin of a sphere that does not turn is set to zero (frictionless contacts
//! through its centre neither see nor change it, [`super::members`]); a box's inertia is its
//! world tensor R J Rᵀ.
//!
//! **A singular G under the simultaneous law** (a box resting flat on four corners: more
//! contacts than the motions they stop) has a family of impulses; as for one body
//! ([`crate::simulate::impact`]) the law is solved on a basis of the contacts — the first
//! ones, in the log's order, whose rows are independent — and every contact left out must meet
//! Newton's law v⁺ = −k v⁻ with the basis' answer (to 10⁻⁹ of the speeds), or the impact has no
//! answer under that law. The note says so.

use crate::impact::admissibility::{energy_gain, verdicts};
use crate::impact::friction::Restitution;
use crate::impact::multiple::{ContactLaw as LzbLaw, solve_lzb};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::body::RigidBody;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};
use crate::mechanics::system::{Pair, System, SystemBody, SystemScrew, allowed};

use super::super::body::V3;
use super::super::impact::{ImpactError, Law, frictional, left_out_meets_law, list, verdict_name};
use super::super::world::Plane;
use super::gaps::{Candidate, Gap, gap};
use super::joints::Link;
use super::members::{Member, SystemState};

/// What an impact gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Rebound {
    /// v_b after, per member (world).
    pub v: Vec<V3>,
    /// ω_b after, per member (world; a sphere's unchanged).
    pub w: Vec<V3>,
    /// The normal impulse of each contact (N s).
    pub impulses: Vec<f64>,
    /// Why the answer is not physical, empty when it is.
    pub verdicts: Vec<String>,
    /// How it was solved, when that needs saying (a basis of a singular G).
    pub note: Option<String>,
}

fn vec3(v: &V3) -> Vec3<f64> {
    Vec3::new(v.x, v.y, v.z)
}

/// The impact problem of the contacts `at` (indices into `candidates`) at `s`.
///
/// # Errors
/// [`ImpactError::Invalid`] when the system refuses the problem.
pub fn system(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    at: &[usize],
    s: &SystemState,
    joints: &[Link],
) -> Result<System<f64>, ImpactError> {
    let bodies: Vec<SystemBody<f64>> = members
        .iter()
        .enumerate()
        .map(|(b, m)| {
            let body = match m.radius() {
                Some(r) => {
                    let j = 0.4 * m.mass() * r * r;
                    RigidBody::principal(m.mass(), Vec3::new(j, j, j))
                }
                None => {
                    // R J Rᵀ, symmetric to the bit (its rounding is not)
                    let t = m.body.world_inertia(&s.rotation(b));
                    RigidBody::with_tensor(
                        m.mass(),
                        std::array::from_fn(|i| {
                            std::array::from_fn(|j| 0.5 * (t[(i, j)] + t[(j, i)]))
                        }),
                    )
                }
            };
            SystemBody {
                body,
                centre: vec3(&s.x[b]),
            }
        })
        .collect();
    let velocity = SystemScrew(
        members
            .iter()
            .enumerate()
            .map(|(b, m)| {
                let w = if m.turns() { s.w[b] } else { V3::zeros() };
                Screw::new(vec3(&w), vec3(&s.v[b]))
            })
            .collect(),
    );
    let mut contacts = Vec::with_capacity(at.len());
    let mut pairs = Vec::with_capacity(at.len());
    let mut levers = Vec::with_capacity(at.len());
    for &k in at {
        let c = &candidates[k];
        let g = gap(&c.touch, members, planes, s);
        let sides: Vec<_> = g.sides().copied().collect();
        let Some(first) = sides.first() else {
            return Err(ImpactError::Invalid(
                "a contact that acts on no member".to_string(),
            ));
        };
        // the normal out of the first member
        let normal = g.normal * -first.sign;
        let second = sides.get(1);
        pairs.push(Pair {
            first: first.body,
            second: second.map(|s| s.body),
        });
        levers.push((vec3(&first.arm), second.map(|s| vec3(&s.arm))));
        contacts.push(
            Contact::new(vec3(&g.point), vec3(&normal), c.law.k)
                .with_energetic(c.law.k_energetic)
                .with_friction(c.law.mu),
        );
    }
    let joints: Vec<_> = joints.iter().map(|j| j.at(s)).collect();
    let velocity =
        allowed(&bodies, &joints, &velocity).map_err(|e| ImpactError::Invalid(e.to_string()))?;
    System::new(bodies, velocity, contacts, pairs, joints)
        .and_then(|sys| sys.with_lever_arms(levers))
        .map_err(|e| ImpactError::Invalid(e.to_string()))
}

/// Solve the impact of the contacts `at` at `s` under `law`, to the relative `tolerance` of
/// the integrated LZB law.
///
/// # Errors
/// [`ImpactError`]: the problem refused, or no answer under the law (energetic restitution is
/// refused under the unilateral law, as for one body).
#[allow(clippy::too_many_arguments)] // the system's parts, one by one as this folder passes them
pub fn solve(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    at: &[usize],
    s: &SystemState,
    joints: &[Link],
    law: Law,
    tolerance: f64,
) -> Result<Rebound, ImpactError> {
    let sys = system(members, planes, candidates, at, s, joints)?;
    let twists = |v: &SystemScrew<f64>| after(members, s, v);
    let model = |r: Restitution| match r {
        Restitution::Poisson => Model::Poisson,
        // the energetic law is integrated with the frictional solve (below)
        Restitution::Newton | Restitution::Energetic => Model::Newton,
    };
    let no = |e: &dyn std::fmt::Display| ImpactError::NoAnswer(e.to_string());
    let rough = at.iter().any(|&k| candidates[k].law.mu > 0.0);
    match law {
        Law::Lzb => {
            let laws: Vec<LzbLaw> = at
                .iter()
                .map(|&k| {
                    let l = &candidates[k].law;
                    LzbLaw {
                        stiffness: l.stiffness,
                        exponent: l.exponent,
                        restitution: l.k_energetic,
                    }
                })
                .collect();
            let out = solve_lzb(&sys, &laws, tolerance).map_err(|e| no(&e))?;
            let (v, w) = twists(&out.velocity);
            Ok(Rebound {
                v,
                w,
                impulses: out.impulses.clone(),
                verdicts: Vec::new(),
                note: None,
            })
        }
        Law::Simultaneous(r) | Law::Unilateral(r) if rough || r == Restitution::Energetic => {
            let (velocity, impulses, verdicts, note) = frictional(&sys, law, r, tolerance)?;
            let (v, w) = twists(&velocity);
            Ok(Rebound {
                v,
                w,
                impulses,
                verdicts,
                note,
            })
        }
        Law::Simultaneous(r) => {
            let model = model(r);
            let mut impact = Impact::assemble(&sys).map_err(|e| no(&e))?;
            if impact.singular() {
                return on_basis(members, planes, candidates, at, s, joints, model);
            }
            let mut out = Outcome::default();
            impact.solve(model, &mut out).map_err(|e| no(&e))?;
            let verdicts = verdicts(&impact, model, &out)
                .iter()
                .map(|v| verdict_name(v, |c| c + 1))
                .collect();
            let (v, w) = twists(&out.velocity);
            Ok(Rebound {
                v,
                w,
                impulses: out.impulses_hat.clone(),
                verdicts,
                note: None,
            })
        }
        Law::Unilateral(r) => {
            let model = model(r);
            let mut impact = Impact::assemble(&sys).map_err(|e| no(&e))?;
            let mut out = Outcome::default();
            impact
                .solve_unilateral(model, &mut out)
                .map_err(|e| no(&e))?;
            let (v, w) = twists(&out.velocity);
            Ok(Rebound {
                v,
                w,
                impulses: out.impulses_hat.clone(),
                verdicts: energy_gain(&impact, &out)
                    .into_iter()
                    .map(|v| v.name().to_string())
                    .collect(),
                note: None,
            })
        }
    }
}

/// Each member's (v, ω) in the twists `v` after an impact at `s` (a sphere keeps its spin).
fn after(members: &[Member], s: &SystemState, v: &SystemScrew<f64>) -> (Vec<V3>, Vec<V3>) {
    v.0.iter()
        .enumerate()
        .map(|(b, t)| {
            let (w, c) = (t.top(), t.bottom());
            let w = if members[b].turns() {
                V3::new(w[0], w[1], w[2])
            } else {
                s.w[b]
            };
            (V3::new(c[0], c[1], c[2]), w)
        })
        .unzip()
}

/// The rate J u of the contact `g` at the velocities `v`, `w`.
fn rate(g: &Gap, members: &[Member], v: &[V3], w: &[V3]) -> f64 {
    g.sides()
        .map(|i| {
            let turning = if members[i.body].turns() {
                i.moment.dot(&w[i.body])
            } else {
                0.0
            };
            i.sign * (g.normal.dot(&v[i.body]) + turning)
        })
        .sum()
}

/// The simultaneous law on a basis of the contacts of a singular G (module docs).
fn on_basis(
    members: &[Member],
    planes: &[Plane],
    candidates: &[Candidate],
    at: &[usize],
    s: &SystemState,
    joints: &[Link],
    model: Model,
) -> Result<Rebound, ImpactError> {
    let no = |e: &dyn std::fmt::Display| ImpactError::NoAnswer(e.to_string());
    let mut basis: Vec<usize> = Vec::new();
    for i in 0..at.len() {
        let mut trial = basis.clone();
        trial.push(i);
        let sub: Vec<usize> = trial.iter().map(|&p| at[p]).collect();
        let sys = system(members, planes, candidates, &sub, s, joints)?;
        if !Impact::assemble(&sys).map_err(|e| no(&e))?.singular() {
            basis = trial;
        }
    }
    let sub: Vec<usize> = basis.iter().map(|&p| at[p]).collect();
    let sys = system(members, planes, candidates, &sub, s, joints)?;
    let mut reduced = Impact::assemble(&sys).map_err(|e| no(&e))?;
    let mut out = Outcome::default();
    reduced.solve(model, &mut out).map_err(|e| no(&e))?;
    let (v, w) = after(members, s, &out.velocity);
    let gaps: Vec<Gap> = at
        .iter()
        .map(|&k| gap(&candidates[k].touch, members, planes, s))
        .collect();
    let scale = gaps
        .iter()
        .map(|g| rate(g, members, &s.v, &s.w).abs())
        .fold(f64::MIN_POSITIVE, f64::max);
    let mut impulses = vec![0.0; at.len()];
    for (k, &i) in basis.iter().enumerate() {
        impulses[i] = out.impulses_hat[k];
    }
    for (i, g) in gaps.iter().enumerate() {
        if basis.contains(&i) {
            continue;
        }
        let before = rate(g, members, &s.v, &s.w);
        let after = rate(g, members, &v, &w);
        left_out_meets_law(i, &basis, before, after, candidates[at[i]].law.k, scale)?;
    }
    let verdicts = verdicts(&reduced, model, &out)
        .iter()
        .map(|v| verdict_name(v, |c| basis[c] + 1))
        .collect();
    Ok(Rebound {
        v,
        w,
        impulses,
        verdicts,
        note: Some(format!(
            "G singular: solved on the basis {} (the split among dependent contacts is not \
             determined by the law; the others meet it)",
            list(&basis)
        )),
    })
}
