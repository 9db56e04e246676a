//! Float results beyond the range of f64: a scaled solve's value and the power of two of its
//! unit ([`crate::scene::scale`]).
//!
//! A scene solved in units 2^a kg, 2^b m, 2^c s gives each output y′ in those units; the output
//! is y = y′·2^K with K from its dimension. Where that product leaves f64 (Δ = det G ~ M⁻ᴺ of
//! a body of 10⁻³⁰⁰ kg is 10⁶⁰⁰ kg⁻ᴺ; an inertance 1/m of a body of 10³⁰⁸ kg is subnormal),
//! the pair (y′, K) still holds it exactly: it is reported as decimal text computed from the
//! pair in integers, never as ∞ or 0.

use num_bigint::BigInt;

/// A value `mantissa · 2^exponent` outside the normal range of f64 (or rounding to 0 there).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wide {
    /// The value in scaled units: finite, nonzero.
    pub mantissa: f64,
    /// The power of two of its unit.
    pub exponent: i64,
}

impl Wide {
    /// x·2^k when it is not a normal f64 (it overflows, or is subnormal or rounds to 0 while
    /// x ≠ 0); `None` when f64 holds it (or x is 0 or not finite).
    pub fn of(x: f64, k: i64) -> Option<Wide> {
        if x == 0.0 || !x.is_finite() {
            return None;
        }
        let y = crate::scene::scale::ldexp(x, k);
        (!y.is_finite() || y.abs() < f64::MIN_POSITIVE).then_some(Wide {
            mantissa: x,
            exponent: k,
        })
    }

    /// The value rounded to f64: ±∞ or 0 or a subnormal (what f64 holds of it).
    pub fn to_f64(&self) -> f64 {
        crate::scene::scale::ldexp(self.mantissa, self.exponent)
    }

    /// The value in decimal scientific notation with `digits` significant digits (≥ 1),
    /// correctly rounded (ties to even), e.g. `1.234568e600`: computed exactly in integers
    /// from the mantissa's bits and the exponent, so it holds at any exponent.
    pub fn decimal(&self, digits: usize) -> String {
        let digits = digits.max(1);
        let (m, q, sign) = num_traits::Float::integer_decode(self.mantissa);
        // value = m · 2^e = n · 10^d with n an integer.
        let e = i64::from(q) + self.exponent;
        let (n, d) = if e >= 0 {
            (BigInt::from(m) << e as usize, 0)
        } else {
            let five = num_traits::pow(BigInt::from(5), e.unsigned_abs() as usize);
            (BigInt::from(m) * five, e)
        };
        let s = n.to_string();
        let (mut kept, rest) = if s.len() > digits {
            (s[..digits].to_string(), &s[digits..])
        } else {
            (format!("{s:0<digits$}"), "")
        };
        let mut power = s.len() as i64 - 1 + d;
        if round_up(&kept, rest) {
            let bumped: BigInt = BigInt::parse_bytes(kept.as_bytes(), 10).unwrap_or_default() + 1;
            kept = bumped.to_string();
            if kept.len() > digits {
                kept.truncate(digits);
                power += 1;
            }
        }
        let (head, tail) = kept.split_at(1);
        let sign = if sign < 0 { "-" } else { "" };
        if tail.is_empty() {
            format!("{sign}{head}e{power}")
        } else {
            format!("{sign}{head}.{tail}e{power}")
        }
    }
}

/// Whether digits `kept` followed by the dropped digits `rest` round up (half to even).
fn round_up(kept: &str, rest: &str) -> bool {
    let mut r = rest.bytes();
    match r.next() {
        Some(b'6'..=b'9') => true,
        Some(b'5') => {
            r.any(|b| b != b'0') || kept.bytes().last().is_some_and(|b| (b - b'0') % 2 == 1)
        }
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The decimal text against f64's own formatting where f64 holds the value.
    #[test]
    fn decimal_agrees_with_f64_in_range() {
        for x in [1.0, -2.5, 3.0e-7, 6.02214076e23, 1.0 / 3.0, 9.999999999e-5] {
            for k in [-40, 0, 33] {
                let y = x * 2f64.powi(k);
                let w = Wide {
                    mantissa: x,
                    exponent: i64::from(k),
                };
                assert_eq!(w.decimal(7), format!("{y:.6e}"), "{x} 2^{k}");
                assert_eq!(w.decimal(17).parse::<f64>().ok(), Some(y), "{x} 2^{k}");
            }
        }
    }

    /// 2^2000 and 2^-2000 exactly: 1.148130695274254524…e602 and 8.7098098162172166…e-603.
    #[test]
    fn decimal_beyond_f64() {
        let w = |e| Wide {
            mantissa: 1.0,
            exponent: e,
        };
        assert_eq!(w(2000).decimal(10), "1.148130695e602");
        assert_eq!(w(-2000).decimal(10), "8.709809816e-603");
        assert_eq!(w(2000).to_f64(), f64::INFINITY);
        assert!(w(2000).decimal(1) == "1e602");
        // 0.5·2^2000 = 2^1999 = 5.740653476…e601.
        assert_eq!(
            Wide::of(0.5, 2000).map(|w| w.decimal(4)),
            Some("5.741e601".into())
        );
        assert_eq!(Wide::of(0.5, 1000), None);
        assert!(Wide::of(1.0, -1030).is_some(), "subnormal");
        assert_eq!(Wide::of(0.0, 5000), None);
    }

    #[test]
    fn rounding_carries_into_the_exponent() {
        // 9.9999999999999995e-1·2^0 to 3 digits: 1.00e0.
        let w = Wide {
            mantissa: 0.9999999,
            exponent: 0,
        };
        assert_eq!(w.decimal(3), "1.00e0");
    }
}
