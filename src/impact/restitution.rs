//! The restitution laws: Newton (eq. 14–15, 20) and Poisson (eq. 21–23).
//!
//! Both close the impulse–velocity relation of eq. (13), v_ix − v_ix⁰ = −Σ_j g_ij P_j, with
//! one equation per contact, and both lead to a linear system in the inertance matrix G:
//!
//! * **Newton**: v_ix = −k_i^N v_ix⁰, so G P = b with b_i = (1 + k_i^N) v_ix⁰ (eq. 15).
//! * **Poisson**: the compression impulses bring every normal velocity to zero,
//!   G P^c = v⁰_x (eq. 21), and the total impulse is P_i = (1 + k_i^P) P_i^c (eq. 23).
//!
//! The two coincide when every k_i is equal, or when G is diagonal (eq. 50–55).

use std::fmt;

/// A restitution model.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Model {
    /// Newton's kinematic law, v_ix = −k_i^N v_ix⁰ (eq. 14).
    Newton,
    /// Poisson's kinetic law, P_i = (1 + k_i^P) P_i^c (eq. 23).
    Poisson,
}

impl Model {
    /// Both models, in report order.
    pub const ALL: [Model; 2] = [Model::Newton, Model::Poisson];

    /// The lower-case name used in scenes and reports.
    pub fn name(self) -> &'static str {
        match self {
            Model::Newton => "newton",
            Model::Poisson => "poisson",
        }
    }

    /// The model called `name` (`"newton"` or `"poisson"`).
    pub fn from_name(name: &str) -> Option<Model> {
        match name {
            "newton" => Some(Model::Newton),
            "poisson" => Some(Model::Poisson),
            _ => None,
        }
    }
}

impl fmt::Display for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
