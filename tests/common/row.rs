//! Rows of balls and the compliant-contact dynamics in time: the independent reference of the
//! LZB law's tests (`tests/lzb.rs`, `tests/lzb_siconos.rs`).

use inertance::impact::multiple::Lzb;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Screws, Vec3};
use inertance::mechanics::system::{Pair, System, SystemBody, SystemScrew};

fn v3(x: f64, y: f64, z: f64) -> Vec3<f64> {
    Vec3::new(x, y, z)
}

/// Balls of masses `masses` in a row along x, touching, the first moving at `speed` into the
/// rest: contact i between ball i and ball i + 1, normal +x out of ball i.
pub fn row(masses: &[f64], speed: f64) -> System<f64> {
    let bodies = masses
        .iter()
        .enumerate()
        .map(|(i, &m)| SystemBody {
            body: RigidBody::principal(m, v3(0.4 * m, 0.4 * m, 0.4 * m)),
            centre: v3(2.0 * i as f64, 0.0, 0.0),
        })
        .collect();
    let twists = (0..masses.len())
        .map(|i| {
            let v = if i == 0 { speed } else { 0.0 };
            Screw::new(v3(0.0, 0.0, 0.0), v3(v, 0.0, 0.0))
        })
        .collect();
    let contacts = (0..masses.len() - 1)
        .map(|i| Contact::new(v3(2.0 * i as f64 + 1.0, 0.0, 0.0), v3(1.0, 0.0, 0.0), 1.0))
        .collect();
    let pairs = (0..masses.len() - 1)
        .map(|i| Pair {
            first: i,
            second: Some(i + 1),
        })
        .collect();
    System::new(bodies, SystemScrew(twists), contacts, pairs, Vec::new()).expect("a valid row")
}

/// The compliant-contact dynamics in time, independently of the crate: generalised velocities
/// q̇ with a diagonal mass matrix `mass`, contact i's indentation rate δ̇_i = J_i q̇ (J frozen),
/// F_i = K_i δ_i^η_i for δ_i > 0, M q̈ = −Σ_i F_i J_iᵀ; classical RK4 with the step `dt`, run
/// until no contact is loaded and none approaches. Returns q̇ at the end.
pub fn compliant(
    mass: &[f64],
    jac: &[Vec<f64>],
    laws: &[(f64, f64)],
    qdot0: &[f64],
    dt: f64,
) -> Vec<f64> {
    let (m, n) = (mass.len(), jac.len());
    // State: δ (n), q̇ (m).
    let rhs = |s: &[f64]| -> Vec<f64> {
        let mut d = vec![0.0; n + m];
        for i in 0..n {
            d[i] = (0..m).map(|a| jac[i][a] * s[n + a]).sum();
        }
        for i in 0..n {
            let delta = s[i];
            if delta > 0.0 {
                let f = laws[i].0 * delta.powf(laws[i].1);
                for a in 0..m {
                    d[n + a] -= f * jac[i][a] / mass[a];
                }
            }
        }
        d
    };
    let mut s: Vec<f64> = vec![0.0; n];
    s.extend_from_slice(qdot0);
    let axpy = |s: &[f64], k: &[f64], h: f64| -> Vec<f64> {
        s.iter().zip(k).map(|(a, b)| a + h * b).collect()
    };
    for step in 0.. {
        assert!(step < 100_000_000, "the compliant integration does not end");
        let k1 = rhs(&s);
        let k2 = rhs(&axpy(&s, &k1, dt / 2.0));
        let k3 = rhs(&axpy(&s, &k2, dt / 2.0));
        let k4 = rhs(&axpy(&s, &k3, dt));
        for q in 0..n + m {
            s[q] += dt / 6.0 * (k1[q] + 2.0 * k2[q] + 2.0 * k3[q] + k4[q]);
        }
        let rates = rhs(&s);
        if (0..n).all(|i| s[i] <= 0.0 && rates[i] <= 0.0) {
            break;
        }
    }
    s[n..].to_vec()
}

/// The compliant dynamics at `dt` and `dt/2`: the finer velocities and their difference.
pub fn compliant_checked(
    mass: &[f64],
    jac: &[Vec<f64>],
    laws: &[(f64, f64)],
    qdot0: &[f64],
    dt: f64,
) -> (Vec<f64>, f64) {
    let coarse = compliant(mass, jac, laws, qdot0, dt);
    let fine = compliant(mass, jac, laws, qdot0, dt / 2.0);
    let d = coarse
        .iter()
        .zip(&fine)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    (fine, d)
}

/// ‖G‖∞ = max_i Σ_j |g_ij|.
pub fn g_norm<S: Screws<f64>>(out: &Lzb<S>) -> f64 {
    let n = out.impulses.len();
    (0..n)
        .map(|i| (0..n).map(|j| out.blocks.k[i * n + j].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// What a velocity after impact of scale `speed` may be off by (module docs).
pub fn velocity_bound<S: Screws<f64>>(out: &Lzb<S>, speed: f64) -> f64 {
    let n = out.impulses.len() as f64;
    2.0 * g_norm(out) * out.error_estimate + 64.0 * n * f64::EPSILON * speed
}
