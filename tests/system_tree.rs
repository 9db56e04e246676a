//! The joints of a system eliminated along their tree by the articulated-body recursion
//! (`mechanics::system::articulated`, Featherstone 2008 ch. 7, linear in the bodies) against the
//! dense pivoted factorization of K (`mechanics::system::mobility`), which forms K = Hᵀ η W₀ H
//! and knows nothing of the graph — exactly, in rationals:
//!
//! * random forests of 2–6 bodies (chains and branched trees, revolute, spherical, prismatic
//!   and fixed joints, some trees held to the ground, some free), with random twists the
//!   joints allow (built joint by joint from the joints' free screws, not by the solver): the
//!   tree path is taken, and W{E} for every body's unit wrenches, the impact (G, every output
//!   of Newton and Poisson) and the joints' impulses (read off the bodies' momentum balance
//!   along the tree on one path, solved from K on the other) are equal to the dense path's, value for
//!   value; W is symmetric ({E}ᵀ η W {F} = {F}ᵀ η W {E}) and every W{E} moves the bodies as
//!   the joints allow (invariants neither path is built from);
//! * joints that close a loop — two joints between the same bodies, two joints to the ground
//!   on one tree, a ring of bodies — take the dense path, and where the extra joint is
//!   redundant the answers equal the tree's for the system without it;
//! * a planar chain of 200 links in f64 against the same chain in rationals, within a
//!   tolerance derived from its conditioning (the test's doc).

use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::{Mobility, RigidBody};
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Screws, Vec3};
use inertance::mechanics::system::{Pair, System, SystemBody, SystemJoint, SystemScrew};
use inertance::scalar::{Exact, Scalar, int, ratio};
use num_bigint::BigInt;
use proptest::prelude::*;

fn q(n: i64, d: i64) -> Exact {
    Exact::new(BigInt::from(n), BigInt::from(d))
}

fn vi(x: i64, y: i64, z: i64) -> Vec3<Exact> {
    Vec3::new(int(x), int(y), int(z))
}

/// A small rational vector.
fn vec3() -> impl Strategy<Value = Vec3<Exact>> {
    (-6i64..=6, -6i64..=6, -6i64..=6, 1i64..=3)
        .prop_map(|(x, y, z, d)| Vec3::new(q(x, d), q(y, d), q(z, d)))
}

fn direction() -> impl Strategy<Value = Vec3<Exact>> {
    (-3i64..=3, -3i64..=3, -3i64..=3)
        .prop_filter("nonzero", |v| *v != (0, 0, 0))
        .prop_map(|(x, y, z)| vi(x, y, z))
}

/// A body: principal moments, or a full tensor (diagonally dominant, so positive definite).
fn body() -> impl Strategy<Value = RigidBody<Exact>> {
    (
        1i64..=8,
        1i64..=8,
        1i64..=8,
        1i64..=8,
        -1i64..=1,
        any::<bool>(),
    )
        .prop_map(|(m, a, b, c, off, tensor)| {
            let (a, b, c) = (q(a, 2), q(b, 2), q(c, 2));
            if tensor {
                let o = q(off, 4);
                let d = |x: Exact| x + int::<Exact>(1);
                RigidBody::with_tensor(
                    q(m, 2),
                    [
                        [d(a), o.clone(), int(0)],
                        [o.clone(), d(b), o.clone()],
                        [int(0), o, d(c)],
                    ],
                )
            } else {
                RigidBody::principal(q(m, 2), Vec3::new(a, b, c))
            }
        })
}

/// A joint of the kinds a chain or tree is made of, at a world point.
fn joint() -> impl Strategy<Value = Joint<Exact>> {
    prop_oneof![
        3 => (vec3(), direction()).prop_map(|(point, axis)| Joint::Revolute { point, axis }),
        2 => vec3().prop_map(|point| Joint::Spherical { point }),
        1 => direction().prop_map(|axis| Joint::Prismatic { axis }),
        1 => vec3().prop_map(|point| Joint::Fixed { point }),
    ]
}

/// The twist field [ω; v_O] of `s` about C read about the world origin, and back.
fn at_origin(s: &Screw<Exact>, c: &Vec3<Exact>) -> Screw<Exact> {
    // v_O = v_C + ω × (O − C) = v_C − ω × C.
    Screw::new(s.top(), s.bottom() - s.top().cross(c))
}

fn at_centre(s: &Screw<Exact>, c: &Vec3<Exact>) -> Screw<Exact> {
    Screw::new(s.top(), s.bottom() + s.top().cross(c))
}

/// A forest: body i > 0 hangs from a body before it or from the ground, body 0 is held to the
/// ground or free; the twists are built down the trees from the joints' free screws (the first
/// body's twist about O = the second's + Σ rate · free screw), roots free or at rest.
#[derive(Clone, Debug)]
struct Forest {
    bodies: Vec<SystemBody<Exact>>,
    velocity: SystemScrew<Exact>,
    joints: Vec<SystemJoint<Exact>>,
}

fn forest() -> impl Strategy<Value = Forest> {
    (2usize..=6)
        .prop_flat_map(|n| {
            (
                prop::collection::vec((body(), vec3()), n),
                // Per body: its parent (a body before it; n = ground), its joint, which of the
                // two is the joint's first body, and the joint's rates.
                prop::collection::vec(
                    (
                        0..=n,
                        joint(),
                        any::<bool>(),
                        prop::collection::vec(-3i64..=3, 3),
                    ),
                    n,
                ),
                (vec3(), vec3()),
                any::<bool>(),
            )
        })
        .prop_map(|(bodies, links, root_twist, ground_first)| {
            let n = bodies.len();
            let bodies: Vec<SystemBody<Exact>> = bodies
                .into_iter()
                .map(|(body, centre)| SystemBody { body, centre })
                .collect();
            let mut origin: Vec<Screw<Exact>> = Vec::with_capacity(n);
            let mut joints = Vec::new();
            for (i, (parent, joint, first, rates)) in links.into_iter().enumerate() {
                // Body 0 goes to the ground or is free; the others to an earlier body or ground.
                let parent = if i == 0 {
                    (ground_first).then_some(n)
                } else if parent >= i && parent != n {
                    Some(parent % i)
                } else {
                    Some(parent)
                };
                let Some(parent) = parent else {
                    origin.push(Screw::new(root_twist.0.clone(), root_twist.1.clone()));
                    continue;
                };
                let mut twist = if parent == n {
                    Screw::zero()
                } else {
                    origin[parent].clone()
                };
                for (f, r) in joint.free_screws().iter().zip(rates) {
                    twist.add_scaled(&int(r), f);
                }
                origin.push(twist);
                let second = (parent != n).then_some(parent);
                let pair = match (first, second) {
                    (true, Some(p)) => Pair {
                        first: p,
                        second: Some(i),
                    },
                    _ => Pair { first: i, second },
                };
                joints.push(SystemJoint { joint, pair });
            }
            let velocity = SystemScrew(
                origin
                    .iter()
                    .zip(&bodies)
                    .map(|(s, b)| at_centre(s, &b.centre))
                    .collect(),
            );
            Forest {
                bodies,
                velocity,
                joints,
            }
        })
}

fn contacts(bodies: usize) -> impl Strategy<Value = Vec<(Contact<Exact>, Pair)>> {
    prop::collection::vec(
        (vec3(), direction(), 0usize..64, 0usize..64, 0i64..=4),
        1..=2,
    )
    .prop_map(move |cs| {
        cs.into_iter()
            .map(|(point, normal, a, b, k)| {
                let first = a % bodies;
                let second = (b % (bodies + 1) != first && b % (bodies + 1) < bodies)
                    .then_some(b % (bodies + 1));
                (Contact::new(point, normal, q(k, 4)), Pair { first, second })
            })
            .collect()
    })
}

fn system(f: &Forest, contacts: &[(Contact<Exact>, Pair)]) -> System<Exact> {
    System::new(
        f.bodies.clone(),
        f.velocity.clone(),
        contacts.iter().map(|c| c.0.clone()).collect(),
        contacts.iter().map(|c| c.1).collect(),
        f.joints.clone(),
    )
    .expect("valid by construction")
}

/// Every body's six unit wrenches.
fn unit_wrenches(bodies: usize) -> Vec<SystemScrew<Exact>> {
    let mut out = Vec::new();
    for b in 0..bodies {
        for k in 0..6 {
            let mut e = SystemScrew::zeros(bodies);
            e.0[b].0[k] = int(1);
            out.push(e);
        }
    }
    out
}

/// Hᵀ η {V} = 0 for every joint: the relative twist of its bodies about O lies in the span of
/// its free screws — checked by the joint's own screws, without the system's rows: the
/// relative twist is reciprocal to every screw reciprocal to all the free screws, i.e. it is
/// a combination of them (rank test by elimination).
fn joints_allow(
    joints: &[SystemJoint<Exact>],
    bodies: &[SystemBody<Exact>],
    v: &SystemScrew<Exact>,
) -> bool {
    joints.iter().all(|j| {
        let at = |b: usize| at_origin(&v.0[b], &bodies[b].centre);
        let rel = match j.pair.second {
            Some(s) => Screws::minus(&at(j.pair.first), &at(s)),
            None => at(j.pair.first),
        };
        let free = j.joint.free_screws();
        rank(&free) == rank(&[free.clone(), vec![rel]].concat())
    })
}

fn rank(screws: &[Screw<Exact>]) -> usize {
    let mut rows: Vec<Vec<Exact>> = screws.iter().map(|s| s.as_slice().to_vec()).collect();
    let mut r = 0;
    for c in 0..6 {
        let Some(p) = (r..rows.len()).find(|&i| rows[i][c] != int(0)) else {
            continue;
        };
        rows.swap(r, p);
        let pivot = rows[r].clone();
        for (i, row) in rows.iter_mut().enumerate() {
            if i != r && row[c] != int(0) {
                let f = row[c].clone() / &pivot[c];
                for (x, y) in row.iter_mut().zip(&pivot) {
                    *x -= f.clone() * y;
                }
            }
        }
        r += 1;
    }
    r
}

/// Newton's and Poisson's outcomes (or why the impact has none).
fn outcomes<T: Scalar>(s: &System<T>) -> Vec<Result<Outcome<T, SystemScrew<T>>, String>> {
    let mut impact = match Impact::assemble(s) {
        Ok(i) => i,
        Err(e) => return vec![Err(e.to_string())],
    };
    [Model::Newton, Model::Poisson]
        .into_iter()
        .map(|m| {
            let mut out = Outcome::default();
            impact
                .solve(m, &mut out)
                .map(|()| out)
                .map_err(|e| e.to_string())
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn a_forest_of_joints_gives_the_dense_answers_exactly(
        (f, cs) in forest().prop_flat_map(|f| {
            let n = f.bodies.len();
            (Just(f), contacts(n))
        })
    ) {
        let tree = system(&f, &cs);
        prop_assert!(tree.joints_factored_along_tree());
        prop_assert!(!tree.redundant_joints());
        let dense = tree.clone().with_dense_joints().expect("factors");
        prop_assert!(!dense.joints_factored_along_tree());
        let n = f.bodies.len();
        let units = unit_wrenches(n);
        let responses: Vec<_> = units.iter().map(|e| tree.response(e)).collect();
        for (e, w) in units.iter().zip(&responses) {
            prop_assert_eq!(w, &dense.response(e));
            prop_assert!(joints_allow(&f.joints, &f.bodies, w));
        }
        for (a, wa) in units.iter().zip(&responses) {
            for (b, wb) in units.iter().zip(&responses) {
                prop_assert_eq!(Screws::reciprocal(a, wb), Screws::reciprocal(b, wa));
            }
        }
        let (t, d) = (outcomes(&tree), outcomes(&dense));
        prop_assert_eq!(&t, &d);
        for out in t.iter().flatten() {
            prop_assert!(joints_allow(&f.joints, &f.bodies, &out.velocity));
            prop_assert_eq!(tree.joint_reactions(&out.constraint_impulses), dense.joint_reactions(&out.constraint_impulses));
        }
    }
}

/// Two bars hinged at the origin about z, the second hinged to the first at (2, 0, 0); a
/// contact at the tip. `extra` adds joints to the ground or between them.
fn hinged(extra: Vec<SystemJoint<Exact>>) -> System<Exact> {
    let bar = |x: i64| SystemBody {
        body: RigidBody::principal(int(1), Vec3::new(ratio(1, 10), ratio(4, 3), ratio(4, 3))),
        centre: vi(x, 0, 0),
    };
    let ez = vi(0, 0, 1);
    let hinge = |x: i64, pair: Pair| SystemJoint {
        joint: Joint::Revolute {
            point: vi(x, 0, 0),
            axis: ez.clone(),
        },
        pair,
    };
    // ω₁ = −1, ω₂ = −2 about z: v_C1 = (0, −1, 0), v_C2 = (0, −2 − 2, 0).
    let mut joints = vec![
        hinge(
            0,
            Pair {
                first: 0,
                second: None,
            },
        ),
        hinge(
            2,
            Pair {
                first: 1,
                second: Some(0),
            },
        ),
    ];
    joints.extend(extra);
    System::new(
        vec![bar(1), bar(3)],
        SystemScrew(vec![
            Screw::new(vi(0, 0, -1), vi(0, -1, 0)),
            Screw::new(vi(0, 0, -2), vi(0, -4, 0)),
        ]),
        vec![
            Contact::new(vi(4, 0, 0), vi(0, -1, 0), ratio(1, 2)),
            Contact::new(vi(2, 0, 0), vi(0, -1, 0), ratio(1, 2)),
        ],
        vec![
            Pair {
                first: 1,
                second: None,
            },
            Pair {
                first: 0,
                second: None,
            },
        ],
        joints,
    )
    .expect("valid")
}

#[test]
fn redundant_joints_take_the_dense_path_and_answer_as_without_them() {
    let tree = hinged(Vec::new());
    assert!(tree.joints_factored_along_tree());
    let spherical = |pair: Pair| SystemJoint {
        joint: Joint::Spherical { point: vi(2, 0, 0) },
        pair,
    };
    // A ball joint at the hinge between the bars (two joints, one pair of bodies), and a
    // second hinge to the ground (a loop through the ground): each blocks nothing new.
    let doubled = hinged(vec![spherical(Pair {
        first: 0,
        second: Some(1),
    })]);
    let grounded = hinged(vec![SystemJoint {
        joint: Joint::Revolute {
            point: vi(0, 0, 0),
            axis: vi(0, 0, 5),
        },
        pair: Pair {
            first: 0,
            second: None,
        },
    }]);
    for redundant in [&doubled, &grounded] {
        assert!(!redundant.joints_factored_along_tree());
        assert!(redundant.redundant_joints());
        for e in unit_wrenches(2) {
            assert_eq!(redundant.response(&e), tree.response(&e));
        }
        let (a, b) = (outcomes(redundant), outcomes(&tree));
        for (a, b) in a.iter().zip(&b) {
            let (a, b) = (a.as_ref().expect("solves"), b.as_ref().expect("solves"));
            assert_eq!(a.impulses_hat, b.impulses_hat);
            assert_eq!(a.velocity, b.velocity);
            assert_eq!(a.kinetic_energy_loss, b.kinetic_energy_loss);
        }
    }
}

#[test]
fn a_ring_of_bodies_takes_the_dense_path() {
    // Three balls joined in a ring by ball joints at the midpoints: a closed loop, not
    // redundant in every direction; the dense path answers and the invariants hold.
    let ball = |c: Vec3<Exact>| SystemBody {
        body: RigidBody::principal(int(2), Vec3::new(int(1), int(1), int(1))),
        centre: c,
    };
    let centres = [vi(0, 0, 0), vi(4, 0, 0), vi(2, 4, 0)];
    let bodies: Vec<_> = centres.iter().cloned().map(ball).collect();
    let joints: Vec<_> = (0..3)
        .map(|i| {
            let j = (i + 1) % 3;
            SystemJoint {
                joint: Joint::Spherical {
                    point: (centres[i].clone() + centres[j].clone()) / int::<Exact>(2),
                },
                pair: Pair {
                    first: i,
                    second: Some(j),
                },
            }
        })
        .collect();
    let s = System::new(
        bodies.clone(),
        SystemScrew(vec![Screw::new(vi(0, 0, 0), vi(-1, 0, 0)); 3]),
        vec![Contact::new(vi(-1, 0, 0), vi(-1, 0, 0), ratio(1, 3))],
        vec![Pair {
            first: 0,
            second: None,
        }],
        joints.clone(),
    )
    .expect("valid");
    assert!(!s.joints_factored_along_tree());
    let units = unit_wrenches(3);
    let w: Vec<_> = units.iter().map(|e| s.response(e)).collect();
    for (a, wa) in units.iter().zip(&w) {
        assert!(joints_allow(&joints, &bodies, wa));
        for (b, wb) in units.iter().zip(&w) {
            assert_eq!(Screws::reciprocal(a, wb), Screws::reciprocal(b, wa));
        }
    }
    let out = &outcomes(&s)[0];
    let out = out.as_ref().expect("solves");
    assert!(joints_allow(&joints, &bodies, &out.velocity));
}

/// A planar chain of `links` bars of length 2 along x, hinged about z, the first to the
/// ground at the origin, all turning together at ω = −1 (so v_C = ω × C); contacts at the tip
/// and at the end of the middle link, normals −y (the ground below them, struck from above).
/// Masses and moments are multiplied by `heavy` (a change of the unit of mass).
fn chain<T: Scalar>(links: usize, heavy: i64) -> System<T> {
    let c = |n: i64, d: i64| T::from_rational(&num_rational::BigRational::new(n.into(), d.into()));
    let v = |x: T, y: T, z: T| Vec3::new(x, y, z);
    let (m, jx, jz) = (c(heavy, 1), c(heavy, 100), c(heavy, 3) + c(heavy, 100));
    let mut bodies = Vec::new();
    let mut velocity = Vec::new();
    let mut joints = Vec::new();
    for i in 0..links as i64 {
        bodies.push(SystemBody {
            body: RigidBody::principal(m.clone(), v(jx.clone(), jz.clone(), jz.clone())),
            centre: v(c(2 * i + 1, 1), c(0, 1), c(0, 1)),
        });
        velocity.push(Screw::new(
            v(c(0, 1), c(0, 1), c(-1, 1)),
            v(c(0, 1), c(-(2 * i + 1), 1), c(0, 1)),
        ));
        joints.push(SystemJoint {
            joint: Joint::Revolute {
                point: v(c(2 * i, 1), c(0, 1), c(0, 1)),
                axis: v(c(0, 1), c(0, 1), c(1, 1)),
            },
            pair: Pair {
                first: i as usize,
                second: (i > 0).then(|| i as usize - 1),
            },
        });
    }
    let n = links as i64;
    let mid = (links - 1) / 2;
    System::new(
        bodies,
        SystemScrew(velocity),
        vec![
            Contact::new(
                v(c(2 * n, 1), c(0, 1), c(0, 1)),
                v(c(0, 1), c(-1, 1), c(0, 1)),
                c(1, 2),
            ),
            Contact::new(
                v(c(2 * mid as i64 + 2, 1), c(0, 1), c(0, 1)),
                v(c(0, 1), c(-1, 1), c(0, 1)),
                c(1, 2),
            ),
        ],
        vec![
            Pair {
                first: links - 1,
                second: None,
            },
            Pair {
                first: mid,
                second: None,
            },
        ],
        joints,
    )
    .expect("valid")
}

/// ‖a − b‖∞ / ‖b‖∞ over paired values (b exact).
fn relative<'a>(pairs: impl Iterator<Item = (&'a f64, &'a Exact)>) -> f64 {
    let (mut err, mut size) = (0.0f64, 0.0f64);
    for (a, b) in pairs {
        let b = b.to_f64();
        err = err.max((a - b).abs());
        size = size.max(b.abs());
    }
    err / size
}

/// A chain of `links` in f64 against its exact solve.
///
/// The tolerance, from the error model of the f64 path: the articulated-body recursion passes
/// each body twice (up and down), each step a few products of 6-vectors and an unpivoted LDLᵀ
/// of a definite block of size ≤ 6, backward stable (Higham, *Accuracy and Stability of
/// Numerical Algorithms*, §10.1), so each contact's response W{Ê} carries a relative error of
/// a few ε per step it passes through — at most 2·links along a chain, ≤ 6 entries each:
/// 12·links·ε; the 2×2 solve G P = b then amplifies
/// a relative error in G and b by cond∞(G) (computed here exactly), and the twist
/// {v⁰} − Σ P̂ W{Ê} inherits both. So every impulse and twist is within
/// 2 · 12·links·ε · cond∞(G) relative (normwise, ∞), the factor 2 for the two stages.
fn f64_agrees_with_exact(links: usize, heavy: i64) {
    let exact = chain::<Exact>(links, heavy);
    let float = chain::<f64>(links, heavy);
    assert!(exact.joints_factored_along_tree() && float.joints_factored_along_tree());
    let g = Impact::assemble(&exact)
        .expect("assembles")
        .g_hat()
        .to_vec();
    let det = g[0].clone() * &g[3] - g[1].clone() * &g[2];
    let norm = |a: &Exact, b: &Exact| a.to_f64().abs() + b.to_f64().abs();
    let cond = norm(&g[0], &g[1]).max(norm(&g[2], &g[3]))
        * norm(&g[3], &g[1]).max(norm(&g[2], &g[0]))
        / det.to_f64().abs();
    let tolerance = 2.0 * 12.0 * links as f64 * f64::EPSILON * cond;
    for (e, f) in outcomes(&exact).iter().zip(&outcomes(&float)) {
        let (e, f) = (e.as_ref().expect("solves"), f.as_ref().expect("solves"));
        let impulses = relative(f.impulses_hat.iter().zip(&e.impulses_hat));
        let twist = relative(
            f.velocity
                .0
                .iter()
                .zip(&e.velocity.0)
                .flat_map(|(a, b)| a.as_slice().iter().zip(b.as_slice())),
        );
        assert!(
            impulses <= tolerance && twist <= tolerance,
            "impulses {impulses:e}, twist {twist:e} against {tolerance:e} (cond∞ G = {cond})"
        );
        assert!(f.impulses_hat.iter().all(|p| *p > 0.0), "both compressive");
    }
}

/// 200 links (3 s in rationals, release).
#[test]
fn a_long_chain_in_f64_agrees_with_its_exact_solve() {
    f64_agrees_with_exact(200, 1);
}

/// In a unit of mass 10¹⁸ times smaller every articulated inertia is 10¹⁸ times larger: the
/// tree's pivot tests must be relative to the block's own entries, or the f64 chain would be
/// refused the tree.
#[test]
fn a_chain_of_heavy_links_keeps_its_tree_in_f64() {
    f64_agrees_with_exact(10, 1_000_000_000_000_000_000);
}
