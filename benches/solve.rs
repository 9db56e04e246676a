//! The cost of a solve per scalar type: the paper's Example 3 (free body, two contacts, Newton
//! and Poisson, every output; in f64 also impulses and twist only) with a hand-written f64
//! closed form as the baseline; N = 3 and 6
//! contacts (solve) and 12, 24 (assemble + analyze: beyond six contacts a free body is always
//! singular); a constrained scene (Example 6); building a scene apart from solving it; and a
//! batch of scenes. The unilateral law (assemble + unilateral Newton + Poisson, every output)
//! on Example 3 and on N = 3, 6, 12, 24 contacts — where, beyond six, the simultaneous solve
//! is impossible (G singular) and the unilateral one still answers. The lean path
//! (impulses and twist only, `impact::lean`) against a hand-written closed form of those
//! outputs, and the structure-of-arrays batch (`impact::batch`). At the end it prints the
//! ratios generic f64 (every output) / its hand-written baseline and lean / its baseline,
//! measured in the same run.
//!
//! `cargo bench --bench solve`

use std::hint::black_box;

use criterion::Criterion;
use inertance::analysis::wrench_space::WrenchSpace;
use inertance::analysis::{analyze, analyze_reduced};
use inertance::impact::batch::{self, Outcomes, Scenes};
use inertance::impact::lean::Lean;
use inertance::impact::outputs::Outputs;
use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome};
use inertance::scalar::dd::DoubleDouble;
use inertance::scalar::{Exact, Scalar};
use inertance::scene::Scene;
use inertance::tools::lean_bench::{example_3_class, random_boxes};

const EXAMPLE_3: &str = r#"
[body]
mass = 1
inertia = [12, 1.6, 12]
velocity = [3, 2, 0]
angular_velocity = [0, 0, 0.4]
[[contact]]
point = [0, -2, 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = 0.3
[[contact]]
point = [0, 4, 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = 0.2
"#;

fn solve_both<T: Scalar>(
    p: &Problem<T>,
    impact: &mut Impact<T>,
    n: &mut Outcome<T>,
    q: &mut Outcome<T>,
) {
    impact.reassemble(p).unwrap();
    impact.solve(Model::Newton, n).unwrap();
    impact.solve(Model::Poisson, q).unwrap();
}

fn solve_unilateral_both<T: Scalar>(
    p: &Problem<T>,
    impact: &mut Impact<T>,
    n: &mut Outcome<T>,
    q: &mut Outcome<T>,
) {
    impact.reassemble(p).unwrap();
    impact.solve_unilateral(Model::Newton, n).unwrap();
    impact.solve_unilateral(Model::Poisson, q).unwrap();
}

/// The unilateral solve of `scene`, named `{group}/unilateral/{scalar}`.
fn bench_unilateral<T: Scalar>(c: &mut Criterion, group: &str, scene: &Scene) {
    let p = scene.problem::<T>().unwrap();
    let (mut impact, mut n, mut q) = (
        Impact::assemble(&p).unwrap(),
        Outcome::default(),
        Outcome::default(),
    );
    c.bench_function(&format!("{group}/unilateral/{}", T::NAME), |b| {
        b.iter(|| {
            solve_unilateral_both(black_box(&p), &mut impact, &mut n, &mut q);
            black_box(&q.kinetic_energy_loss);
        })
    });
}

fn bench_scalar<T: Scalar>(c: &mut Criterion, scene: &Scene) {
    let p = scene.problem::<T>().unwrap();
    let (mut impact, mut n, mut q) = (
        Impact::assemble(&p).unwrap(),
        Outcome::default(),
        Outcome::default(),
    );
    c.bench_function(&format!("example3/{}", T::NAME), |b| {
        b.iter(|| {
            solve_both(black_box(&p), &mut impact, &mut n, &mut q);
            black_box(&q.kinetic_energy_loss);
        })
    });
}

/// Example 3 in f64 assembled and solved for `outputs` only (`impact::outputs`), named
/// `example3/f64/{outputs}`: the cheapest public path, impulses and twist, against every output.
fn bench_outputs(c: &mut Criterion, scene: &Scene, outputs: Outputs) {
    let p = scene.problem::<f64>().unwrap();
    let (mut impact, mut n, mut q) = (
        Impact::assemble_for(&p, outputs).unwrap(),
        Outcome::default(),
        Outcome::default(),
    );
    c.bench_function(&format!("example3/f64/{outputs}"), |b| {
        b.iter(|| {
            solve_both(black_box(&p), &mut impact, &mut n, &mut q);
            black_box(&q.velocity);
        })
    });
}

/// The two-contact free-body solve written out by hand in f64, with no abstraction at all,
/// computing every output the generic solve computes: the contact frames (x = n, y given,
/// z = x × y), the inertances g_ij,xx/yx/zx (eq. 57), the contact velocities before impact,
/// Newton and Poisson impulses by Cramer's rule (eq. 20, 22–23), the twist after impact
/// (eq. 24), the contact velocities after impact (eq. 13, 25–26) and both energies (eq. 28,
/// 32). Unit normals and tangents, as the paper writes them. This is the floor the generic
/// f64 path is measured against.
#[inline(never)]
#[allow(clippy::too_many_arguments)] // the inputs of the problem, spelled out on purpose
fn closed_form(
    m: f64,
    j: [f64; 3],
    w: [f64; 3],
    v: [f64; 3],
    p: [[f64; 3]; 2],
    n: [[f64; 3]; 2],
    y: [[f64; 3]; 2],
    k: [f64; 2],
) -> [f64; 48] {
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    // Frames: axes (x, y, z) and their moments r × axis.
    let mut axes = [[[0.0; 3]; 3]; 2];
    let mut moments = [[[0.0; 3]; 3]; 2];
    let mut before = [[0.0; 3]; 2];
    for c in 0..2 {
        axes[c] = [n[c], y[c], cross(n[c], y[c])];
        let va = [
            v[0] + w[1] * p[c][2] - w[2] * p[c][1],
            v[1] + w[2] * p[c][0] - w[0] * p[c][2],
            v[2] + w[0] * p[c][1] - w[1] * p[c][0],
        ];
        for a in 0..3 {
            moments[c][a] = cross(p[c], axes[c][a]);
            before[c][a] = dot(axes[c][a], va);
        }
    }
    // g[a][i][j] = {E_ia}ᵀ η M⁻¹ {E_jx}.
    let mut g = [[[0.0; 2]; 2]; 3];
    for a in 0..3 {
        for i in 0..2 {
            for jj in 0..2 {
                let (u, s) = (axes[i][a], moments[i][a]);
                let (un, sn) = (axes[jj][0], moments[jj][0]);
                g[a][i][jj] = dot(u, un) / m
                    + s[0] * sn[0] / j[0]
                    + s[1] * sn[1] / j[1]
                    + s[2] * sn[2] / j[2];
            }
        }
    }
    let det = g[0][0][0] * g[0][1][1] - g[0][0][1] * g[0][1][0];
    let t0 = 0.5 * (m * dot(v, v) + j[0] * w[0] * w[0] + j[1] * w[1] * w[1] + j[2] * w[2] * w[2]);
    let mut out = [0.0; 48];
    for (model, o) in out.chunks_mut(24).enumerate() {
        let r = if model == 0 {
            [(1.0 + k[0]) * before[0][0], (1.0 + k[1]) * before[1][0]]
        } else {
            [before[0][0], before[1][0]]
        };
        let mut pi = [
            (r[0] * g[0][1][1] - r[1] * g[0][0][1]) / det,
            (g[0][0][0] * r[1] - g[0][1][0] * r[0]) / det,
        ];
        if model == 1 {
            o[2] = pi[0];
            o[3] = pi[1];
            pi = [(1.0 + k[0]) * pi[0], (1.0 + k[1]) * pi[1]];
        }
        o[0] = pi[0];
        o[1] = pi[1];
        let mut w1 = w;
        let mut v1 = v;
        for c in 0..2 {
            for q in 0..3 {
                w1[q] -= pi[c] * moments[c][0][q] / j[q];
                v1[q] -= pi[c] * n[c][q] / m;
            }
        }
        o[4..7].copy_from_slice(&w1);
        o[7..10].copy_from_slice(&v1);
        for c in 0..2 {
            for a in 0..3 {
                o[10 + 3 * c + a] = before[c][a] - g[a][c][0] * pi[0] - g[a][c][1] * pi[1];
            }
        }
        let (dw, dv) = (
            [w1[0] - w[0], w1[1] - w[1], w1[2] - w[2]],
            [v1[0] - v[0], v1[1] - v[1], v1[2] - v[2]],
        );
        o[16] = 0.5
            * (m * dot(dv, dv)
                + j[0] * dw[0] * dw[0]
                + j[1] * dw[1] * dw[1]
                + j[2] * dw[2] * dw[2]);
        o[17] = t0
            - 0.5
                * (m * dot(v1, v1)
                    + j[0] * w1[0] * w1[0]
                    + j[1] * w1[1] * w1[1]
                    + j[2] * w1[2] * w1[2]);
        o[18..21].copy_from_slice(&before[0]);
        o[21..24].copy_from_slice(&before[1]);
    }
    out
}

/// The two-contact free-body solve written out by hand in f64, computing only the impulses
/// (Newton and Poisson) and the twist after impact — the outputs of the lean path: the
/// responses M⁻¹{E_j} = [J⁻¹ (r_j × n_j); n_j / m] (eq. 9, 11), the inertances
/// g_ij = {E_i}ᵀ η M⁻¹{E_j} (eq. 12, 57; g_21 = g_12), the velocities along the normals before
/// impact (eq. 8), the impulses by Cramer's rule (eq. 20, 22–23) and the twist after impact
/// (eq. 24). The floor the lean path is measured against.
#[inline(never)]
fn closed_form_impulses_twist(
    m: f64,
    j: [f64; 3],
    w: [f64; 3],
    v: [f64; 3],
    p: [[f64; 3]; 2],
    n: [[f64; 3]; 2],
    k: [f64; 2],
) -> [f64; 16] {
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let mut moments = [[0.0; 3]; 2];
    let mut turn = [[0.0; 3]; 2];
    let mut push = [[0.0; 3]; 2];
    let mut before = [0.0; 2];
    for c in 0..2 {
        let mu = cross(p[c], n[c]);
        moments[c] = mu;
        turn[c] = [mu[0] / j[0], mu[1] / j[1], mu[2] / j[2]];
        push[c] = [n[c][0] / m, n[c][1] / m, n[c][2] / m];
        before[c] = dot(n[c], v) + dot(mu, w);
    }
    let g = |a: usize, b: usize| dot(n[a], push[b]) + dot(moments[a], turn[b]);
    let (g11, g12, g22) = (g(0, 0), g(0, 1), g(1, 1));
    let det = g11 * g22 - g12 * g12;
    let mut out = [0.0; 16];
    for (model, o) in out.chunks_mut(8).enumerate() {
        let r = if model == 0 {
            [(1.0 + k[0]) * before[0], (1.0 + k[1]) * before[1]]
        } else {
            [before[0], before[1]]
        };
        let mut pi = [
            (r[0] * g22 - r[1] * g12) / det,
            (g11 * r[1] - g12 * r[0]) / det,
        ];
        if model == 1 {
            pi = [(1.0 + k[0]) * pi[0], (1.0 + k[1]) * pi[1]];
        }
        o[0] = pi[0];
        o[1] = pi[1];
        for q in 0..3 {
            o[2 + q] = w[q] - pi[0] * turn[0][q] - pi[1] * turn[1][q];
            o[5 + q] = v[q] - pi[0] * push[0][q] - pi[1] * push[1][q];
        }
    }
    out
}

/// A scene with `n` contacts spread over a box (deterministic), as TOML.
fn many_contacts(n: usize) -> String {
    let mut t = String::from(
        "[body]\nmass = 5\ninertia = [1.5, 2, 2.5]\nvelocity = [1, -0.5, 0.25]\nangular_velocity = [0.3, 0.2, -0.1]\n",
    );
    for i in 0..n {
        let f = i as f64;
        t += &format!(
            "[[contact]]\npoint = [{:.1}, {:.1}, {:.1}]\nnormal = [{:.1}, {:.1}, 1]\nk = 0.{}\n",
            (f * 0.7).sin() * 2.0,
            (f * 1.3).cos() * 2.0,
            (f * 0.4).sin(),
            (f * 2.1).cos(),
            (f * 0.9).sin(),
            i % 10
        );
    }
    t
}

const EXAMPLE_6: &str = r#"
[body]
mass = 10
inertia = ["10/3", "10/3", "10/3"]
velocity = [0, 0, 0]
angular_velocity = [0, 0, 1]
[[contact]]
point = [0, "-1/3", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = 0.5
[[contact]]
point = [0, "1/3", 0]
normal = [1, 0, 0]
tangent = [0, 1, 0]
k = 0.25
[[constraints.joint]]
kind = "revolute"
point = [0, -1, 0]
axis = [0, 0, 1]
[[constraints.joint]]
kind = "prismatic"
axis = [1, 0, 0]
"#;

fn bench_contacts<T: Scalar>(c: &mut Criterion, n: usize) {
    let scene = Scene::parse(&many_contacts(n), "many").unwrap();
    let p = scene.problem::<T>().unwrap();
    if n <= 6 {
        let (mut impact, mut a, mut b) = (
            Impact::assemble(&p).unwrap(),
            Outcome::default(),
            Outcome::default(),
        );
        c.bench_function(&format!("contacts-{n}/solve/{}", T::NAME), |bch| {
            bch.iter(|| solve_both(black_box(&p), &mut impact, &mut a, &mut b))
        });
    } else {
        c.bench_function(&format!("contacts-{n}/analyze/{}", T::NAME), |bch| {
            bch.iter(|| {
                let mut impact = Impact::assemble(black_box(&p)).unwrap();
                black_box(analyze(&mut impact, &Model::ALL))
            })
        });
    }
}

/// `analyze` on the linear-cost route against N (issue 15): a group per scalar, one point per
/// N, so criterion's report shows the curve ([`inertance::tools::n_curve`] fits its exponent).
fn bench_n_curve<T: Scalar>(c: &mut Criterion, sizes: &[usize]) {
    let mut group = c.benchmark_group(format!("analyze-linear/{}", T::NAME));
    group.sample_size(10);
    for &n in sizes {
        let p = inertance::tools::n_curve::landing::<T>(0x11_4ea2, n);
        group.bench_function(format!("{n}"), |b| {
            b.iter(|| {
                let space = WrenchSpace::build(black_box(&p)).unwrap();
                black_box(analyze_reduced(&space, &Model::ALL))
            })
        });
    }
    group.finish();
}

fn bench_constrained<T: Scalar>(c: &mut Criterion) {
    let scene = Scene::parse(EXAMPLE_6, "example 6").unwrap();
    let p = inertance::scene::pipeline::prepare::<T>(&scene).unwrap();
    let (mut impact, mut out) = (Impact::assemble(&p).unwrap(), Outcome::default());
    c.bench_function(&format!("example6-constrained/{}", T::NAME), |b| {
        b.iter(|| {
            impact.reassemble(black_box(&p)).unwrap();
            impact.solve(Model::Newton, &mut out).unwrap();
            impact.solve(Model::Poisson, &mut out).unwrap();
        })
    });
}

fn benches(c: &mut Criterion) {
    let scene = Scene::parse(EXAMPLE_3, "example 3").unwrap();
    let (x, yy) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    c.bench_function("example3/closed-form-f64", |b| {
        b.iter(|| black_box(baseline(x, yy)))
    });
    c.bench_function("example3/impulses-twist/closed-form-f64", |b| {
        b.iter(|| black_box(baseline_impulses_twist(x)))
    });
    {
        let p = scene.problem::<f64>().unwrap();
        c.bench_function("example3/impulses-twist/lean-f64", |b| {
            b.iter(|| black_box(lean_both(black_box(&p))))
        });
    }
    bench_scalar::<f32>(c, &scene);
    bench_scalar::<f64>(c, &scene);
    bench_outputs(c, &scene, Outputs::IMPULSES | Outputs::TWIST);
    bench_outputs(c, &scene, Outputs::ALL);
    bench_scalar::<DoubleDouble>(c, &scene);
    bench_scalar::<Exact>(c, &scene);
    bench_n_curve::<f64>(c, &[100, 1000, 10_000, 100_000]);
    bench_n_curve::<Exact>(c, &[10, 100, 1000]);
    bench_unilateral::<f64>(c, "example3", &scene);
    bench_unilateral::<Exact>(c, "example3", &scene);
    c.bench_function("example3/parse-scene", |b| {
        b.iter(|| Scene::parse(black_box(EXAMPLE_3), "example 3").unwrap())
    });
    c.bench_function("example3/build-problem-f64", |b| {
        b.iter(|| black_box(&scene).problem::<f64>().unwrap())
    });
    for n in [3, 6, 12, 24] {
        bench_contacts::<f32>(c, n);
        bench_contacts::<f64>(c, n);
        bench_contacts::<DoubleDouble>(c, n);
        if n <= 12 {
            bench_contacts::<Exact>(c, n);
        }
        // The normals of `many_contacts` all have n_z = 1: no impulses ≥ 0 cancel, so the
        // unilateral law never jams, whatever N.
        let many = Scene::parse(&many_contacts(n), "many").unwrap();
        bench_unilateral::<f64>(c, &format!("contacts-{n}"), &many);
        if n <= 12 {
            bench_unilateral::<Exact>(c, &format!("contacts-{n}"), &many);
        }
    }
    bench_constrained::<f32>(c);
    bench_constrained::<f64>(c);
    bench_constrained::<DoubleDouble>(c);
    bench_constrained::<Exact>(c);
    // A batch: 256 Example-3-class scenes (k₁ and v_y varied) solved one after another,
    // buffers reused.
    let batch = example_3_class(256);
    let (mut impact, mut n, mut q) = (
        Impact::assemble(&batch[0]).unwrap(),
        Outcome::default(),
        Outcome::default(),
    );
    c.bench_function("batch-256/f64", |b| {
        b.iter(|| {
            for p in &batch {
                solve_both(black_box(p), &mut impact, &mut n, &mut q)
            }
        })
    });
    // The same 256 scenes, impulses and twist only: one by one on the lean path, and as one
    // structure-of-arrays batch (impact::batch, lanes of the machine's width).
    bench_lean_and_batch(c, "batch-256", &batch);
    // 256 random boxes (tools::lean_bench::random_boxes, cond G ≤ 100): the lean path and the
    // batch on the scenes the lean route accepts, then every scene one by one (lean, else
    // generic) and as one batch (which does the same).
    let random = random_boxes(256, 0x1ea2_ba7c);
    let accepted: Vec<Problem<f64>> = random
        .iter()
        .filter(|p| Lean::<f64, 2>::new(p).is_ok())
        .cloned()
        .collect();
    bench_lean_and_batch(c, "random-accepted", &accepted);
    c.bench_function("random-256/lean-or-generic-f64", |b| {
        b.iter(|| {
            for p in &random {
                match Lean::<f64, 2>::new(black_box(p)) {
                    Ok(lean) => {
                        black_box((
                            lean.solve(Model::Newton).unwrap(),
                            lean.solve(Model::Poisson).unwrap(),
                        ));
                    }
                    Err(_) => {
                        impact.reassemble(p).unwrap();
                        impact.solve(Model::Newton, &mut n).unwrap();
                        impact.solve(Model::Poisson, &mut q).unwrap();
                        black_box((&n.impulses_hat, &q.impulses_hat));
                    }
                }
            }
        })
    });
    let scenes = soa(&random);
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    c.bench_function("random-256/soa-lanes-f64", |b| {
        b.iter(|| {
            batch::solve_both(black_box(&scenes), &mut newton, &mut poisson).unwrap();
        })
    });
}

/// `problems` as structure of arrays.
fn soa(problems: &[Problem<f64>]) -> Scenes<2> {
    let mut scenes = Scenes::<2>::default();
    for p in problems {
        scenes.push(p).unwrap();
    }
    scenes
}

/// `{group}/lean-f64` (one by one on the lean path) and `{group}/soa-lanes-f64` (one batch)
/// over `problems`, every one of which the lean route accepts.
fn bench_lean_and_batch(c: &mut Criterion, group: &str, problems: &[Problem<f64>]) {
    c.bench_function(&format!("{group}/lean-f64"), |b| {
        b.iter(|| {
            for p in problems {
                black_box(lean_both(black_box(p)));
            }
        })
    });
    let scenes = soa(problems);
    let (mut newton, mut poisson) = (Outcomes::default(), Outcomes::default());
    c.bench_function(&format!("{group}/soa-lanes-f64"), |b| {
        b.iter(|| {
            batch::solve_both(black_box(&scenes), &mut newton, &mut poisson).unwrap();
        })
    });
}

/// The lean path on a two-contact problem: assemble once, Newton and Poisson.
fn lean_both(p: &Problem<f64>) -> [f64; 16] {
    let lean = Lean::<f64, 2>::new(p).unwrap();
    let (n, q) = (
        lean.solve(Model::Newton).unwrap(),
        lean.solve(Model::Poisson).unwrap(),
    );
    let mut out = [0.0; 16];
    for (o, r) in out.chunks_mut(8).zip([n, q]) {
        o[..2].copy_from_slice(&r.impulses_hat);
        o[2..].copy_from_slice(&r.velocity);
    }
    out
}

/// The baseline on Example 3's data. Every input goes through `black_box`: the generic solve
/// reads its inputs from memory, so the baseline must not have them constant-folded into its
/// body (LLVM propagates constants into a function with a single call site even when it is
/// not inlined).
fn baseline(x: [f64; 3], yy: [f64; 3]) -> [f64; 48] {
    let (m, j, w, v) = black_box((1.0, [12.0, 1.6, 12.0], [0.0, 0.0, 0.4], [3.0, 2.0, 0.0]));
    let (p, n, y, k) = black_box((
        [[0.0, -2.0, 0.0], [0.0, 4.0, 0.0]],
        [x, x],
        [yy, yy],
        [0.3, 0.2],
    ));
    closed_form(m, j, w, v, p, n, y, k)
}

/// The baseline of impulses and twist on Example 3's data, every input through `black_box`
/// (see [`baseline`]).
fn baseline_impulses_twist(x: [f64; 3]) -> [f64; 16] {
    let (m, j, w, v) = black_box((1.0, [12.0, 1.6, 12.0], [0.0, 0.0, 0.4], [3.0, 2.0, 0.0]));
    let (p, n, k) = black_box(([[0.0, -2.0, 0.0], [0.0, 4.0, 0.0]], [x, x], [0.3, 0.2]));
    closed_form_impulses_twist(m, j, w, v, p, n, k)
}

/// `path` / `base`, timed back to back in this run: the median over 15 interleaved rounds of
/// the per-round ratio, so that a burst of load on the shared machine during one round does
/// not decide the answer.
fn ratio(mut base: impl FnMut(), mut path: impl FnMut()) -> f64 {
    let reps = 100_000;
    let mut ratios = Vec::with_capacity(15);
    for _ in 0..15 {
        let t = std::time::Instant::now();
        for _ in 0..reps {
            base();
        }
        let b = t.elapsed().as_secs_f64();
        let t = std::time::Instant::now();
        for _ in 0..reps {
            path();
        }
        ratios.push(t.elapsed().as_secs_f64() / b);
    }
    ratios.sort_by(f64::total_cmp);
    ratios[ratios.len() / 2]
}

/// The two ratios the issue asks for, on Example 3: the generic f64 solve (every output)
/// over the every-output closed form, and the lean path over the impulses-and-twist one.
fn ratios() -> (f64, f64) {
    let scene = Scene::parse(EXAMPLE_3, "example 3").unwrap();
    let p = scene.problem::<f64>().unwrap();
    let (mut impact, mut a, mut b) = (
        Impact::assemble(&p).unwrap(),
        Outcome::default(),
        Outcome::default(),
    );
    let (x, yy) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let every = ratio(
        || {
            black_box(baseline(x, yy));
        },
        || solve_both(black_box(&p), &mut impact, &mut a, &mut b),
    );
    let lean = ratio(
        || {
            black_box(baseline_impulses_twist(x));
        },
        || {
            black_box(lean_both(black_box(&p)));
        },
    );
    (every, lean)
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    benches(&mut c);
    c.final_summary();
    // `cargo test` runs this binary too (criterion's test mode, unoptimised): measure only
    // under `cargo bench`, which passes `--bench`.
    if std::env::args().any(|a| a == "--bench") {
        let (every, lean) = ratios();
        println!(
            "\ngeneric f64 solve / hand-written closed form (Example 3, every output): {every:.2}×\n\
             lean f64 path / hand-written closed form (Example 3, impulses and twist): {lean:.2}×"
        );
    }
}
