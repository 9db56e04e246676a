//! Regression: near a singular G the f64 twist after impact inherited cond(G), although the
//! twist is well determined.
//!
//! Two contacts 10⁻⁸ apart with the same normal on a small body: cond₂ G ≈ 1.6·10¹³, and the
//! twist after impact was off by 1.3·10⁻⁴ relative (issue 16; the reconstruction below, a
//! body 2.5 cm across, has cond 2.6·10¹³ and was off by 5.2·10⁻⁴). The impulses were solved from the
//! normal equations G P = b and the twist summed as {v⁰} − Σ P_j W E_j: the split of the impulse
//! between the two contacts is uncertain to cond(G)·ε, and that sum turned the uncertainty into
//! twist although it lies along a wrench difference E_2 − E_1 that hardly moves the body. Float
//! solves of such problems now orthogonalise the wrenches in the metric ηW
//! (`impact::gram_schmidt`: the small wrench E_2 − u E_1 is formed from the data, not from G)
//! and take impulses, twist, contact velocities and energies from that basis; the normal
//! equations are kept only where G is well conditioned enough for them to meet the same
//! bounds (`impact::route`; every scene here takes the orthogonalised wrenches, asserted).
//!
//! **The bounds asserted** are the accuracy contract's (`analysis::accuracy`, where they are
//! derived), first order in ε, with V = ‖v⁰‖_M + ‖Δv‖_M the impact's speed in the
//! kinetic-energy norm and κ = cond₂ G:
//!
//! - twist: ‖δv‖_M ≤ c·ε·(√κ·V + 4·δk·κ·‖v⁰‖_M), with c = μ(2√N(3ℓ + 16N) + 1) — c ≈ 100 for
//!   these two-contact scenes (N = 2, no cancellation in r × n: ℓ = 1; free body: μ = 1). The
//!   κ term, with δk the half-spread of Poisson's k_i, is there only for Poisson with unequal
//!   coefficients, whose twist does depend on the split (then V itself carries the factor
//!   √κ); for Newton and equal coefficients the bound is c·√κ·ε·V;
//! - impulses: ‖δP‖₂ ≤ 4c·ε·(√κ·‖P‖₂ + κ·V/√λ_max(G)), a C·cond(G)·ε bound.
//!
//! Measured before → after (f64, the relative twist error ‖δv‖_M/V; "before" is the normal
//! equations' route, which `twist_from_normal_equations` below reproduces):
//!
//! | scene | cond₂ G | unequal k | equal k |
//! |---|---|---|---|
//! | gap 10⁻⁶ on the unit body | 4.2·10¹² | 2.0·10⁻⁴ → 2.9·10⁻¹¹ | 9.4·10⁻⁵ → 1.2·10⁻¹⁶ |
//! | gap 10⁻⁷ on the unit body | 4.2·10¹⁴ | 4.1·10⁻³ → 5.3·10⁻¹⁰ | 1.9·10⁻³ → 1.3·10⁻¹⁶ |
//! | gap 10⁻¹⁰ on 1 mm | 4.2·10¹⁴ | 4.1·10⁻³ → 1.1·10⁻¹⁰ | 1.9·10⁻³ → 1.1·10⁻¹⁶ |
//! | the issue's: gap 10⁻⁸ on 2.5 cm | 2.6·10¹³ | 5.2·10⁻⁴ → 2.9·10⁻¹¹ | 2.4·10⁻⁴ → 1.1·10⁻¹⁶ |
//! | normals 10⁻⁶ apart | 6.5·10¹² | 8.9·10⁻⁵ → 1.3·10⁻¹⁶ | 4.9·10⁻¹¹ → 4.9·10⁻¹⁷ |
//!
//! With unequal k the twist itself grows like √κ (the contacts must leave at different speeds
//! from points 10⁻⁸ apart) and its error is about 0.06·√κ·ε relative to it, the rounding of the
//! gap itself; with equal k it is ε. The largest ratio of the twist error to c·√κ·ε·V is
//! printed (2·10⁻³); the impulse errors are at most 6·10⁻⁴ of their bound.

use inertance::analysis::accuracy::{Check, Conditioning, measure, speeds};
use inertance::impact::restitution::Model;
use inertance::impact::route::Route;
use inertance::impact::solve::{Impact, Outcome};
use inertance::linalg::{factor_psd, solve_factored};
use inertance::mechanics::screw::Screw;
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;

/// Two contacts on the x-facing side of a body of size `size` (moments 0.4·size², mass 1),
/// at y = size/2 and size/2 + `gap`, normals [1, 0, 0] and `normal2`; k as given.
fn pair(size: &str, gap: &str, normal2: &str, k2: (&str, &str)) -> Scene {
    let text = format!(
        "name = 'gap {gap} on {size}, normal {normal2}'\n\
         [body]\nmass = 1\ninertia = [\"0.4*({size})^2\", \"0.4*({size})^2\", \"0.4*({size})^2\"]\n\
         velocity = [1, 0, 0]\nangular_velocity = [0, 0, \"0.5/({size})\"]\n\
         [[contact]]\npoint = [0, \"({size})/2\", 0]\nnormal = [1, 0, 0]\nk_newton = 0.3\nk_poisson = 0.3\n\
         [[contact]]\npoint = [0, \"({size})/2 + {gap}\", 0]\nnormal = {normal2}\nk_newton = {}\nk_poisson = {}\n",
        k2.0, k2.1
    );
    Scene::parse(&text, "pair").unwrap()
}

/// The scenes of the regression: gaps 10⁻⁴ … 10⁻¹⁰ m on a 1 mm body (gap/size 10⁻¹ … 10⁻⁷,
/// cond up to 2.6·10¹⁴), gaps 10⁻⁴ … 10⁻⁷ on the corpus's unit body, the issue's 10⁻⁸ on
/// 2.5 cm; and normals 10⁻⁴ … 10⁻⁷ apart at one point — each with unequal, then equal k.
fn scenes() -> Vec<Scene> {
    let mut out = Vec::new();
    for k2 in [("0.6", "0.2"), ("0.3", "0.3")] {
        for e in 4..=10 {
            out.push(pair("1e-3", &format!("1e-{e}"), "[1, 0, 0]", k2));
        }
        for e in 4..=7 {
            out.push(pair("1", &format!("1e-{e}"), "[1, 0, 0]", k2));
        }
        out.push(pair("0.025", "1e-8", "[1, 0, 0]", k2));
        for e in 4..=7 {
            out.push(pair("1", "0", &format!("[1, \"1e-{e}\", 0]"), k2));
        }
    }
    out
}

/// The twist by the old route: impulses from the normal equations (pivoted LDLᵀ of the
/// computed G), then {v⁰} − Σ P̂_j W Ê_j.
fn twist_from_normal_equations(impact: &Impact<f64>, model: Model) -> Screw<f64> {
    let n = impact.contacts();
    let mut factor = impact.g_hat().to_vec();
    let mut perm = vec![0; n];
    factor_psd(&mut factor, n, &mut perm).unwrap();
    let contacts = impact.problem().contacts();
    let mut p: Vec<f64> = (0..n)
        .map(|i| match model {
            Model::Newton => (1.0 + contacts[i].k_newton) * impact.before_hat()[i][0],
            Model::Poisson => impact.before_hat()[i][0],
        })
        .collect();
    solve_factored(&factor, n, &perm, &mut p, &mut vec![0.0; n]);
    let mut v = impact.problem().velocity().clone();
    for (i, r) in impact.responses().iter().enumerate() {
        let scale = match model {
            Model::Newton => 1.0,
            Model::Poisson => 1.0 + contacts[i].k_poisson,
        };
        v.add_scaled(&-(scale * p[i]), r);
    }
    v
}

/// ‖a − e‖_M for an f64 twist `a` against the exact `e`.
fn twist_error(impact: &Impact<Exact>, a: &Screw<f64>, e: &Screw<Exact>) -> f64 {
    let mut d = Screw::zero();
    for k in 0..6 {
        d.0[k] = Exact::from(a.0[k].exact_value().unwrap()) - &e.0[k];
    }
    (2.0 * impact.problem().body().kinetic_energy(&d).to_f64()).sqrt()
}

/// Per model: the exact outcome and the contract's checks of the float one (`None`: the
/// float type declared G singular).
type Models = Vec<(Model, Outcome<Exact>, Option<[Check; 5]>)>;

/// Solve `scene` exactly and in `T`: the exact impact, its conditioning, and per model the
/// exact outcome with the float checks.
fn solve_both<T: Scalar>(scene: &Scene) -> (Impact<Exact>, Conditioning, Models) {
    let mut exact = Impact::assemble(&scene.problem::<Exact>().unwrap()).unwrap();
    let cond = Conditioning::of(&mut exact).expect("G is regular");
    let mut float = Impact::assemble(&scene.problem::<T>().unwrap()).unwrap();
    if !float.singular() {
        assert_eq!(
            float.route(),
            Route::OrthogonalWrenches,
            "{}: the orthogonalised wrenches",
            scene.name
        );
    }
    let mut models = Vec::new();
    for m in Model::ALL {
        let (mut e, mut f) = (Outcome::default(), Outcome::default());
        exact.solve(m, &mut e).unwrap();
        let checks = float
            .solve(m, &mut f)
            .ok()
            .map(|()| measure(&exact, &cond, m, &e, &float, &f).expect("finite"));
        models.push((m, e, checks));
    }
    (exact, cond, models)
}

#[test]
fn the_f64_twist_near_a_singular_g_does_not_inherit_its_condition() {
    let mut worst = 0f64;
    let mut solved = 0;
    for scene in scenes() {
        let (exact, cond, models) = solve_both::<f64>(&scene);
        let name = &scene.name;
        assert!(
            cond.cond > 1e2,
            "{name}: a near-singular scene (cond {:e})",
            cond.cond
        );
        for (model, e, checks) in &models {
            let Some([impulses, twist, ..]) = *checks else {
                // Singular to working precision (the unit body with gaps below 10⁻⁷: cond
                // ≳ 10¹⁶), and f64 says so; double-double is tested there below.
                assert!(
                    cond.cond * f64::EPSILON > 1e-3,
                    "{name}: cond {:e}",
                    cond.cond
                );
                continue;
            };
            assert!(
                twist.error <= twist.bound,
                "{name} {model:?}: twist error {:e} > bound {:e} (cond {:e})",
                twist.error,
                twist.bound,
                cond.cond
            );
            assert!(
                impulses.error <= impulses.bound,
                "{name} {model:?}: impulse error {:e} > bound {:e}",
                impulses.error,
                impulses.bound
            );
            let (v0, dv) = speeds(&exact, e);
            let sqrt_bound = cond.constant() * cond.cond.sqrt() * f64::EPSILON * (v0 + dv);
            worst = worst.max(twist.error / sqrt_bound);
            solved += 1;
        }
    }
    assert!(solved >= 40, "the f64 cases ran ({solved})");
    eprintln!("largest twist error / (c·√κ·ε·V) in f64: {worst:.2e}");
}

/// Beyond f64's reach (the unit body, gaps 10⁻⁸ and 10⁻¹⁰: cond 2.6·10¹⁶ and 2.6·10²⁰),
/// double-double meets the same bounds with its own ε = 2⁻¹⁰⁴.
#[test]
fn double_double_meets_the_bounds_where_f64_cannot() {
    for e in [8, 10] {
        for k2 in [("0.6", "0.2"), ("0.3", "0.3")] {
            let scene = pair("1", &format!("1e-{e}"), "[1, 0, 0]", k2);
            let (_, cond, models) = solve_both::<DoubleDouble>(&scene);
            assert!(cond.cond > 1e16, "{}: cond {:e}", scene.name, cond.cond);
            for (model, _, checks) in &models {
                let checks = checks.expect("double-double solves");
                for (what, c) in ["impulses", "twist"].iter().zip(&checks[..2]) {
                    assert!(
                        c.error <= c.bound,
                        "{} {model:?}: {what} error {:e} > bound {:e}",
                        scene.name,
                        c.error,
                        c.bound
                    );
                }
            }
        }
    }
}

/// The issue's scene: contacts 10⁻⁸ apart on a 2.5 cm body, cond₂ G ≈ 1.6·10¹³. The twist by
/// the normal equations' route misses the bound by orders of magnitude (what broke); the solve
/// meets it.
#[test]
fn the_issues_scene_is_solved_within_the_bound() {
    let scene = pair("0.025", "1e-8", "[1, 0, 0]", ("0.6", "0.2"));
    let (exact, cond, models) = solve_both::<f64>(&scene);
    assert!(
        (1e13..3e13).contains(&cond.cond),
        "cond₂ G = {:e}",
        cond.cond
    );
    let float = Impact::assemble(&scene.problem::<f64>().unwrap()).unwrap();
    for (model, e, checks) in &models {
        let twist = checks.expect("f64 solves")[1];
        let (v0, dv) = speeds(&exact, e);
        let old = twist_error(
            &exact,
            &twist_from_normal_equations(&float, *model),
            &e.velocity,
        );
        eprintln!(
            "{model:?}: relative twist error, normal equations {:.1e}, orthogonalised {:.1e}",
            old / (v0 + dv),
            twist.error / (v0 + dv)
        );
        assert!(twist.error <= twist.bound, "{model:?}: {twist:?}");
        assert!(
            old > 100.0 * twist.bound,
            "{model:?}: the old route, {old:e}"
        );
    }
}
