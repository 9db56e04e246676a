//! The operators of [`Rational`]: by value and by reference, each dispatching to the word
//! path when both operands are words ([`super::word`]) and to the big path otherwise
//! ([`super::big`]).

use std::borrow::Cow;
use std::iter::{Product, Sum};
use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_bigint::BigInt;
use num_traits::{One, Zero};

use super::{Rational, Repr, big, word};

impl Rational {
    /// Numerator and denominator as big integers (borrowed when stored so).
    fn parts(&self) -> (Cow<'_, BigInt>, Cow<'_, BigInt>) {
        match &self.0 {
            Repr::Word(n, d) => (Cow::Owned(BigInt::from(*n)), Cow::Owned(BigInt::from(*d))),
            Repr::Big(q) => (Cow::Borrowed(q.numer()), Cow::Borrowed(q.denom())),
        }
    }

    /// `f` on the two operands' words, or `g` on their big-integer parts.
    fn binary(
        &self,
        rhs: &Rational,
        f: fn(i64, i64, i64, i64) -> word::Wide,
        g: fn(&BigInt, &BigInt, &BigInt, &BigInt) -> big::Parts,
    ) -> Rational {
        match (&self.0, &rhs.0) {
            (Repr::Word(a, b), Repr::Word(c, d)) => Rational::from_wide(f(*a, *b, *c, *d)),
            _ => {
                let ((a, b), (c, d)) = (self.parts(), rhs.parts());
                let (n, d) = g(&a, &b, &c, &d);
                Rational::from_parts(n, d)
            }
        }
    }

    fn add_ref(&self, rhs: &Rational) -> Rational {
        if rhs.is_zero() {
            return self.clone();
        }
        if self.is_zero() {
            return rhs.clone();
        }
        self.binary(rhs, word::add, big::add)
    }

    fn sub_ref(&self, rhs: &Rational) -> Rational {
        if rhs.is_zero() {
            return self.clone();
        }
        self.binary(rhs, word::sub, |a, b, c, d| big::add(a, b, &-c, d))
    }

    fn mul_ref(&self, rhs: &Rational) -> Rational {
        if self.is_zero() || rhs.is_zero() {
            return Rational::zero();
        }
        self.binary(rhs, word::mul, big::mul)
    }

    /// # Panics
    /// On division by zero, like `BigRational`.
    fn div_ref(&self, rhs: &Rational) -> Rational {
        assert!(!rhs.is_zero(), "division by zero");
        if self.is_zero() {
            return Rational::zero();
        }
        self.binary(rhs, word::div, big::div)
    }
}

impl Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        match self.0 {
            // |n| ≤ 2⁶³ − 1: −n is a word.
            Repr::Word(n, d) => Rational(Repr::Word(-n, d)),
            Repr::Big(q) => Rational(Repr::Big(Box::new(-*q))),
        }
    }
}

impl Neg for &Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        -self.clone()
    }
}

macro_rules! binary_ops {
    ($tr:ident, $method:ident, $tra:ident, $amethod:ident, $op:ident) => {
        impl $tr<&Rational> for &Rational {
            type Output = Rational;
            fn $method(self, rhs: &Rational) -> Rational {
                self.$op(rhs)
            }
        }
        impl $tr<&Rational> for Rational {
            type Output = Rational;
            fn $method(self, rhs: &Rational) -> Rational {
                self.$op(rhs)
            }
        }
        impl $tr<Rational> for &Rational {
            type Output = Rational;
            fn $method(self, rhs: Rational) -> Rational {
                self.$op(&rhs)
            }
        }
        impl $tr for Rational {
            type Output = Rational;
            fn $method(self, rhs: Rational) -> Rational {
                self.$op(&rhs)
            }
        }
        impl $tra<&Rational> for Rational {
            fn $amethod(&mut self, rhs: &Rational) {
                *self = self.$op(rhs);
            }
        }
        impl $tra for Rational {
            fn $amethod(&mut self, rhs: Rational) {
                *self = self.$op(&rhs);
            }
        }
    };
}

binary_ops!(Add, add, AddAssign, add_assign, add_ref);
binary_ops!(Sub, sub, SubAssign, sub_assign, sub_ref);
binary_ops!(Mul, mul, MulAssign, mul_assign, mul_ref);
binary_ops!(Div, div, DivAssign, div_assign, div_ref);

impl Sum for Rational {
    fn sum<I: Iterator<Item = Rational>>(iter: I) -> Rational {
        iter.fold(Rational::zero(), |s, x| s + x)
    }
}

impl<'a> Sum<&'a Rational> for Rational {
    fn sum<I: Iterator<Item = &'a Rational>>(iter: I) -> Rational {
        iter.fold(Rational::zero(), |s, x| s + x)
    }
}

impl Product for Rational {
    fn product<I: Iterator<Item = Rational>>(iter: I) -> Rational {
        iter.fold(Rational::one(), |s, x| s * x)
    }
}
