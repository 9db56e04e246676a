//! Issue 28, item 1: `"80/3 deg"` was read as 80/(3 deg).
//!
//! The grammar bound `deg` to the atom before it, so a quotient written before the unit took the
//! unit on its denominator: `--param "theta=80/3 deg"` posed a rod at 80/(3·π/180) rad ≈ 1528°
//! and printed P = 1.449818 N s with status 0, where (80/3)° gives 0.630641. Sweeps of a
//! parameter in degrees wrote their grid points as `p/q deg` and hit the same rule at every
//! fractional point. `deg` now multiplies the whole product or quotient before it
//! (`src/number/expr.rs` states the grammar and its precedence table), and every number the
//! tool writes back into a parameter is parenthesised (`(p/q) deg`).
//!
//! Checked against what the parser does not compute: a rational r written as text, read with
//! `deg` and multiplied by 180/π is r exactly (π/π cancels in the exact evaluator), for every
//! spelling; and a thin rod posed at θ and dropped on its end gets the textbook impulse
//! P = (1 + k) m v / (1 + 3 sin²θ) (the end's lever arm (L/2) sin θ, J = m L²/12), in f64 at
//! fractional angles and in exact radicals at θ = 45/3 deg = 15°, where
//! P = 6/(10 − 3√3) = 6(10 + 3√3)/73.

mod common;

use common::SceneFile;
use inertance::number::{format_rational, parse_number};
use num_bigint::BigInt;
use num_rational::BigRational;
use proptest::prelude::*;

/// r read back through `deg`, times 180/π: exactly r when `deg` took the whole quotient.
fn degrees_back(text: &str) -> BigRational {
    let n = parse_number(&format!("({text})*180/pi")).expect("reads");
    n.exact
        .expect("a rational multiple of pi over pi is rational")
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn any_rational_written_before_deg_is_that_many_degrees(
        p in -1_000_000i64..=1_000_000,
        q in 1i64..=1_000_000,
    ) {
        let r = BigRational::new(BigInt::from(p), BigInt::from(q));
        for text in [
            format!("{p}/{q} deg"),
            format!("{p} / {q} deg"),
            format!("{p}/{q}deg"),
            format!("({p}/{q}) deg"),
            format!("{} deg", format_rational(&r)),
            format!("-({}) deg", format_rational(&-r.clone())),
            format!("{p} deg / {q}"),
            format!("2*{p}/{q} deg / 2"),
        ] {
            prop_assert_eq!(degrees_back(&text), r.clone(), "{}", text);
        }
        // In a sum, `deg` stays with its own term: (p/q)° + (p/q)° is twice the angle.
        prop_assert_eq!(
            degrees_back(&format!("{p}/{q} deg + {p}/{q} deg")),
            r.clone() * BigRational::from_integer(2.into())
        );
    }
}

#[test]
fn deg_binds_looser_than_products_and_tighter_than_sums() {
    let rat = |s: &str| parse_number(s).expect("reads").exact.expect("rational");
    let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
    // (80/3)°, not 80/(3°).
    assert_eq!(degrees_back("80/3 deg"), q(80, 3));
    assert_eq!(degrees_back("-80/3 deg"), q(-80, 3));
    assert_eq!(degrees_back("2^3 deg"), q(8, 1));
    assert_eq!(degrees_back("90 deg - 1/3 deg"), q(269, 3));
    // Exact trigonometry at the angles the old rule broke: 90/3 deg is 30°, 180/4 deg is 45°.
    assert_eq!(rat("sin(90/3 deg)"), q(1, 2));
    assert_eq!(rat("cos(360/6 deg)"), q(1, 2));
    // A sum: `30 deg + 1/2` is π/6 + 1/2, not (30 + 1/2)°.
    let x = parse_number("30 deg + 1/2").expect("reads").approx;
    assert_eq!(x, std::f64::consts::PI / 6.0 + 0.5);
    // Two units in one product, or a power of a unit, are refused with the fix.
    for (text, fix) in [
        ("30 deg * 2 deg", "(30 deg)*(2 deg)"),
        ("30 deg^2", "(30 deg)^2"),
    ] {
        let e = parse_number(text).expect_err("refused").to_string();
        assert!(e.contains(fix), "{text}: {e}");
    }
}

/// A thin rod (L = 1 m, m = 1 kg) posed at θ about y, dropped at 1 m/s on its lower end, k = 1/2.
const ROD: &str = r#"
name = "rod on its end"
[params]
theta = "30 deg"
[body]
shape = { rod = 1 }
mass = 1
pose = { axis = [0, 1, 0], angle = "theta" }
velocity = [0, 0, -1]
angular_velocity = [0, 0, 0]
[[obstacle]]
name = "floor"
normal = [0, 0, 1]
[[contact]]
obstacle = "floor"
body_point = [0, 0, -0.5]
k = 0.5
"#;

/// The rod's impulse at θ degrees: (1 + k) m v / (1 + 3 sin²θ).
fn rod_impulse(degrees: f64) -> f64 {
    let s = degrees.to_radians().sin();
    1.5 / (1.0 + 3.0 * s * s)
}

fn json(out: &std::process::Output) -> serde_json::Value {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON")
}

fn newton_p1(j: &serde_json::Value) -> f64 {
    j["models"]["newton"]["impulses"][0]
        .as_f64()
        .expect("a number")
}

#[test]
fn a_rod_posed_at_80_over_3_deg_gets_the_textbook_impulse() {
    let s = SceneFile::new("angle-80-3", ROD);
    let spellings = ["theta=80/3 deg", "theta=(80/3) deg", "theta=80/3"];
    let outs: Vec<serde_json::Value> = spellings
        .iter()
        .map(|p| json(&s.run(&["solve", "--json", "--param", p])))
        .collect();
    for (p, j) in spellings.iter().zip(&outs) {
        assert_eq!(j, &outs[0], "{p}");
    }
    // The condition of a one-contact solve is 1: a few roundings of the pose and the division.
    let p = newton_p1(&outs[0]);
    let expected = rod_impulse(80.0 / 3.0);
    assert!(
        (p - expected).abs() <= 8.0 * f64::EPSILON * expected,
        "{p} vs {expected}"
    );
}

#[test]
fn a_quotient_in_degrees_is_exact_in_radicals() {
    let s = SceneFile::new("angle-45-3", ROD);
    let quotient = json(&s.run(&["solve", "--exact", "--json", "--param", "theta=45/3 deg"]));
    let whole = json(&s.run(&["solve", "--exact", "--json", "--param", "theta=15 deg"]));
    assert_eq!(quotient, whole);
    assert_eq!(
        quotient["models"]["newton"]["impulses"][0],
        "6/73*(10 + 3*sqrt(3))"
    );
}

#[test]
fn a_sweep_in_degrees_writes_its_fractional_points_as_angles() {
    let s = SceneFile::new("angle-sweep", ROD);
    let csv = s.sweep(&["--vary", "theta=1:60:7"]);
    // Points 1 + 59k/6 degrees: most are fractions.
    let mut fractions = 0;
    for r in 0..csv.rows.len() {
        let degrees: f64 = csv.cell(r, "theta").parse().expect("a number");
        fractions += usize::from(degrees.fract() != 0.0);
        let p: f64 = csv.cell(r, "newton_P1").parse().expect("a number");
        let expected = rod_impulse(degrees);
        assert!(
            (p - expected).abs() <= 1e-14 * expected,
            "θ = {degrees}°: {p} vs {expected}"
        );
    }
    assert!(fractions >= 4, "{:?}", csv.rows);
}
