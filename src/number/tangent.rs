//! The derivative of an expression with respect to one of its names, in f64 (forward mode).
//!
//! A scene parameter seeded for a sensitivity run (`sweep --sensitivity`) gives every number
//! that names it a tangent: the value of d(expression)/d(parameter) at the parameter's value.
//! The rules are those of dual numbers (x + x′ε, ε² = 0):
//!
//! ```text
//! (a ± b)′ = a′ ± b′      (ab)′ = a′b + ab′      (a/b)′ = (a′b − ab′)/b²
//! (aᵇ)′ = b aᵇ⁻¹ a′ + aᵇ ln a · b′      (√a)′ = a′/(2√a)
//! sin′ = cos · a′         cos′ = −sin · a′        tan′ = (1 + tan²) a′      (a deg)′ = a′ π/180
//! ```
//!
//! A sub-expression that names no parameter has tangent 0 and its value from the ordinary
//! evaluator; angles are in radians, so the derivative with respect to `theta = "3 deg"` is
//! per radian.

use std::f64::consts::PI;

use super::expr::{Func, Kind, Node, Op};
use super::{Number, evaluate};

/// (value, derivative).
type Dual = (f64, f64);

/// The value and derivative of `node` (a tree of `src`), with `name` giving each name's value
/// and derivative; `None` when a name is unknown to it or a sub-expression has no value.
pub(crate) fn derivative(
    src: &str,
    node: &Node,
    name: &dyn Fn(&str) -> Option<Dual>,
) -> Option<Dual> {
    if !node.has_name {
        return evaluate(src, node).ok().map(|n: Number| (n.approx, 0.0));
    }
    Some(match &node.kind {
        Kind::Name(n) => name(n)?,
        Kind::Lit(_) | Kind::Pi | Kind::NonFinite => return None,
        Kind::Neg(e) => {
            let (v, d) = derivative(src, e, name)?;
            (-v, -d)
        }
        Kind::Chain(first, rest) => {
            let mut acc = derivative(src, first, name)?;
            for (op, rhs) in rest {
                let (b, db) = derivative(src, rhs, name)?;
                let (a, da) = acc;
                acc = match op {
                    Op::Add => (a + b, da + db),
                    Op::Sub => (a - b, da - db),
                    Op::Mul => (a * b, da * b + a * db),
                    Op::Div => (a / b, (da * b - a * db) / (b * b)),
                };
            }
            acc
        }
        Kind::Pow(base, exp) => {
            let (a, da) = derivative(src, base, name)?;
            let (b, db) = derivative(src, exp, name)?;
            let v = a.powf(b);
            let mut d = b * a.powf(b - 1.0) * da;
            if db != 0.0 {
                d += v * a.ln() * db;
            }
            (v, d)
        }
        Kind::Deg(e) => {
            let (v, d) = derivative(src, e, name)?;
            (v.to_radians(), d * PI / 180.0)
        }
        Kind::Call(func, e) => {
            let (a, da) = derivative(src, e, name)?;
            match func {
                Func::Sqrt => {
                    let r = a.sqrt();
                    (r, da / (2.0 * r))
                }
                Func::Sin => (a.sin(), a.cos() * da),
                Func::Cos => (a.cos(), -a.sin() * da),
                Func::Tan => {
                    let t = a.tan();
                    (t, (1.0 + t * t) * da)
                }
            }
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::number::parse_checked;

    fn d(text: &str, x: f64) -> Dual {
        let names = ["x".to_string()];
        let root = parse_checked(text, &names).expect("parses");
        derivative(text, &root, &|n: &str| (n == "x").then_some((x, 1.0))).expect("a value")
    }

    #[test]
    fn rules_of_the_derivative() {
        // Polynomials and quotients are exact in binary at these points.
        assert_eq!(d("3*x^2 - x/2 + 1", 2.0), (12.0, 11.5));
        assert_eq!(d("(x + 1)/(x - 1)", 3.0), (2.0, -0.5));
        assert_eq!(d("-x", 5.0), (-5.0, -1.0));
        let (v, dv) = d("sqrt(x)", 4.0);
        assert_eq!((v, dv), (2.0, 0.25));
        // d/dx sin(x deg) = cos(x°)·π/180, within a few ulps of the closed form.
        let (v, dv) = d("sin(x deg)", 30.0);
        assert!((v - 0.5).abs() < 1e-15);
        assert!((dv - (30f64.to_radians().cos() * PI / 180.0)).abs() < 1e-17);
        let (_, dt) = d("tan(x)", 0.3);
        assert!((dt - 1.0 / 0.3f64.cos().powi(2)).abs() < 4.0 * f64::EPSILON);
        // 2^x: the exponent carries the derivative, 2^x ln 2.
        let (v, dv) = d("2^x", 3.0);
        assert_eq!(v, 8.0);
        assert!((dv - 8.0 * 2f64.ln()).abs() < 4.0 * f64::EPSILON * 8.0);
    }
}
