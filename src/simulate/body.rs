//! The body that moves between impacts: its mass properties, its shape's features (the points
//! that can strike an obstacle) and its state — in f64, in the world frame.
//!
//! The state is (x, q, v, ω): the centre of mass C (world), the attitude as a unit quaternion
//! q (body → world, R = R(q)), the velocity of C and the angular velocity, both in the world.
//! A body point a (body axes, from C) is at x + R a and moves at v + ω × R a. The kinetic
//! energy is ½ m |v|² + ½ ωᵀ (R J Rᵀ) ω and the potential energy of gravity −m g · x.

use nalgebra::{Matrix3, Quaternion, UnitQuaternion, Vector3};

/// A vector in f64.
pub type V3 = Vector3<f64>;

/// The shape of the body, centred on C with its edges (or axis) along the body axes: what
/// its features are.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape {
    /// A sphere of this radius: its feature is the point of it nearest each plane.
    Sphere {
        /// r.
        radius: f64,
    },
    /// A box with these half edges (a/2, b/2, c/2): its eight corners.
    Box {
        /// The half edges.
        half: V3,
    },
    /// A thin rod of this half length along body z: its two ends.
    Rod {
        /// L/2.
        half_length: f64,
    },
    /// A solid cylinder of this radius and half height about body z: its two rims, and on
    /// each rim four body points 90° apart (which stand for the face when it lies flat), each
    /// rim's points before it.
    Cylinder {
        /// r.
        radius: f64,
        /// h/2.
        half_height: f64,
    },
}

/// What can strike an obstacle plane.
#[derive(Clone, Debug, PartialEq)]
pub enum Feature {
    /// A body point (body axes, from C), named as a scene names it (`corner [1, 1, -1]`).
    Point {
        /// a.
        at: V3,
        /// Its name in the log.
        label: String,
    },
    /// A sphere about C: the point of it nearest a plane with normal N is x − r N.
    Sphere {
        /// r.
        radius: f64,
    },
    /// A circle of the body (a cylinder's rim): its point nearest a plane
    /// ([`super::world::gap`]).
    Rim {
        /// Its centre c (body axes, from C).
        centre: V3,
        /// Its axis a (body axes, unit).
        axis: V3,
        /// ρ.
        radius: f64,
        /// Its name in the log (`rim [0, 0, 1]`).
        label: String,
    },
}

impl Feature {
    /// Its name in the log.
    pub fn label(&self) -> &str {
        match self {
            Feature::Point { label, .. } | Feature::Rim { label, .. } => label,
            Feature::Sphere { .. } => "sphere",
        }
    }
}

/// The body's mass properties and shape.
#[derive(Clone, Debug, PartialEq)]
pub struct Body {
    /// m > 0.
    pub mass: f64,
    /// J_C in body axes.
    pub inertia: Matrix3<f64>,
    /// J_C⁻¹.
    pub inverse: Matrix3<f64>,
    /// The shape.
    pub shape: Shape,
    /// The features, in the order the log numbers them.
    pub features: Vec<Feature>,
}

impl Body {
    /// A body of mass `mass` and central inertia `inertia` (body axes, symmetric positive
    /// definite), of shape `shape`; `plane`: the unit normal (body axes) of the plane of a planar
    /// motion, to which a box's corners are reduced (each edge perpendicular to it, by the
    /// midpoint of the edge: the planar model of a block, `[simulate] plane`). `None` when J is
    /// not invertible.
    pub fn new(mass: f64, inertia: Matrix3<f64>, shape: Shape, plane: Option<V3>) -> Option<Body> {
        let inverse = inertia.try_inverse()?;
        let features = features(&shape, plane.as_ref());
        Some(Body {
            mass,
            inertia,
            inverse,
            shape,
            features,
        })
    }

    /// R J Rᵀ.
    pub fn world_inertia(&self, r: &Matrix3<f64>) -> Matrix3<f64> {
        r * self.inertia * r.transpose()
    }

    /// R J⁻¹ Rᵀ.
    pub fn world_inverse(&self, r: &Matrix3<f64>) -> Matrix3<f64> {
        r * self.inverse * r.transpose()
    }

    /// The largest distance of a feature's point from C (the sphere's radius).
    pub fn reach(&self) -> f64 {
        self.features
            .iter()
            .map(|f| match f {
                Feature::Point { at, .. } => at.norm(),
                Feature::Sphere { radius } => *radius,
                Feature::Rim { centre, radius, .. } => centre.norm().hypot(*radius),
            })
            .fold(0.0, f64::max)
    }

    /// ½ m |v|² + ½ ωᵀ R J Rᵀ ω.
    pub fn kinetic_energy(&self, s: &State) -> f64 {
        let r = s.rotation();
        0.5 * self.mass * s.v.norm_squared() + 0.5 * s.w.dot(&(self.world_inertia(&r) * s.w))
    }
}

/// The features of a shape; a box's corners reduced to the plane of motion when `plane` is
/// given (the sign of the coordinate along the plane's normal set to 0).
fn features(shape: &Shape, plane: Option<&V3>) -> Vec<Feature> {
    match shape {
        Shape::Sphere { radius } => vec![Feature::Sphere { radius: *radius }],
        Shape::Rod { half_length } => [1.0, -1.0]
            .iter()
            .map(|&s| Feature::Point {
                at: V3::new(0.0, 0.0, s * half_length),
                label: format!("end [0, 0, {}]", s as i64),
            })
            .collect(),
        Shape::Cylinder {
            radius,
            half_height,
        } => {
            let mut out = Vec::new();
            for sz in [1i64, -1] {
                let centre = V3::new(0.0, 0.0, sz as f64 * half_height);
                for (deg, (cx, cy)) in [
                    (0, (1.0, 0.0)),
                    (90, (0.0, 1.0)),
                    (180, (-1.0, 0.0)),
                    (270, (0.0, -1.0)),
                ] {
                    out.push(Feature::Point {
                        at: centre + V3::new(cx, cy, 0.0) * *radius,
                        label: format!("rim [0, 0, {sz}] at {deg}°"),
                    });
                }
                // after its body points: a rim nearest at one of them is that point's contact
                // (the first feature at a point is the contact), and a landing face its four
                out.push(Feature::Rim {
                    centre,
                    axis: V3::z(),
                    radius: *radius,
                    label: format!("rim [0, 0, {sz}]"),
                });
            }
            out
        }
        Shape::Box { half } => {
            let mut out: Vec<Feature> = Vec::new();
            for sx in [1i64, -1] {
                for sy in [1i64, -1] {
                    for sz in [1i64, -1] {
                        let mut s = [sx, sy, sz];
                        if let Some(n) = plane {
                            // the axis along the plane's normal: its sign is dropped
                            let k = (0..3)
                                .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
                                .unwrap_or(2);
                            s[k] = 0;
                        }
                        let at = V3::new(
                            s[0] as f64 * half.x,
                            s[1] as f64 * half.y,
                            s[2] as f64 * half.z,
                        );
                        let label = if s.contains(&0) {
                            format!("edge [{}, {}, {}]", s[0], s[1], s[2])
                        } else {
                            format!("corner [{}, {}, {}]", s[0], s[1], s[2])
                        };
                        if !out.iter().any(|f| f.label() == label) {
                            out.push(Feature::Point { at, label });
                        }
                    }
                }
            }
            out
        }
    }
}

/// The body's state: C, the attitude, the velocity of C and the angular velocity (world).
#[derive(Clone, Debug, PartialEq)]
pub struct State {
    /// x: the centre of mass (world).
    pub x: V3,
    /// q: body → world.
    pub q: UnitQuaternion<f64>,
    /// v: the velocity of C (world).
    pub v: V3,
    /// ω (world).
    pub w: V3,
}

/// q̇ = ½ (0, ω) ⊗ q as (w, i, j, k): the attitude's rate at the angular velocity ω (world).
pub fn quaternion_rate(q: &UnitQuaternion<f64>, w: &V3) -> [f64; 4] {
    let q = q.quaternion();
    [
        -0.5 * (w.x * q.i + w.y * q.j + w.z * q.k),
        0.5 * (w.x * q.w + w.y * q.k - w.z * q.j),
        0.5 * (-w.x * q.k + w.y * q.w + w.z * q.i),
        0.5 * (w.x * q.j - w.y * q.i + w.z * q.w),
    ]
}

impl State {
    /// R(q).
    pub fn rotation(&self) -> Matrix3<f64> {
        self.q.to_rotation_matrix().into_inner()
    }

    /// The packed state y = (x, q_w, q_i, q_j, q_k, v, ω) the integrator steps.
    pub fn pack(&self) -> [f64; 13] {
        let q = self.q.quaternion();
        [
            self.x.x, self.x.y, self.x.z, q.w, q.i, q.j, q.k, self.v.x, self.v.y, self.v.z,
            self.w.x, self.w.y, self.w.z,
        ]
    }

    /// The state of a packed y, its quaternion normalised.
    pub fn unpack(y: &[f64; 13]) -> State {
        State {
            x: V3::new(y[0], y[1], y[2]),
            q: UnitQuaternion::from_quaternion(Quaternion::new(y[3], y[4], y[5], y[6])),
            v: V3::new(y[7], y[8], y[9]),
            w: V3::new(y[10], y[11], y[12]),
        }
    }
}
