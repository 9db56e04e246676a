//! Rationals that fit machine words: n/d with |n|, d ≤ 2⁶³ − 1, in lowest terms, d ≥ 1.
//!
//! Every operation takes such fractions and returns its result as an exact **wide** fraction
//! ([`Wide`]: i128 numerator, i128 denominator) in lowest terms, by Henrici's product and sum
//! (stated, with why they are in lowest terms, in the docs of [`super`]); the caller stores it
//! back in words when it fits and promotes it to big integers otherwise. No operation can
//! overflow: a product of two word values has at most 126 bits, a sum of two such products
//! at most 127.

/// An exact fraction n/d in lowest terms with d ≥ 1, in 128-bit integers.
pub(super) type Wide = (i128, i128);

/// gcd(a, b); gcd(0, b) = b. Binary ([`binary_gcd`]) after one remainder when the sizes are
/// far apart (a numerator beside a small denominator): the remainder replaces the dozens of
/// binary steps that would only wear the larger argument down to the size of the smaller.
pub(super) fn gcd(a: u64, b: u64) -> u64 {
    let (mut a, b) = (a.max(b), a.min(b));
    if b <= 1 {
        return if b == 0 { a } else { 1 };
    }
    if a >> 16 > b {
        a %= b;
        if a == 0 {
            return b;
        }
    }
    binary_gcd(a, b)
}

/// gcd(a, b) for a, b ≥ 1: Stein's binary algorithm with `trailing_zeros`.
fn binary_gcd(mut a: u64, mut b: u64) -> u64 {
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// gcd(a, b) of two 128-bit integers, binary, finishing in [`gcd`] once both fit a word.
pub(crate) fn gcd_u128(mut a: u128, mut b: u128) -> u128 {
    if a == 0 {
        return b;
    }
    if b == 0 {
        return a;
    }
    let shift = (a | b).trailing_zeros();
    a >>= a.trailing_zeros();
    loop {
        b >>= b.trailing_zeros();
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        if b <= u128::from(u64::MAX) {
            // Both odd words now: the rest of the common factor is odd.
            return u128::from(gcd(a as u64, b as u64)) << shift;
        }
        b -= a;
        if b == 0 {
            return a << shift;
        }
    }
}

/// gcd(t, g) for a 128-bit t and a word g ≥ 1: one remainder brings t into a word.
fn gcd_wide(t: u128, g: u64) -> u64 {
    if g == 1 {
        return 1;
    }
    match u64::try_from(t) {
        Ok(t) => gcd(t, g),
        Err(_) => gcd((t % u128::from(g)) as u64, g),
    }
}

/// x / g, skipping the (slow) division when g = 1, the common case.
#[inline]
fn div_exact<I: std::ops::Div<Output = I> + From<i8> + PartialEq + Copy>(x: I, g: I) -> I {
    if g == I::from(1) { x } else { x / g }
}

/// a/b · c/d (Henrici's product, module docs).
pub(super) fn mul(a: i64, b: i64, c: i64, d: i64) -> Wide {
    if a == 0 || c == 0 {
        return (0, 1);
    }
    let g1 = gcd(a.unsigned_abs(), d as u64) as i64;
    let g2 = gcd(c.unsigned_abs(), b as u64) as i64;
    let num = i128::from(div_exact(a, g1)) * i128::from(div_exact(c, g2));
    let den = i128::from(div_exact(b, g2)) * i128::from(div_exact(d, g1));
    (num, den)
}

/// a/b ÷ c/d = a/b · d/c, for c ≠ 0 (the sign moves to the numerator).
pub(super) fn div(a: i64, b: i64, c: i64, d: i64) -> Wide {
    debug_assert!(c != 0, "division by zero is the caller's to refuse");
    if c < 0 {
        // |c| ≤ 2⁶³ − 1, so −c and −d are words.
        mul(a, b, -d, -c)
    } else {
        mul(a, b, d, c)
    }
}

/// a/b + c/d (Henrici's sum, module docs).
pub(super) fn add(a: i64, b: i64, c: i64, d: i64) -> Wide {
    if b == d {
        // One denominator (integers among them): reduce the sum by gcd(t, b).
        let t = i128::from(a) + i128::from(c);
        if b == 1 {
            return (t, 1);
        }
        let g = i128::from(gcd_wide(t.unsigned_abs(), b as u64));
        return (div_exact(t, g), div_exact(i128::from(b), g));
    }
    let g1 = gcd(b as u64, d as u64) as i64;
    if g1 == 1 {
        let num = i128::from(a) * i128::from(d) + i128::from(c) * i128::from(b);
        return (num, i128::from(b) * i128::from(d));
    }
    let (b1, d1) = (b / g1, d / g1);
    let t = i128::from(a) * i128::from(d1) + i128::from(c) * i128::from(b1);
    if t == 0 {
        return (0, 1);
    }
    let g2 = gcd_wide(t.unsigned_abs(), g1 as u64) as i64;
    (
        div_exact(t, i128::from(g2)),
        i128::from(b1) * i128::from(div_exact(d, g2)),
    )
}

/// a/b − c/d.
pub(super) fn sub(a: i64, b: i64, c: i64, d: i64) -> Wide {
    // |c| ≤ 2⁶³ − 1: −c is a word.
    add(a, b, -c, d)
}

/// The sign of a/b − c/d: compares a·d with c·b, exactly in 128 bits.
pub(super) fn cmp(a: i64, b: i64, c: i64, d: i64) -> std::cmp::Ordering {
    if b == d {
        return a.cmp(&c);
    }
    (i128::from(a) * i128::from(d)).cmp(&(i128::from(c) * i128::from(b)))
}

/// n/d for a word fraction, correctly rounded, when both parts are exact in f64 (≤ 2⁵³):
/// IEEE division of two exact operands is correctly rounded. `None` otherwise.
pub(super) fn to_f64(n: i64, d: i64) -> Option<f64> {
    const EXACT: u64 = 1 << 53;
    (n.unsigned_abs() <= EXACT && d as u64 <= EXACT).then(|| n as f64 / d as f64)
}

/// √(n/d) when it is rational: both parts perfect squares (n/d in lowest terms).
pub(super) fn sqrt(n: i64, d: i64) -> Option<(i64, i64)> {
    if n < 0 {
        return None;
    }
    let (rn, rd) = (n.isqrt(), d.isqrt());
    (rn * rn == n && rd * rd == d).then_some((rn, rd))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gcd_of_words() {
        assert_eq!(gcd(0, 0), 0);
        assert_eq!(gcd(0, 7), 7);
        assert_eq!(gcd(12, 18), 6);
        assert_eq!(gcd(1 << 40, 3 << 38), 1 << 38);
        assert_eq!(gcd(u64::MAX, u64::MAX - 1), 1);
        assert_eq!(gcd_wide(u128::MAX, 3), 3);
        assert_eq!(gcd_u128(0, 5), 5);
        assert_eq!(gcd_u128(3 << 100, 6 << 90), 3 << 91);
        assert_eq!(gcd_u128(u128::MAX, u128::MAX - 1), 1);
        assert_eq!(gcd_u128((1 << 127) + 1, 1), 1);
        assert_eq!(gcd_u128(u128::MAX, u128::MAX), u128::MAX);
    }

    #[test]
    fn henrici_results_are_in_lowest_terms() {
        assert_eq!(mul(2, 3, 9, 4), (3, 2));
        assert_eq!(add(1, 6, 1, 10), (4, 15));
        assert_eq!(add(1, 6, -1, 6), (0, 1));
        assert_eq!(sub(5, 6, 1, 3), (1, 2));
        assert_eq!(div(1, 2, -3, 4), (-2, 3));
    }

    #[test]
    fn the_extremes_do_not_overflow() {
        let m = i64::MAX;
        assert_eq!(mul(m, 1, m, 1), (i128::from(m) * i128::from(m), 1));
        assert_eq!(mul(-m, 1, m, 1), (-i128::from(m) * i128::from(m), 1));
        assert_eq!(add(m, 1, m, 1), (2 * i128::from(m), 1));
        assert_eq!(add(-m, 1, -m, 1), (-2 * i128::from(m), 1));
        let (n, d) = add(m, m - 1, m - 1, m);
        assert_eq!(d, i128::from(m) * i128::from(m - 1));
        assert_eq!(
            n,
            i128::from(m) * i128::from(m) + i128::from(m - 1) * i128::from(m - 1)
        );
    }
}
