//! A symbolic scalar: rational functions of named symbols with exact rational coefficients,
//! so that the *unchanged* solver derives the paper's closed forms and they can be checked as
//! identities (issue 6).
//!
//! * [`Poly`]: multivariate polynomials in named symbols (m, J_x, k_1, …) with `BigRational`
//!   coefficients. Symbols are interned once per process (a name ↦ `u32` id table behind a
//!   lock; display sorts by name, so output does not depend on creation order). Canonical:
//!   terms in a fixed monomial order, no zero coefficient, reduced modulo side relations.
//! * **Side relations** x² = p(other symbols): a square root √n is a product of symbols r_p
//!   (r_p² = p, one per prime, so √6 = r_2·r_3 and √12 = 2·r_3); an angle θ is a pair
//!   (c, s) = (cos θ, sin θ) with s² = 1 − c². The relations' leading monomials are pure
//!   powers of distinct symbols, pairwise coprime, so by Buchberger's first criterion they are
//!   a Gröbner basis and the reduced forms are canonical (see [`poly`]).
//! * [`RatFun`]: the scalar, a numerator over a factored denominator. After every operation
//!   the rational content goes to the numerator, common monomials cancel, and the numerator
//!   is divided by each denominator factor that divides it exactly — which catches the
//!   common factors Gaussian elimination produces, but is no full multivariate gcd.
//!   **Equality and zero tests are exact**: a/b = c/d iff a·d − b·c reduces to the zero
//!   polynomial — never by evaluation at points — so no identity check depends on how far a
//!   result was simplified.
//! * [`crate::scalar::Scalar`] for [`RatFun`]: where the solver branches on a value with free
//!   symbols (a pivot, a sign), the symbolic run records the condition it assumed
//!   ([`Assumption`]: f ≠ 0 for every denominator factor divided by, v > 0 for every sign
//!   taken), collected per thread by [`take_assumptions`]. Constants with radicals are
//!   decided exactly (rigorous rational enclosures), without assumptions.
//!
//! ```
//! use inertance::scalar::symbolic::{RatFun, take_assumptions};
//! let (m, jz, y1) = (RatFun::symbol("m"), RatFun::symbol("Jz"), RatFun::symbol("y1"));
//! // g_11 of eq. (17) with f_11 = −y1.
//! let g11 = RatFun::from_integer(1) / &m + y1.clone() * &y1 / &jz;
//! assert_eq!(g11.to_text(), "(m*y1^2 + Jz)/(Jz*m)");
//! assert_eq!(g11, (jz.clone() + m.clone() * &y1 * &y1) / (m * &jz));
//! let conditions: Vec<String> = take_assumptions().iter().map(|a| a.to_string()).collect();
//! assert_eq!(conditions, ["m ≠ 0", "Jz ≠ 0"]);
//! ```

mod eval;
pub mod factor;
pub mod poly;
mod radical;
pub mod ratfun;
mod symbols;

use std::cell::RefCell;
use std::fmt;

pub use eval::{symbol_names, symbolic};
pub use factor::{Factored, factor};
pub use poly::Poly;
pub use ratfun::RatFun;

/// What an [`Assumption`] asserts about its expression.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum AssumptionKind {
    /// expr ≠ 0 (a division by it).
    NonZero,
    /// expr > 0 (its sign was taken as positive).
    Positive,
}

/// A condition a symbolic run assumed: the derived results hold where every recorded
/// assumption does (e.g. Δ ≠ 0, g_11 > 0).
#[derive(Clone, Debug, PartialEq)]
pub struct Assumption {
    /// The expression the condition is on.
    pub expr: RatFun,
    /// The condition.
    pub kind: AssumptionKind,
}

impl fmt::Display for Assumption {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.kind {
            AssumptionKind::NonZero => {
                // The sign of a nonzero condition is immaterial: show it with a positive
                // leading term.
                let e = if self.expr.numer().display_sign() < 0 {
                    -self.expr.clone()
                } else {
                    self.expr.clone()
                };
                write!(f, "{e} ≠ 0")
            }
            AssumptionKind::Positive => write!(f, "{} > 0", self.expr),
        }
    }
}

thread_local! {
    static LOG: RefCell<Vec<Assumption>> = const { RefCell::new(Vec::new()) };
}

/// The assumptions recorded on this thread since the last call, in order of first
/// occurrence, without duplicates; clears the log.
pub fn take_assumptions() -> Vec<Assumption> {
    LOG.with(|log| std::mem::take(&mut *log.borrow_mut()))
}

/// The assumptions recorded on this thread so far, without clearing them.
pub fn assumptions() -> Vec<Assumption> {
    LOG.with(|log| log.borrow().clone())
}

/// Record `a` unless an identical one (same canonical representation) is already logged.
pub(crate) fn record(a: Assumption) {
    LOG.with(|log| {
        let mut log = log.borrow_mut();
        if !log
            .iter()
            .any(|b| b.kind == a.kind && b.expr.same_repr(&a.expr))
        {
            log.push(a);
        }
    });
}
