//! One impact of a sphere system, solved by the impact layer: the contacts at the event
//! brought to a [`System`] ([`crate::mechanics::system`]: world axes, each sphere's screws
//! about its centre, the contact normal out of the pair's first body — a sphere's −N on a
//! plane, n from a to b between two spheres) and solved by the scene's law through the same
//! functions as any system's impact:
//!
//! | law | solved by |
//! |---|---|
//! | simultaneous (Newton, Poisson) | [`Impact::solve`] over the system (eq. 12–15, 20–23) |
//! | unilateral (Newton, Poisson) | [`Impact::solve_unilateral`] |
//! | LZB | [`solve_lzb`] over the system ([`crate::impact::mechanism::Mechanism`]) |
//!
//! Every sphere of the system is a body of the impact problem (one not touched takes no
//! impulse), with its spin set to zero: frictionless contacts through the centres neither see
//! nor change it ([`super::spheres`]).

use crate::impact::admissibility::{energy_gain, verdicts};
use crate::impact::friction::Restitution;
use crate::impact::multiple::{ContactLaw as LzbLaw, solve_lzb};
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::mechanics::body::RigidBody;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};
use crate::mechanics::system::{Pair, System, SystemBody, SystemScrew};

use super::super::body::V3;
use super::super::impact::{ImpactError, Law, verdict_name};
use super::super::world::Plane;
use super::gaps::{Candidate, Touch, gap};
use super::spheres::{Sphere, SystemState};

/// What an impact gave.
#[derive(Clone, Debug, PartialEq)]
pub struct Rebound {
    /// v_b after, per sphere (world).
    pub v: Vec<V3>,
    /// The normal impulse of each contact (N s).
    pub impulses: Vec<f64>,
    /// Why the answer is not physical, empty when it is.
    pub verdicts: Vec<String>,
}

fn vec3(v: &V3) -> Vec3<f64> {
    Vec3::new(v.x, v.y, v.z)
}

/// The impact problem of the contacts `at` (indices into `candidates`) at `s`.
///
/// # Errors
/// [`ImpactError::Invalid`] when the system refuses the problem.
pub fn system(
    spheres: &[Sphere],
    planes: &[Plane],
    candidates: &[Candidate],
    at: &[usize],
    s: &SystemState,
) -> Result<System<f64>, ImpactError> {
    let bodies = spheres
        .iter()
        .zip(&s.x)
        .map(|(b, x)| {
            let j = 0.4 * b.mass * b.radius * b.radius;
            SystemBody {
                body: RigidBody::principal(b.mass, Vec3::new(j, j, j)),
                centre: vec3(x),
            }
        })
        .collect();
    let velocity = SystemScrew(
        s.v.iter()
            .map(|v| Screw::new(Vec3::zeros(), vec3(v)))
            .collect(),
    );
    let mut contacts = Vec::with_capacity(at.len());
    let mut pairs = Vec::with_capacity(at.len());
    let mut levers = Vec::with_capacity(at.len());
    for &k in at {
        let c = &candidates[k];
        let g = gap(&c.touch, spheres, planes, s);
        let (normal, pair, lever) = match c.touch {
            // the sphere's outward normal at its lowest point: −N
            Touch::Plane { body, .. } => (
                -g.normal,
                Pair {
                    first: body,
                    second: None,
                },
                (-g.normal * spheres[body].radius, None),
            ),
            Touch::Pair { a, b } => (
                g.normal,
                Pair {
                    first: a,
                    second: Some(b),
                },
                (g.normal * spheres[a].radius, Some(g.point - s.x[b])),
            ),
        };
        contacts.push(
            Contact::new(vec3(&g.point), vec3(&normal), c.law.k).with_energetic(c.law.k_energetic),
        );
        pairs.push(pair);
        levers.push((vec3(&lever.0), lever.1.as_ref().map(vec3)));
    }
    System::new(bodies, velocity, contacts, pairs, Vec::new())
        .and_then(|sys| sys.with_lever_arms(levers))
        .map_err(|e| ImpactError::Invalid(e.to_string()))
}

/// Solve the impact of the contacts `at` at `s` under `law`, to the relative `tolerance` of
/// the integrated LZB law.
///
/// # Errors
/// [`ImpactError`]: the problem refused, or no answer under the law (energetic restitution is
/// refused: it is integrated with friction, which sphere systems do not have yet).
pub fn solve(
    spheres: &[Sphere],
    planes: &[Plane],
    candidates: &[Candidate],
    at: &[usize],
    s: &SystemState,
    law: Law,
    tolerance: f64,
) -> Result<Rebound, ImpactError> {
    let sys = system(spheres, planes, candidates, at, s)?;
    let velocities = |v: &SystemScrew<f64>| -> Vec<V3> {
        v.0.iter()
            .map(|t| {
                let b = t.bottom();
                V3::new(b[0], b[1], b[2])
            })
            .collect()
    };
    let model = |r: Restitution| match r {
        Restitution::Poisson => Ok(Model::Poisson),
        Restitution::Newton => Ok(Model::Newton),
        Restitution::Energetic => Err(ImpactError::NoAnswer(
            "the energetic restitution law is not simulated for systems of spheres yet: use \
             newton or poisson"
                .to_string(),
        )),
    };
    let no = |e: &dyn std::fmt::Display| ImpactError::NoAnswer(e.to_string());
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
            Ok(Rebound {
                v: velocities(&out.velocity),
                impulses: out.impulses.clone(),
                verdicts: Vec::new(),
            })
        }
        Law::Simultaneous(r) => {
            let model = model(r)?;
            let mut impact = Impact::assemble(&sys).map_err(|e| no(&e))?;
            let mut out = Outcome::default();
            impact.solve(model, &mut out).map_err(|e| no(&e))?;
            let v = verdicts(&impact, model, &out)
                .iter()
                .map(|v| verdict_name(v, |c| c + 1))
                .collect();
            Ok(Rebound {
                v: velocities(&out.velocity),
                impulses: out.impulses_hat.clone(),
                verdicts: v,
            })
        }
        Law::Unilateral(r) => {
            let model = model(r)?;
            let mut impact = Impact::assemble(&sys).map_err(|e| no(&e))?;
            let mut out = Outcome::default();
            impact
                .solve_unilateral(model, &mut out)
                .map_err(|e| no(&e))?;
            Ok(Rebound {
                v: velocities(&out.velocity),
                impulses: out.impulses_hat.clone(),
                verdicts: energy_gain(&impact, &out)
                    .into_iter()
                    .map(|v| v.name().to_string())
                    .collect(),
            })
        }
    }
}
