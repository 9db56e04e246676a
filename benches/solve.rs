//! The cost of a solve per scalar type on the paper's Example 3 (free body, two contacts,
//! Newton and Poisson, every output), with a hand-written f64 closed form (eq. 17–20, no
//! abstraction at all) as the baseline.
//!
//! `cargo bench --bench solve`

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use inertance::restitution::Model;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::solve::{Impact, Outcome, Problem};

const EXAMPLE_3: &str = r#"
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
k = 0.2
"#;

fn solve_both<T: Scalar>(
    p: &Problem<T>,
    impact: &mut Impact<T>,
    n: &mut Outcome<T>,
    q: &mut Outcome<T>,
) {
    impact.assemble(p, &p.body).unwrap();
    impact.solve(p, Model::Newton, n).unwrap();
    impact.solve(p, Model::Poisson, q).unwrap();
}

fn bench_scalar<T: Scalar>(c: &mut Criterion, scene: &Scene) {
    let p = scene.problem::<T>().unwrap();
    let (mut impact, mut n, mut q) = (Impact::new(), Outcome::default(), Outcome::default());
    c.bench_function(&format!("example3/{}", T::NAME), |b| {
        b.iter(|| {
            solve_both(black_box(&p), &mut impact, &mut n, &mut q);
            black_box(&q.kinetic_energy_loss);
        })
    });
}

/// The planar two-contact Newton + Poisson solve written out by hand (eq. 17–20, 22–24, 31):
/// the floor the generic f64 path is measured against.
#[inline(never)]
fn closed_form(m: f64, jz: f64, y: [f64; 2], v: [f64; 2], w: f64, k: [f64; 2]) -> [f64; 8] {
    let f = [-y[0], -y[1]];
    let (g11, g12, g22) = (
        1.0 / m + f[0] * f[0] / jz,
        1.0 / m + f[0] * f[1] / jz,
        1.0 / m + f[1] * f[1] / jz,
    );
    let det = g11 * g22 - g12 * g12;
    let v0 = [v[0] + f[0] * w, v[0] + f[1] * w];
    let r = [(1.0 + k[0]) * v0[0], (1.0 + k[1]) * v0[1]];
    let pn = [
        (r[0] * g22 - r[1] * g12) / det,
        (g11 * r[1] - g12 * r[0]) / det,
    ];
    let pc = [
        (v0[0] * g22 - v0[1] * g12) / det,
        (g11 * v0[1] - g12 * v0[0]) / det,
    ];
    let pp = [(1.0 + k[0]) * pc[0], (1.0 + k[1]) * pc[1]];
    let mut out = [0.0; 8];
    for (o, p) in out.chunks_mut(4).zip([pn, pp]) {
        let wz = w - (p[0] * f[0] + p[1] * f[1]) / jz;
        let vx = v[0] - (p[0] + p[1]) / m;
        let ep = 0.5 * (p[0] * p[0] * g11 + 2.0 * p[0] * p[1] * g12 + p[1] * p[1] * g22);
        let de = 0.5 * (m * (v[0] * v[0] - vx * vx) + jz * (w * w - wz * wz));
        o.copy_from_slice(&[p[0], p[1], ep, de]);
    }
    out
}

fn benches(c: &mut Criterion) {
    let scene = Scene::parse(EXAMPLE_3, "example 3").unwrap();
    c.bench_function("example3/closed-form-f64", |b| {
        b.iter(|| {
            black_box(closed_form(
                black_box(1.0),
                12.0,
                [-2.0, 4.0],
                [3.0, 2.0],
                0.4,
                [0.3, 0.2],
            ))
        })
    });
    bench_scalar::<f64>(c, &scene);
    bench_scalar::<f32>(c, &scene);
    bench_scalar::<Exact>(c, &scene);
    c.bench_function("example3/parse-scene", |b| {
        b.iter(|| Scene::parse(black_box(EXAMPLE_3), "example 3").unwrap())
    });
}

criterion_group!(solve, benches);
criterion_main!(solve);
