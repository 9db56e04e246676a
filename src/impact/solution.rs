//! The outcome of a collision in the paper's units: the one-call entry point [`solve`].
//!
//! The solver works with the contact axes as given (see [`crate::impact::solve::Impact`]);
//! here the norms are put back:
//!
//! ```text
//! P_i = P̂_i |n_i|   [N s]          v_ia = v̂_ia / |a_i|   [m/s], a = x, y, z
//! g_ij = ĝ_ij / (|n_i| |n_j|)  [1/kg]    Δ = det G = Δ̂ / Π_i |n_i|²
//! ```
//!
//! A quantity that carries a norm is a [`Surd`] q·√r: exact in exact types even when |n_i| is
//! irrational (n = (1, 1, 0) gives P = P̂·√2), one number through [`Surd::value`] whenever √r
//! is (always in floats, for perfect squares in rationals). The twist after impact, Δ, both
//! energies and the constraint impulses (q, and the wrench U q) carry no norm and are plain
//! values.

use crate::impact::outputs::Outputs;
use crate::impact::problem::Problem;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::impact::unilateral::UnilateralError;
use crate::mechanics::contact::Surd;
use crate::mechanics::reaction::{Wrench, joint_reactions};
use crate::mechanics::screw::Screw;
use crate::scalar::Scalar;

/// One restitution model solved, every quantity in the paper's units.
#[derive(Clone, Debug, PartialEq)]
pub struct Solution<T: Scalar> {
    /// The restitution model.
    pub model: Model,
    /// Δ = det G, with G = \[g_ij,xx\] in 1/kg (eq. 15–20).
    pub det: T,
    /// G = \[g_ij,xx\] (eq. 12), N×N row-major, 1/kg.
    pub inertances: Vec<Surd<T>>,
    /// P_i, the impulse at A_i along −n_i, N s (eq. 20, 23).
    pub impulses: Vec<Surd<T>>,
    /// P_i^c, the compression impulses (Poisson, eq. 21–22); empty for Newton.
    pub compression_impulses: Vec<Surd<T>>,
    /// {v} = [ω; v_C] after impact (eq. 24): rad/s and m/s, body axes.
    pub twist: Screw<T>,
    /// (v_ix⁰, v_iy⁰, v_iz⁰) before impact, along the unit axes of contact i's frame (eq. 8).
    pub contact_velocities_before: Vec<[Surd<T>; 3]>,
    /// (v_ix, v_iy, v_iz) after impact, along the unit axes of contact i's frame
    /// (eq. 13, 25, 26).
    pub contact_velocities: Vec<[Surd<T>; 3]>,
    /// E_p, the energy of the lost velocities, J (eq. 28).
    pub lost_velocity_energy: T,
    /// ΔE_c = T⁰ − T, the loss of kinetic energy, J (eq. 32).
    pub kinetic_energy_loss: T,
    /// q, the constraint impulses (eq. 90–93), one per constraint screw; empty for a free
    /// body.
    pub constraint_impulses: Vec<T>,
    /// U q = [F; M_C]: the impulsive force the constraints apply (N s) and its moment about C
    /// (N m s), whatever basis U is in; zero for a free body ([`crate::mechanics::reaction`]).
    pub constraint_wrench: Screw<T>,
    /// For a body held by joints, each joint's reaction: that wrench reduced to the joint's
    /// anchor (its point, or C for a prismatic or planar joint); empty otherwise.
    pub joint_reactions: Vec<Wrench<T>>,
}

/// Solve `problem` under the restitution `model`: the impulses, the motion after impact and the
/// energies, in the paper's units.
///
/// ```
/// use inertance::{Contact, Model, Problem, RigidBody, Screw, Vec3, solve};
///
/// // A bar on two supports (the paper's Example 3, in f64).
/// let body = RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0));
/// let twist = Screw::new(Vec3::new(0.0, 0.0, 0.4), Vec3::new(3.0, 2.0, 0.0));
/// let at = |y: f64, k: f64| Contact::new(Vec3::new(0.0, y, 0.0), Vec3::new(1.0, 0.0, 0.0), k);
/// let problem = Problem::new(body, twist, vec![at(-2.0, 0.3), at(4.0, 0.2)])?;
/// let newton = solve(&problem, Model::Newton)?;
/// assert!((newton.impulses[0].to_f64() - 3.655556).abs() < 1e-6);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// [`SolveError::Singular`] when G is singular (Δ = 0, §8): the impulses are not unique; see
/// [`crate::analysis`].
pub fn solve<T: Scalar>(problem: &Problem<T>, model: Model) -> Result<Solution<T>, SolveError> {
    Impact::assemble(problem)?.solution(model)
}

/// [`solve`] computing only the `outputs` asked for ([`crate::impact::outputs`]), each bit for
/// bit what [`solve`] gives; the vectors of the others are empty, their numbers zero, and
/// without [`Outputs::TANGENTIAL`] the tangential velocity components are zero.
///
/// ```
/// use inertance::{Contact, Model, Outputs, Problem, RigidBody, Screw, Vec3, solve, solve_for};
///
/// let body = RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0));
/// let twist = Screw::new(Vec3::new(0.0, 0.0, 0.4), Vec3::new(3.0, 2.0, 0.0));
/// let at = |y: f64, k: f64| Contact::new(Vec3::new(0.0, y, 0.0), Vec3::new(1.0, 0.0, 0.0), k);
/// let problem = Problem::new(body, twist, vec![at(-2.0, 0.3), at(4.0, 0.2)])?;
/// let fast = solve_for(&problem, Model::Newton, Outputs::IMPULSES | Outputs::TWIST)?;
/// let all = solve(&problem, Model::Newton)?;
/// assert_eq!((&fast.impulses, &fast.twist), (&all.impulses, &all.twist));
/// assert!(fast.contact_velocities.is_empty());
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// As [`solve`].
pub fn solve_for<T: Scalar>(
    problem: &Problem<T>,
    model: Model,
    outputs: Outputs,
) -> Result<Solution<T>, SolveError> {
    Impact::assemble_for(problem, outputs)?.solution(model)
}

/// Solve `problem` under the restitution `model` in **inequality form** (the unilateral law of
/// [`crate::impact::unilateral`]): contacts that would pull separate instead. In the paper's
/// units; `solution.impulses[i]` is zero at a contact that separates.
///
/// # Errors
/// [`UnilateralError::Jammed`] when no admissible impulses exist.
pub fn solve_unilateral<T: Scalar>(
    problem: &Problem<T>,
    model: Model,
) -> Result<Solution<T>, UnilateralError> {
    let mut impact = Impact::assemble(problem)?;
    let mut out = Outcome::default();
    impact.solve_unilateral(model, &mut out)?;
    Ok(Solution::from_hatted(&impact, model, out))
}

impl<T: Scalar> Impact<T> {
    /// Solve `model` on the assembled problem, in the paper's units (allocates the
    /// [`Solution`]; [`Impact::solve`] fills a reused hatted [`Outcome`] instead).
    ///
    /// # Errors
    /// [`SolveError::Singular`] when G is singular (Δ = 0, §8).
    pub fn solution(&mut self, model: Model) -> Result<Solution<T>, SolveError> {
        let mut out = Outcome::default();
        self.solve(model, &mut out)?;
        Ok(Solution::from_hatted(self, model, out))
    }
}

impl<T: Scalar> Solution<T> {
    /// The paper's units from the hatted `out` that `impact` solved.
    fn from_hatted(impact: &Impact<T>, model: Model, out: Outcome<T>) -> Self {
        let n = impact.contacts();
        let frames = impact.frames();
        let normal2 = |i: usize| &frames[i].norm2[0];
        let mut det = impact.det_hat().clone();
        for i in 0..n {
            det /= normal2(i);
        }
        let inertances = (0..n * n)
            .map(|k| {
                let (i, j) = (k / n, k % n);
                Surd::over_norm(&impact.g_hat()[k], &(normal2(i).clone() * normal2(j)))
            })
            .collect();
        let impulses = |hat: &[T]| -> Vec<Surd<T>> {
            hat.iter()
                .enumerate()
                .map(|(i, p)| Surd::times_norm(p, normal2(i)))
                .collect()
        };
        // Without the tangent axes (norm 0), their components are reported as zero.
        let tangential = impact.outputs().contains(Outputs::TANGENTIAL);
        let velocities = |hat: &[[T; 3]]| -> Vec<[Surd<T>; 3]> {
            hat.iter()
                .zip(frames)
                .map(|(v, f)| {
                    std::array::from_fn(|a| match a == 0 || tangential {
                        true => Surd::over_norm(&v[a], &f.norm2[a]),
                        false => Surd::times_norm(&T::zero(), &T::one()),
                    })
                })
                .collect()
        };
        Solution {
            model,
            det,
            inertances,
            impulses: impulses(&out.impulses_hat),
            compression_impulses: impulses(&out.compression_hat),
            twist: match impact.outputs().contains(Outputs::TWIST) {
                true => out.velocity,
                false => Screw::zero(),
            },
            contact_velocities_before: velocities(impact.before_hat()),
            contact_velocities: velocities(&out.after_hat),
            lost_velocity_energy: out.lost_velocity_energy,
            kinetic_energy_loss: out.kinetic_energy_loss,
            joint_reactions: match impact.problem().constraints() {
                Some(c) if impact.outputs().contains(Outputs::CONSTRAINT_IMPULSES) => {
                    joint_reactions(&out.constraint_wrench, &c.joints)
                }
                _ => Vec::new(),
            },
            constraint_impulses: out.constraint_impulses,
            constraint_wrench: out.constraint_wrench,
        }
    }
}
