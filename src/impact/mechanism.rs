//! What an impact is solved on: a **mechanism** — one body, free or held by ideal constraints
//! to the ground (the paper, §2–13), or a system of bodies joined to each other
//! ([`crate::mechanics::system`]).
//!
//! The solve of [`crate::impact::solve::Impact`] is written once against this trait. It asks
//! of a mechanism only what eq. 12–34 use: its velocity {v⁰} in its screw space, each
//! contact's frame as axis screws in that space (for a contact between two bodies, the
//! axis's screw on the first minus its screw on the second, so that {Ê}ᵀ η {v} is the
//! relative velocity of the contact point along the axis), the mobility W ({v} − {v⁰} =
//! −Σ P̂_j W{Ê_jx}, [`Mobility`]) and the kinetic energy ½ {v}ᵀ η M {v}. G, Δ, the laws, the
//! energies and their identity follow unchanged. The constraint impulses are the
//! mechanism's own business, as are the fast paths a single free body takes.

use crate::impact::restitution::Model;
use crate::impact::route::Route;
use crate::impact::solve::{Impact, Outcome, SolveError};
use crate::mechanics::body::{Mobility, RigidBody};
use crate::mechanics::contact::{Contact, ContactFrame, TangentNotPerpendicular};
use crate::mechanics::screw::{Screws, Vec3};
use crate::scalar::Scalar;

/// A mechanism an impact is solved on (module docs).
pub trait Mechanism<T: Scalar>: Mobility<T, Self::Screw> + Clone + std::fmt::Debug {
    /// The screw space of its twists and axes.
    type Screw: Screws<T>;

    /// The contacts: coefficients of restitution and friction, normal, tangent, point.
    fn contacts(&self) -> &[Contact<T>];

    /// {v⁰}, the velocity before impact.
    fn velocity(&self) -> &Self::Screw;

    /// The frame of contact `i` (eq. 2–4, 112–123); with `tangential` false its normal only
    /// ([`ContactFrame::normal`]).
    ///
    /// # Errors
    /// A tangent not perpendicular to its normal.
    fn frame(
        &self,
        i: usize,
        tangential: bool,
    ) -> Result<ContactFrame<T, Self::Screw>, TangentNotPerpendicular>;

    /// The screw of the axis through contact `i`'s point with direction `u`, |u| as given
    /// (eq. 3–4; for a contact between two bodies, its screw on the first minus its screw on
    /// the second): {E}ᵀ η {v} is the velocity of the point along u, relative to the second
    /// body.
    fn contact_axis(&self, i: usize, u: &Vec3<T>) -> Self::Screw;

    /// The unit normals of planes other than the coordinate ones that a frictional impact of
    /// this mechanism may stay in, in the order to try them; asked in exact types only, once
    /// the coordinate planes have failed. Each is only a candidate:
    /// [`crate::impact::friction::blocks`] tests every plane exactly (no impulse along a
    /// stacked axis, nor the velocity before, moves a frictional contact out of it) before
    /// integrating in it. None by default: such a scene is then integrated as a spatial one.
    fn planes(&self) -> Vec<Vec3<T>> {
        Vec::new()
    }

    /// ½ {v}ᵀ η M {v} (eq. 28, 32).
    fn kinetic_energy(&self, v: &Self::Screw) -> T;

    /// Which route a float solve takes ([`crate::impact::route`]), from Ĝ (N×N).
    fn route(&self, g_hat: &[T], n: usize) -> Route;

    /// The constraint impulses of the twist change `dv` and the impulses of `out` into `out`
    /// (none for a free body or system).
    fn constraint_impulses(
        &self,
        dv: &Self::Screw,
        frames: &[ContactFrame<T, Self::Screw>],
        out: &mut Outcome<T, Self::Screw>,
    );

    /// The mechanism's one free body, when it is one ([`crate::impact::solve`]'s small-N
    /// float lane serves it): a body without constraints, or a system of one body with no
    /// joints hit only against obstacles. `None` by default.
    fn lane_body(&self) -> Option<&RigidBody<T>> {
        None
    }

    /// Assemble `impact` by a faster path than the general one, if the mechanism has one for
    /// it (`true`: done): the small-N float lane for one free body ([`Mechanism::lane_body`]).
    ///
    /// # Errors
    /// As [`Impact::assemble`].
    fn assemble_fast(impact: &mut Impact<T, Self>) -> Result<bool, SolveError>
    where
        Self: Sized,
    {
        impact.build_lane()
    }

    /// Solve `model` on `impact` by the fast path it was assembled by, if any (`true`: done).
    fn solve_fast(
        impact: &mut Impact<T, Self>,
        model: Model,
        out: &mut Outcome<T, Self::Screw>,
    ) -> bool
    where
        Self: Sized,
    {
        impact.lane != 0 && impact.solve_lane(model, out)
    }
}
