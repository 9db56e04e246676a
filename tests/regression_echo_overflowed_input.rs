//! Regression (issue 28, item 15): an input echoed through f64. A blocked screw written
//! `"10^400"` (`[constraints] blocked`, the paper's form) came out of the f64 report as `inf`
//! in the table and `null` in the JSON: the report read the screws back from the float solve,
//! whose units had scaled the screw to 1 and scaled it back beyond f64. Its constraint
//! impulse q₁ = F_z / 10⁴⁰⁰ ≈ 4.94·10⁻⁴⁰⁰ would have come out 0 the same way.
//!
//! Now a written screw whose number f64 does not hold is echoed as written (its text, a
//! string in the JSON), and D, U, M_red and the constraint impulses — which depend on the
//! scale the user gave each screw — are held beyond f64 as a value and a power of two
//! (`report::Wide`), printed as decimals, never ∞, 0 or `null`.
//!
//! **The closed form.** The body moves in its xy plane (free: ω_z, v_x, v_y; blocked: F_z
//! scaled by s = 10^±400, M_x, M_y), hit at A = (0, −2, 0) along n = (3, 0, 4)/5 with
//! k = 3/10. The impulse acts in the plane through its x component, and the z component
//! 4P/5 is taken by the blocked screw: q₁ s = 4P/5. The exact solve gives P = 247/40 N s
//! (also in the f64 table: 6.175), so q₁ = 247/50 / s. In f64 q₁ comes from a scaled solve
//! whose screw is of order 1 and a power of two: its relative error is that of a
//! well-conditioned 3×3 solve of short decimals, a few ε; 16ε is the claim.

use std::process::Command;

use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::pipeline::run;
use num_rational::BigRational;

fn scene(scale: &str) -> String {
    format!(
        "[body]\nmass = 1\ninertia = [12, 1.6, 12]\nvelocity = [3, 2, 0]\n\
         angular_velocity = [0, 0, 0.4]\n[[contact]]\npoint = [0, -2, 0]\nnormal = [3, 0, 4]\n\
         k = 0.3\n[constraints]\nfree = [[0, 0, 1, 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0]]\n\
         blocked = [[0, 0, \"{scale}\", 0, 0, 0], [0, 0, 0, 1, 0, 0], [0, 0, 0, 0, 1, 0]]\n"
    )
}

/// Run the binary on `text` with `args` after the file; (status, stdout, stderr).
fn cli(text: &str, args: &[&str]) -> (Option<i32>, String, String) {
    static RUNS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let run = RUNS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("inertance-echo-{}-{run}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("scene.toml");
    std::fs::write(&path, text).unwrap();
    let mut all = vec!["solve", path.to_str().unwrap()];
    all.extend_from_slice(args);
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(&all)
        .output()
        .unwrap();
    std::fs::remove_dir_all(&dir).ok();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// (mantissa, power of ten) of a decimal in scientific notation, `"4.94e-400"`.
fn decimal(text: &str) -> (f64, i64) {
    let (m, e) = text.split_once('e').expect("scientific notation");
    (m.parse().unwrap(), e.parse().unwrap())
}

#[test]
fn the_written_screw_is_echoed_as_written() {
    for scale in ["10^400", "10^-400"] {
        let text = scene(scale);
        let (status, table, err) = cli(&text, &[]);
        assert_eq!(status, Some(0), "{err}");
        assert!(
            table.contains(&format!("U = [0, 0, {scale}, 0, 0, 0]")),
            "{table}"
        );
        assert!(!table.contains("inf"), "{table}");
        let (status, json, err) = cli(&text, &["--json"]);
        assert_eq!(status, Some(0), "{err}");
        let json: serde_json::Value = serde_json::from_str(&json).unwrap();
        assert_eq!(json["constraints"]["blocked"][0][2], scale);
        assert_eq!(json["constraints"]["blocked"][1][3], 1.0);
    }
}

/// q₁ = 247/50 / s beyond f64 in both directions, against the exact solve and the closed
/// form (module docs), in the JSON (a decimal string) and the table.
#[test]
fn the_constraint_impulse_beyond_f64_is_held() {
    for (scale, power) in [("10^400", -400), ("10^-400", 400)] {
        let text = scene(scale);
        let exact = run::<Exact>(&Scene::parse(&text, "x.toml").unwrap(), None).unwrap();
        let ten = num_traits::pow(num_bigint::BigInt::from(10), 400);
        let q1 = if power < 0 {
            BigRational::new(247.into(), num_bigint::BigInt::from(50) * ten)
        } else {
            BigRational::new(num_bigint::BigInt::from(247) * ten, 50.into())
        };
        for m in &exact.report.models {
            assert_eq!(m.impulses[0].exact.as_deref(), Some("247/40"));
            let text = m.constraint_impulses[0].exact.as_deref().unwrap();
            assert_eq!(text.parse::<BigRational>().unwrap(), q1);
        }
        let (status, json, err) = cli(&text, &["--json"]);
        assert_eq!(status, Some(0), "{err}");
        let json: serde_json::Value = serde_json::from_str(&json).unwrap();
        for model in ["newton", "poisson"] {
            let q = json["models"][model]["constraint_impulses"][0]
                .as_str()
                .unwrap_or_else(|| panic!("{model}: q1 is not a decimal string: {json}"));
            let (mantissa, exponent) = decimal(q);
            assert_eq!(exponent, power, "{q}");
            assert!(
                (mantissa - 4.94).abs() <= 16.0 * f64::EPSILON * 4.94,
                "{model}: q1 = {q}"
            );
        }
        let (_, table, _) = cli(&text, &[]);
        let line = table.lines().find(|l| l.contains("q1 [N s]")).unwrap();
        assert!(line.contains(&format!("4.940000e{power}")), "{line}");
    }
}
