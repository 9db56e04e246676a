//! Found by the fuzz harness (`tests/fuzz.rs`): an exact value beyond the range of f64 was
//! printed `p/q ≈ inf` (and one below it `p/q ≈ 0`) in `solve --exact`'s table. The decimals now
//! come from the exact value itself.

use std::process::Command;

fn exact_table(scene: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz_corpus")
        .join(scene);
    let out = Command::new(env!("CARGO_BIN_EXE_inertance"))
        .args(["solve", path.to_str().unwrap(), "--exact"])
        .output()
        .unwrap();
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn exact_values_above_f64_print_their_decimals_not_inf() {
    let t = exact_table("exact-values-beyond-f64.toml");
    assert!(!t.contains("inf"), "{t}");
    // g11 = 1 + 10^400, Δ the same.
    assert!(t.contains("≈ 1.000000e400"), "{t}");
    // E_p = 9/(8·10^400 + 8) in both models.
    assert!(t.contains("≈ 1.125000e-400"), "{t}");
}

#[test]
fn exact_values_below_f64_print_their_decimals_not_zero() {
    let t = exact_table("exact-values-below-f64.toml");
    assert!(!t.contains("≈ 0 ") && !t.trim_end().ends_with("≈ 0"), "{t}");
    // P1 = (1 + k)/g11 = 1.5/(2·10^400).
    assert!(t.contains("≈ 7.500000e-401"), "{t}");
    assert!(t.contains("≈ 2.000000e400"), "{t}");
}

#[test]
fn a_mantissa_rounding_to_ten_carries_into_the_exponent() {
    // P1c = 1/(10^400 + 1) = 9.99…e-401: seven significant digits round it to 1.000000e-400.
    let t = exact_table("exact-mantissa-rounds-to-ten.toml");
    assert!(!t.contains("≈ 10."), "{t}");
    assert!(t.contains("≈ 1.000000e-400"), "{t}");
}
