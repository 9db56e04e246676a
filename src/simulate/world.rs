//! The obstacles and the gap functions: how far each feature is from each plane, how fast the
//! gap closes, and the contact's law there.
//!
//! An obstacle is a plane with the unit normal N pointing out of it, toward the body, through
//! a point P. The gap of a body point p is g = N · (p − P) and of the sphere of radius r about
//! C, g = N · (x − P) − r (its nearest point x − r N). Its rate is ġ = N · u with u the
//! velocity of the point; a contact approaches when ġ < 0. The contact's outward normal, as
//! the impact layer wants it (the body's), is −N.

use super::body::{Body, Feature, State, V3};

/// The law of the contacts a plane makes (every feature that strikes it).
#[derive(Clone, Debug, PartialEq)]
pub struct ContactLaw {
    /// Newton's and Poisson's coefficient k.
    pub k: f64,
    /// Stronge's energetic coefficient (the LZB law's e, the energetic restitution law's).
    pub k_energetic: f64,
    /// Coulomb's μ ≥ 0.
    pub mu: f64,
    /// The LZB stiffness K.
    pub stiffness: f64,
    /// The LZB exponent η.
    pub exponent: f64,
}

/// An obstacle plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Plane {
    /// Its name (`floor`), or `obstacle[i]`.
    pub name: String,
    /// N: unit, out of the obstacle.
    pub normal: V3,
    /// P: a point of it.
    pub point: V3,
    /// The law of its contacts.
    pub law: ContactLaw,
}

/// A feature against a plane, at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// g (m).
    pub gap: f64,
    /// ġ (m/s): negative approaching.
    pub rate: f64,
    /// The point of the feature nearest the plane (world).
    pub point: V3,
    /// Its distance from C (m): what its acceleration grows with when the body turns.
    pub arm: f64,
    /// ṙ: the velocity of the contact point relative to C (world) — ω × r for a body point,
    /// which moves with the body; 0 for a sphere's nearest point, which stays at −r N from C
    /// however the sphere turns. The contact point's acceleration at zero v̇ and ω̇ is ω × ṙ
    /// (differentiate u = v + ω × r with r = p − C: u̇ = v̇ + ω̇ × r + ω × ṙ), the bias of its
    /// rows in persistent contact ([`super::contact`]).
    pub drift: V3,
}

/// The gap of `feature` against `plane` when the body is at `s`.
pub fn gap(feature: &Feature, plane: &Plane, s: &State) -> Gap {
    let n = &plane.normal;
    let (point, arm) = match feature {
        Feature::Point { at, .. } => {
            let r = s.rotation() * at;
            (s.x + r, at.norm())
        }
        Feature::Sphere { radius } => (s.x - n * *radius, *radius),
    };
    let r = point - s.x;
    let u = s.v + s.w.cross(&r);
    let drift = match feature {
        Feature::Point { .. } => s.w.cross(&r),
        Feature::Sphere { .. } => V3::zeros(),
    };
    Gap {
        gap: n.dot(&(point - plane.point)),
        rate: n.dot(&u),
        point,
        arm,
        drift,
    }
}

/// Every feature's gap against every plane, feature-major: entry `f * planes + p`.
pub fn gaps(body: &Body, planes: &[Plane], s: &State) -> Vec<Gap> {
    let mut out = Vec::with_capacity(body.features.len() * planes.len());
    for f in &body.features {
        for p in planes {
            out.push(gap(f, p, s));
        }
    }
    out
}
