//! The impact of a system of bodies ([`crate::mechanics::system`]): its [`Mechanism`].
//!
//! A contact's frame is built as for one body (eq. 2–4; §12's tangent from the velocity of the
//! contact point, here relative to the second body), its axes the system's
//! ([`System::contact_axis`]: the axis's screw on the first body minus its screw on the
//! second). The solve, the laws, the energies and their identity are then those of
//! [`crate::impact::solve`], unchanged. The constraint impulses are the joints' impulses λ, one
//! per blocked screw ([`crate::mechanics::system::mobility`]); their wrenches are
//! [`System::joint_reactions`].
//!
//! **Route.** A free system whose bodies are in principal axes and whose G passes
//! [`crate::impact::route`]'s test takes the normal equations in floats; one held by joints,
//! with a body's full inertia tensor (a posed body in world axes), or with an
//! ill-conditioned G, takes the
//! orthogonalised contact wrenches in the metric ηW ([`crate::impact::gram_schmidt`]), which
//! keeps the twist to √cond G·ε as for one body.

use crate::impact::friction::blocks::plane_normals;
use crate::impact::mechanism::Mechanism;
use crate::impact::route::{self, Route};
use crate::impact::solve::Outcome;
use crate::mechanics::body::{Inertia, RigidBody};
use crate::mechanics::contact::{Contact, ContactFrame, TangentNotPerpendicular};
use crate::mechanics::screw::Vec3;
use crate::mechanics::system::{System, SystemScrew};
use crate::scalar::Scalar;

impl<T: Scalar> Mechanism<T> for System<T> {
    type Screw = SystemScrew<T>;

    fn contacts(&self) -> &[Contact<T>] {
        System::contacts(self)
    }

    fn velocity(&self) -> &SystemScrew<T> {
        System::velocity(self)
    }

    fn frame(
        &self,
        i: usize,
        tangential: bool,
    ) -> Result<ContactFrame<T, SystemScrew<T>>, TangentNotPerpendicular> {
        let c = &self.contacts()[i];
        let axis = |u: &Vec3<T>| System::contact_axis(self, i, u);
        if tangential {
            ContactFrame::with_axes(i, c, || self.relative_velocity(i), axis)
        } else {
            Ok(ContactFrame::normal_with(c, axis))
        }
    }

    fn contact_axis(&self, i: usize, u: &Vec3<T>) -> SystemScrew<T> {
        System::contact_axis(self, i, u)
    }

    /// One body with no joints, every contact against an obstacle: it is the single body of
    /// [`crate::impact::problem::Problem`], and takes its float lane, so that its results are
    /// that body's bit for bit.
    fn lane_body(&self) -> Option<&RigidBody<T>> {
        match (self.bodies(), self.joints().is_empty()) {
            ([body], true) if self.pairs().iter().all(|p| p.second.is_none()) => Some(&body.body),
            _ => None,
        }
    }

    /// The planes of rational unit normal built from the system's vectors
    /// ([`plane_normals`]): each body's ω⁰ (along the normal of a planar motion), and as
    /// vectors of the plane the contact points and the bodies' centres from the first contact
    /// point, the normals, each body's v_C⁰ and ω⁰.
    fn planes(&self) -> Vec<Vec3<T>> {
        let contacts = System::contacts(self);
        let origin = contacts[0].point.clone();
        let spins: Vec<Vec3<T>> = self.velocity().0.iter().map(|v| v.top()).collect();
        let mut vectors: Vec<Vec3<T>> = contacts
            .iter()
            .flat_map(|c| [c.point.clone() - origin.clone(), c.normal.clone()])
            .collect();
        vectors.extend(
            self.bodies()
                .iter()
                .map(|b| b.centre.clone() - origin.clone()),
        );
        for v in &self.velocity().0 {
            vectors.extend([v.bottom(), v.top()]);
        }
        plane_normals(contacts, &spins, &vectors)
    }

    fn kinetic_energy(&self, v: &SystemScrew<T>) -> T {
        System::kinetic_energy(self, v)
    }

    /// As one body's ([`route::route`]): the normal equations for a free system whose every
    /// body has its inertia in principal axes — the metric ηM⁻¹ diagonal, where the route's
    /// bound on the rounding of the inertances holds — and whose G passes the test.
    fn route(&self, g_hat: &[T], n: usize) -> Route {
        let principal = || {
            self.bodies()
                .iter()
                .all(|b| matches!(b.body.inertia, Inertia::Principal(_)))
        };
        if T::IS_EXACT
            || (self.joints().is_empty() && principal() && route::well_conditioned(g_hat, n))
        {
            Route::NormalEquations
        } else {
            Route::OrthogonalWrenches
        }
    }

    fn constraint_impulses(
        &self,
        dv: &SystemScrew<T>,
        frames: &[ContactFrame<T, SystemScrew<T>>],
        out: &mut Outcome<T, SystemScrew<T>>,
    ) {
        let axes = frames.iter().map(|f| &f.axes[0]);
        out.constraint_impulses = self.joint_impulses(dv, out.impulses_hat.iter().zip(axes));
    }
}
