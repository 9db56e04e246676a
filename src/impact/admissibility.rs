//! Is a simultaneous answer physical? The paper's hypothesis — every contact approaching,
//! taking a compressive impulse and meeting its law at once — can fail while its linear
//! system still has a unique solution. This module reads the verdicts off a solved outcome, so
//! that no inadmissible number is reported without saying so (the unilateral law of
//! [`crate::impact::unilateral`] is then the physical answer).
//!
//! | verdict | test (hatted; the signs are those of the physical values) |
//! |---|---|
//! | tensile | P_i < 0: the obstacle would have to pull |
//! | separating | v_ix⁰ < 0: a law imposed on a contact that was moving away |
//! | still approaching | v_ix > 0 after impact (Poisson with unequal k_i and some g_ij < 0) |
//! | energy gain | ΔE_c < 0: kinetic energy created by the impact |
//!
//! Exact types decide each sign exactly. In floats a value counts only beyond the rounding
//! error of the solve: 16·N·ε times its scale (the largest impulse, the largest normal velocity,
//! T⁰), the bound the energy identity is checked to.

use crate::impact::mechanism::Mechanism;
use crate::impact::restitution::Model;
use crate::impact::solve::{Impact, Outcome};
use crate::scalar::Scalar;

/// Why a simultaneous answer is not physical.
#[derive(Clone, Debug, PartialEq)]
pub enum Inadmissible {
    /// P_i < 0 at this contact (0-based).
    Tensile {
        /// The contact.
        contact: usize,
    },
    /// v_ix⁰ < 0: the contact was separating, yet the law was imposed on it.
    Separating {
        /// The contact.
        contact: usize,
    },
    /// v_ix > 0 after impact: the contact would still be approaching.
    StillApproaching {
        /// The contact.
        contact: usize,
    },
    /// ΔE_c < 0.
    EnergyGain,
}

impl Inadmissible {
    /// The short name used in sweep statuses and JSON (`tensile`, `separating`,
    /// `still-approaching`, `energy-gain`).
    pub fn name(&self) -> &'static str {
        match self {
            Inadmissible::Tensile { .. } => "tensile",
            Inadmissible::Separating { .. } => "separating",
            Inadmissible::StillApproaching { .. } => "still-approaching",
            Inadmissible::EnergyGain => "energy-gain",
        }
    }

    /// The contact concerned, if any (0-based).
    pub fn contact(&self) -> Option<usize> {
        match self {
            Inadmissible::Tensile { contact }
            | Inadmissible::Separating { contact }
            | Inadmissible::StillApproaching { contact } => Some(*contact),
            Inadmissible::EnergyGain => None,
        }
    }
}

impl std::fmt::Display for Inadmissible {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Inadmissible::Tensile { contact } => write!(
                f,
                "contact {} takes a tensile impulse (P{} < 0): the obstacle would have to pull",
                contact + 1,
                contact + 1
            ),
            Inadmissible::Separating { contact } => write!(
                f,
                "contact {} was separating before impact (v{}x⁰ < 0), yet the law is imposed on it",
                contact + 1,
                contact + 1
            ),
            Inadmissible::StillApproaching { contact } => write!(
                f,
                "contact {} is still approaching after impact (v{}x > 0)",
                contact + 1,
                contact + 1
            ),
            Inadmissible::EnergyGain => {
                write!(f, "the impact creates kinetic energy (ΔE_c < 0)")
            }
        }
    }
}

/// ΔE_c < 0 beyond rounding: the one verdict that also applies to a unilateral outcome
/// (complementarity holds there by construction, but Moreau's Newton law can create energy
/// when a contact that was not approaching takes an impulse: see `crate::impact::unilateral`).
pub fn energy_gain<T: Scalar, M: Mechanism<T>>(
    impact: &Impact<T, M>,
    out: &Outcome<T, M::Screw>,
) -> Option<Inadmissible> {
    let scale = impact.kinetic_before().clone() + &out.lost_velocity_energy;
    let x = &out.kinetic_energy_loss;
    (x.signum_i8() < 0 && !x.is_negligible(&scale, 16 * impact.contacts().max(1)))
        .then_some(Inadmissible::EnergyGain)
}

/// The verdicts on the simultaneous `out` of `model` solved on `impact`; empty when it is
/// admissible.
pub fn verdicts<T: Scalar, M: Mechanism<T>>(
    impact: &Impact<T, M>,
    model: Model,
    out: &Outcome<T, M::Screw>,
) -> Vec<Inadmissible> {
    let n = impact.contacts();
    let tol = 16 * n.max(1);
    let largest = |xs: &mut dyn Iterator<Item = &T>| {
        xs.fold(T::zero(), |m, x| if x.abs_gt(&m) { x.clone() } else { m })
    };
    let impulse_scale = largest(&mut out.impulses_hat.iter());
    let speed_scale = largest(
        &mut impact
            .before_hat()
            .iter()
            .chain(&out.after_hat)
            .map(|v| &v[0]),
    );
    let negative = |x: &T, scale: &T| x.signum_i8() < 0 && !x.is_negligible(scale, tol);
    let mut found = Vec::new();
    for i in 0..n {
        if negative(&impact.before_hat()[i][0], &speed_scale) {
            found.push(Inadmissible::Separating { contact: i });
        }
    }
    for (i, p) in out.impulses_hat.iter().enumerate() {
        if negative(p, &impulse_scale) {
            found.push(Inadmissible::Tensile { contact: i });
        }
    }
    if model == Model::Poisson {
        for (i, v) in out.after_hat.iter().enumerate() {
            if negative(&-v[0].clone(), &speed_scale) {
                found.push(Inadmissible::StillApproaching { contact: i });
            }
        }
    }
    found.extend(energy_gain(impact, out));
    found
}
