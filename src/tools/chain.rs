//! The planar chain the `systems` bench (`benches/systems.rs`), `inertance bench`'s systems
//! section ([`crate::tools::system_bench`]), `examples/chain_timing.rs` and
//! `benches/peers/chains.py` (Pinocchio) all solve — one definition.
//!
//! N slender bars of length 1 and mass 1 lie along +x, bar i from x = i to x = i + 1, its
//! centre at (i + ½, 0, 0) and central moments (J_x, J_y, J_z) = (1/1200, 1/12 + 1/1200,
//! 1/12 + 1/1200) (a bar of square section 0.1 × 0.1: m (b² + c²)/12 about each axis). Hinges
//! about z at x = i join bar i to bar i − 1, the first to the ground at the origin. The chain
//! turns as one bar at ω = −1 about z (v_C = ω × C: falling onto the ground y = 0 below it)
//! and strikes it with its tip (x = N) and the far end of its middle bar (bar ⌊(N − 1)/2⌋, at
//! x = ⌊(N − 1)/2⌋ + 1), normals −y out of the bars, one coefficient k = 1/2 for both. A single
//! bar has one degree of freedom, so N = 1 keeps the tip contact only.

use crate::impact::outputs::Outputs;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::body::RigidBody;
use crate::mechanics::constraint::Joint;
use crate::mechanics::contact::Contact;
use crate::mechanics::screw::{Screw, Vec3};
use crate::mechanics::system::{Pair, System, SystemBody, SystemJoint, SystemScrew};
use crate::scalar::Scalar;
use num_rational::BigRational;

/// The parts of a chain of `links` bars, to build its [`System`] from (so a timing can include
/// [`System::new`], where the joints are factored).
#[derive(Clone, Debug)]
pub struct Chain<T: Scalar> {
    /// The bars, bar i centred at (i + ½, 0, 0).
    pub bodies: Vec<SystemBody<T>>,
    /// Their twists before impact: the chain turning as one bar at ω = −1 about z.
    pub velocity: SystemScrew<T>,
    /// The tip and (N > 1) the middle bar's far end, against the ground.
    pub contacts: Vec<Contact<T>>,
    /// Each contact's body (and the ground).
    pub pairs: Vec<Pair>,
    /// The hinges, the first to the ground.
    pub joints: Vec<SystemJoint<T>>,
}

impl<T: Scalar> Chain<T> {
    /// The chain of `links` bars (at least one).
    ///
    /// # Panics
    /// For `links` = 0.
    pub fn new(links: usize) -> Self {
        let c = |n: i64, d: i64| T::from_rational(&BigRational::new(n.into(), d.into()));
        let v = |x: T, y: T, z: T| Vec3::new(x, y, z);
        let zero = || c(0, 1);
        let (jx, jz) = (c(1, 1200), c(1, 12) + c(1, 1200));
        let mut bodies = Vec::with_capacity(links);
        let mut velocity = Vec::with_capacity(links);
        let mut joints = Vec::with_capacity(links);
        for i in 0..links as i64 {
            bodies.push(SystemBody {
                body: RigidBody::principal(c(1, 1), v(jx.clone(), jz.clone(), jz.clone())),
                centre: v(c(2 * i + 1, 2), zero(), zero()),
            });
            // ω = −e_z, v_C = ω × C = (0, −(i + ½), 0).
            velocity.push(Screw::new(
                v(zero(), zero(), c(-1, 1)),
                v(zero(), c(-(2 * i + 1), 2), zero()),
            ));
            joints.push(SystemJoint {
                joint: Joint::Revolute {
                    point: v(c(i, 1), zero(), zero()),
                    axis: v(zero(), zero(), c(1, 1)),
                },
                pair: Pair {
                    first: i as usize,
                    second: (i > 0).then(|| i as usize - 1),
                },
            });
        }
        let mid = (links - 1) / 2;
        let down = || v(zero(), c(-1, 1), zero());
        let mut contacts = vec![Contact::new(
            v(c(links as i64, 1), zero(), zero()),
            down(),
            c(1, 2),
        )];
        let mut pairs = vec![Pair {
            first: links - 1,
            second: None,
        }];
        if links > 1 {
            contacts.push(Contact::new(
                v(c(mid as i64 + 1, 1), zero(), zero()),
                down(),
                c(1, 2),
            ));
            pairs.push(Pair {
                first: mid,
                second: None,
            });
        }
        Chain {
            bodies,
            velocity: SystemScrew(velocity),
            contacts,
            pairs,
            joints,
        }
    }

    /// The system (a clone of the parts: the timed path builds it from data every time).
    ///
    /// # Panics
    /// Never for a chain built by [`Chain::new`].
    pub fn system(&self) -> System<T> {
        System::new(
            self.bodies.clone(),
            self.velocity.clone(),
            self.contacts.clone(),
            self.pairs.clone(),
            self.joints.clone(),
        )
        .expect("a valid chain")
    }
}

impl<T: Scalar> Chain<T> {
    /// One solve from the data, as every chain timing counts it: [`System::new`] (the joints'
    /// rows and their tree factorization), [`Impact::assemble`] and each of `models`, every
    /// output, into `out` (the last model's outcome).
    ///
    /// # Errors
    /// A singular G (never for a chain of [`Chain::new`]).
    pub fn solve(
        &self,
        models: &[Model],
        out: &mut Outcome<T, SystemScrew<T>>,
    ) -> Result<(), SolveError> {
        self.solve_for(models, Outputs::ALL, out)
    }

    /// [`Chain::solve`] computing only `outputs` (what Pinocchio's `impulseDynamics` returns
    /// is [`Outputs::IMPULSES`] and [`Outputs::TWIST`]).
    ///
    /// # Errors
    /// As [`Chain::solve`].
    pub fn solve_for(
        &self,
        models: &[Model],
        outputs: Outputs,
        out: &mut Outcome<T, SystemScrew<T>>,
    ) -> Result<(), SolveError> {
        let system = self.system();
        let mut impact = Impact::assemble_owned(std::hint::black_box(system), outputs)?;
        for &m in models {
            impact.solve(m, out)?;
        }
        Ok(())
    }
}
