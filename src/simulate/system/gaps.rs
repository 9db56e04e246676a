//! The contacts a system can make and their gap functions: every feature of every member
//! against every obstacle plane, every pair of spheres against each other, and every feature of
//! a member (a box's corner, a sphere) against every face of a box.
//!
//! A feature of member b against a plane (unit normal N out of it, through P) is the single
//! body's gap ([`crate::simulate::world::gap`]); for a sphere (centre x_b, radius r_b):
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
//! (the last term: n turns as the pair does). A feature of a, at p, against the face of box b
//! whose outward unit normal is n = R_b e (e = ±x, ±y or ±z of b's axes) at the half edge h
//! from b's centre, with D = p − x_b:
//!
//! ```text
//! g = n · D − h,    ġ = ṅ · D + n · Ḋ,    g̈ = n̈ · D + 2 ṅ · Ḋ + n · D̈,    ṅ = ω_b × n
//! ```
//!
//! with p = x_a + r_a for a corner (r_a = R_a a, ṗ = v_a + ω_a × r_a, p̈ = a_a + α_a × r_a +
//! ω_a × (ω_a × r_a)) and p = x_a − ρ n for a sphere of radius ρ (ṗ = v_a − ρ ṅ). The face
//! contact is watched where it can be one: while p (a sphere's centre) lies over the face —
//! its coordinates ℓ along b's two other axes within the half edges h_j, to 10⁻⁹ of b's reach,
//! on the face's side of b's centre, and nearer the face's plane than any other face's
//! (±ℓ_k − h_k ≥ max_j (|ℓ_j| − h_j): a point at an edge or inside the box belongs to the face
//! it is least deep under); elsewhere its gap is +∞ (the face's plane beside b is no
//! obstacle).
//!
//! Each is g̈ = J a + c: the row J of the contact acts on each member i it touches as
//! σ_i [n; r_i × n] (σ_i = ±1 the side, r_i = the contact point − x_i: the force λ σ_i n at the
//! point), and c is the curvature term — the part of g̈ in the velocities alone:
//! n · (ω × (ω × r)) for a corner on a plane, 0 for a sphere on it, the pair's above, and
//! n̈_v · D + 2 ṅ · Ḋ + n · p̈_v on a face (n̈_v = ω_b × ṅ; p̈_v = ω_a × (ω_a × r_a) for a corner,
//! −ρ n̈_v for a sphere). That is what the acceleration-level problem of [`super::persist`]
//! assembles, and ġ = J u. A contact force λ ≥ 0 acts along Jᵀ: it opens the gap. The
//! moments r × n of a sphere's side are zero (its force passes through its centre), written
//! as zeros.

use super::super::body::{Feature, Shape, State, V3};
use super::super::world::{ContactLaw, Plane};
use super::members::{Member, SystemState};

/// What touches.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Touch {
    /// Feature `feature` of member `body` on obstacle `plane`.
    Plane {
        /// The member.
        body: usize,
        /// Its feature (index in its [`crate::simulate::body::Body::features`]).
        feature: usize,
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
    /// Feature `feature` of member `a` on face `face` of box `b` (face 2k + 0 is +e_k, 2k + 1
    /// is −e_k, in b's axes).
    Face {
        /// The member whose feature strikes.
        a: usize,
        /// Its feature.
        feature: usize,
        /// The box.
        b: usize,
        /// Its face.
        face: usize,
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

/// One member a contact's row acts on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Side {
    /// The member.
    pub body: usize,
    /// σ: +1 where the force λ n pushes it, −1 where it pushes it along −n.
    pub sign: f64,
    /// r: the contact point − its centre (world).
    pub arm: V3,
    /// r × n (zero for a sphere).
    pub moment: V3,
    /// ṙ: how fast the arm turns and slides — ω × r for a material point (a corner), the rate
    /// of a sphere's r = ∓ρ n as n turns (zero on a plane), and for a box's face the rate of
    /// the contact point less its centre's, ṗ − v_b. The slip u = Σ σ_i (v_i + ω_i × r_i) of
    /// the contact then changes at u̇ = Σ σ_i (a_i + α_i × r_i + ω_i × ṙ_i): what a sticking
    /// contact holds at zero along its tangents ([`super::persist`]).
    pub arm_rate: V3,
}

/// A contact's gap at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gap {
    /// g (m); +∞ for a face contact not over its face (module docs).
    pub gap: f64,
    /// ġ (m/s): negative approaching.
    pub rate: f64,
    /// The unit normal n (a plane's N; from a's centre to b's; a face's outward normal).
    pub normal: V3,
    /// The curvature term c of g̈ = J a + c (m/s²).
    pub curvature: f64,
    /// The contact point (world): on the first member's surface.
    pub point: V3,
    /// How far the point lies inside its face's edges (m; +∞ but for a face contact).
    pub inside: f64,
    /// The rate of `inside` (m/s; negative: the point moves out over the nearest edge).
    pub inside_rate: f64,
    /// The members the row acts on: one on a plane, two between members.
    pub sides: [Option<Side>; 2],
}

impl Gap {
    /// The sides the row acts on.
    pub fn sides(&self) -> impl Iterator<Item = &Side> {
        self.sides.iter().flatten()
    }
}

impl Touch {
    /// The members the contact's row J acts on, with the sign of the normal on each
    /// (+1: the force λ n pushes it; −1: λ n pulls it, i.e. pushes along −n).
    pub fn bodies(&self) -> Vec<(usize, f64)> {
        match *self {
            Touch::Plane { body, .. } => vec![(body, 1.0)],
            Touch::Pair { a, b } => vec![(a, -1.0), (b, 1.0)],
            Touch::Face { a, b, .. } => vec![(a, 1.0), (b, -1.0)],
        }
    }

    /// Its name in the log: `bead 1 on floor`, `bead 1 on bead 2`, `top corner [1, 1, -1]` on
    /// `base face +z` — the first and the second of `a on b`.
    pub fn name(&self, members: &[Member], planes: &[Plane]) -> (String, String) {
        let feature = |m: usize, f: usize| -> String {
            let member = &members[m];
            match &member.body.shape {
                Shape::Sphere { .. } => member.name.clone(),
                _ => format!("{} {}", member.name, member.body.features[f].label()),
            }
        };
        match *self {
            Touch::Plane {
                body,
                feature: f,
                plane,
            } => (feature(body, f), planes[plane].name.clone()),
            Touch::Pair { a, b } => (members[a].name.clone(), members[b].name.clone()),
            Touch::Face {
                a,
                feature: f,
                b,
                face,
            } => (
                feature(a, f),
                format!(
                    "{} face {}{}",
                    members[b].name,
                    if face.is_multiple_of(2) { '+' } else { '-' },
                    ['x', 'y', 'z'][face / 2]
                ),
            ),
        }
    }
}

/// Member `b`'s state as the single body's.
pub fn state_of(s: &SystemState, b: usize) -> State {
    State {
        x: s.x[b],
        q: s.q[b],
        v: s.v[b],
        w: s.w[b],
    }
}

/// A sphere's side: its normal force passes through its centre.
fn round_side(body: usize, sign: f64, arm: V3, arm_rate: V3) -> Side {
    Side {
        body,
        sign,
        arm,
        moment: V3::zeros(),
        arm_rate,
    }
}

/// The gap of `touch` at `s` (module docs).
pub fn gap(touch: &Touch, members: &[Member], planes: &[Plane], s: &SystemState) -> Gap {
    match *touch {
        Touch::Plane {
            body,
            feature,
            plane,
        } => {
            let p = &planes[plane];
            let n = p.normal;
            let f = &members[body].body.features[feature];
            if let Feature::Sphere { radius: r } = f {
                return Gap {
                    gap: n.dot(&(s.x[body] - p.point)) - r,
                    rate: n.dot(&s.v[body]),
                    normal: n,
                    curvature: 0.0,
                    point: s.x[body] - n * *r,
                    inside: f64::INFINITY,
                    inside_rate: 0.0,
                    sides: [Some(round_side(body, 1.0, -n * *r, V3::zeros())), None],
                };
            }
            let st = state_of(s, body);
            let g = super::super::world::gap(f, p, &st);
            let r = g.point - st.x;
            Gap {
                gap: g.gap,
                rate: g.rate,
                normal: n,
                curvature: n.dot(&st.w.cross(&g.drift)),
                point: g.point,
                inside: f64::INFINITY,
                inside_rate: 0.0,
                sides: [
                    Some(Side {
                        body,
                        sign: 1.0,
                        arm: r,
                        moment: r.cross(&n),
                        arm_rate: g.drift,
                    }),
                    None,
                ],
            }
        }
        Touch::Pair { a, b } => {
            let d = s.x[b] - s.x[a];
            let len = d.norm();
            let n = d / len;
            let u = s.v[b] - s.v[a];
            let along = n.dot(&u);
            let (ra, rb) = (
                members[a].radius().unwrap_or(0.0),
                members[b].radius().unwrap_or(0.0),
            );
            let point = s.x[a] + n * ra;
            // ṅ: n turns as the pair does
            let ndot = (u - n * along) / len;
            Gap {
                gap: len - ra - rb,
                rate: along,
                normal: n,
                curvature: (u.norm_squared() - along * along).max(0.0) / len,
                point,
                inside: f64::INFINITY,
                inside_rate: 0.0,
                sides: [
                    Some(round_side(a, -1.0, n * ra, ndot * ra)),
                    Some(round_side(
                        b,
                        1.0,
                        point - s.x[b],
                        s.v[a] + ndot * ra - s.v[b],
                    )),
                ],
            }
        }
        Touch::Face {
            a,
            feature,
            b,
            face,
        } => face_gap(members, s, a, feature, b, face),
    }
}

/// A feature of `a` on face `face` of box `b` (module docs).
fn face_gap(
    members: &[Member],
    s: &SystemState,
    a: usize,
    feature: usize,
    b: usize,
    face: usize,
) -> Gap {
    // a face contact is on a box ([`super::run::SystemSetup::candidates`]); none else is
    let Shape::Box { half } = members[b].body.shape else {
        return apart(s, a);
    };
    let (k, sign) = (face / 2, if face.is_multiple_of(2) { 1.0 } else { -1.0 });
    let rb = s.rotation(b);
    let n = rb.column(k) * sign;
    let wb = s.w[b];
    let ndot = wb.cross(&n);
    let nddot = wb.cross(&ndot);
    // the point, its velocity and the velocity part of its acceleration; the side on a; the
    // point whose place over the face decides (a sphere's centre) and its velocity
    let (p, pdot, pddot, side_a, (centre, centre_dot)) = match &members[a].body.features[feature] {
        Feature::Sphere { radius } => (
            s.x[a] - n * *radius,
            s.v[a] - ndot * *radius,
            -nddot * *radius,
            round_side(a, 1.0, -n * *radius, -ndot * *radius),
            (s.x[a], s.v[a]),
        ),
        Feature::Point { at, .. } => {
            let r = s.rotation(a) * at;
            let wa = s.w[a];
            let p = s.x[a] + r;
            let pdot = s.v[a] + wa.cross(&r);
            (
                p,
                pdot,
                wa.cross(&wa.cross(&r)),
                Side {
                    body: a,
                    sign: 1.0,
                    arm: r,
                    moment: r.cross(&n),
                    arm_rate: wa.cross(&r),
                },
                (p, pdot),
            )
        }
        // no rim strikes a face ([`super::run::SystemSetup::candidates`])
        Feature::Rim { .. } => return apart(s, a),
    };
    let d = p - s.x[b];
    let local = rb.transpose() * (centre - s.x[b]);
    // the nearest edge j, and how fast the point moves out over it (in b's axes, relative to
    // b's material point there)
    let (nearest, inside) = (0..3)
        .filter(|&j| j != k)
        .map(|j| (j, half[j] - local[j].abs()))
        .fold((k, f64::INFINITY), |m, e| if e.1 < m.1 { e } else { m });
    let relative = rb.transpose() * (centre_dot - s.v[b] - wb.cross(&(centre - s.x[b])));
    let inside_rate = -local[nearest].signum() * relative[nearest];
    let ddot = pdot - s.v[b];
    // over the face: within its edges, on its side of the centre, and nearer its plane than
    // any other face's (a point inside the box belongs to the face it is least deep under)
    let margin = 1e-9 * members[b].body.reach();
    let over =
        sign * local[k] > 0.0 && inside >= -margin && sign * local[k] - half[k] >= -inside - margin;
    Gap {
        gap: if over {
            n.dot(&d) - half[k]
        } else {
            f64::INFINITY
        },
        rate: ndot.dot(&d) + n.dot(&ddot),
        normal: n,
        curvature: nddot.dot(&d) + 2.0 * ndot.dot(&ddot) + n.dot(&pddot),
        point: p,
        inside,
        inside_rate,
        sides: [
            Some(side_a),
            Some(Side {
                body: b,
                sign: -1.0,
                arm: d,
                moment: d.cross(&n),
                arm_rate: ddot,
            }),
        ],
    }
}

/// A contact that is no contact (+∞ gap, no rows): what a face contact the candidates never
/// make would be.
fn apart(s: &SystemState, a: usize) -> Gap {
    Gap {
        gap: f64::INFINITY,
        rate: 0.0,
        normal: V3::z(),
        curvature: 0.0,
        point: s.x[a],
        inside: f64::NEG_INFINITY,
        inside_rate: 0.0,
        sides: [None, None],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::body::Body;
    use nalgebra::{Matrix3, UnitQuaternion};

    fn cuboid(name: &str, half: V3) -> Member {
        let m = 2.0;
        let j = |a: f64, b: f64| m * (a * a + b * b) / 3.0;
        Member {
            name: name.into(),
            body: Body::new(
                m,
                Matrix3::from_diagonal(&V3::new(
                    j(half.y, half.z),
                    j(half.x, half.z),
                    j(half.x, half.y),
                )),
                Shape::Box { half },
                None,
            )
            .expect("a box"),
            spins: false,
        }
    }

    fn ball(name: &str, radius: f64) -> Member {
        Member {
            name: name.into(),
            body: Body::new(
                1.0,
                Matrix3::identity() * 0.4 * radius * radius,
                Shape::Sphere { radius },
                None,
            )
            .expect("a ball"),
            spins: false,
        }
    }

    /// Both members moving rigidly at constant v and ω (no acceleration, no angular
    /// acceleration): then ġ = J u and g̈ = c, the curvature term alone. Central differences
    /// of g(t) over h = 10⁻⁴ s (errors O(h²) ≈ 10⁻⁸ of the motion's scales) check the rate and
    /// the curvature of a corner and of a sphere on a turning box's faces — the derivation of
    /// the module docs against the definition g = n · (p − x_b) − h.
    #[test]
    fn a_face_gaps_rate_and_curvature_are_its_derivatives() {
        let members = vec![
            cuboid("a", V3::new(0.2, 0.1, 0.05)),
            cuboid("b", V3::new(0.5, 0.4, 0.1)),
            ball("c", 0.05),
        ];
        let q0 = [
            UnitQuaternion::from_scaled_axis(V3::new(0.3, -0.2, 0.4)),
            UnitQuaternion::from_scaled_axis(V3::new(-0.1, 0.25, 0.2)),
            UnitQuaternion::identity(),
        ];
        let x0 = [
            V3::new(0.05, 0.02, 0.45),
            V3::new(0.0, 0.0, 0.0),
            V3::new(-0.1, 0.1, 0.3),
        ];
        let v = [
            V3::new(0.3, -0.1, -1.2),
            V3::new(-0.2, 0.4, 0.1),
            V3::new(0.1, 0.2, -0.7),
        ];
        let w = [
            V3::new(1.1, -2.3, 0.7),
            V3::new(0.6, 0.9, -1.4),
            V3::zeros(),
        ];
        let at = |t: f64| SystemState {
            x: (0..3).map(|b| x0[b] + v[b] * t).collect(),
            v: v.to_vec(),
            q: (0..3)
                .map(|b| UnitQuaternion::from_scaled_axis(w[b] * t) * q0[b])
                .collect(),
            w: w.to_vec(),
        };
        let planes: Vec<Plane> = Vec::new();
        let h = 1e-4;
        let mut checked = 0;
        for (a, feature) in [(0, 0), (0, 3), (0, 5), (2, 0)] {
            for face in 0..6 {
                let touch = Touch::Face {
                    a,
                    feature,
                    b: 1,
                    face,
                };
                let g0 = gap(&touch, &members, &planes, &at(0.0));
                if !g0.gap.is_finite() {
                    continue;
                }
                let (gp, gm) = (
                    gap(&touch, &members, &planes, &at(h)).gap,
                    gap(&touch, &members, &planes, &at(-h)).gap,
                );
                let rate = (gp - gm) / (2.0 * h);
                let second = (gp - 2.0 * g0.gap + gm) / (h * h);
                assert!(
                    (rate - g0.rate).abs() <= 1e-7,
                    "{touch:?}: ġ {rate} ≠ {}",
                    g0.rate
                );
                assert!(
                    (second - g0.curvature).abs() <= 1e-5,
                    "{touch:?}: g̈ {second} ≠ {}",
                    g0.curvature
                );
                // ġ = J u over the sides
                let ju: f64 = g0
                    .sides()
                    .map(|i| i.sign * (g0.normal.dot(&v[i.body]) + i.moment.dot(&w[i.body])))
                    .sum();
                assert!((ju - g0.rate).abs() <= 1e-14, "{touch:?}: J u {ju}");
                checked += 1;
            }
        }
        // each feature is over one face of b (the top, +z)
        assert_eq!(checked, 4);
    }

    /// A corner beside a box, below its top face's plane, is over no face (+∞): the plane of a
    /// face is no obstacle beyond its edges; and at a box's edge the corner belongs to the face
    /// it is nearest.
    #[test]
    fn a_face_is_an_obstacle_over_itself_only() {
        let members = vec![
            cuboid("a", V3::new(0.1, 0.1, 0.1)),
            cuboid("b", V3::new(0.5, 0.5, 0.1)),
        ];
        let state = |xa: V3| SystemState {
            x: vec![xa, V3::zeros()],
            v: vec![V3::zeros(); 2],
            q: vec![UnitQuaternion::identity(); 2],
            w: vec![V3::zeros(); 2],
        };
        let planes: Vec<Plane> = Vec::new();
        // corner [-1, -1, -1] of a is feature 7 (signs +, − in x, y, z order: see Body)
        let lowest = members[0]
            .body
            .features
            .iter()
            .position(|f| f.label() == "corner [-1, -1, -1]")
            .expect("corner");
        let face = |xa: V3, face: usize| {
            gap(
                &Touch::Face {
                    a: 0,
                    feature: lowest,
                    b: 1,
                    face,
                },
                &members,
                &planes,
                &state(xa),
            )
            .gap
        };
        // 0.05 above the top face, over it: the gap
        assert!((face(V3::new(0.0, 0.0, 0.25), 4) - 0.05).abs() < 1e-15);
        // beside the box (its corner at x = 0.6 > 0.5), below the top's plane: no obstacle
        assert_eq!(face(V3::new(0.7, 0.0, 0.15), 4), f64::INFINITY);
        // beside the +x face, within its edges: that face's gap, not the top's
        assert!((face(V3::new(0.65, 0.0, 0.1), 0) - 0.05).abs() < 1e-15);
        assert_eq!(face(V3::new(0.65, 0.0, 0.1), 4), f64::INFINITY);
    }
}
