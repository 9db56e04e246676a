//! The falling rod of `examples/simulate/falling-rod.toml` against an independent integration
//! written here from the textbook, sharing nothing with `simulate` but the scene's numbers:
//!
//! * **flight** in closed form — the planar rod's centre on its parabola and its angle
//!   φ(t) = φ₀ + ω t (no torque in flight; a planar rod has no gyroscopic term) — and the next
//!   impact as the first root of an end's height z ± (L/2) cos φ(t), bracketed on a grid of
//!   10⁻⁴ s and bisected to 10⁻¹⁵ s (no conservative advancement, no Runge–Kutta);
//! * **each impact** of one end on the rough floor by Routh's construction in the impulse plane:
//!   the contact velocity u = (u_t, u_n) changes by du = K dP with the planar K of the end,
//!   K = [[1/m + r_z²/J, −r_x r_z/J], [−r_x r_z/J, 1/m + r_x²/J]]; the normal impulse p grows
//!   until Newton's u_n = −k u_n⁰; while the end slides dP_t = −μ sgn(u_t) dp; when u_t reaches
//!   0 it sticks if |K_tn/K_tt| ≤ μ (dP_t/dp = −K_tn/K_tt) and otherwise slides the other way
//!   (the piecewise-linear impulse path of the toolkit's §14 law for one contact, solved here
//!   segment by segment in closed form).
//!
//! **Tolerance.** Our simulation locates each impact to the gap tolerance 10⁻¹¹ L and solves
//! it to 10⁻¹⁰ relative; the reference here to rounding. Each impact carries the differences
//! before it into the flight's rotation and height, so they grow impact by impact: measured,
//! 2.5·10⁻¹² m/s over the first ten impacts, 7·10⁻¹⁰ m/s (and 7·10⁻¹¹ s) by the twentieth,
//! 7·10⁻⁸ m/s by the thirtieth, and at the thirty-fourth (speeds of 5·10⁻⁴ m/s, impacts 10⁻⁵ s
//! apart, the rod chattering to rest) the two disagree on which end strikes next. The test
//! holds the first twenty to 10⁻⁸ (s, m/s, N s; the speeds are of order 1 m/s): ten times the
//! largest measured there.

use inertance::scene::SimulationScene;
use inertance::simulate::simulate;

const L: f64 = 1.0;
const M: f64 = 1.0;
const G: f64 = 9.81;
const K_REST: f64 = 0.5;
const MU: f64 = 0.3;

#[derive(Clone, Copy, Debug)]
struct Rod {
    x: f64,
    z: f64,
    phi: f64,
    vx: f64,
    vz: f64,
    w: f64,
}

impl Rod {
    /// The end `s` (±1): its offset from C, r = s (L/2) (sin φ, cos φ) in (x, z).
    fn arm(&self, s: f64) -> (f64, f64) {
        (s * L / 2.0 * self.phi.sin(), s * L / 2.0 * self.phi.cos())
    }

    fn fly(&self, t: f64) -> Rod {
        Rod {
            x: self.x + self.vx * t,
            z: self.z + self.vz * t - 0.5 * G * t * t,
            phi: self.phi + self.w * t,
            vx: self.vx,
            vz: self.vz - G * t,
            w: self.w,
        }
    }

    fn height(&self, s: f64, t: f64) -> f64 {
        let r = self.fly(t);
        r.z + r.arm(s).1
    }
}

/// The next impact from `rod` (just after an impact or at rest at the start): the time and
/// the end (±1), the first to reach the floor.
fn next_impact(rod: &Rod) -> (f64, f64) {
    let h = 1e-4;
    let mut t = 0.0;
    loop {
        for s in [-1.0, 1.0] {
            // a sign change from above the floor (the end just struck starts at 0, rising)
            let (a, b) = (rod.height(s, t), rod.height(s, t + h));
            if a > -1e-13 && b < 0.0 && (t > 0.0 || a > 1e-12 || rod.fly(0.0).vz < 0.0) {
                let (mut lo, mut hi) = (t, t + h);
                while hi - lo > 1e-15 {
                    let mid = 0.5 * (lo + hi);
                    if rod.height(s, mid) > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return (0.5 * (lo + hi), s);
            }
        }
        t += h;
        assert!(t < 10.0, "no impact");
    }
}

/// Routh's impact of end `s` (module docs): the rod after, the contact's normal speed before
/// and after, and the normal impulse.
fn impact(rod: &Rod, s: f64) -> (Rod, f64, f64, f64) {
    let j = M * L * L / 12.0;
    let (rx, rz) = rod.arm(s);
    // contact velocity: v + ω e_y × r, e_y × (r_x, 0, r_z) = (r_z, 0, −r_x)
    let u = |vx: f64, vz: f64, w: f64| (vx + w * rz, vz - w * rx);
    let ktt = 1.0 / M + rz * rz / j;
    let ktn = -rx * rz / j;
    let knn = 1.0 / M + rx * rx / j;
    let (ut0, un0) = u(rod.vx, rod.vz, rod.w);
    let target = -K_REST * un0;
    let (mut ut, mut un) = (ut0, un0);
    let (mut pt, mut pn) = (0.0, 0.0);
    while un < target - 1e-15 * un0.abs() {
        // the direction of the impulse path: dP_t/dp
        let slope = if ut.abs() > 1e-14 * un0.abs() {
            -MU * ut.signum()
        } else if (ktn / ktt).abs() <= MU {
            -ktn / ktt
        } else {
            -MU * ktn.signum()
        };
        let dut = ktt * slope + ktn; // du_t/dp
        let dun = ktn * slope + knn; // du_n/dp
        assert!(dun > 0.0, "the normal speed grows along the path");
        let mut dp = (target - un) / dun;
        if ut.abs() > 1e-14 * un0.abs() && dut * ut < 0.0 {
            dp = dp.min(-ut / dut); // the slip stops first
        }
        pt += slope * dp;
        pn += dp;
        ut += dut * dp;
        un += dun * dp;
        if ut.abs() <= 1e-14 * un0.abs() {
            ut = 0.0;
        }
    }
    let after = Rod {
        vx: rod.vx + pt / M,
        vz: rod.vz + pn / M,
        w: rod.w + (rz * pt - rx * pn) / j,
        ..*rod
    };
    (after, un0, un, pn)
}

#[test]
fn the_falling_rod_matches_an_independent_integration_impact_by_impact() {
    let scene = SimulationScene::load(std::path::Path::new("examples/simulate/falling-rod.toml"))
        .expect("reads");
    let sim = simulate(&scene.setup).expect("runs");
    let phi0 = std::f64::consts::FRAC_PI_4;
    let mut rod = Rod {
        x: 0.0,
        z: 0.5 + 0.5 * phi0.cos(),
        phi: phi0,
        vx: 0.0,
        vz: 0.0,
        w: 0.0,
    };
    let mut t = 0.0;
    let mut worst = [0.0f64; 3];
    for (n, ours) in sim.impacts.iter().take(20).enumerate() {
        let (tau, s) = next_impact(&rod);
        rod = rod.fly(tau);
        t += tau;
        let (after, before_n, after_n, p) = impact(&rod, s);
        rod = after;
        let end = if s < 0.0 {
            "end [0, 0, -1]"
        } else {
            "end [0, 0, 1]"
        };
        assert_eq!(ours.contacts.len(), 1, "impact {}: one end", n + 1);
        let c = &ours.contacts[0];
        assert!(
            c.feature.starts_with(end),
            "impact {}: {} against {end}",
            n + 1,
            c.feature
        );
        let d = [
            (ours.t - t).abs(),
            (c.before - before_n).abs().max((c.after - after_n).abs()),
            (c.impulse - p).abs(),
        ];
        eprintln!(
            "impact {}: Δt {:.1e} s, Δġ {:.1e} m/s, ΔP {:.1e} N s",
            n + 1,
            d[0],
            d[1],
            d[2]
        );
        assert!(d[0] < 1e-8, "impact {}: t {} against {t}", n + 1, ours.t);
        assert!(
            d[1] < 1e-8,
            "impact {}: ġ {} → {} against {before_n} → {after_n}",
            n + 1,
            c.before,
            c.after
        );
        assert!(d[2] < 1e-8, "impact {}: P {} against {p}", n + 1, c.impulse);
        for k in 0..3 {
            worst[k] = worst[k].max(d[k]);
        }
    }
    eprintln!("largest differences over twenty impacts: {worst:?}");
}
