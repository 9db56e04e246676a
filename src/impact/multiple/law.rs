//! The LZB contact law's parameters, per contact (Liu, Zhao & Brogliato 2008, §2; Siconos
//! `MultipleImpactNSL(e, K, η)`): a stiffness K_i, a compliance exponent η_i and Stronge's
//! energetic coefficient of restitution e_i.
//!
//! The contact's force–indentation relation is F = K δ^η (η = 1 linear, η = 3/2 Hertz), with
//! potential energy E = K δ^(η+1)/(η+1), so that the force is a function of the energy alone
//! (LZB 2008, §2; the equation numbers of the papers were not checked here):
//!
//! ```text
//! F = K^(1/(η+1)) ((η+1) E)^(η/(η+1))
//! ```
//!
//! The integration ([`super::lzb`]) carries u = E^(1/(η+1)) instead of E, in which the force
//! reads F = (η+1) c u^η with c = (K/(η+1))^(1/(η+1)), and u = c δ during compression.

use crate::scalar::Real;

/// Why a contact's LZB parameters were refused.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LawError {
    /// K ≤ 0 or not finite.
    #[error("the stiffness K must be a finite number > 0 (got {value})")]
    Stiffness {
        /// The value given.
        value: f64,
    },
    /// η ≤ 0 or not finite.
    #[error(
        "the compliance exponent η must be a finite number > 0 (1 linear, 3/2 Hertz; got {value})"
    )]
    Exponent {
        /// The value given.
        value: f64,
    },
    /// e outside [0, 1].
    #[error("the energetic coefficient of restitution e must lie in [0, 1] (got {value})")]
    Restitution {
        /// The value given.
        value: f64,
    },
}

/// One contact's LZB law: F = K δ^η while loaded, the energy released in expansion e² times the
/// energy stored in compression.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactLaw {
    /// K_i > 0; only the ratios K_i/K_j change the outcome (the absolute value sets the
    /// duration of the impact, not its result).
    pub stiffness: f64,
    /// η_i > 0: 1 linear, 3/2 Hertz.
    pub exponent: f64,
    /// Stronge's energetic coefficient e_i ∈ [0, 1].
    pub restitution: f64,
}

impl Default for ContactLaw {
    /// K = 1, η = 3/2 (Hertz), e = 1.
    fn default() -> Self {
        ContactLaw {
            stiffness: 1.0,
            exponent: 1.5,
            restitution: 1.0,
        }
    }
}

impl ContactLaw {
    /// A checked law.
    ///
    /// # Errors
    /// [`LawError`] for K ≤ 0, η ≤ 0, e ∉ [0, 1] or a number that is not finite.
    pub fn new(stiffness: f64, exponent: f64, restitution: f64) -> Result<Self, LawError> {
        let law = ContactLaw {
            stiffness,
            exponent,
            restitution,
        };
        law.validate()?;
        Ok(law)
    }

    /// Whether the parameters have a meaning (as [`ContactLaw::new`]).
    ///
    /// # Errors
    /// As [`ContactLaw::new`].
    pub fn validate(&self) -> Result<(), LawError> {
        if !(self.stiffness.is_finite() && self.stiffness > 0.0) {
            return Err(LawError::Stiffness {
                value: self.stiffness,
            });
        }
        if !(self.exponent.is_finite() && self.exponent > 0.0) {
            return Err(LawError::Exponent {
                value: self.exponent,
            });
        }
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(LawError::Restitution {
                value: self.restitution,
            });
        }
        Ok(())
    }

    /// F(E) = K^(1/(η+1)) ((η+1) E)^(η/(η+1)) (LZB 2008, §2), for E ≥ 0.
    pub fn force(&self, energy: f64) -> f64 {
        let m = self.exponent + 1.0;
        self.stiffness.powf(1.0 / m) * (m * energy.max(0.0)).powf(self.exponent / m)
    }

    /// c = (K/(η+1))^(1/(η+1)): u = E^(1/(η+1)) = c δ during compression. In the
    /// integration's type `T`, from the parameters' exact `f64` values (η + 1 and its inverse
    /// are formed in `T`, not rounded to `f64`).
    pub(crate) fn c<T: Real>(&self) -> T {
        let m = T::of(self.exponent) + T::one();
        (T::of(self.stiffness) / m).powf(T::one() / m)
    }

    /// F as a function of u = E^(1/(η+1)): (η+1) c u^η (zero for u ≤ 0).
    pub(crate) fn force_of_u<T: Real>(&self, c: T, u: T) -> T {
        if u.signum_i8() <= 0 {
            T::zero()
        } else {
            (T::of(self.exponent) + T::one()) * c * u.powf(T::of(self.exponent))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// F(E) written through u agrees with F = K δ^η at E = K δ^(η+1)/(η+1).
    #[test]
    fn force_through_energy_is_k_delta_to_the_eta() {
        for (k, eta) in [(1.0, 1.0), (3.0, 1.5), (0.2, 2.0)] {
            let law = ContactLaw::new(k, eta, 0.5).expect("valid");
            let delta: f64 = 0.37;
            let e = k * delta.powf(eta + 1.0) / (eta + 1.0);
            let f = k * delta.powf(eta);
            assert!((law.force(e) - f).abs() <= 4.0 * f64::EPSILON * f);
            let c: f64 = law.c();
            let u = e.powf(1.0 / (eta + 1.0));
            assert!((u - c * delta).abs() <= 4.0 * f64::EPSILON * u);
            assert!((law.force_of_u(c, u) - f).abs() <= 8.0 * f64::EPSILON * f);
        }
    }

    #[test]
    fn meaningless_parameters_are_refused() {
        assert_eq!(
            ContactLaw::new(0.0, 1.5, 1.0),
            Err(LawError::Stiffness { value: 0.0 })
        );
        assert_eq!(
            ContactLaw::new(1.0, f64::NAN, 1.0).map_err(|e| e.to_string().contains("exponent")),
            Err(true)
        );
        assert_eq!(
            ContactLaw::new(1.0, 1.5, 1.5),
            Err(LawError::Restitution { value: 1.5 })
        );
    }
}
