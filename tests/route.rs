//! The route a float solve takes (`impact::route`): the normal equations G x = b where G is
//! well conditioned, the contact wrenches orthogonalised in ηW elsewhere — and that on the
//! problems where the normal equations are taken, the two routes agree within the accuracy
//! contract (`analysis::accuracy`).
//!
//! - Example 3 (two contacts, the cosine of their wrenches 0.19) takes the normal equations in
//!   f32, f64 and double-double; two contacts 10⁻⁸ apart, a constrained body and a body with a
//!   full inertia tensor take the orthogonalised wrenches; exact types always take G x = b.
//! - On the contract's corpora (the hard cases and the scenes spanning ratios of 10^±12) both
//!   routes are taken in f64, and on every problem routed to the normal equations, in each
//!   float type, the orthogonalised wrenches' outcome is computed too: both are within the
//!   contract's bounds of the exact outcome, and the normal equations' within the same bounds
//!   of the orthogonalised wrenches'.

use std::path::Path;

use inertance::analysis::accuracy::{Conditioning, Output, measure};
use inertance::impact::route::{Route, correlation, correlation_limit, theta_limit};
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::screw::Screw;
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::scene::pipeline::prepare;
use inertance::tools::accuracy::{hard_cases, ratio_scenes};

const EXAMPLE_3: &str = "name = 'example 3'\n[body]\nmass = 1\ninertia = [12, 1.6, 12]\n\
    velocity = [3, 2, 0]\nangular_velocity = [0, 0, 0.4]\n\
    [[contact]]\npoint = [0, -2, 0]\nnormal = [1, 0, 0]\nk = 0.3\n\
    [[contact]]\npoint = [0, 4, 0]\nnormal = [1, 0, 0]\nk = 0.2\n";

/// Two contacts 10⁻⁸ apart with the same normal (cond₂ G ≈ 10¹³ on this 2.5 cm body).
const PAIR: &str = "name = 'pair'\n[body]\nmass = 1\ninertia = ['2.5e-4', '2.5e-4', '2.5e-4']\n\
    velocity = [1, 0, 0]\nangular_velocity = [0, 0, 20]\n\
    [[contact]]\npoint = [0, 0.0125, 0]\nnormal = [1, 0, 0]\nk = 0.3\n\
    [[contact]]\npoint = [0, 0.01250001, 0]\nnormal = [1, 0, 0]\nk = 0.6\n";

/// The paper's Example 6: a body held by a revolute and a prismatic joint.
const EXAMPLE_6: &str = "name = 'example 6'\n[body]\nmass = 10\n\
    inertia = ['10/3', '10/3', '10/3']\nvelocity = [0, 0, 0]\nangular_velocity = [0, 0, 1]\n\
    [[contact]]\npoint = [0, '-1/3', 0]\nnormal = [1, 0, 0]\nk = 0.5\n\
    [[contact]]\npoint = [0, '1/3', 0]\nnormal = [1, 0, 0]\nk = 0.25\n\
    [[constraints.joint]]\nkind = 'revolute'\npoint = [0, -1, 0]\naxis = [0, 0, 1]\n\
    [[constraints.joint]]\nkind = 'prismatic'\naxis = [1, 0, 0]\n";

fn route_of<T: Scalar>(text: &str) -> Route {
    let scene = Scene::parse(text, "route").unwrap();
    Impact::assemble(&prepare::<T>(&scene).unwrap())
        .unwrap()
        .route()
}

fn every_route(text: &str) -> [Route; 4] {
    [
        route_of::<f32>(text),
        route_of::<f64>(text),
        route_of::<DoubleDouble>(text),
        route_of::<Exact>(text),
    ]
}

#[test]
fn a_well_conditioned_scene_takes_the_normal_equations_and_a_near_singular_one_does_not() {
    use Route::{NormalEquations as Normal, OrthogonalWrenches as Orthogonal};
    assert_eq!(every_route(EXAMPLE_3), [Normal; 4]);
    assert_eq!(
        every_route(PAIR),
        [Orthogonal, Orthogonal, Orthogonal, Normal]
    );
    // Constraints: the bound of the normal equations' rounding needs ℓ and μ.
    assert_eq!(
        every_route(EXAMPLE_6),
        [Orthogonal, Orthogonal, Orthogonal, Normal]
    );
    // Example 3's G: ĝ_12/(ĝ_11 ĝ_22)^½ = (1/3)/(4/3 · 7/3)^½ ≈ 0.189.
    let scene = Scene::parse(EXAMPLE_3, "route").unwrap();
    let impact = Impact::assemble(&scene.problem::<f64>().unwrap()).unwrap();
    let s = correlation(impact.g_hat(), 2);
    assert!((s - 1.0 / 28f64.sqrt()).abs() < 1e-15, "{s}");
    assert!(s <= correlation_limit(2) && correlation_limit(2) <= 1.0 - 1.0 / theta_limit(2));
}

/// A full inertia tensor keeps the orthogonalised wrenches however well conditioned G is (the
/// normal equations' bound would need cond J); the same body in principal axes does not.
#[test]
fn a_full_inertia_tensor_takes_the_orthogonalised_wrenches() {
    let scene = Scene::parse(EXAMPLE_3, "route").unwrap();
    let principal = scene.problem::<f64>().unwrap();
    let (_, twist, contacts) = principal.clone().into_parts();
    let j = [[12.0, 0.5, 0.0], [0.5, 1.6, 0.0], [0.0, 0.0, 12.0]];
    let tensor = inertance::Problem::new(RigidBody::with_tensor(1.0, j), twist, contacts).unwrap();
    assert_eq!(
        Impact::assemble(&principal).unwrap().route(),
        Route::NormalEquations
    );
    assert_eq!(
        Impact::assemble(&tensor).unwrap().route(),
        Route::OrthogonalWrenches
    );
}

/// The scene in the units float solves use (as `tools::accuracy` does).
fn in_solver_units(scene: &Scene) -> Scene {
    inertance::scene::scale::scale(scene).map_or_else(|| scene.clone(), |(s, _)| s)
}

/// The exact value of a float outcome, as an outcome in rationals.
fn exact_outcome<T: Scalar>(o: &Outcome<T>) -> Outcome<Exact> {
    let x = |x: &T| -> Exact { x.exact_value().unwrap().into() };
    let all = |v: &[T]| -> Vec<Exact> { v.iter().map(x).collect() };
    let screw = |s: &Screw<T>| {
        let mut e = Screw::zero();
        for k in 0..6 {
            e.0[k] = x(&s.0[k]);
        }
        e
    };
    Outcome {
        impulses_hat: all(&o.impulses_hat),
        compression_hat: all(&o.compression_hat),
        velocity: screw(&o.velocity),
        after_hat: o
            .after_hat
            .iter()
            .map(|a| a.clone().map(|v| x(&v)))
            .collect(),
        lost_velocity_energy: x(&o.lost_velocity_energy),
        kinetic_energy_loss: x(&o.kinetic_energy_loss),
        constraint_impulses: all(&o.constraint_impulses),
        constraint_wrench: screw(&o.constraint_wrench),
    }
}

/// How many problems took the normal equations in `T`, the orthogonalised wrenches, and the
/// normal equations with more than one contact; and for those routed to the normal equations
/// the largest ratio error/bound of (normal equations vs exact, orthogonalised vs exact,
/// normal equations vs orthogonalised), asserting each at most 1.
fn agreement<T: Scalar>(scenes: &[Scene]) -> ([usize; 3], [f64; 3]) {
    let mut taken = [0, 0, 0];
    let mut worst = [0f64; 3];
    for scene in scenes {
        let scene = in_solver_units(scene);
        let Ok(problem) = prepare::<Exact>(&scene) else {
            continue;
        };
        let mut exact = Impact::assemble(&problem).unwrap();
        let Some(cond) = Conditioning::of(&mut exact) else {
            continue;
        };
        let Ok(mut float) = prepare::<T>(&scene).map(|p| Impact::assemble(&p).unwrap()) else {
            continue;
        };
        if float.singular() {
            continue;
        }
        if float.route() == Route::OrthogonalWrenches {
            taken[1] += 1;
            continue;
        }
        taken[0] += 1;
        if float.contacts() > 1 {
            taken[2] += 1;
        }
        for &model in &scene.models {
            let (mut e, mut normal, mut orthogonal) =
                (Outcome::default(), Outcome::default(), Outcome::default());
            exact.solve(model, &mut e).unwrap();
            float.solve(model, &mut normal).unwrap();
            float.solve_orthogonal(model, &mut orthogonal).unwrap();
            let reference = exact_outcome(&orthogonal);
            let checks = [
                measure(&exact, &cond, model, &e, &float, &normal),
                measure(&exact, &cond, model, &e, &float, &orthogonal),
                measure(&exact, &cond, model, &reference, &float, &normal),
            ];
            for (k, c) in checks.iter().enumerate() {
                for (o, c) in Output::ALL.iter().zip(c.expect("finite")) {
                    assert!(
                        c.error <= c.bound,
                        "{} {}, {model:?}, {}: {} error {:e} > bound {:e} (cond {:e})",
                        T::NAME,
                        scene.name,
                        [
                            "normal equations",
                            "orthogonalised",
                            "normal vs orthogonalised"
                        ][k],
                        o.name(),
                        c.error,
                        c.bound,
                        cond.cond
                    );
                    worst[k] = worst[k].max(c.ratio());
                }
            }
        }
    }
    (taken, worst)
}

fn corpus() -> Vec<Scene> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/hard_cases");
    let mut scenes = hard_cases(&dir);
    scenes.extend(ratio_scenes(120, 0x5eed_0016));
    scenes
}

#[test]
fn both_routes_are_taken_on_the_corpus_and_agree_within_the_contract() {
    let scenes = corpus();
    for (name, (taken, worst)) in [
        (f32::NAME, agreement::<f32>(&scenes)),
        (f64::NAME, agreement::<f64>(&scenes)),
        (DoubleDouble::NAME, agreement::<DoubleDouble>(&scenes)),
    ] {
        eprintln!(
            "{name}: {} problems took the normal equations ({} of them with several contacts), \
             {} the orthogonalised wrenches; largest error/bound: normal equations {:.1e}, \
             orthogonalised {:.1e}, between them {:.1e}",
            taken[0], taken[2], taken[1], worst[0], worst[1], worst[2]
        );
        assert!(
            taken[0] >= 20 && taken[1] >= 20 && taken[2] >= 5,
            "{name}: {taken:?}"
        );
    }
}

/// Problems with two to four contacts that take the normal equations (Example 3's points;
/// three pure forces along the axes, C = I; the same with a fourth contact whose wrench has
/// the cosine 1/2 with one of them): the routes agree within the contract.
#[test]
fn the_routes_agree_on_well_conditioned_scenes_with_several_contacts() {
    let mut scenes = Vec::new();
    for (i, points) in [
        vec!["[0, -2, 0]", "[0, 4, 0]"],
        vec!["[1, 0, 0]", "[0, 1, 0]", "[0, 0, 1]"],
        vec!["[0.5, 0, 0]", "[0, 0.5, 0]", "[0, 0, 0.5]", "[0, 0, 1]"],
    ]
    .iter()
    .enumerate()
    {
        let mut text = format!(
            "name = 'well {i}'\n[body]\nmass = 3\ninertia = [1, 2, 3]\n\
             velocity = [1, -2, 0.5]\nangular_velocity = [0.3, 0.1, -0.2]\n"
        );
        let normals = ["[1, 0, 0]", "[0, 1, 0]", "[0, 0, 1]", "[0, 1, 0]"];
        for (j, p) in points.iter().enumerate() {
            text += &format!(
                "[[contact]]\npoint = {p}\nnormal = {}\nk_newton = 0.{}\nk_poisson = 0.{}\n",
                normals[j],
                j + 2,
                7 - j
            );
        }
        scenes.push(Scene::parse(&text, "well").unwrap());
    }
    let (taken, worst) = agreement::<f64>(&scenes);
    assert_eq!(taken, [3, 0, 3], "every scene takes the normal equations");
    eprintln!("largest error/bound between the routes: {:.1e}", worst[2]);
}

/// Random scenes of unit scale (a free body in principal axes, two to five contacts, points
/// in [−1, 1]³ with two decimals, integer normals), seeded: many of them take the normal
/// equations, and there they are within the contract of the exact outcome, in every float
/// type, as are the orthogonalised wrenches.
#[test]
fn random_well_conditioned_scenes_are_within_the_contract() {
    let mut state = 0x0015_2026_u64;
    let mut pick = |lo: i64, hi: i64| {
        // SplitMix64: a fixed, portable sequence.
        state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = state;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        lo + ((z ^ (z >> 31)) % (hi - lo + 1) as u64) as i64
    };
    let mut scenes = Vec::new();
    for i in 0..150 {
        let mut text = format!(
            "name = 'random {i}'\n[body]\nmass = {}\ninertia = [{}, {}, {}]\n\
             velocity = [{}, {}, {}]\nangular_velocity = [{}, {}, {}]\n",
            pick(1, 20),
            pick(1, 20),
            pick(1, 20),
            pick(1, 20),
            pick(-9, 9),
            pick(-9, 9),
            pick(-9, 9),
            pick(-9, 9),
            pick(-9, 9),
            pick(-9, 9),
        );
        for _ in 0..pick(2, 5) {
            let point: Vec<String> = (0..3)
                .map(|_| format!("{}", pick(-100, 100) as f64 / 100.0))
                .collect();
            let normal = loop {
                let n: Vec<i64> = (0..3).map(|_| pick(-3, 3)).collect();
                if n.iter().any(|&x| x != 0) {
                    break n;
                }
            };
            text += &format!(
                "[[contact]]\npoint = [{}]\nnormal = {normal:?}\nk_newton = 0.{}\nk_poisson = 0.{}\n",
                point.join(", "),
                pick(0, 9),
                pick(0, 9)
            );
        }
        scenes.push(Scene::parse(&text, "random").unwrap());
    }
    for (name, (taken, worst)) in [
        (f32::NAME, agreement::<f32>(&scenes)),
        (f64::NAME, agreement::<f64>(&scenes)),
        (DoubleDouble::NAME, agreement::<DoubleDouble>(&scenes)),
    ] {
        eprintln!(
            "{name}: {} random scenes took the normal equations, {} the orthogonalised \
             wrenches; largest error/bound: normal equations {:.1e}, between the routes {:.1e}",
            taken[2], taken[1], worst[0], worst[2]
        );
        assert!(taken[2] >= 30, "{name}: {taken:?}");
    }
}
