//! The bodies of a system and their state, in f64, in the world frame.
//!
//! Each member is a rigid body of the single body's kind ([`crate::simulate::body::Body`]: its
//! mass, central inertia J in body axes, shape and features) — a sphere, a box or a thin rod
//! here (a rod's J completed about its axis, as the single body's: no contact of a thin rod
//! has a moment about it). Its state
//! is the single body's: the centre x_b, the attitude q_b (body → world), the velocity v_b of
//! the centre and the angular velocity ω_b (world). A sphere whose contacts are all frictionless
//! carries its attitude and spin but does not integrate them: its contacts pass through its
//! centre, so no force has a moment about it, its spin keeps its initial value for the whole
//! run, and nothing else sees its attitude. A sphere that a rough contact can touch
//! ([`Member::spins`]) turns as a box does (J = ⅖ m r² I: friction at its surface spins it, and
//! its spin makes it slip or roll). The kinetic energy is Σ ½ m_b |v_b|² + ½ ω_bᵀ R_b J_b R_bᵀ
//! ω_b (the constant spin energy of a sphere that does not turn left out) and the potential
//! energy of gravity −Σ m_b g · x_b.

use nalgebra::{Matrix3, Quaternion, UnitQuaternion};

use super::super::body::{Body, Shape, V3};

/// One body of the system.
#[derive(Clone, Debug, PartialEq)]
pub struct Member {
    /// Its name in the log (`bead 3`, `top`).
    pub name: String,
    /// Its mass properties, shape and features.
    pub body: Body,
    /// For a sphere: whether its spin is integrated (a contact with μ > 0 can touch it; module
    /// docs). Every other shape turns whatever this says.
    pub spins: bool,
}

impl Member {
    /// A sphere's radius (`None` for another shape).
    pub fn radius(&self) -> Option<f64> {
        match self.body.shape {
            Shape::Sphere { radius } => Some(radius),
            _ => None,
        }
    }

    /// Whether its attitude and spin are integrated (every shape but a sphere that no rough
    /// contact touches: module docs).
    pub fn turns(&self) -> bool {
        self.spins || self.radius().is_none()
    }

    /// m.
    pub fn mass(&self) -> f64 {
        self.body.mass
    }
}

/// The state of every member (world).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemState {
    /// x_b.
    pub x: Vec<V3>,
    /// v_b.
    pub v: Vec<V3>,
    /// q_b: body → world.
    pub q: Vec<UnitQuaternion<f64>>,
    /// ω_b.
    pub w: Vec<V3>,
}

impl SystemState {
    /// The packed y = (x_0, …, x_(B−1), v_0, …, v_(B−1), q_0, …, q_(B−1), ω_0, …, ω_(B−1))
    /// the integrator steps (each q as (w, i, j, k)).
    pub fn pack(&self) -> Vec<f64> {
        let mut y: Vec<f64> = self
            .x
            .iter()
            .chain(&self.v)
            .flat_map(|p| [p.x, p.y, p.z])
            .collect();
        for q in &self.q {
            let q = q.quaternion();
            y.extend([q.w, q.i, q.j, q.k]);
        }
        y.extend(self.w.iter().flat_map(|p| [p.x, p.y, p.z]));
        y
    }

    /// The state of a packed y, each quaternion normalised.
    pub fn unpack(y: &[f64]) -> SystemState {
        let b = y.len() / 13;
        let at = |k: usize| V3::new(y[3 * k], y[3 * k + 1], y[3 * k + 2]);
        let q0 = 6 * b;
        let w0 = 10 * b;
        SystemState {
            x: (0..b).map(at).collect(),
            v: (b..2 * b).map(at).collect(),
            q: (0..b)
                .map(|i| {
                    let k = q0 + 4 * i;
                    UnitQuaternion::from_quaternion(Quaternion::new(
                        y[k],
                        y[k + 1],
                        y[k + 2],
                        y[k + 3],
                    ))
                })
                .collect(),
            w: (0..b)
                .map(|i| V3::new(y[w0 + 3 * i], y[w0 + 3 * i + 1], y[w0 + 3 * i + 2]))
                .collect(),
        }
    }

    /// R_b.
    pub fn rotation(&self, b: usize) -> Matrix3<f64> {
        self.q[b].to_rotation_matrix().into_inner()
    }

    /// The kinetic energy of member `b`: ½ m |v|², plus ½ ωᵀ R J Rᵀ ω for a body that turns.
    pub fn kinetic_energy_of(&self, members: &[Member], b: usize) -> f64 {
        let m = &members[b];
        let linear = 0.5 * m.mass() * self.v[b].norm_squared();
        if m.turns() {
            let r = self.rotation(b);
            linear + 0.5 * self.w[b].dot(&(m.body.world_inertia(&r) * self.w[b]))
        } else {
            linear
        }
    }

    /// Σ ½ m_b |v_b|² + ½ ω_bᵀ R_b J_b R_bᵀ ω_b (module docs).
    pub fn kinetic_energy(&self, members: &[Member]) -> f64 {
        (0..members.len())
            .map(|b| self.kinetic_energy_of(members, b))
            .sum()
    }

    /// −Σ m_b g · x_b.
    pub fn potential_energy(&self, members: &[Member], gravity: &V3) -> f64 {
        members
            .iter()
            .zip(&self.x)
            .map(|(s, x)| -s.mass() * gravity.dot(x))
            .sum()
    }
}
