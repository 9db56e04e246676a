//! Shared strategies and independent reference computations for the integration tests.
//!
//! Strategies are bounded (small rationals), as nalgebra's suites do, so exact arithmetic
//! stays fast and no strategy breeds overflow.

#![allow(dead_code)]

use inertance::impact::problem::Problem;
use inertance::impact::restitution::Model;
use inertance::impact::solve::{Impact, Outcome, SolveError};
use inertance::mechanics::body::{Inertia, RigidBody};
use inertance::mechanics::constraint::Joint;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::{Exact, Scalar, int};
use num_bigint::BigInt;
use num_traits::Zero;
use proptest::prelude::*;

pub mod row;

/// n/d with n in [-lo, lo], d in [1, den].
pub fn rational(lo: i64, den: i64) -> impl Strategy<Value = Exact> {
    (-lo..=lo, 1..=den).prop_map(|(n, d)| Exact::new(BigInt::from(n), BigInt::from(d)))
}

/// A positive rational n/d with n in [1, hi].
pub fn positive(hi: i64, den: i64) -> impl Strategy<Value = Exact> {
    (1..=hi, 1..=den).prop_map(|(n, d)| Exact::new(BigInt::from(n), BigInt::from(d)))
}

/// A coefficient of restitution in [0, 1] (multiples of 1/8, so 0 and 1 occur often).
pub fn coefficient() -> impl Strategy<Value = Exact> {
    (0i64..=8).prop_map(|n| Exact::new(BigInt::from(n), BigInt::from(8)))
}

pub fn vec3(lo: i64, den: i64) -> impl Strategy<Value = Vec3<Exact>> {
    (rational(lo, den), rational(lo, den), rational(lo, den))
        .prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

/// A nonzero direction with small integer components (so its norm is generally irrational).
pub fn direction() -> impl Strategy<Value = Vec3<Exact>> {
    (-4i64..=4, -4i64..=4, -4i64..=4)
        .prop_filter("nonzero", |(x, y, z)| (*x, *y, *z) != (0, 0, 0))
        .prop_map(|(x, y, z)| Vec3::new(int::<Exact>(x), int(y), int(z)))
}

/// A joint of any kind, its point near C and its axis a small integer direction.
pub fn joint() -> impl Strategy<Value = Joint<Exact>> {
    prop_oneof![
        (vec3(4, 2), direction()).prop_map(|(point, axis)| Joint::Revolute { point, axis }),
        direction().prop_map(|axis| Joint::Prismatic { axis }),
        (vec3(4, 2), direction()).prop_map(|(point, axis)| Joint::Cylindrical { point, axis }),
        vec3(4, 2).prop_map(|point| Joint::Spherical { point }),
        direction().prop_map(|normal| Joint::Planar { normal }),
    ]
}

pub fn body() -> impl Strategy<Value = RigidBody<Exact>> {
    (
        positive(20, 4),
        positive(20, 4),
        positive(20, 4),
        positive(20, 4),
    )
        .prop_map(|(m, a, b, c)| RigidBody::principal(m, Vec3::new(a, b, c)))
}

pub fn contact() -> impl Strategy<Value = Contact<Exact>> {
    (vec3(6, 3), direction(), coefficient(), coefficient()).prop_map(|(p, n, kn, kp)| Contact {
        point: p,
        normal: n,
        tangent: None,
        k_newton: kn,
        k_poisson: kp.clone(),
        k_energetic: kp,
        mu: Exact::zero(),
    })
}

/// A free-body problem with 1..=max contacts.
pub fn problem(max: usize) -> impl Strategy<Value = Problem<Exact>> {
    (
        body(),
        vec3(5, 2),
        vec3(5, 2),
        prop::collection::vec(contact(), 1..=max),
    )
        .prop_map(|(body, w, v, contacts)| {
            Problem::new(body, Screw::new(w, v), contacts).expect("valid by construction")
        })
}

/// The same problem in another scalar type (inputs rounded once).
pub fn convert<T: Scalar>(p: &Problem<Exact>) -> Problem<T> {
    let c = |x: &Exact| T::from_rational(&x.to_big_rational());
    let v = |x: &Vec3<Exact>| Vec3::new(c(&x[0]), c(&x[1]), c(&x[2]));
    let mass = c(&p.body().mass);
    let body = match &p.body().inertia {
        Inertia::Principal(j) => RigidBody::principal(mass, v(j)),
        Inertia::Tensor(t) => RigidBody::with_tensor(
            mass,
            std::array::from_fn(|i| std::array::from_fn(|k| c(&t.matrix()[(i, k)]))),
        ),
    };
    let velocity = Screw::new(v(&p.velocity().top()), v(&p.velocity().bottom()));
    let contacts = p
        .contacts()
        .iter()
        .map(|k| Contact {
            point: v(&k.point),
            normal: v(&k.normal),
            tangent: k.tangent.as_ref().map(v),
            k_newton: c(&k.k_newton),
            k_poisson: c(&k.k_poisson),
            k_energetic: c(&k.k_energetic),
            mu: c(&k.mu),
        })
        .collect();
    Problem::new(body, velocity, contacts).expect("rounding keeps a valid problem valid")
}

/// A problem in the paper's form, validated: `Problem::new(...).unwrap()` for fixtures.
pub fn valid<T: Scalar>(
    body: RigidBody<T>,
    velocity: Screw<T>,
    contacts: Vec<Contact<T>>,
) -> Problem<T> {
    Problem::new(body, velocity, contacts).expect("a valid problem")
}

/// An assembled impact and the hatted outcome of each model solved on it.
pub type Solved<T> = (Impact<T>, Vec<(Model, Outcome<T>)>);

/// Assemble `p` and solve each of `models` (hatted outcomes, as the solver computes them).
pub fn solve_models<T: Scalar>(p: &Problem<T>, models: &[Model]) -> Result<Solved<T>, SolveError> {
    let mut impact = Impact::assemble(p)?;
    let mut outcomes = Vec::with_capacity(models.len());
    for &m in models {
        let mut out = Outcome::default();
        impact.solve(m, &mut out)?;
        outcomes.push((m, out));
    }
    Ok((impact, outcomes))
}

/// ½(m|v_C|² + Σ_ik J_ik ω_i ω_k), written out independently of the library.
pub fn kinetic_energy(body: &RigidBody<Exact>, twist: &Screw<Exact>) -> Exact {
    let (w, v) = (twist.top(), twist.bottom());
    let mut t =
        body.mass.clone() * (v[0].clone() * &v[0] + v[1].clone() * &v[1] + v[2].clone() * &v[2]);
    for i in 0..3 {
        for k in 0..3 {
            t += body.inertia.entry(i, k) * &w[i] * &w[k];
        }
    }
    t / Exact::from_integer(2.into())
}

/// `p` with each contact changed by `f`, validated again.
pub fn map_contacts<T: Scalar>(p: Problem<T>, f: impl FnMut(&mut Contact<T>)) -> Problem<T> {
    let (body, velocity, mut contacts) = p.into_parts();
    contacts.iter_mut().for_each(f);
    valid(body, velocity, contacts)
}

/// x with A x = b for the k×k row-major A, or `None` when A is singular.
pub fn gauss(mut a: Vec<Exact>, mut b: Vec<Exact>, k: usize) -> Option<Vec<Exact>> {
    for col in 0..k {
        let p = (col..k).find(|&r| !a[r * k + col].is_zero())?;
        for j in 0..k {
            a.swap(col * k + j, p * k + j);
        }
        b.swap(col, p);
        for r in 0..k {
            if r != col && !a[r * k + col].is_zero() {
                let f = a[r * k + col].clone() / &a[col * k + col];
                for j in 0..k {
                    let d = f.clone() * &a[col * k + j];
                    a[r * k + j] -= d;
                }
                let d = f * &b[col];
                b[r] -= d;
            }
        }
    }
    Some((0..k).map(|i| b[i].clone() / &a[i * k + i]).collect())
}

/// w = M z + q.
pub fn residual(m: &[Exact], q: &[Exact], z: &[Exact]) -> Vec<Exact> {
    let n = q.len();
    (0..n)
        .map(|i| (0..n).fold(q[i].clone(), |s, j| s + m[i * n + j].clone() * &z[j]))
        .collect()
}

/// A solution (z, w) of LCP(M, q) found by enumerating supports S with M_SS nonsingular (complete
/// for a symmetric semidefinite M: see `tests/lcp.rs`), or `None` when the LCP has none.
pub fn enumerate(m: &[Exact], q: &[Exact]) -> Option<(Vec<Exact>, Vec<Exact>)> {
    let n = q.len();
    for mask in 0u32..(1 << n) {
        let s: Vec<usize> = (0..n).filter(|i| mask >> i & 1 == 1).collect();
        let k = s.len();
        let a = s
            .iter()
            .flat_map(|&i| s.iter().map(move |&j| m[i * n + j].clone()))
            .collect();
        let b = s.iter().map(|&i| -q[i].clone()).collect();
        let Some(zs) = gauss(a, b, k) else { continue };
        if zs.iter().any(|x| x.is_negative()) {
            continue;
        }
        let mut z = vec![Exact::zero(); n];
        for (&i, x) in s.iter().zip(zs) {
            z[i] = x;
        }
        let w = residual(m, q, &z);
        if w.iter().all(|x| !x.is_negative()) {
            return Some((z, w));
        }
    }
    None
}

/// A scene file in a fresh temporary directory, removed when dropped; `run` calls the binary
/// with the file as the subcommand's first argument.
pub struct SceneFile {
    dir: std::path::PathBuf,
    /// The file.
    pub path: std::path::PathBuf,
}

impl SceneFile {
    /// Write `text` to a new directory named after the test (`name`) and this process.
    pub fn new(name: &str, text: &str) -> SceneFile {
        let dir = std::env::temp_dir().join(format!("inertance-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("scene.toml");
        std::fs::write(&path, text).unwrap();
        SceneFile { dir, path }
    }

    /// The directory, for a command's other output files.
    pub fn dir(&self) -> &std::path::Path {
        &self.dir
    }

    /// `inertance args[0] FILE args[1..]`.
    pub fn run(&self, args: &[&str]) -> std::process::Output {
        let mut all = vec![args[0], self.path.to_str().unwrap()];
        all.extend(&args[1..]);
        std::process::Command::new(env!("CARGO_BIN_EXE_inertance"))
            .args(&all)
            .output()
            .unwrap()
    }
}

impl SceneFile {
    /// `inertance sweep FILE args… --out DIR/sweep.csv`, which must succeed: its CSV.
    pub fn sweep(&self, args: &[&str]) -> Csv {
        let csv = self.dir.join("sweep.csv");
        let mut all = vec!["sweep"];
        all.extend(args);
        all.extend(["--out", csv.to_str().unwrap()]);
        let out = self.run(&all);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        Csv::parse(&std::fs::read_to_string(&csv).unwrap())
    }
}

/// A sweep's CSV, its cells by row and column name.
pub struct Csv {
    header: Vec<String>,
    /// The rows after the header.
    pub rows: Vec<Vec<String>>,
}

impl Csv {
    fn parse(text: &str) -> Csv {
        let mut lines = text
            .lines()
            .map(|l| l.split(',').map(str::to_string).collect());
        Csv {
            header: lines.next().unwrap_or_default(),
            rows: lines.collect(),
        }
    }

    /// The cell of row `r` (0: the first after the header) in column `name`.
    pub fn cell(&self, r: usize, name: &str) -> &str {
        let c = self
            .header
            .iter()
            .position(|h| h == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.header));
        &self.rows[r][c]
    }
}

impl Drop for SceneFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }
}

/// The exact problem an f64 problem is (its inputs' binary values; principal axes).
pub fn exact_of(p: &Problem<f64>) -> Problem<Exact> {
    let e = |x: &f64| Exact::from(x.exact_value().expect("finite"));
    let v = |x: &Vec3<f64>| Vec3::new(e(&x[0]), e(&x[1]), e(&x[2]));
    let Inertia::Principal(j) = &p.body().inertia else {
        unreachable!("principal bodies here")
    };
    let contacts = p
        .contacts()
        .iter()
        .map(|c| {
            let mut k = Contact::new(v(&c.point), v(&c.normal), e(&c.k_newton))
                .with_coefficients(e(&c.k_newton), e(&c.k_poisson));
            k.tangent = c.tangent.as_ref().map(v);
            k
        })
        .collect();
    let w = p.velocity();
    Problem::new(
        RigidBody::principal(e(&p.body().mass), v(j)),
        Screw::new(v(&w.top()), v(&w.bottom())),
        contacts,
    )
    .expect("the binary values of a valid problem")
}

/// The machine epsilon of a float type, by its name (the accuracy contract's tests).
pub fn epsilon(scalar: &str) -> f64 {
    match scalar {
        "f32" => f32::EPSILON as f64,
        "f64" => f64::EPSILON,
        _ => 2f64.powi(-104),
    }
}

/// Every bound holds, and G is declared singular only beyond the type's precision; the
/// number of solves measured per type.
pub fn assert_contract(
    corpus: &str,
    rows: &[inertance::tools::accuracy::ContractRow],
) -> Vec<usize> {
    let mut solved = Vec::new();
    let mut failures = Vec::new();
    for r in rows {
        let eps = epsilon(r.scalar);
        let mut count = 0;
        for m in &r.measurements {
            match m.checks {
                Some(checks) => {
                    count += 1;
                    for (o, c) in inertance::analysis::accuracy::Output::ALL
                        .iter()
                        .zip(checks)
                    {
                        if c.error > c.bound {
                            failures.push(format!(
                                "{corpus}, {} {}: {} error {:e} > bound {:e} ({}; cond {:e})",
                                r.scalar,
                                m.case,
                                o.name(),
                                c.error,
                                c.bound,
                                o.bound_text(),
                                m.cond
                            ));
                        }
                    }
                }
                None if m.cond * eps < 1e-3 => failures.push(format!(
                    "{corpus}, {} {}: declared singular at cond {:e}",
                    r.scalar, m.case, m.cond
                )),
                None => {}
            }
        }
        eprintln!("{corpus}, {}: {count} solves measured", r.scalar);
        for o in inertance::analysis::accuracy::Output::ALL {
            let (ratio, case) = r.worst(o);
            eprintln!("  {:20} largest error/bound {ratio:.1e} ({case})", o.name());
        }
        solved.push(count);
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    solved
}
