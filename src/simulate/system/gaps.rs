//! The contacts a sphere system can make and their gap functions: every sphere against every
//! obstacle plane, every pair of spheres against each other.
//!
//! A sphere b (centre x_b, radius r_b) against a plane (unit normal N out of it, through P):
//!
//! ```text
//! g = N · (x_b − P) − r_b,     ġ = N · v_b,     g̈ = N · a_b
//! ```
//!
//! Two spheres a, b, with d = x_b − x_a, n = d/|d| and u = v_b − v_a:
//!
//! ```text
//! g = |d| − r_a − r_b,     ġ = n · u,     g̈ = n · (a_b − a_a) + (|u|² − (n · u)²)/|d|
//! ```
//!
//! (the last term: n turns as the pair does). Both are g̈ = J a + c with the row J of the
//! contact (+N on b; −n on a and +n on b) and the curvature term c, which is what the
//! acceleration-level problem of [`super::persist`] assembles. A contact force λ ≥ 0 acts along
//! Jᵀ: it opens the gap.

use super::super::body::V3;
use super::super::world::{ContactLaw, Plane};
use super::spheres::{Sphere, SystemState};

/// What touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Touch {
    /// Sphere `body` on obstacle `plane`.
    Plane {
        /// The sphere.
        body: usize,
        /// The plane.
        plane: usize,
    },
    /// Sphere `a` on sphere `b` (a < b).
    Pair {
        /// The first sphere.
        a: usize,
        /// The second.
        b: usize,
    },
}

/// A contact the simulation watches, and its law.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// What touches.
    pub touch: Touch,
    /// Its law (k, μ = 0, the LZB stiffness and exponent).
    pub law: ContactLaw,
}

/// A contact's gap at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// g (m).
    pub gap: f64,
    /// ġ (m/s): negative approaching.
    pub rate: f64,
    /// The unit normal n (a plane's N; from a's centre to b's).
    pub normal: V3,
    /// The curvature term c of g̈ = J a + c (m/s²).
    pub curvature: f64,
    /// The contact point (world): on the first sphere's surface along the normal.
    pub point: V3,
}

impl Touch {
    /// The bodies the contact's row J acts on, with the sign of the normal on each
    /// (+1: the force λ n pushes it; −1: λ n pulls it, i.e. pushes along −n).
    pub fn bodies(&self) -> Vec<(usize, f64)> {
        match *self {
            Touch::Plane { body, .. } => vec![(body, 1.0)],
            Touch::Pair { a, b } => vec![(a, -1.0), (b, 1.0)],
        }
    }

    /// Its name in the log: `bead 1 on floor`, `bead 1 on bead 2`.
    pub fn name(&self, spheres: &[Sphere], planes: &[Plane]) -> (String, String) {
        match *self {
            Touch::Plane { body, plane } => {
                (spheres[body].name.clone(), planes[plane].name.clone())
            }
            Touch::Pair { a, b } => (spheres[a].name.clone(), spheres[b].name.clone()),
        }
    }
}

/// The gap of `touch` at `s` (module docs).
pub fn gap(touch: &Touch, spheres: &[Sphere], planes: &[Plane], s: &SystemState) -> Gap {
    match *touch {
        Touch::Plane { body, plane } => {
            let p = &planes[plane];
            let n = p.normal;
            let r = spheres[body].radius;
            Gap {
                gap: n.dot(&(s.x[body] - p.point)) - r,
                rate: n.dot(&s.v[body]),
                normal: n,
                curvature: 0.0,
                point: s.x[body] - n * r,
            }
        }
        Touch::Pair { a, b } => {
            let d = s.x[b] - s.x[a];
            let len = d.norm();
            let n = d / len;
            let u = s.v[b] - s.v[a];
            let along = n.dot(&u);
            Gap {
                gap: len - spheres[a].radius - spheres[b].radius,
                rate: along,
                normal: n,
                curvature: (u.norm_squared() - along * along).max(0.0) / len,
                point: s.x[a] + n * spheres[a].radius,
            }
        }
    }
}
