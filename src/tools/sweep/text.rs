//! How exact values are written: in the CSV (full-precision f64), for people (`1/3`, `0.01`)
//! and as TOML that reads back exactly (so a varied value can be set in a scene document).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use crate::number::format_rational;

/// A full-precision f64 for the CSV.
pub(super) fn num(x: f64) -> String {
    format!("{x:?}")
}

/// An exact value as a person writes it: `3`, `0.01`, or `1/3`.
pub(super) fn text(q: &BigRational) -> String {
    match decimal(q) {
        Some(d) => d,
        None => format_rational(q),
    }
}

/// The TOML text of an exact value: an integer or decimal literal when it has a short one
/// (so messages show `1.5`), else the string `"p/q"`; either is read back exactly.
pub(super) fn toml_text(q: &BigRational) -> String {
    match decimal(q) {
        Some(d) => d,
        None => format!("\"{}\"", format_rational(q)),
    }
}

/// q as a terminating decimal of at most 40 places, if it is one.
fn decimal(q: &BigRational) -> Option<String> {
    if q.is_integer() {
        return Some(q.numer().to_string());
    }
    let (two, five) = (BigInt::from(2), BigInt::from(5));
    let mut den = q.denom().clone();
    let mut places = [0u32; 2];
    for (k, p) in [&two, &five].into_iter().enumerate() {
        while (&den % p).is_zero() {
            den /= p;
            places[k] += 1;
        }
    }
    let scale = places[0].max(places[1]);
    if !den.is_one() || scale > 40 {
        return None;
    }
    let scaled = q * BigRational::from_integer(BigInt::from(10).pow(scale));
    let digits = scaled.numer().abs().to_string();
    let digits = format!("{digits:0>width$}", width = scale as usize + 1);
    let (int, frac) = digits.split_at(digits.len() - scale as usize);
    let sign = if q.is_negative() { "-" } else { "" };
    Some(format!("{sign}{int}.{frac}"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::parse_number;
    use crate::tools::sweep::q;

    #[test]
    fn toml_text_reads_back_exactly() {
        for (n, d, want) in [
            (0, 1, "0"),
            (3, 2, "1.5"),
            (1, 100, "0.01"),
            (-1, 8, "-0.125"),
            (-7, 1, "-7"),
            (1, 3, "\"1/3\""),
            (-2, 3, "\"-2/3\""),
        ] {
            let x = q(n, d);
            let t = toml_text(&x);
            assert_eq!(t, want);
            let read = parse_number(t.trim_matches('"')).unwrap().exact.unwrap();
            assert_eq!(read, x);
        }
    }
}
