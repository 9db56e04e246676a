//! What the constraints exert on the body (§9–11): the constraint impulse as a force and a
//! moment, and each joint's reaction at its anchor.
//!
//! The multipliers q (eq. 90–93) are coordinates in the basis U the constraints are written in;
//! the wrench they make, U q = [F; M_C], is not. Row by row the momentum balance
//! M({v} − {v⁰}) = −Σ P_i {E_ix} + U q (eq. 76) is
//!
//! ```text
//! m Δv_C = −Σ P_i n_i + F,        J Δω = −Σ P_i r_i × n_i + M_C
//! ```
//!
//! so F is the impulsive force the constraints apply to the body (N s) and M_C its moment about
//! the centre of mass C (N m s). The solver forms the wrench as that balance's remainder,
//! M({v} − {v⁰}) + Σ P_i {E_ix} ([`crate::mechanics::constraint::Constrained::impulses_into`]),
//! so it follows from the motion alone, whatever basis U is in.
//!
//! **Joints.** Joints compose as a serial chain — D is the union of their free screws, the
//! links between them massless — so every joint transmits the whole wrench U q. Reduced to a
//! point p (from C) a wrench keeps its force and moves its moment:
//!
//! ```text
//! M_p = M_C − p × F
//! ```
//!
//! A joint's anchor is its `point` (revolute, cylindrical, spherical). Prismatic and planar
//! joints have none, and their reaction includes a moment whose value depends on the point it
//! is taken about; they are reduced to C, the origin of every position in the reports (a
//! prismatic joint's moment is then the full reaction moment, for it blocks every rotation).
//!
//! [`Wrench`] is a force and a moment about a named point, so that a joint between two bodies
//! can later carry its own wrench at its own anchor.

use crate::mechanics::constraint::Joint;
use crate::mechanics::screw::{Screw, Vec3};
use crate::scalar::Scalar;

/// An impulsive wrench reduced to a point: the force F (N s) and the moment about `point`
/// (N m s), positions from the centre of mass C.
#[derive(Clone, Debug, PartialEq)]
pub struct Wrench<T: Scalar> {
    /// The point p the moment is taken about, from C.
    pub point: Vec3<T>,
    /// F.
    pub force: Vec3<T>,
    /// M_p.
    pub moment: Vec3<T>,
}

impl<T: Scalar> Wrench<T> {
    /// The wrench screw [F; M_C] reduced to `point` p: M_p = M_C − p × F.
    pub fn about(screw: &Screw<T>, point: Vec3<T>) -> Self {
        let force = screw.top();
        let moment = screw.bottom() - point.cross(&force);
        Wrench {
            point,
            force,
            moment,
        }
    }

    /// The wrench screw [F; M_C] = [F; M_p + p × F], about C again.
    pub fn screw(&self) -> Screw<T> {
        Screw::new(
            self.force.clone(),
            self.moment.clone() + self.point.cross(&self.force),
        )
    }
}

/// Each joint's reaction: the constraint wrench `wrench` = U q = [F; M_C] reduced to the
/// joint's anchor — its point, or C for a joint without one (module docs).
pub fn joint_reactions<T: Scalar>(wrench: &Screw<T>, joints: &[Joint<T>]) -> Vec<Wrench<T>> {
    joints
        .iter()
        .map(|j| Wrench::about(wrench, j.anchor().cloned().unwrap_or_else(Vec3::zeros)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scalar::{Exact, int};

    fn v(x: i64, y: i64, z: i64) -> Vec3<Exact> {
        Vec3::new(int(x), int(y), int(z))
    }

    #[test]
    fn a_force_through_the_point_has_no_moment_about_it() {
        // F = (0, 0, 2) along the line through p = (1, 3, 0): M_C = p × F = (6, −2, 0).
        let p = v(1, 3, 0);
        let screw = Screw::axis(&p, &v(0, 0, 2));
        let w = Wrench::about(&screw, p);
        assert_eq!(w.force, v(0, 0, 2));
        assert_eq!(w.moment, v(0, 0, 0));
        assert_eq!(w.screw(), screw);
    }

    #[test]
    fn a_couple_is_the_same_about_every_point() {
        let couple = Screw::new(v(0, 0, 0), v(1, -2, 5));
        assert_eq!(Wrench::about(&couple, v(7, -3, 2)).moment, v(1, -2, 5));
    }
}
