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

/// Below this sine of the tilt between a rim's plane and an obstacle plane, √(1 − s²), the rim
/// lies flat on it: its four body points stand for it, and its own nearest point is taken as
/// the one at 0° (a body point: the same contact). Its true nearest point is then at most
/// ρ · 10⁻⁴ · (1 − cos 45°) ≈ 3·10⁻⁵ ρ lower than the lowest of the four — the bound on what
/// a rim landing flat may sink between them. The bound is not smaller because the nearest
/// point's velocity grows as 1/tilt (u̇ below): nearer flat, a face that slaps down or lifts
/// off by a rounding's tilt swings it around the rim faster than the steps can follow
/// (derivations/cylinder-rim-kinematics.md).
pub const FLAT: f64 = 1e-4;

/// The gap of `feature` against `plane` when the body is at `s`.
///
/// A rim (centre c, axis a, radius ρ; in the world r_c = R c, a = R a_b) meets a plane of
/// normal N nearest at p = C + r_c − ρ u, with s = N · a and u = (N − s a)/√(1 − s²) the unit
/// direction of the rim's plane most along N: g = N · (C + r_c − P) − ρ √(1 − s²). Its rate is
/// the body point's at p (the envelope theorem: p minimises the height over the rim), and p
/// moves around the rim as the body turns: ṙ_p = ω × r_c − ρ u̇ with
///
/// ```text
/// ṡ = N · (ω × a),   u̇ = (−ṡ a − s (ω × a))/√(1 − s²) + (N − s a) s ṡ/(1 − s²)^{3/2}
/// ```
///
/// (derivations/cylinder-rim-kinematics.md). Flat (√(1 − s²) < [`FLAT`]) u is the body's x
/// axis, as a body point.
pub fn gap(feature: &Feature, plane: &Plane, s: &State) -> Gap {
    let n = &plane.normal;
    let (point, arm, drift) = match feature {
        Feature::Point { at, .. } => {
            let r = s.rotation() * at;
            (s.x + r, at.norm(), s.w.cross(&r))
        }
        Feature::Sphere { radius } => (s.x - n * *radius, *radius, V3::zeros()),
        Feature::Rim {
            centre,
            axis,
            radius,
            ..
        } => {
            let rot = s.rotation();
            let rc = rot * centre;
            let a = rot * axis;
            let sa = n.dot(&a);
            let tilt = (1.0 - sa * sa).max(0.0).sqrt();
            let (u, du) = if tilt > FLAT {
                let u = (n - a * sa) / tilt;
                let wa = s.w.cross(&a);
                let ds = n.dot(&wa);
                let du = (-a * ds - wa * sa) / tilt + (n - a * sa) * (sa * ds / tilt.powi(3));
                (u, du)
            } else {
                // flat: a body direction in the rim's plane
                let side = if axis.x.abs() < 0.9 { V3::x() } else { V3::y() };
                let u = (rot * (side - axis * axis.dot(&side))).normalize();
                (u, s.w.cross(&u))
            };
            let r = rc - u * *radius;
            (
                s.x + r,
                centre.norm().hypot(*radius),
                s.w.cross(&rc) - du * *radius,
            )
        }
    };
    let r = point - s.x;
    let u = s.v + s.w.cross(&r);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::body::{Body, Shape};
    use nalgebra::{Matrix3, UnitQuaternion};

    /// A cylinder r = 0.3, h = 0.4 of unit mass and inertia.
    fn can() -> Body {
        Body::new(
            1.0,
            Matrix3::identity(),
            Shape::Cylinder {
                radius: 0.3,
                half_height: 0.2,
            },
            None,
        )
        .expect("body")
    }

    fn floor() -> Plane {
        Plane {
            name: "floor".into(),
            normal: V3::z(),
            point: V3::zeros(),
            law: ContactLaw {
                k: 0.5,
                k_energetic: 0.5,
                mu: 0.0,
                stiffness: 0.0,
                exponent: 1.5,
            },
        }
    }

    /// A rim's contact point and its drift against central differences along a free rotation
    /// at constant ω (R(t) = exp(ω̂ t) R₀, C fixed): p(t ± h) − C, h = 10⁻⁴, whose truncation
    /// error is h²/6 |d³r/dt³| ≈ 10⁻⁸·(|ω|³ρ/s-scale) — bound 10⁻⁶ here (|ω| ≤ 3, ρ = 0.3,
    /// tilts from 0.2 to 1.2 rad); the gap's rate against the gap's difference quotient likewise.
    #[test]
    fn a_rims_nearest_point_moves_as_its_drift_says() {
        let body = can();
        let rim = body
            .features
            .iter()
            .find(|f| matches!(f, Feature::Rim { .. }))
            .expect("a can has rims");
        let w = V3::new(1.3, -2.1, 0.7);
        for tilt in [0.2, 0.7, 1.2] {
            let q0 = UnitQuaternion::from_scaled_axis(V3::new(tilt, 0.3, 0.1));
            let at = |t: f64| State {
                x: V3::new(0.0, 0.0, 1.0),
                q: UnitQuaternion::from_scaled_axis(w * t) * q0,
                v: V3::zeros(),
                w,
            };
            let h = 1e-4;
            let g0 = gap(rim, &floor(), &at(0.0));
            let (gp, gm) = (gap(rim, &floor(), &at(h)), gap(rim, &floor(), &at(-h)));
            let fd = ((gp.point - at(h).x) - (gm.point - at(-h).x)) / (2.0 * h);
            assert!(
                (fd - g0.drift).norm() <= 1e-6,
                "tilt {tilt}: {fd} ≠ {}",
                g0.drift
            );
            let rate = (gp.gap - gm.gap) / (2.0 * h);
            assert!(
                (rate - g0.rate).abs() <= 1e-6,
                "tilt {tilt}: {rate} ≠ {}",
                g0.rate
            );
        }
    }

    /// At a symmetric pose in closed form: the axis tilted by θ about y, C at height z: the
    /// lower rim's nearest point is at height z − h cos θ − ρ sin θ.
    #[test]
    fn a_tilted_rims_gap_is_the_closed_form() {
        let body = can();
        let lower = body
            .features
            .iter()
            .find(|f| f.label() == "rim [0, 0, -1]")
            .expect("the lower rim");
        let th = 0.4_f64;
        let s = State {
            x: V3::new(0.0, 0.0, 1.0),
            q: UnitQuaternion::from_scaled_axis(V3::new(0.0, th, 0.0)),
            v: V3::zeros(),
            w: V3::zeros(),
        };
        let g = gap(lower, &floor(), &s);
        let want = 1.0 - 0.2 * th.cos() - 0.3 * th.sin();
        assert!((g.gap - want).abs() <= 1e-15, "{} ≠ {want}", g.gap);
    }
}
