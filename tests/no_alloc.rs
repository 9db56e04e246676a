//! The f64 solve allocates nothing: once an `Impact` and its `Outcome`s have been sized by a
//! first solve, assembling and solving again (the same or another scene with no more
//! contacts, a body in principal axes or with a full inertia tensor, by either route of
//! `impact::route`) performs no heap allocation. Shown with a counting global allocator that counts only the allocations of the
//! thread under test (the test harness allocates on its own threads meanwhile).

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::route::Route;
use inertance::impact::solve::{Impact, Outcome};
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};

/// A validated problem (fixtures are valid by construction).
fn valid<T: inertance::Scalar>(
    body: inertance::mechanics::body::RigidBody<T>,
    velocity: inertance::mechanics::screw::Screw<T>,
    contacts: Vec<inertance::mechanics::contact::Contact<T>>,
) -> inertance::Problem<T> {
    inertance::Problem::new(body, velocity, contacts).expect("a valid problem")
}

struct Counting;

thread_local! {
    static COUNTING: Cell<bool> = const { Cell::new(false) };
    /// This thread's count: the tests run on threads of their own, side by side, and one
    /// test's allocations must not be counted in another's.
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

/// This thread's allocations counted so far.
fn allocations() -> usize {
    ALLOCATIONS.with(Cell::get)
}

fn count() {
    if COUNTING.try_with(Cell::get).unwrap_or(false) {
        let _ = ALLOCATIONS.try_with(|n| n.set(n.get() + 1));
    }
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count();
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count();
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn scene(n: usize, shift: f64) -> Problem<f64> {
    let contacts = (0..n)
        .map(|i| {
            let t = i as f64 + shift;
            Contact {
                point: Vec3::new(t.cos(), t.sin(), 0.3 * t),
                normal: Vec3::new(1.0 + t.sin(), 0.5 * t.cos(), 1.0),
                tangent: None,
                k_newton: 0.3,
                k_poisson: 0.6,
                k_energetic: 0.6,
                mu: 0.0,
            }
        })
        .collect();
    valid(
        RigidBody::principal(2.0, Vec3::new(1.0, 2.0, 3.0)),
        Screw::new(Vec3::new(0.1, -0.2, 0.3), Vec3::new(1.0, 2.0, -0.5)),
        contacts,
    )
}

/// The same scene with a full inertia tensor (J⁻¹ stored in the body: no allocation either).
fn tensor(p: Problem<f64>) -> Problem<f64> {
    let (_, velocity, contacts) = p.into_parts();
    let j = [[1.0, 0.2, -0.1], [0.2, 2.0, 0.3], [-0.1, 0.3, 3.0]];
    valid(RigidBody::with_tensor(2.0, j), velocity, contacts)
}

#[test]
fn repeated_f64_solves_do_not_allocate() {
    let scenes: Vec<Problem<f64>> = (0..8)
        .map(|s| scene(6, s as f64 * 0.37))
        .chain([scene(2, 0.1), tensor(scene(6, 0.2)), tensor(scene(3, 1.1))])
        .collect();
    let (mut newton, mut poisson) = (Outcome::default(), Outcome::default());
    // Size the buffers once.
    let mut impact = Impact::assemble(&scenes[0]).unwrap();
    impact.solve(Model::Newton, &mut newton).unwrap();
    impact.solve(Model::Poisson, &mut poisson).unwrap();
    // The unilateral law's buffers too (tableau, right-hand sides, the sub-matrix of the
    // contacts that meet their law, whose size varies by scene): one pass sizes them.
    let (mut un, mut up) = (Outcome::default(), Outcome::default());
    let mut routes = Vec::new();
    for p in &scenes {
        impact.reassemble(p).unwrap();
        routes.push(impact.route());
        impact.solve_unilateral(Model::Newton, &mut un).unwrap();
        impact.solve_unilateral(Model::Poisson, &mut up).unwrap();
    }

    // The first scene takes the orthogonalised wrenches; the two-contact one, assembled
    // later, the normal equations, whose buffers that first assemble sized too.
    assert_eq!(routes[0], Route::OrthogonalWrenches);
    assert_eq!(routes[8], Route::NormalEquations);

    // The counter works: one allocation on this thread is seen.
    COUNTING.with(|c| c.set(true));
    let probe = allocations();
    drop(std::hint::black_box(Vec::<u8>::with_capacity(8)));
    assert_eq!(allocations() - probe, 1);

    let before = allocations();
    let mut checksum = 0.0;
    let mut pivots = 0;
    for _ in 0..50 {
        for p in &scenes {
            impact.reassemble(p).unwrap();
            impact.solve(Model::Newton, &mut newton).unwrap();
            impact.solve(Model::Poisson, &mut poisson).unwrap();
            checksum += newton.kinetic_energy_loss + poisson.lost_velocity_energy;
            let a = impact.solve_unilateral(Model::Newton, &mut un).unwrap();
            let b = impact.solve_unilateral(Model::Poisson, &mut up).unwrap();
            checksum += un.kinetic_energy_loss + up.kinetic_energy_loss;
            pivots += a.pivots + b.pivots;
        }
    }
    let after = allocations();
    COUNTING.with(|c| c.set(false));
    assert!(checksum.is_finite());
    assert!(pivots > 0, "the unilateral solves did pivot");
    assert_eq!(
        after - before,
        0,
        "allocations during 1100 assemble+solve rounds (both laws)"
    );
}

/// The lean path of a system (`impact::lean_system`): once built and sized by a first solve,
/// solving again — the factorization of the joints' tree, the responses, the basis, either
/// law — allocates nothing.
#[test]
fn repeated_lean_system_solves_do_not_allocate() {
    use inertance::impact::lean_system::LeanSystem;
    use inertance::tools::chain::Chain;
    let systems: Vec<_> = [1, 2, 7].map(|n| Chain::<f64>::new(n).system()).into();
    let mut leans: Vec<LeanSystem<f64>> = systems
        .iter()
        .map(|s| {
            let mut lean = LeanSystem::new(s).expect("a chain is a tree");
            lean.solve(s, Model::Newton).expect("solves");
            lean.solve(s, Model::Poisson).expect("solves");
            lean
        })
        .collect();
    COUNTING.with(|c| c.set(true));
    let before = allocations();
    let mut checksum = 0.0;
    for _ in 0..50 {
        for (lean, system) in leans.iter_mut().zip(&systems) {
            for model in [Model::Newton, Model::Poisson] {
                lean.solve(system, model).expect("solves");
                checksum += lean.impulses_hat()[0] + lean.velocity().0[0].0[2];
            }
        }
    }
    let after = allocations();
    COUNTING.with(|c| c.set(false));
    assert!(checksum.is_finite());
    assert_eq!(after - before, 0, "allocations in 300 lean system solves");
}
