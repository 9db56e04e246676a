//! The analysis in the space of the contact wrenches ([`inertance::analysis::wrench_space`],
//! cost linear in N) against the N×N analysis ([`inertance::analysis::analyze`]) on random
//! scenes of 1 to 40 contacts, in exact rationals: everything the law determines uniquely is
//! equal — rank, classification, rank [G | b], the least-norm impulses, the twist after
//! impact, contact velocities, both energies, the constraint impulses, admissibility, whether
//! the twist is fixed along the family and its dimension, Newton = Poisson, coincidences; Δ
//! and whether G is singular. Then a scene of 10⁴ contacts analysed with no allocation of
//! order N² (the largest single allocation is counted), and the CLI on 60,000 contacts.

mod common;

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

use common::*;
use inertance::analysis::wrench_space::WrenchSpace;
use inertance::analysis::{Analysis, analyze, analyze_reduced};
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::Impact;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, int};
use num_traits::Zero;
use proptest::prelude::*;

/// Counts the largest single allocation (bytes) while `TRACK` is set.
struct Largest;

static LARGEST: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Largest {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        LARGEST.fetch_max(layout.size(), Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        LARGEST.fetch_max(new_size, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Largest = Largest;

const MODELS: [Model; 2] = [Model::Newton, Model::Poisson];

/// Contacts of three kinds, so that every classification occurs: anywhere with any normal;
/// on the plane z = 0 with the normal (0, 0, −1) (dependent beyond three); and repeats of
/// an earlier contact (coincident points, the same axis).
fn scene(max: usize) -> impl Strategy<Value = Problem<Exact>> {
    let contact = prop_oneof![
        contact(),
        (rational(4, 2), rational(4, 2), coefficient()).prop_map(|(x, y, k)| Contact {
            point: Vec3::new(x, y, Exact::zero()),
            normal: Vec3::new(int(0), int(0), int(-1)),
            tangent: None,
            k_newton: k.clone(),
            k_poisson: k.clone(),
            k_energetic: k,
            mu: Exact::zero(),
        }),
    ];
    (
        body(),
        vec3(5, 2),
        vec3(5, 2),
        prop::collection::vec(contact, 1..=max),
        prop::collection::vec(any::<prop::sample::Index>(), 0..4),
        prop::option::of(coefficient()),
    )
        .prop_map(|(body, w, v, mut contacts, repeats, k)| {
            for r in repeats {
                let c = contacts[r.index(contacts.len())].clone();
                contacts.push(c);
            }
            if let Some(k) = k {
                // Equal coefficients everywhere: Newton's b in the range of G.
                for c in &mut contacts {
                    c.k_newton = k.clone();
                    c.k_poisson = k.clone();
                }
            }
            Problem::new(body, Screw::new(w, v), contacts).expect("valid by construction")
        })
}

fn both(
    p: &Problem<Exact>,
) -> (
    Analysis<Exact>,
    Analysis<Exact>,
    Impact<Exact>,
    WrenchSpace<Exact>,
) {
    let mut impact = Impact::assemble(p).expect("assembled");
    let dense = analyze(&mut impact, &MODELS);
    let space = WrenchSpace::build(p).expect("built");
    let reduced = analyze_reduced(&space, &MODELS);
    (dense, reduced, impact, space)
}

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 160,
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn reduced_analysis_equals_the_dense_one_on_what_is_unique(p in scene(40)) {
        let (dense, reduced, impact, space) = both(&p);
        prop_assert_eq!(dense.rank, reduced.rank);
        prop_assert_eq!(&impact.det_hat().clone(), &space.det_hat());
        prop_assert_eq!(dense.tolerance, reduced.tolerance);
        prop_assert_eq!(&dense.newton_equals_poisson, &reduced.newton_equals_poisson);
        prop_assert_eq!(&dense.coincident, &reduced.coincident);
        for (a, b) in dense.models.iter().zip(&reduced.models) {
            prop_assert_eq!(a.model, b.model);
            prop_assert_eq!(a.classification, b.classification);
            prop_assert_eq!(a.augmented_rank, b.augmented_rank);
            prop_assert_eq!(a.nullity, b.nullity);
            prop_assert_eq!(a.family.len(), a.nullity);
            prop_assert!(b.family.is_empty());
            prop_assert_eq!(a.twist_fixed, b.twist_fixed);
            prop_assert_eq!(&a.admissible, &b.admissible);
            prop_assert_eq!(a.energy_gain, b.energy_gain);
            // The outcome: the unique one, or the family's least-norm member (unique too).
            prop_assert_eq!(&a.outcome, &b.outcome);
        }
    }
}

/// Every classification occurs among the scenes above (so the comparison is not vacuous).
#[test]
fn the_scenes_cover_every_classification() {
    use inertance::analysis::Classification::*;
    use proptest::strategy::ValueTree;
    use proptest::test_runner::TestRunner;
    let mut runner = TestRunner::deterministic();
    let mut seen = std::collections::HashSet::new();
    for _ in 0..200 {
        let p = scene(40).new_tree(&mut runner).unwrap().current();
        let space = WrenchSpace::build(&p).unwrap();
        for m in analyze_reduced(&space, &MODELS).models {
            seen.insert(m.classification.name());
        }
    }
    for c in [Unique, SingularCompatible, SingularIncompatible] {
        assert!(seen.contains(c.name()), "{} never occurs", c.name());
    }
}

/// A table of `n` contacts on z = −1 under a falling, spinning box, in f64.
fn table(n: usize) -> Problem<f64> {
    let contacts = (0..n)
        .map(|i| {
            let (x, y) = (
                (i % 300) as f64 / 100.0 - 1.5,
                (i / 300) as f64 / 1000.0 - 0.2,
            );
            Contact::new(Vec3::new(x, y, -1.0), Vec3::new(0.0, 0.0, -1.0), 0.5)
        })
        .collect();
    Problem::new(
        RigidBody::principal(2.0, Vec3::new(1.0, 2.0, 3.0)),
        Screw::new(Vec3::new(0.1, 0.2, 0.0), Vec3::new(0.0, 0.0, -1.0)),
        contacts,
    )
    .unwrap()
}

/// 10⁴ contacts: the largest single allocation is O(N) — a few hundred bytes per contact,
/// far below the 800 MB one N×N matrix of f64 would take.
#[test]
fn ten_thousand_contacts_without_an_n_squared_allocation() {
    let n = 10_000;
    let p = table(n);
    LARGEST.store(0, Ordering::Relaxed);
    let space = WrenchSpace::build(&p).unwrap();
    let a = analyze_reduced(&space, &MODELS);
    let largest = LARGEST.load(Ordering::Relaxed);
    assert_eq!(a.rank, 3);
    for m in &a.models {
        assert_eq!(m.nullity, n - 3);
        assert!(m.twist_fixed);
        let out = m.outcome.as_ref().expect("compatible: equal coefficients");
        // The table stops the box's fall and spin about horizontal axes: v_z = −k·v_z⁰
        // (Newton) for the rebound, ω_x = ω_y = 0 … up to rounding over 10⁴ sums.
        let v = out.velocity.as_slice();
        assert!((v[5] - 0.5).abs() < 1e-9, "{v:?}");
    }
    assert!(
        largest <= 1000 * n,
        "largest allocation {largest} bytes for {n} contacts"
    );
}

/// The same comparison on every scene of `tests/hard_cases/`, `tests/modelled/` and `examples/` that reads in exact
/// rationals — constrained bodies among them (a semidefinite metric ηW: rank ≤ dof).
#[test]
fn reduced_analysis_equals_the_dense_one_on_the_scene_files() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut compared = (0, 0);
    for dir in ["tests/hard_cases", "tests/modelled", "examples"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        for path in entries.flatten().map(|e| e.path()) {
            if path.extension().is_none_or(|e| e != "toml") {
                continue;
            }
            let Ok(scene) = inertance::scene::Scene::load(&path) else {
                continue;
            };
            let Ok(p) = inertance::scene::pipeline::prepare::<Exact>(&scene) else {
                continue;
            };
            let (dense, reduced, impact, space) = both(&p);
            let name = path.display();
            assert_eq!(dense.rank, reduced.rank, "{name}");
            assert_eq!(impact.det_hat(), &space.det_hat(), "{name}");
            assert_eq!(
                dense.newton_equals_poisson, reduced.newton_equals_poisson,
                "{name}"
            );
            assert_eq!(dense.coincident, reduced.coincident, "{name}");
            for (a, b) in dense.models.iter().zip(&reduced.models) {
                assert_eq!(a.classification, b.classification, "{name}");
                assert_eq!(a.augmented_rank, b.augmented_rank, "{name}");
                assert_eq!(a.nullity, b.nullity, "{name}");
                assert_eq!(a.twist_fixed, b.twist_fixed, "{name}");
                assert_eq!(a.admissible, b.admissible, "{name}");
                assert_eq!(a.outcome, b.outcome, "{name}");
            }
            compared.0 += 1;
            compared.1 += usize::from(p.constraints().is_some());
        }
    }
    assert!(compared.0 >= 10 && compared.1 >= 2, "{compared:?}");
}
