//! `Lanes<L>`: L independent f64 values operated on together, one scene per lane.
//!
//! Each operation is a loop over a fixed-size array, which the compiler turns into vector
//! instructions: one per operation when L f64 fill a register of the instruction set the code
//! is compiled for ([`super`] runs it compiled for AVX-512 or AVX2 when the CPU has them). It
//! implements [`crate::scalar::Field`], so the lean solve's field-generic arithmetic
//! ([`crate::impact::lean`]) runs on it unchanged: lane i performs exactly the f64 operations,
//! in exactly the order, that the single-scene solve performs on scene i — the results agree
//! bit for bit (IEEE 754 operations are correctly rounded lane by lane; Rust contracts no
//! `a * b + c` into a fused multiply-add). A plain array rather than a SIMD crate's vector
//! type: the `Field` bounds (`Zero::zero()`, operators without an instruction-set token) need
//! a type that exists outside the dispatched function, and these loops vectorise inside it.

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
    ($op:ident, $f:ident, $assign:ident, $fa:ident) => {
        impl<const L: usize> $op for Lanes<L> {
            type Output = Self;
            #[inline(always)]
            fn $f(mut self, o: Self) -> Self {
                // A plain loop on a copy (not `array::from_fn`): the optimiser keeps it in
                // one register.
                for (a, b) in self.0.iter_mut().zip(o.0) {
                    <f64 as $assign>::$fa(a, b);
                }
                self
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

lanewise!(Add, add, AddAssign, add_assign);
lanewise!(Sub, sub, SubAssign, sub_assign);
lanewise!(Mul, mul, MulAssign, mul_assign);
lanewise!(Div, div, DivAssign, div_assign);

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

/// L lane-wise truth values, all bits set for true: the layout of a vector comparison's
/// result, so that tests and their conjunctions stay in vector registers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Mask<const L: usize>(pub [u64; L]);

impl<const L: usize> Mask<L> {
    /// Every lane true.
    #[inline(always)]
    pub fn all_true() -> Self {
        Mask([u64::MAX; L])
    }

    /// Whether every lane is true.
    #[inline(always)]
    pub fn all(&self) -> bool {
        self.0.iter().fold(u64::MAX, |a, m| a & m) == u64::MAX
    }

    /// Lane `l`.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> bool {
        self.0[l] != 0
    }
}

impl<const L: usize> std::ops::BitAnd for Mask<L> {
    type Output = Self;
    #[inline(always)]
    fn bitand(mut self, o: Self) -> Self {
        for (a, b) in self.0.iter_mut().zip(o.0) {
            *a &= b;
        }
        self
    }
}

impl<const L: usize> std::ops::BitAndAssign for Mask<L> {
    #[inline(always)]
    fn bitand_assign(&mut self, o: Self) {
        *self = *self & o;
    }
}

impl<const L: usize> std::ops::BitOr for Mask<L> {
    type Output = Self;
    #[inline(always)]
    fn bitor(mut self, o: Self) -> Self {
        for (a, b) in self.0.iter_mut().zip(o.0) {
            *a |= b;
        }
        self
    }
}

impl<const L: usize> Lanes<L> {
    /// Lane by lane, whether `self` and `o` stand in the relation `f` (IEEE comparisons:
    /// false for NaN).
    #[inline(always)]
    pub fn test(&self, o: &Self, f: impl Fn(f64, f64) -> bool) -> Mask<L> {
        let mut m = [0; L];
        for ((m, a), b) in m.iter_mut().zip(self.0).zip(o.0) {
            *m = if f(a, b) { u64::MAX } else { 0 };
        }
        Mask(m)
    }
}
