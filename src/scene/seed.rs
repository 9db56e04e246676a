//! Seeding a scene for a sensitivity run: which input the derivative is taken with respect to.
//!
//! A sensitivity is the unchanged pipeline run over dual numbers ([`crate::scalar::dual`]).
//! Every scene number enters the run with its value and its [`Number::tangent`], read as
//! dx/dθ — the derivative of that number with respect to the one parameter θ the run
//! differentiates by — and every output comes out with dy/dθ. Seeding is nothing but writing
//! those tangents, and the pipeline reads nothing else:
//!
//! * θ a number of the scene ([`seeded`]): tangent 1 on it, 0 on every other number;
//! * θ a parameter the scene's numbers are computed from: on each number x(θ), its derivative
//!   x′(θ) (an `f64`; exact in `Dual<Exact>` as that f64), 0 on the numbers that do not
//!   depend on θ.
//!
//! [`Number::tangent`]: crate::number::Number::tangent

use super::Scene;

/// `scene` seeded to differentiate with respect to its number at `key` (a path of
/// [`Scene::numbers`]; `contact[i].k` names both `k_newton` and `k_poisson`, as setting it sets
/// both): that number's tangent 1, every other number's 0. `None` when `key` names no number.
pub fn seeded(scene: &Scene, key: &str) -> Option<Scene> {
    let both_k = key
        .strip_suffix(".k")
        .map(|c| (format!("{c}.k_newton"), format!("{c}.k_poisson")));
    let mut s = scene.clone();
    let mut found = false;
    for (k, n) in s.numbers_mut() {
        let hit = k == key || both_k.as_ref().is_some_and(|(kn, kp)| k == *kn || k == *kp);
        n.tangent = if hit { 1.0 } else { 0.0 };
        found |= hit;
    }
    found.then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &str = r#"
        [body]
        mass = 1
        inertia = [12, 1.6, 12]
        velocity = [3, 2, 0]
        angular_velocity = [0, 0, 0.4]
        [[contact]]
        point = [0, -2, 0]
        normal = [1, 0, 0]
        k = 0.3
        [[contact]]
        point = [0, 4, 0]
        normal = [1, 0, 0]
        tangent = [0, 1, 0]
        k_newton = 0.2
        k_poisson = 0.1
        k_energetic = 0.5
        mu = 0.1
        [[constraints.joint]]
        kind = "planar"
        normal = [0, 0, 1]
    "#;

    fn tangents(s: &Scene) -> Vec<(String, f64)> {
        s.numbers()
            .filter(|(_, n)| n.tangent != 0.0)
            .map(|(k, n)| (k, n.tangent))
            .collect()
    }

    #[test]
    fn numbers_mut_lists_the_keys_of_numbers() {
        let mut s = Scene::parse(SCENE, "s.toml").unwrap();
        let keys: Vec<String> = s.numbers().map(|(k, _)| k).collect();
        let texts: Vec<String> = s.numbers().map(|(_, n)| n.text.clone()).collect();
        let mutable: Vec<(String, String)> =
            s.numbers_mut().map(|(k, n)| (k, n.text.clone())).collect();
        assert_eq!(
            mutable,
            keys.into_iter().zip(texts).collect::<Vec<_>>(),
            "the same numbers under the same keys"
        );
    }

    #[test]
    fn seeding_marks_one_number_and_clears_the_rest() {
        let s = Scene::parse(SCENE, "s.toml").unwrap();
        let one = |k: &str| vec![(k.to_string(), 1.0)];
        for key in [
            "body.mass",
            "body.inertia[2]",
            "contact[1].normal[0]",
            "contact[1].tangent[1]",
            "contact[1].k_energetic",
            "contact[0].mu",
            "constraints.joint[0].normal[2]",
        ] {
            let seeded = seeded(&s, key).unwrap();
            assert_eq!(tangents(&seeded), one(key));
            // Seeding again for another key clears the first.
            let again = super::seeded(&seeded, "body.mass").unwrap();
            assert_eq!(tangents(&again), one("body.mass"));
        }
        assert_eq!(
            tangents(&seeded(&s, "contact[1].k").unwrap()),
            vec![
                ("contact[1].k_newton".to_string(), 1.0),
                ("contact[1].k_poisson".to_string(), 1.0)
            ]
        );
        assert!(seeded(&s, "contact[2].k").is_none());
        assert!(seeded(&s, "body.inertia").is_none());
    }
}
