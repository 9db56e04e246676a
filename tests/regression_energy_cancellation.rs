//! Regression: ΔE_c was computed as T⁰ − T, which cancels when the loss is small beside T⁰ —
//! a body sliding fast along its supports hits them softly. In f64 the impulses were right to
//! 10⁻¹⁵ but ΔE_c only to 10⁻⁵ relative. Now ΔE_c = ½ Σ P_i (v_ix⁰ + v_ix) (the momentum
//! balance), whose terms under Newton are P_i (1 − k_i) v_ix⁰ ≥ 0 when every contact approaches:
//! no cancellation, so its error is that of the impulses, O(cond(G)·ε) relative to ΔE_c itself.

use inertance::scene::Scene;
use inertance::scene::pipeline::run;
use inertance::{Exact, Model};

/// Example 3's bar sliding along y at `speed` m/s while it strikes at 3 m/s: T⁰ ≈ ½·speed².
fn scene(speed: &str) -> Scene {
    let text = format!(
        "[body]\nmass = 1\ninertia = [12, 1.6, 12]\nvelocity = [3, {speed}, 0]\nangular_velocity = [0, 0, 0.4]\n\
         [[contact]]\npoint = [0, -2, 0]\nnormal = [1, 0, 0]\nk = 0.3\n\
         [[contact]]\npoint = [0, 4, 0]\nnormal = [1, 0, 0]\nk = 0.2\n[solve]\nmodels = [\"newton\"]\n"
    );
    Scene::parse(&text, "sliding").unwrap()
}

#[test]
fn the_loss_of_kinetic_energy_is_accurate_relative_to_itself() {
    for speed in ["1e4", "1e6", "1e8"] {
        let s = scene(speed);
        let exact = run::<Exact>(&s, None).unwrap().report;
        let float = run::<f64>(&s, None).unwrap().report;
        let (e, f) = (&exact.models[0], &float.models[0]);
        assert_eq!(e.model, Model::Newton);
        // cond₂(G) = 3.0 here (G = [[4/3, 1/3], [1/3, 7/3]]): a few ε·cond suffice; 10⁻¹⁴.
        for (name, x, y) in [
            ("ΔE_c", &e.kinetic_energy_loss, &f.kinetic_energy_loss),
            ("E_p", &e.lost_velocity_energy, &f.lost_velocity_energy),
        ] {
            let rel = ((x.f64 - y.f64) / x.f64).abs();
            assert!(rel <= 1e-14, "speed {speed}: {name} relative error {rel:e}");
        }
        // The loss does not depend on the sliding speed at all (the supports are frictionless).
        assert_eq!(e.kinetic_energy_loss.exact.as_deref(), Some("223769/45000"));
    }
}
