//! The bodies of a sphere system and their state, in f64, in the world frame.
//!
//! Each body is a sphere (mass m_b, radius r_b) whose centre x_b moves at v_b. Its spin is
//! left out of the state: every contact here is frictionless and passes through the centres, so
//! no force has a moment about any centre and each sphere's angular velocity keeps its initial
//! value for the whole run without touching anything else. The kinetic energy is
//! Σ ½ m_b |v_b|² (the constant spin energy left out) and the potential energy of gravity
//! −Σ m_b g · x_b.

use super::super::body::V3;

/// One sphere.
#[derive(Clone, Debug, PartialEq)]
pub struct Sphere {
    /// Its name in the log (`bead 3`).
    pub name: String,
    /// m > 0.
    pub mass: f64,
    /// r > 0.
    pub radius: f64,
}

/// The state of every sphere: its centre and the velocity of its centre (world).
#[derive(Clone, Debug, PartialEq)]
pub struct SystemState {
    /// x_b.
    pub x: Vec<V3>,
    /// v_b.
    pub v: Vec<V3>,
}

impl SystemState {
    /// The packed y = (x_0, …, x_(B−1), v_0, …, v_(B−1)) the integrator steps.
    pub fn pack(&self) -> Vec<f64> {
        self.x
            .iter()
            .chain(&self.v)
            .flat_map(|p| [p.x, p.y, p.z])
            .collect()
    }

    /// The state of a packed y.
    pub fn unpack(y: &[f64]) -> SystemState {
        let b = y.len() / 6;
        let at = |k: usize| V3::new(y[3 * k], y[3 * k + 1], y[3 * k + 2]);
        SystemState {
            x: (0..b).map(at).collect(),
            v: (b..2 * b).map(at).collect(),
        }
    }

    /// Σ ½ m_b |v_b|².
    pub fn kinetic_energy(&self, spheres: &[Sphere]) -> f64 {
        spheres
            .iter()
            .zip(&self.v)
            .map(|(s, v)| 0.5 * s.mass * v.norm_squared())
            .sum()
    }

    /// −Σ m_b g · x_b.
    pub fn potential_energy(&self, spheres: &[Sphere], gravity: &V3) -> f64 {
        spheres
            .iter()
            .zip(&self.x)
            .map(|(s, x)| -s.mass * gravity.dot(x))
            .sum()
    }
}
