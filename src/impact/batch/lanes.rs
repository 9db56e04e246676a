//! `Lanes<L>`: L independent f64 values operated on together, one scene per lane.
//!
//! Each operation is a loop over a fixed-size array, which the compiler turns into vector
//! instructions (two f64 per SSE2 register on the default x86-64 target, four with AVX). It
//! implements [`crate::scalar::Field`], so the lean solve's field-generic arithmetic
//! ([`crate::impact::lean`]) runs on it unchanged: lane i performs exactly the f64 operations,
//! in exactly the order, that the single-scene solve performs on scene i — the results agree
//! bit for bit (IEEE 754 operations are correctly rounded lane by lane; Rust contracts no
//! `a * b + c` into a fused multiply-add). Hand-written rather than a SIMD crate: the portable
//! `std::simd` is unstable, and the measured loops already vectorise.

use std::ops::{Add, AddAssign, Div, DivAssign, Mul, MulAssign, Neg, Sub, SubAssign};

use num_traits::{One, Zero};

/// L f64 lanes (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lanes<const L: usize>(pub [f64; L]);

impl<const L: usize> Lanes<L> {
    /// Every lane `x`.
    #[inline(always)]
    pub fn splat(x: f64) -> Self {
        Lanes([x; L])
    }
}

macro_rules! lanewise {
    ($op:ident, $f:ident, $assign:ident, $fa:ident, $sym:tt) => {
        impl<const L: usize> $op for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: Self) -> Self {
                Lanes(std::array::from_fn(|i| self.0[i] $sym o.0[i]))
            }
        }
        impl<'a, const L: usize> $op<&'a Lanes<L>> for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, o: &'a Self) -> Self {
                self.$f(*o)
            }
        }
        impl<const L: usize> $assign for Lanes<L> {
            #[inline(always)]
            fn $fa(&mut self, o: Self) {
                *self = (*self).$f(o);
            }
        }
        impl<'a, const L: usize> $assign<&'a Lanes<L>> for Lanes<L> {
            #[inline(always)]
            fn $fa(&mut self, o: &'a Self) {
                *self = (*self).$f(*o);
            }
        }
    };
}

lanewise!(Add, add, AddAssign, add_assign, +);
lanewise!(Sub, sub, SubAssign, sub_assign, -);
lanewise!(Mul, mul, MulAssign, mul_assign, *);
lanewise!(Div, div, DivAssign, div_assign, /);

impl<const L: usize> Neg for Lanes<L> {
    type Output = Self;
    #[inline(always)]
    fn neg(mut self) -> Self {
        for a in &mut self.0 {
            *a = -*a;
        }
        self
    }
}

impl<const L: usize> Zero for Lanes<L> {
    #[inline(always)]
    fn zero() -> Self {
        Lanes::splat(0.0)
    }
    fn is_zero(&self) -> bool {
        self.0.iter().all(|x| *x == 0.0)
    }
}

impl<const L: usize> One for Lanes<L> {
    #[inline(always)]
    fn one() -> Self {
        Lanes::splat(1.0)
    }
}
