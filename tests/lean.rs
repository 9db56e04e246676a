//! The lean path (`impact::lean`) and the batch (`impact::batch`) against the generic solve:
//! exact equality in rationals, the accuracy contract in f64 against the exact solve of the
//! rounded problem, refusals of singular and ill-conditioned inputs, and the batch equal bit
//! for bit to the single-scene lean path.

mod common;

use common::*;
use inertance::analysis::accuracy::{Bounds, Conditioning};
use inertance::impact::batch::{self, BatchError, Outcomes, Reason, Route, Scenes};
use inertance::impact::lean::{Lean, LeanError, LeanOutcome};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar};
use num_traits::Zero;
use proptest::prelude::*;

/// The generic solve of `model`; `None` when G is singular.
fn generic<T: Scalar>(p: &Problem<T>, model: Model) -> Option<(Impact<T>, Outcome<T>)> {
    let mut impact = Impact::assemble(p).ok()?;
    let mut out = Outcome::default();
    impact.solve(model, &mut out).ok()?;
    Some((impact, out))
}

/// Lean over exact rationals against the generic exact solve, for N contacts: the same
/// numbers exactly, and a singular G refused by both.
fn exact_agrees<const N: usize>(p: &Problem<Exact>) {
    let lean = Lean::<Exact, N>::new(p);
    for model in Model::ALL {
        match (&lean, generic(p, model)) {
            (Ok(lean), Some((_, out))) => {
                let o = lean.solve(model).expect("exact outputs are finite");
                assert_eq!(o.impulses_hat.to_vec(), out.impulses_hat, "{model:?}");
                assert_eq!(o.twist(), out.velocity, "{model:?}");
            }
            (Err(LeanError::Singular { .. }), None) => {}
            (l, g) => panic!("lean {l:?} but generic {:?}", g.map(|x| x.1)),
        }
    }
}

/// The contract's impulse and twist bounds (`analysis::accuracy`) for a float solve with
/// epsilon `eps` of `model`, and the measured errors of `o`: (error, bound) for each.
fn contract<const N: usize>(
    exact: &Problem<Exact>,
    model: Model,
    o: &LeanOutcome<f64, N>,
) -> [(f64, f64); 2] {
    let (mut impact, out) = generic(exact, model).expect("nonsingular");
    let cond = Conditioning::of(&mut impact).expect("nonsingular");
    let bounds = Bounds::of(&impact, &cond, model, &out, f64::EPSILON);
    let mut diff2 = Exact::zero();
    for (i, contact) in exact.contacts().iter().enumerate() {
        let n2: Exact = contact.normal.iter().map(|x| x * x).sum();
        let d = Exact::from(o.impulses_hat[i].exact_value().unwrap()) - &out.impulses_hat[i];
        diff2 += &d * &d * &n2;
    }
    let mut dvel = Screw::<Exact>::zero();
    for k in 0..6 {
        dvel.0[k] = Exact::from(o.velocity[k].exact_value().unwrap()) - &out.velocity.0[k];
    }
    let twist = (2.0 * exact.body().kinetic_energy(&dvel).to_f64()).sqrt();
    [
        (diff2.to_f64().sqrt(), bounds.impulses),
        (twist, bounds.twist),
    ]
}

/// Lean in f64 against the exact solve of the same (rounded) problem: when it accepts the
/// problem, impulses and twist within the accuracy contract; when it refuses, the reason is
/// a singular or ill-conditioned G, never a non-finite output.
fn float_within_contract<const N: usize>(p: &Problem<Exact>) {
    let float = convert::<f64>(p);
    let exact = exact_of(&float);
    let lean = match Lean::<f64, N>::new(&float) {
        Ok(lean) => lean,
        Err(LeanError::Singular { .. } | LeanError::IllConditioned { .. }) => return,
        Err(e) => panic!("{e}"),
    };
    for model in Model::ALL {
        let o = lean.solve(model).expect("finite for small inputs");
        if generic(&exact, model).is_none() {
            // Exactly singular, yet the f64 pivots came out positive and the test passed:
            // cannot happen, the exact cosine is then 1.
            panic!("lean accepted an exactly singular G");
        }
        for (what, (error, bound)) in ["impulses", "twist"]
            .iter()
            .zip(contract(&exact, model, &o))
        {
            assert!(
                error <= bound,
                "{model:?} {what}: error {error:e} > contract {bound:e}"
            );
        }
    }
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 128,
        ..ProptestConfig::default()
    }
}

/// A problem with exactly `n` contacts.
fn problem_n(n: usize) -> impl Strategy<Value = Problem<Exact>> {
    problem(n).prop_filter("n contacts", move |p| p.contacts().len() == n)
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn exact_lean_is_the_generic_solve_2(p in problem_n(2)) {
        exact_agrees::<2>(&p);
    }

    #[test]
    fn exact_lean_is_the_generic_solve_3(p in problem_n(3)) {
        exact_agrees::<3>(&p);
    }

    #[test]
    fn exact_lean_is_the_generic_solve_1(p in problem_n(1)) {
        exact_agrees::<1>(&p);
    }

    #[test]
    fn f64_lean_keeps_the_contract_2(p in problem_n(2)) {
        float_within_contract::<2>(&p);
    }

    #[test]
    fn f64_lean_keeps_the_contract_3(p in problem_n(3)) {
        float_within_contract::<3>(&p);
    }

    #[test]
    fn f64_lean_keeps_the_contract_4(p in problem_n(4)) {
        float_within_contract::<4>(&p);
    }

    /// The batch, bit for bit the single-scene lean path on the scenes it accepts; the
    /// generic f64 solve on the others.
    #[test]
    fn batch_is_the_lean_path(ps in prop::collection::vec(problem_n(2), 1..12)) {
        let floats: Vec<Problem<f64>> = ps.iter().map(convert::<f64>).collect();
        let mut scenes = Scenes::<2>::default();
        for p in &floats {
            scenes.push(p).unwrap();
        }
        let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
        batch::solve_both(&scenes, &mut newton, &mut poisson).unwrap();
        for (model, out) in [(Model::Newton, &newton), (Model::Poisson, &poisson)] {
            let mut single = Outcomes::default();
            batch::solve(&scenes, model, &mut single).unwrap();
            prop_assert_eq!(&single, out);
            for (s, p) in floats.iter().enumerate() {
                let got: Vec<f64> = (0..2).map(|j| out.impulses_hat[j][s])
                    .chain((0..6).map(|k| out.velocity[k][s])).collect();
                match (out.routes[s], Lean::<f64, 2>::new(p)) {
                    (Route::Lean, Ok(lean)) => {
                        let o = lean.solve(model).unwrap();
                        let want: Vec<f64> = o.impulses_hat.iter().chain(&o.velocity).cloned().collect();
                        prop_assert_eq!(got.iter().map(|x| x.to_bits()).collect::<Vec<_>>(),
                            want.iter().map(|x| x.to_bits()).collect::<Vec<_>>());
                    }
                    (Route::Generic, Err(_)) => {
                        let (_, o) = generic(p, model).unwrap();
                        let want: Vec<f64> = o.impulses_hat.iter().chain(o.velocity.as_slice()).cloned().collect();
                        prop_assert_eq!(got, want);
                    }
                    (Route::Refused, Err(_)) => {
                        prop_assert!(generic(p, model).is_none());
                        prop_assert!(got.iter().all(|x| *x == 0.0));
                    }
                    (r, l) => prop_assert!(false, "batch route {:?}, lean {:?}", r, l.err()),
                }
            }
        }
    }
}

/// Example 3's body and velocity with two contacts along x at heights `y1`, `y2`.
fn two_contacts(y1: f64, y2: f64) -> Problem<f64> {
    valid(
        RigidBody::principal(1.0, Vec3::new(12.0, 1.6, 12.0)),
        Screw::new(Vec3::new(0.0, 0.0, 0.4), Vec3::new(3.0, 2.0, 0.0)),
        vec![
            Contact::new(Vec3::new(0.0, y1, 0.0), Vec3::new(1.0, 0.0, 0.0), 0.3),
            Contact::new(Vec3::new(0.0, y2, 0.0), Vec3::new(1.0, 0.0, 0.0), 0.2),
        ],
    )
}

#[test]
fn example_3_in_f64_matches_the_generic_solve() {
    let p = two_contacts(-2.0, 4.0);
    let lean = Lean::<f64, 2>::new(&p).expect("well conditioned");
    for model in Model::ALL {
        let o = lean.solve(model).unwrap();
        let (_, g) = generic(&p, model).unwrap();
        // Both within the contract of the exact answer; here (cond G ≈ 2) within 8 ε of
        // each other relative to the largest entry.
        let scale = g
            .impulses_hat
            .iter()
            .chain(g.velocity.as_slice())
            .fold(0.0f64, |a, x| a.max(x.abs()));
        for (a, b) in o
            .impulses_hat
            .iter()
            .chain(&o.velocity)
            .zip(g.impulses_hat.iter().chain(g.velocity.as_slice()))
        {
            assert!((a - b).abs() <= 8.0 * f64::EPSILON * scale, "{a} vs {b}");
        }
    }
}

#[test]
fn coincident_contacts_are_refused() {
    // The same contact twice: G exactly singular.
    let p = two_contacts(4.0, 4.0);
    assert!(matches!(
        Lean::<f64, 2>::new(&p),
        Err(LeanError::Singular { .. } | LeanError::IllConditioned { .. })
    ));
    let e = exact_of(&p);
    assert_eq!(
        Lean::<Exact, 2>::new(&e),
        Err(LeanError::Singular { pivot: 1 })
    );
}

#[test]
fn nearly_coincident_contacts_take_the_generic_route() {
    // Contacts 10⁻⁵ apart: cond G ≈ 10¹¹ — the normal equations would lose the contract.
    let p = two_contacts(4.0, 4.0 + 1e-5);
    let Err(LeanError::IllConditioned { spread }) = Lean::<f64, 2>::new(&p) else {
        panic!("accepted a nearly singular G");
    };
    let s = inertance::impact::route::correlation_limit(2);
    assert!(spread > s * s && spread <= 1.0);
    let mut scenes = Scenes::<2>::default();
    scenes.push(&p).unwrap();
    let mut out = Outcomes::default();
    batch::solve(&scenes, Model::Newton, &mut out).unwrap();
    assert_eq!(out.routes, [Route::Generic]);
    assert!(matches!(
        out.reasons[0],
        (0, Reason::Lean(LeanError::IllConditioned { .. }))
    ));
}

#[test]
fn wrong_count_and_constraints_are_refused() {
    let p = two_contacts(-2.0, 4.0);
    assert_eq!(
        Lean::<f64, 3>::new(&p),
        Err(LeanError::Contacts {
            expected: 3,
            found: 2
        })
    );
}

#[test]
fn overflow_is_an_error_not_nan() {
    let p = valid(
        RigidBody::principal(1e-300, Vec3::new(1e-300, 1e-300, 1e-300)),
        Screw::new(Vec3::new(1e300, 0.0, 0.4), Vec3::new(1e300, 2.0, 0.0)),
        vec![
            Contact::new(Vec3::new(0.0, -1e300, 0.0), Vec3::new(1e300, 0.0, 0.0), 0.3),
            Contact::new(Vec3::new(0.0, 1e300, 0.0), Vec3::new(1.0, 1e300, 0.0), 0.2),
        ],
    );
    match Lean::<f64, 2>::new(&p) {
        Ok(lean) => {
            for model in Model::ALL {
                match lean.solve(model) {
                    Ok(o) => assert!(
                        o.impulses_hat
                            .iter()
                            .chain(&o.velocity)
                            .all(|x| x.is_finite())
                    ),
                    Err(e) => assert_eq!(e, LeanError::NotFinite),
                }
            }
        }
        Err(e) => assert!(
            matches!(
                e,
                LeanError::Singular { .. } | LeanError::IllConditioned { .. }
            ),
            "{e}"
        ),
    }
}

#[test]
fn batch_refuses_invalid_scenes_and_ragged_arrays() {
    let mut scenes = Scenes::<2>::default();
    for y in [-2.0, -3.0, -1.0, -4.0, -2.5] {
        // |c₁₂| ≤ 0.42 for each against the contact at y = 4: the lean route.
        scenes.push(&two_contacts(y, 4.0)).unwrap();
    }
    scenes.mass[3] = -1.0;
    scenes.k_newton[1][4] = 1.5;
    let mut out = Outcomes::default();
    batch::solve(&scenes, Model::Newton, &mut out).unwrap();
    assert_eq!(
        out.routes,
        [
            Route::Lean,
            Route::Lean,
            Route::Lean,
            Route::Refused,
            Route::Refused
        ]
    );
    assert!(matches!(out.reasons[0], (3, Reason::Invalid(_))));
    assert!(matches!(out.reasons[1], (4, Reason::Invalid(_))));
    assert!(out.velocity.iter().all(|v| v[3] == 0.0 && v[4] == 0.0));
    scenes.velocity[2].pop();
    assert_eq!(
        batch::solve(&scenes, Model::Newton, &mut out),
        Err(BatchError::Lengths {
            what: "velocity[2]".into(),
            found: 4,
            expected: 5
        })
    );
}

#[test]
fn a_full_inertia_tensor_takes_the_generic_route_in_floats_and_is_exact_in_rationals() {
    // The route's proof (impact::route) needs principal axes: a float Lean refuses a tensor;
    // an exact one gives the generic exact solve's numbers.
    let text = r#"
[body]
mass = 2
inertia = [[3, "1/2", 0], ["1/2", 4, 1], [0, 1, 5]]
velocity = [0, -1, 0]
angular_velocity = [0, 0, "1/3"]
[[contact]]
point = [1, -1, 0]
normal = [0, 1, 0]
k = "1/2"
[[contact]]
point = [-1, -1, "1/2"]
normal = [0, 1, 0]
k = "1/4"
"#;
    let scene = inertance::scene::Scene::parse(text, "tensor.toml").unwrap();
    let float = scene.problem::<f64>().unwrap();
    assert_eq!(Lean::<f64, 2>::new(&float), Err(LeanError::Tensor));
    let exact = scene.problem::<Exact>().unwrap();
    let lean = Lean::<Exact, 2>::new(&exact).unwrap();
    for model in Model::ALL {
        let o = lean.solve(model).unwrap();
        let (_, g) = generic(&exact, model).unwrap();
        assert_eq!(o.impulses_hat.to_vec(), g.impulses_hat);
        assert_eq!(o.twist(), g.velocity);
    }
}
