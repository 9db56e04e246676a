//! Choosing the modes at an event, jointly over every contact whose slip is zero.
//!
//! Each such contact may stick, or (in the plane) slide in either sense. An assignment is
//! *consistent* when its rates exist ([`super::rates`]) and
//!
//! ```text
//! stick:      p'_i ≥ 0 and |τ'_i| ≤ μ_i p'_i      (the required rate lies in the cone)
//! slide ±:    ± v'_it > 0                          (the slip grows in the sense assumed)
//! ```
//!
//! Every assignment is tried (3^m for m contacts at zero slip); the first consistent one in the
//! order stick, slide+, slide− per contact is taken, and the number of consistent ones is
//! reported, so that "none" and "several" are verdicts rather than silent choices.

use crate::impact::friction::blocks::Blocks;
use crate::impact::friction::rates::{Mode, Normal, RateFailure, Rates, max_abs, rates};
use crate::mechanics::screw::Screws;
use crate::scalar::Scalar;

/// The modes chosen at an event.
#[derive(Clone, Debug, PartialEq)]
pub struct Resolution<T: Scalar> {
    /// The modes of every contact.
    pub modes: Vec<Mode<T>>,
    /// Their rates.
    pub rates: Rates<T>,
    /// How many assignments were consistent (1: the modes are determined).
    pub consistent: usize,
}

/// No assignment was consistent; `undetermined` when some had undetermined rates.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct NoConsistentModes {
    /// Some assignment had a family of rates that moves the body differently.
    pub undetermined: bool,
}

/// The most contacts at zero slip resolved jointly (3^m assignments).
pub const MAX_CANDIDATES: usize = 8;

/// `x ≥ 0`, to rounding relative to `scale` in floats.
pub(super) fn nonnegative<T: Scalar>(x: &T, scale: &T, n: usize) -> bool {
    x.signum_i8() >= 0 || x.is_negligible(scale, n)
}

/// `x > 0`, beyond rounding relative to `scale` in floats.
pub(super) fn positive<T: Scalar>(x: &T, scale: &T, n: usize) -> bool {
    x.signum_i8() > 0 && !x.is_negligible(scale, n)
}

/// Resolve the planar modes of the `candidates` (contacts at zero slip), the others keeping
/// theirs in `current`.
///
/// # Errors
/// [`NoConsistentModes`] when no assignment is consistent.
pub fn resolve_planar<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    normals: &[Normal<T>],
    current: &[Mode<T>],
    candidates: &[usize],
) -> Result<Resolution<T>, NoConsistentModes> {
    let choices = [
        Mode::Stick,
        Mode::Slide(vec![T::one()]),
        Mode::Slide(vec![-T::one()]),
    ];
    let m = candidates.len();
    let total = 3usize.pow(m as u32);
    let mut first: Option<(Vec<Mode<T>>, Rates<T>)> = None;
    let mut consistent = 0;
    let mut undetermined = false;
    let mut modes = current.to_vec();
    for code in 0..total {
        let mut c = code;
        for &i in candidates.iter().rev() {
            modes[i] = choices[c % 3].clone();
            c /= 3;
        }
        match rates(b, normals, &modes) {
            Ok(r) => {
                if planar_consistent(b, &modes, &r, candidates) {
                    consistent += 1;
                    if first.is_none() {
                        first = Some((modes.clone(), r));
                    }
                }
            }
            Err(RateFailure::Undetermined) => undetermined = true,
            Err(RateFailure::Inconsistent) => {}
        }
    }
    match first {
        Some((modes, rates)) => Ok(Resolution {
            modes,
            rates,
            consistent,
        }),
        None => Err(NoConsistentModes { undetermined }),
    }
}

/// The tests of the module docs for the candidates.
fn planar_consistent<T: Scalar, S: Screws<T>>(
    b: &Blocks<T, S>,
    modes: &[Mode<T>],
    r: &Rates<T>,
    candidates: &[usize],
) -> bool {
    let n = b.len();
    let scale_l = max_abs(&r.lambda);
    let scale_v = max_abs(&r.velocity);
    candidates.iter().all(|&i| {
        let off = b.offset[i];
        match &modes[i] {
            Mode::Stick => {
                let p = &r.lambda[off];
                let bound = b.mu[i].clone() * p;
                let t = &r.lambda[off + 1];
                let t_abs = if t.signum_i8() < 0 {
                    -t.clone()
                } else {
                    t.clone()
                };
                nonnegative(p, &scale_l, n) && nonnegative(&(bound - t_abs), &scale_l, n)
            }
            Mode::Slide(u) => positive(&(u[0].clone() * &r.velocity[off + 1]), &scale_v, n),
            Mode::Free => true,
        }
    })
}
