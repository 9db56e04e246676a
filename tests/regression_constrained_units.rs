//! Regression: a constrained body whose mass and moments differ by many orders of magnitude.
//! A body of 10⁻³⁰⁰ kg with moments of 3.3 kg·m², on a revolute joint and a prismatic one
//! (Example 6's joints), was refused in f64 with "this joint's freedom is already given by the
//! joints before it": M_red = diag(3.3 + …, 10⁻³⁰⁰), and the rank test, relative to the largest
//! entry, took the prismatic joint's 10⁻³⁰⁰ for zero. The free and blocked screws are now
//! orthogonalised in the body's metric, and a screw is dependent only when each of its
//! coordinates is within the rounding of its orthogonalisation (W = D M_red⁻¹ Dᵀ η does not
//! depend on the basis of span D), so each screw is compared with its own size.
//!
//! The opposite extreme, a heavy body with small moments (m·l²/J beyond about 10¹⁰, where the
//! Gram matrix M_red itself is ill-conditioned in the joints' basis), is solved too, since the
//! screws are orthogonalised rather than their Gram matrix formed
//! (tests/regression_constrained_heavy_body.rs).

use inertance::scalar::Exact;
use inertance::scene::Scene;
use inertance::scene::pipeline::run;

/// Example 6's joints with one contact (G is 1×1, never singular), mass `m`.
fn scene(m: &str) -> Scene {
    let text = format!(
        r#"
[body]
mass = "{m}"
inertia = [3.3, 3.3, 3.3]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 1]
[[contact]]
point = [0, -0.3, 0]
normal = [1, 0, 0]
k = 0.5
[[constraints.joint]]
kind = "revolute"
point = [0, -1, 0]
axis = [0, 0, 1]
[[constraints.joint]]
kind = "prismatic"
axis = [1, 0, 0]
[solve]
models = ["newton", "poisson"]
"#
    );
    Scene::parse(&text, "constrained-units.toml").unwrap()
}

#[test]
fn a_light_body_on_joints_is_not_refused_as_dependent_and_matches_exact() {
    // Light bodies: the orthogonalised screws are the joints' own up to a relative m·l²/J.
    for m in ["1e-300", "1e-100", "1e-20", "1e-5", "10"] {
        let s = scene(m);
        let float = run::<f64>(&s, None).unwrap_or_else(|e| panic!("mass {m}: {e}"));
        let exact = run::<Exact>(&s, None).unwrap();
        for (f, x) in float.report.models.iter().zip(&exact.report.models) {
            // One contact: P = (1 + k) v⁰/g, a handful of roundings; the twist and q likewise.
            // 64ε relative to each value's own size (the inputs 0.3, 3.3 are rounded in f64,
            // by ε/2 each, and W applied over the orthogonalised screws adds a few ε).
            let close = |a: f64, b: f64, what: &str| {
                assert!(
                    (a - b).abs() <= 64.0 * f64::EPSILON * b.abs().max(f64::MIN_POSITIVE),
                    "mass {m}, {:?} {what}: f64 {a:e}, exact {b:e}",
                    f.model
                );
            };
            close(f.impulses[0].f64, x.impulses[0].f64, "P1");
            for k in 0..3 {
                close(f.angular_velocity[k].f64, x.angular_velocity[k].f64, "ω");
                close(f.velocity[k].f64, x.velocity[k].f64, "v_C");
            }
            for (a, b) in f.constraint_impulses.iter().zip(&x.constraint_impulses) {
                close(a.f64, b.f64, "q");
            }
        }
    }
}
