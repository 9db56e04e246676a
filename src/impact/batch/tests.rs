//! The batch at every lane width against the one-by-one lean path, bit for bit, on seeded
//! random scenes mixed with scenes the lean route refuses, singular ones and invalid ones, at
//! batch lengths that are not multiples of the width.

use super::*;
use crate::impact::lean::Lean;
use crate::tools::bench::Seeded;
use crate::tools::lean_bench::{example_3_class, random_boxes};

/// A uniform draw in [lo, hi).
fn uniform(rng: &mut Seeded, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * (rng.next() >> 11) as f64 / (1u64 << 53) as f64
}

/// A random free body hit at N contacts (points in [−2, 2]³, normals in [−1, 1]³ with
/// n_z = 1), then spoiled according to `kind` mod 8: 0–3 as drawn, 4 a contact repeated
/// 10⁻⁶ away (the lean route refuses it), 5 a contact repeated exactly (G singular: no
/// answer), 6 and 7 invalid input (negative mass, NaN velocity, k > 1 or a zero normal).
fn scene<const N: usize>(rng: &mut Seeded, kind: u64) -> Scenes<N> {
    let mut v3 = |lo: f64, hi: f64| {
        Vec3::new(
            uniform(rng, lo, hi),
            uniform(rng, lo, hi),
            uniform(rng, lo, hi),
        )
    };
    let body = RigidBody::principal(v3(0.5, 5.0)[0], v3(0.5, 5.0));
    let velocity = Screw::new(v3(-3.0, 3.0), v3(-3.0, 3.0));
    let mut contacts: Vec<Contact<f64>> = (0..N)
        .map(|_| {
            let (p, mut n, k) = (v3(-2.0, 2.0), v3(-1.0, 1.0), v3(0.0, 1.0));
            n[2] = 1.0;
            Contact::new(p, n, k[0]).with_coefficients(k[0], k[1])
        })
        .collect();
    match kind % 8 {
        4 => {
            contacts[N - 1] = contacts[0].clone();
            contacts[N - 1].point[0] += 1e-6;
        }
        5 => contacts[N - 1] = contacts[0].clone(),
        _ => {}
    }
    let problem = Problem::new(body, velocity, contacts).expect("valid as drawn");
    let mut s = Scenes::default();
    s.push(&problem).expect("a free body in principal axes");
    match kind % 8 {
        6 => s.mass[0] = -1.0,
        7 => match kind / 8 % 3 {
            0 => s.velocity[4][0] = f64::NAN,
            1 => s.k_poisson[N - 1][0] = 1.5,
            _ => {
                for k in 0..3 {
                    s.normals[0][k][0] = 0.0;
                }
            }
        },
        _ => {}
    }
    s
}

/// `count` scenes of [`scene`], kinds drawn at random.
fn mixed<const N: usize>(rng: &mut Seeded, count: usize) -> Scenes<N> {
    let mut all = Scenes::<N>::default();
    for _ in 0..count {
        let kind = rng.next() % 24;
        let s = scene::<N>(rng, kind);
        append(&mut all, &s);
    }
    all
}

/// `b`'s scenes after `a`'s.
fn append<const N: usize>(a: &mut Scenes<N>, b: &Scenes<N>) {
    a.mass.extend(&b.mass);
    for k in 0..3 {
        a.inertia[k].extend(&b.inertia[k]);
    }
    for k in 0..6 {
        a.velocity[k].extend(&b.velocity[k]);
    }
    for i in 0..N {
        for k in 0..3 {
            a.points[i][k].extend(&b.points[i][k]);
            a.normals[i][k].extend(&b.normals[i][k]);
        }
        a.k_newton[i].extend(&b.k_newton[i]);
        a.k_poisson[i].extend(&b.k_poisson[i]);
    }
}

/// Both models at L lanes, without dispatch (compiled for the default target).
fn at_width<const L: usize, const N: usize>(scenes: &Scenes<N>) -> [Outcomes<N>; 2] {
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    newton.reset(scenes.len());
    poisson.reset(scenes.len());
    sweep::sweep::<L, N>(
        scenes,
        &mut [(Model::Newton, &mut newton), (Model::Poisson, &mut poisson)],
    );
    [newton, poisson]
}

/// Scene s's outputs in `out`, as bits.
fn bits<const N: usize>(out: &Outcomes<N>, s: usize) -> Vec<u64> {
    out.impulses_hat
        .iter()
        .chain(&out.velocity)
        .map(|v| v[s].to_bits())
        .collect()
}

/// Every scene of `outs` (Newton, Poisson) against its one-by-one solve: the lean path's bits
/// where it answers, the generic solve's where the lean route refuses, zeros and
/// [`Route::Refused`] where neither answers.
fn agrees_one_by_one<const N: usize>(scenes: &Scenes<N>, outs: &[Outcomes<N>; 2]) {
    for (model, out) in Model::ALL.into_iter().zip(outs) {
        assert_eq!(out.routes.len(), scenes.len());
        let mut reasons = out.reasons.iter();
        for s in 0..scenes.len() {
            let problem = scenes.problem(s);
            let lean = problem
                .as_ref()
                .ok()
                .and_then(|p| Lean::<f64, N>::new(p).ok())
                .and_then(|l| l.solve(model).ok());
            match (out.routes[s], lean) {
                (Route::Lean, Some(o)) => {
                    let want: Vec<u64> = o
                        .impulses_hat
                        .iter()
                        .chain(&o.velocity)
                        .map(|x| x.to_bits())
                        .collect();
                    assert_eq!(bits(out, s), want, "scene {s}, {model:?}");
                }
                (Route::Generic, None) => {
                    let p = problem.expect("the generic route answered a valid scene");
                    let mut impact = Impact::assemble(&p).expect("nonsingular");
                    let mut o = Outcome::default();
                    impact.solve(model, &mut o).expect("solvable");
                    let want: Vec<u64> = o
                        .impulses_hat
                        .iter()
                        .chain(o.velocity.as_slice())
                        .map(|x| x.to_bits())
                        .collect();
                    assert_eq!(bits(out, s), want, "scene {s}, {model:?}");
                    let reason = reasons
                        .next()
                        .expect("a reason per scene off the lean route");
                    assert!(matches!(reason, (r, Reason::Lean(_)) if *r == s));
                }
                (Route::Refused, None) => {
                    assert!(bits(out, s).iter().all(|b| *b == 0), "scene {s}");
                    let reason = reasons
                        .next()
                        .expect("a reason per scene off the lean route");
                    assert_eq!(reason.0, s);
                    match &reason.1 {
                        Reason::Invalid(_) => assert!(problem.is_err()),
                        Reason::Unsolvable(_) => {
                            let p = problem.expect("a valid scene");
                            let solved = Impact::assemble(&p).and_then(|mut i| {
                                i.solve(model, &mut Outcome::default()).map(|_| ())
                            });
                            assert!(solved.is_err(), "scene {s}: the generic solve answers");
                        }
                        Reason::Lean(e) => panic!("scene {s} refused for {e}"),
                    }
                }
                (route, lean) => panic!("scene {s}, {model:?}: batch {route:?}, lean {lean:?}"),
            }
        }
        assert!(reasons.next().is_none());
    }
}

/// Every width, and the dispatched one, on `scenes`: each agrees with the one-by-one solve,
/// and all agree with each other bit for bit.
fn check<const N: usize>(scenes: &Scenes<N>) {
    let widths = [
        at_width::<2, N>(scenes),
        at_width::<4, N>(scenes),
        at_width::<8, N>(scenes),
    ];
    for outs in &widths {
        agrees_one_by_one(scenes, outs);
    }
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    solve_both(scenes, &mut newton, &mut poisson).expect("arrays of one length");
    let mut single = Outcomes::default();
    solve(scenes, Model::Poisson, &mut single).expect("arrays of one length");
    assert_eq!(single, poisson);
    for outs in &widths {
        let same = |a: &Outcomes<N>, b: &Outcomes<N>| {
            (0..scenes.len()).all(|s| bits(a, s) == bits(b, s)) && a.routes == b.routes
        };
        assert!(same(&outs[0], &newton) && same(&outs[1], &poisson));
    }
}

#[test]
fn every_width_is_the_lean_path_one_by_one_two_contacts() {
    let mut rng = Seeded(0x5eed_0002);
    let mut seen = Vec::new();
    // 1 … 19 scenes and 61: every remainder modulo 2, 4 and 8.
    for count in (1..=19).chain([61]) {
        let scenes = mixed::<2>(&mut rng, count);
        check(&scenes);
        let mut out = Outcomes::default();
        solve(&scenes, Model::Newton, &mut out).expect("arrays of one length");
        seen.extend(out.routes);
    }
    // Every route was taken: the sample exercises the fallback and the refusals.
    for route in [Route::Lean, Route::Generic, Route::Refused] {
        assert!(seen.contains(&route), "{route:?} never taken");
    }
}

#[test]
fn every_width_is_the_lean_path_one_by_one_three_and_four_contacts() {
    let mut rng = Seeded(0x5eed_0034);
    for count in [1, 3, 7, 9, 13, 30] {
        check(&mixed::<3>(&mut rng, count));
        check(&mixed::<4>(&mut rng, count));
    }
}

#[test]
fn every_width_is_the_lean_path_one_by_one_on_random_boxes() {
    // The benchmark's random boxes (cond G ≤ 100), some of which the lean route refuses.
    let mut scenes = Scenes::<2>::default();
    for p in random_boxes(203, 0xb0c5) {
        scenes.push(&p).expect("a free body in principal axes");
    }
    assert!(!scenes.is_empty());
    check(&scenes);
}

#[test]
fn a_refused_lane_leaves_its_neighbours_on_the_lean_route() {
    // Eleven Example-3-class scenes (contacts at y = −2 and 4, all on the lean route), then
    // scene 2's second contact moved 10⁻⁶ from its first (the lean route refuses it), scene
    // 5's onto its first (G singular) and scene 8's mass made negative (invalid).
    let mut scenes = Scenes::<2>::default();
    for p in example_3_class(11) {
        scenes.push(&p).expect("a free body in principal axes");
    }
    scenes.points[1][1][2] = -2.0 + 1e-6;
    scenes.points[1][1][5] = -2.0;
    scenes.mass[8] = -1.0;
    let [newton, _] = at_width::<8, 2>(&scenes);
    let off: Vec<usize> = newton.reasons.iter().map(|r| r.0).collect();
    assert_eq!(off, [2, 5, 8]);
    for (s, route) in newton.routes.iter().enumerate() {
        assert_eq!(*route == Route::Lean, !off.contains(&s), "scene {s}");
    }
    assert!(matches!(
        newton.reasons[0].1,
        Reason::Lean(LeanError::IllConditioned { .. })
    ));
    assert!(matches!(newton.reasons[2].1, Reason::Invalid(_)));
    check(&scenes);
}

/// Both models at L lanes by the generic lean code on lanes (no N = 2 kernel).
fn generic_at_width<const L: usize, const N: usize>(scenes: &Scenes<N>) -> [Outcomes<N>; 2] {
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    newton.reset(scenes.len());
    poisson.reset(scenes.len());
    sweep::sweep_generic::<L, N>(
        scenes,
        &mut [(Model::Newton, &mut newton), (Model::Poisson, &mut poisson)],
    );
    [newton, poisson]
}

#[test]
fn the_two_contact_kernel_is_the_generic_lane_code_bit_for_bit() {
    // Mixed scenes (refused, singular, invalid lanes among them) and the random boxes: the
    // N = 2 kernel (pair.rs) against the generic lean code on lanes, every width, every
    // output bit, every route and reason.
    let mut rng = Seeded(0x5eed_0022);
    let mut boxes = Scenes::<2>::default();
    for p in random_boxes(101, 0xb0c6) {
        boxes.push(&p).expect("a free body in principal axes");
    }
    for scenes in [mixed::<2>(&mut rng, 67), boxes] {
        let same = |a: &[Outcomes<2>; 2], b: &[Outcomes<2>; 2]| {
            for (a, b) in a.iter().zip(b) {
                assert_eq!(a.routes, b.routes);
                assert_eq!(a.reasons, b.reasons);
                for s in 0..scenes.len() {
                    assert_eq!(bits(a, s), bits(b, s), "scene {s}");
                }
            }
        };
        same(
            &at_width::<2, 2>(&scenes),
            &generic_at_width::<2, 2>(&scenes),
        );
        same(
            &at_width::<4, 2>(&scenes),
            &generic_at_width::<4, 2>(&scenes),
        );
        same(
            &at_width::<8, 2>(&scenes),
            &generic_at_width::<8, 2>(&scenes),
        );
    }
}

#[test]
fn outcomes_reused_across_batches_equal_fresh_ones() {
    // The sweep no longer clears the outcomes before writing: every entry of a reused one must
    // still be written — the lanes' answers, the generic route's, or zeros where no route
    // answers. Fill the outcomes with a batch of other numbers first, then solve a mixed batch
    // (refused, singular and invalid lanes, a partial last chunk) into them.
    let mut rng = Seeded(0x5eed_0077);
    let first = mixed::<2>(&mut rng, 64);
    let second = mixed::<2>(&mut rng, 43);
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    solve_both(&first, &mut newton, &mut poisson).expect("arrays of one length");
    solve_both(&second, &mut newton, &mut poisson).expect("arrays of one length");
    let (mut fresh_newton, mut fresh_poisson) = (Outcomes::default(), Outcomes::default());
    solve_both(&second, &mut fresh_newton, &mut fresh_poisson).expect("arrays of one length");
    for s in 0..second.len() {
        assert_eq!(bits(&newton, s), bits(&fresh_newton, s), "scene {s}");
        assert_eq!(bits(&poisson, s), bits(&fresh_poisson, s), "scene {s}");
    }
    assert_eq!(newton, fresh_newton);
    assert_eq!(poisson, fresh_poisson);
    assert!(newton.routes.contains(&Route::Refused));
}

#[test]
fn the_quick_finiteness_test_never_accepts_a_non_finite_lane() {
    // surely_finite may refuse finite lanes whose sum overflows, never accept a lane with an
    // infinite or NaN value, whatever the other values.
    let (inf, nan, big) = (f64::INFINITY, f64::NAN, f64::MAX);
    let lanes = |xs: [f64; 4]| lanes::Lanes::<4>(xs);
    let columns = [
        lanes([1.0, inf, -inf, nan]),
        lanes([2.0, -inf, inf, 0.0]),
        lanes([-3.0, 0.0, 1.0, -big]),
        lanes([big, big, big, big]),
    ];
    let quick = sweep::surely_finite(&columns);
    assert!(
        quick.lane(0),
        "finite values summing to MAX − 0 are accepted"
    );
    for l in 1..4 {
        assert!(!quick.lane(l), "lane {l} holds ±∞ or NaN");
    }
    let overflowing = [lanes([big; 4]), lanes([big; 4])];
    assert!(
        !sweep::surely_finite(&overflowing).lane(0),
        "an overflowing sum is refused"
    );
    assert!(
        sweep::finite(&overflowing).all(),
        "though every value is finite"
    );
}
