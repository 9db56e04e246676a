//! The slender rod striking a rough floor at one end (Keller 1986; Stronge, *Impact
//! Mechanics*, ch. 5), against closed forms derived in derivations/friction-rod.md and
//! derivations/scripts/rod.py — independent code: the regimes and their impulses are written
//! here from the thresholds, not by calling the solver's rate or mode code.
//!
//! World axes: floor y = 0, rod centre C at the origin, lower end A = C − L(c, s) with
//! c = cos θ, s = sin θ; before impact v_C = (U, −V), ω = 0. The body axes are the rod's
//! principal axes (x along the rod), so the scene is built by rotating these by −θ.

use inertance::impact::friction::{Frictional, ModeLabel, Restitution, Verdict, solve_frictional};
use inertance::impact::problem::Problem;
use inertance::mechanics::body::RigidBody;
use inertance::mechanics::contact::Contact;
use inertance::mechanics::screw::{Screw, Vec3};
use inertance::scalar::symbolic::RatFun;
use inertance::scalar::{Exact, Scalar, int, ratio};

/// One rod impact: the angle as (cos θ, sin θ) from a Pythagorean triple, mass, half-length,
/// approach speed V > 0, slip U, friction μ and the coefficient k of every law.
#[derive(Clone, Debug)]
struct Rod<T> {
    c: T,
    s: T,
    m: T,
    l: T,
    v: T,
    u: T,
    mu: T,
    k: T,
}

impl<T: Scalar> Rod<T> {
    /// The scene in the rod's principal axes: A = (−L, 0, 0), n = (−s, −c, 0) (world −e_y),
    /// so t = e_z × n = (c, −s, 0) is world +e_x; J = mL²/3 about y and z, and an axial
    /// moment that planar motion never touches.
    fn problem(&self) -> Problem<T> {
        let j: T = self.m.clone() * &self.l * &self.l / int::<T>(3);
        let (vcx, vcy) = self.to_body(&self.u, &-self.v.clone());
        Problem::new(
            RigidBody::principal(
                self.m.clone(),
                Vec3::new(j.clone() / int::<T>(100), j.clone(), j),
            ),
            Screw::new(Vec3::zeros(), Vec3::new(vcx, vcy, T::zero())),
            vec![
                Contact::new(
                    Vec3::new(-self.l.clone(), T::zero(), T::zero()),
                    Vec3::new(-self.s.clone(), -self.c.clone(), T::zero()),
                    self.k.clone(),
                )
                .with_friction(self.mu.clone()),
            ],
        )
        .unwrap()
    }

    /// World (X, Y) in body axes: (X c + Y s, −X s + Y c).
    fn to_body(&self, x: &T, y: &T) -> (T, T) {
        (
            x.clone() * &self.c + y.clone() * &self.s,
            -(x.clone() * &self.s) + y.clone() * &self.c,
        )
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum M {
    Stick,
    Slide(i64),
}

/// The closed-form outcome of derivations/friction-rod.md.
#[derive(Debug)]
struct Closed<T> {
    modes: Vec<ModeLabel>,
    events: Vec<T>,
    pc: T,
    p: T,
    tau: T,
    vn: T,
    vt: T,
    omega: T,
    vc_world: (T, T),
    ef: T,
    dec: T,
    ep: T,
}

fn pos<T: Scalar>(x: &T) -> bool {
    x.signum_i8() > 0
}

fn lt<T: Scalar>(a: &T, b: &T) -> bool {
    (b.clone() - a).signum_i8() > 0
}

/// The regimes of the rod (g_nt > 0, 0 < θ < 90°); `None` where the model turns tensile
/// (a backward slide with μ ≥ g_nn/g_nt), outside what the closed forms cover.
fn closed<T: Scalar>(r: &Rod<T>, law: Restitution) -> Option<Closed<T>> {
    let (c, s, m, mu, k, v0, u0) = (&r.c, &r.s, &r.m, &r.mu, &r.k, &r.v, &r.u);
    let one = T::one();
    let two: T = int(2);
    let three: T = int(3);
    // The block: g_nn = (1 + 3c²)/m, g_nt = 3sc/m, g_tt = (1 + 3s²)/m, det = 4/m².
    let gnn = (one.clone() + three.clone() * c * c) / m.clone();
    let gnt = three.clone() * s * c / m.clone();
    let gtt = (one.clone() + three.clone() * s * s) / m.clone();
    let det: T = int::<T>(4) / (m.clone() * m);
    assert_eq!(gnn.clone() * &gtt - gnt.clone() * &gnt, det);
    let gstar = det.clone() / gtt.clone();
    let mubar = gnt.clone() / gtt.clone();
    let a = |md: M| match md {
        M::Stick => gstar.clone(),
        M::Slide(u) => gnn.clone() + int::<T>(u) * mu * &gnt,
    };
    let b = |md: M| match md {
        M::Stick => T::zero(),
        M::Slide(u) => gnt.clone() + int::<T>(u) * mu * &gtt,
    };
    let dtau = |md: M| match md {
        M::Stick => -mubar.clone(),
        M::Slide(u) => int::<T>(u) * mu,
    };
    // Stick is consistent at zero slip iff μ ≥ μ̄ = g_nt/g_tt; otherwise the slip reverses
    // (slide− is the only consistent mode).
    let after_stop = if lt(mu, &mubar) {
        M::Slide(-1)
    } else {
        M::Stick
    };
    let (seq, pst) = if u0.is_zero() {
        (vec![after_stop], None)
    } else {
        let su = if pos(u0) { 1 } else { -1 };
        let bu = b(M::Slide(su));
        if pos(&(int::<T>(su) * &bu)) {
            (vec![M::Slide(su), after_stop], Some(u0.clone() / bu))
        } else {
            (vec![M::Slide(su)], None)
        }
    };
    if seq.iter().any(|&md| !pos(&a(md))) {
        return None;
    }
    // Compression: p' = V / a(mode); the slip stops at p = U / b.
    let mut events = Vec::new();
    let stop_in_compression = pst
        .as_ref()
        .map(|ps| a(seq[0]) * ps / v0.clone())
        .filter(|s1| lt(s1, &one));
    let (pc, wc, rmode, rstop) = match &stop_in_compression {
        Some(s1) => {
            let ps = pst.clone().unwrap();
            let pc = ps.clone() + (one.clone() - s1) * v0 / a(seq[1]);
            let v1 = v0.clone() * (one.clone() - s1);
            let wc = (v0.clone() + &v1) / two.clone() * &ps + v1 / two.clone() * (pc.clone() - &ps);
            events.push(s1.clone());
            (pc, wc, seq[1], None)
        }
        None => {
            let pc = v0.clone() / a(seq[0]);
            let wc = v0.clone() * &pc / two.clone();
            (pc, wc, seq[0], pst.clone())
        }
    };
    // Restitution, σ = s − 1.
    let mut two_modes = stop_in_compression.is_some();
    let p = match law {
        Restitution::Poisson => {
            let p = (one.clone() + k) * &pc;
            if let Some(ps) = rstop.as_ref().filter(|ps| lt(*ps, &p)) {
                events.push(one.clone() + (ps.clone() - &pc) / (k.clone() * &pc));
                two_modes = true;
            }
            p
        }
        Restitution::Newton => {
            let pend = pc.clone() + k.clone() * v0 / a(rmode);
            match rstop.as_ref().filter(|ps| lt(*ps, &pend)) {
                Some(ps) => {
                    let sig = (ps.clone() - &pc) * a(rmode) / (k.clone() * v0);
                    events.push(one.clone() + &sig);
                    two_modes = true;
                    ps.clone() + (one.clone() - sig) * k * v0 / a(seq[1])
                }
                None => pend,
            }
        }
        Restitution::Energetic => {
            // Restitution work W_r(p) = ∫ a (q − p^c) dq piecewise; stop at W_r = k² W_c.
            let target = k.clone() * k * &wc;
            let a0 = a(rmode);
            let w1 = rstop
                .as_ref()
                .map(|ps| a0.clone() * (ps.clone() - &pc) * (ps.clone() - &pc) / two.clone());
            match (&rstop, &w1) {
                (Some(ps), Some(w1)) if lt(w1, &target) => {
                    let a1 = a(seq[1]);
                    let d0 = a0.clone() * (ps.clone() - &pc);
                    let disc = d0.clone() * &d0 + two.clone() * &a1 * (target - w1);
                    events.push(one.clone() + (ps.clone() - &pc) / pc.clone());
                    two_modes = true;
                    ps.clone() + (disc.sqrt_value()? - d0) / a1
                }
                _ => pc.clone() + (two.clone() * target / a0).sqrt_value()?,
            }
        }
    };
    // The tangential impulse and the friction work, mode by mode (v_t linear in p on a slide).
    let pieces = if two_modes {
        let ps = pst.clone().unwrap();
        vec![
            (seq[0], T::zero(), ps.clone(), u0.clone()),
            (seq[1], ps, p.clone(), T::zero()),
        ]
    } else {
        vec![(seq[0], T::zero(), p.clone(), u0.clone())]
    };
    let mut tau = T::zero();
    let mut ef = T::zero();
    for (md, pa, pb, vta) in &pieces {
        let dp = pb.clone() - pa;
        tau += dp.clone() * dtau(*md);
        if let M::Slide(u) = md {
            let vtb = vta.clone() - b(*md) * &dp;
            ef += int::<T>(*u) * mu * (vta.clone() + vtb) / two.clone() * dp;
        }
    }
    let vn = v0.clone() - gnn.clone() * &p - gnt.clone() * &tau;
    let vt = u0.clone() - gnt.clone() * &p - gtt.clone() * &tau;
    let dec = (p.clone() * (v0.clone() + &vn) + tau.clone() * (u0.clone() + &vt)) / two.clone();
    let ep = (gnn * &p * &p + two.clone() * &gnt * &p * &tau + gtt * &tau * &tau) / two;
    let omega = -(three * (c.clone() * &p + s.clone() * &tau)) / (m.clone() * &r.l);
    let vc_world = (
        u0.clone() - tau.clone() / m.clone(),
        -v0.clone() + p.clone() / m.clone(),
    );
    let label = |md: &M| match md {
        M::Stick => ModeLabel::Stick,
        M::Slide(1) => ModeLabel::SlidePlus,
        M::Slide(_) => ModeLabel::SlideMinus,
    };
    let modes = if two_modes { &seq[..] } else { &seq[..1] };
    Some(Closed {
        modes: modes.iter().map(label).collect(),
        events,
        pc,
        p,
        tau,
        vn,
        vt,
        omega,
        vc_world,
        ef,
        dec,
        ep,
    })
}

/// Where the contact's mode changes: the ends of segments followed by another mode.
fn events<T: Scalar>(out: &Frictional<T>) -> Vec<T> {
    out.segments
        .windows(2)
        .filter(|w| w[0].modes[0] != w[1].modes[0])
        .map(|w| w[0].to.clone())
        .collect()
}

/// Solve `rod` under `law` and assert every quantity equals its closed form exactly;
/// `false` when the point lies outside the closed forms (a tensile rate).
fn check<T: Scalar>(rod: &Rod<T>, law: Restitution) -> bool {
    let Some(mut want) = closed(rod, law) else {
        // A backward slide with a₋ = g_nn − μ g_nt ≤ 0: driving v_n down at a fixed rate asks
        // the floor to pull, and the solver must say so (the energetic law may instead stop
        // at a nested radical it cannot hold).
        match solve_frictional(&rod.problem(), law, 1e-10) {
            Ok(out) => assert!(
                out.verdicts
                    .iter()
                    .any(|v| matches!(v, Verdict::TensileRate { .. })),
                "no tensile verdict, {law} at {rod:?}"
            ),
            Err(e) => assert_eq!(law, Restitution::Energetic, "{e}"),
        }
        return false;
    };
    let frictionless = rod.mu.is_zero();
    if frictionless {
        // No tangential axis: one mode, no events, no tangential entries.
        want.modes = vec![ModeLabel::Free];
        want.events.clear();
    }
    let out = solve_frictional(&rod.problem(), law, 1e-10).unwrap();
    let at = format!("{law} at {rod:?}");
    // The solver's tangent, and the senses of slide±, follow the contact's tangent y, which
    // §12 points along the slip before impact: −t when U < 0 (t = world +e_x above).
    let flip = rod.u.signum_i8() < 0;
    let along_y = |x: &T| if flip { -x.clone() } else { x.clone() };
    let relabel = |m: &ModeLabel| match (flip, m) {
        (true, ModeLabel::SlidePlus) => ModeLabel::SlideMinus,
        (true, ModeLabel::SlideMinus) => ModeLabel::SlidePlus,
        _ => *m,
    };
    let modes: Vec<ModeLabel> = want.modes.iter().map(relabel).collect();
    assert_eq!(out.history(0), modes, "modes, {at}");
    assert_eq!(events(&out), want.events, "events, {at}");
    assert_eq!(out.compression[0], want.pc, "p^c, {at}");
    assert_eq!(out.impulses[0], want.p, "P, {at}");
    if frictionless {
        assert!(want.tau.is_zero());
        assert_eq!(out.after, vec![want.vn.clone()], "v after, {at}");
    } else {
        assert_eq!(out.impulses[1], along_y(&want.tau), "tau, {at}");
        assert_eq!(
            out.after,
            vec![want.vn.clone(), along_y(&want.vt)],
            "v after, {at}"
        );
    }
    let (vx, vy) = rod.to_body(&want.vc_world.0, &want.vc_world.1);
    let twist = [T::zero(), T::zero(), want.omega.clone(), vx, vy, T::zero()];
    assert_eq!(out.velocity.as_slice(), &twist[..], "twist, {at}");
    assert_eq!(out.friction_dissipation, want.ef, "E_f, {at}");
    assert_eq!(out.kinetic_energy_loss, want.dec, "dE_c, {at}");
    assert_eq!(out.lost_velocity_energy, want.ep, "E_p, {at}");
    // Invariants.
    assert!(out.energy_residual.is_zero(), "energy residual, {at}");
    assert!(out.friction_dissipation.signum_i8() >= 0, "E_f < 0, {at}");
    if law == Restitution::Energetic {
        assert!(
            out.kinetic_energy_loss.signum_i8() >= 0,
            "energetic dE_c < 0, {at}"
        );
        assert!(!out.verdicts.contains(&Verdict::EnergyGain), "{at}");
    }
    assert!(
        !out.verdicts
            .iter()
            .any(|v| matches!(v, Verdict::TensileRate { .. })),
        "tensile, {at}"
    );
    true
}

/// (cos θ, sin θ) from Pythagorean triples: 3-4-5 both ways, 5-12-13 both ways, 8-15-17.
const ANGLES: [(i64, i64, i64); 5] = [(3, 4, 5), (4, 3, 5), (5, 12, 13), (12, 5, 13), (8, 15, 17)];

/// The μ of each regime for (c, s): around μ̄ = 3cs/(1 + 3s²) (stick vs reversal), μ̄ itself,
/// zero, and large (up to the tensile bound of a backward slide, which filters itself out).
fn mus<T: Scalar>(c: &T, s: &T) -> Vec<T> {
    let three: T = int(3);
    let mubar = three.clone() * c * s / (T::one() + three * s * s);
    vec![
        T::zero(),
        mubar.clone() / int::<T>(2),
        mubar.clone(),
        mubar.clone() * ratio::<T>(3, 2),
        mubar * int::<T>(3),
    ]
}

/// The slips of each regime, relative to V and to the stop ratios b_±/a_± of the closed
/// forms: both senses, zero, and the exact thresholds (stop at s = 1, stop at the end).
fn slips<T: Scalar>(rod: &Rod<T>) -> Vec<T> {
    let three: T = int(3);
    let (c, s, m, mu, v) = (&rod.c, &rod.s, &rod.m, &rod.mu, &rod.v);
    let gnn = (T::one() + three.clone() * c * c) / m.clone();
    let gnt = three.clone() * s * c / m.clone();
    let gtt = (T::one() + three * s * s) / m.clone();
    let ratio_plus = (gnt.clone() + mu.clone() * &gtt) / (gnn + mu.clone() * &gnt);
    let mut out: Vec<T> = [
        ratio::<T>(-2, 1),
        ratio(-1, 4),
        T::zero(),
        ratio(1, 4),
        int(1),
        int(3),
    ]
    .into_iter()
    .map(|x| x * v)
    .collect();
    out.push(ratio_plus.clone() * v);
    out.push(ratio_plus * (T::one() + &rod.k) * v);
    out
}

fn sweep<T: Scalar>(laws: &[Restitution], ks: &[T], thin: usize) -> usize {
    let mut checked = 0;
    let mut n = 0;
    for (ci, si, hi) in ANGLES {
        let (c, s) = (ratio::<T>(ci, hi), ratio::<T>(si, hi));
        for mu in mus(&c, &s) {
            for k in ks {
                for (m, l, v) in [(int(1), int(1), int(1)), (int(2), ratio(3, 2), ratio(5, 2))] {
                    let base = Rod {
                        c: c.clone(),
                        s: s.clone(),
                        m,
                        l,
                        v,
                        u: T::zero(),
                        mu: mu.clone(),
                        k: k.clone(),
                    };
                    for u in slips(&base) {
                        n += 1;
                        if n % thin != 0 {
                            continue;
                        }
                        let rod = Rod { u, ..base.clone() };
                        for &law in laws {
                            if check(&rod, law) {
                                checked += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    checked
}

#[test]
fn newton_and_poisson_match_the_closed_forms_exactly() {
    let checked = sweep::<Exact>(
        &[Restitution::Newton, Restitution::Poisson],
        &[ratio(1, 2), ratio(9, 10), int(1)],
        1,
    );
    assert!(checked > 900, "only {checked} points checked");
}

#[test]
fn energetic_matches_the_closed_forms_with_exact_radicals() {
    let checked = sweep::<RatFun>(&[Restitution::Energetic], &[ratio(1, 2), ratio(9, 10)], 3);
    assert!(checked > 100, "only {checked} points checked");
}

/// The 3-4-5 rod (cos θ = 3/5) of derivations/friction-rod.md, m = L = V = 1.
fn rod_345<T: Scalar>(u: T, mu: T, k: T) -> Rod<T> {
    Rod {
        c: ratio(3, 5),
        s: ratio(4, 5),
        m: int(1),
        l: int(1),
        v: int(1),
        u,
        mu,
        k,
    }
}

#[test]
fn a_contact_at_rest_sticks_from_mu_bar_and_reverses_below_it() {
    // μ̄ = 3cs/(1 + 3s²) = (36/25)/(73/25) = 36/73: the stick test |τ'| ≤ μ p' with
    // τ' = −(g_nt/g_tt) p' holds with equality.
    let at = |mu: Exact| {
        solve_frictional(
            &rod_345(int(0), mu, ratio(1, 2)).problem(),
            Restitution::Poisson,
            0.0,
        )
        .unwrap()
        .history(0)
    };
    assert_eq!(at(ratio(36, 73)), [ModeLabel::Stick]);
    assert_eq!(at(ratio(35, 73)), [ModeLabel::SlideMinus]);
    // A forward slip that stops reverses below μ̄ and sticks from it.
    let stop = |mu: Exact| {
        let out = solve_frictional(
            &rod_345(ratio(1, 4), mu, ratio(1, 2)).problem(),
            Restitution::Poisson,
            0.0,
        )
        .unwrap();
        (out.history(0), events(&out))
    };
    // At μ = 36/73: a₊ = g_nn + μ g_nt = 5092/1825 and b₊ = g_nt + μ g_tt = 72/25 = 5256/1825,
    // so b₊/a₊ = 1314/1273 > U/V = 1/4 and the slip stops in compression at
    // s = (U/V)(a₊/b₊) = 1273/5256.
    assert_eq!(
        stop(ratio(36, 73)),
        (
            vec![ModeLabel::SlidePlus, ModeLabel::Stick],
            vec![ratio(1273, 5256)]
        )
    );
    assert_eq!(
        stop(ratio(35, 73)).0,
        [ModeLabel::SlidePlus, ModeLabel::SlideMinus]
    );
}

/// Kane's paradox (Kane and Levinson 1985; Stronge 1991) on the rod: the slip stops during
/// compression and the end sticks, and Newton's law then returns more energy than it took.
#[test]
fn kane_newton_gains_energy_where_poisson_and_energetic_dissipate() {
    let (u, mu, k) = (
        ratio::<RatFun>(1, 2),
        int::<RatFun>(1),
        ratio::<RatFun>(9, 10),
    );
    let rod = rod_345(u.clone(), mu, k.clone());
    let run = |law| solve_frictional(&rod.problem(), law, 0.0).unwrap();
    let (newton, poisson, energetic) = (
        run(Restitution::Newton),
        run(Restitution::Poisson),
        run(Restitution::Energetic),
    );
    for out in [&newton, &poisson, &energetic] {
        assert_eq!(out.history(0), [ModeLabel::SlidePlus, ModeLabel::Stick]);
        assert_eq!(events(out), [ratio::<RatFun>(44, 109)]);
        assert!(out.energy_residual.signum_i8() == 0);
        assert!(out.after[1].signum_i8() == 0);
    }
    // Newton with the end stuck: the contact velocity after is (−kV, 0), so
    // ΔE_c = [g_tt V²(1 − k²) − 2 g_nt U V + g_nn U²] / (2 det).
    let (gnn, gnt, gtt, det): (RatFun, RatFun, RatFun, RatFun) =
        (ratio(52, 25), ratio(36, 25), ratio(73, 25), int(4));
    let one = RatFun::from_integer(1);
    let newton_loss = (gtt * (one - k.clone() * &k) - int::<RatFun>(2) * gnt * &u + gnn * &u * &u)
        / (int::<RatFun>(2) * det);
    assert_eq!(newton_loss, ratio(-913, 20000));
    assert_eq!(newton.kinetic_energy_loss, newton_loss);
    assert!(newton.verdicts.contains(&Verdict::EnergyGain));
    assert_eq!(poisson.kinetic_energy_loss, ratio(4799, 58400));
    assert!(!poisson.verdicts.contains(&Verdict::EnergyGain));
    // Energetic: ΔE_c = (1 − k²) W_c + E_f, rational although the impulses carry √1535701.
    assert_eq!(energetic.kinetic_energy_loss, ratio(6167, 87200));
    let wc = energetic.work_compression[0].clone();
    assert_eq!(
        energetic.kinetic_energy_loss,
        (RatFun::from_integer(1) - k.clone() * &k) * wc + &energetic.friction_dissipation
    );
    assert!(!energetic.verdicts.contains(&Verdict::EnergyGain));
    // Each against the regime's closed forms too.
    for law in Restitution::ALL {
        assert!(check(&rod, law));
    }
}

/// The scenes of derivations/friction-rod.md, at the values printed there.
#[test]
fn the_scenes_of_the_derivation_file() {
    let case = |u: Exact, mu: Exact, k: Exact, law| {
        let rod = rod_345(u, mu, k);
        assert!(check(&rod, law));
        let out = solve_frictional(&rod.problem(), law, 0.0).unwrap();
        (
            out.impulses[0].clone(),
            events(&out),
            out.kinetic_energy_loss,
        )
    };
    let (quarter, half) = (ratio::<Exact>(1, 4), ratio::<Exact>(1, 2));
    assert_eq!(
        case(
            quarter.clone(),
            half.clone(),
            half.clone(),
            Restitution::Newton
        ),
        (ratio(201, 200), vec![ratio(7, 29)], ratio(1, 5))
    );
    assert_eq!(
        case(
            quarter.clone(),
            half.clone(),
            half.clone(),
            Restitution::Poisson
        ),
        (ratio(24, 25), vec![ratio(7, 29)], ratio(12913, 58400))
    );
    assert_eq!(
        case(
            quarter.clone(),
            quarter.clone(),
            half.clone(),
            Restitution::Newton
        ),
        (
            ratio(15375, 18662),
            vec![ratio(61, 217)],
            ratio(2504710275, 11144647808)
        )
    );
    assert_eq!(
        case(
            quarter.clone(),
            quarter.clone(),
            half.clone(),
            Restitution::Poisson
        ),
        (
            ratio(14925, 18662),
            vec![ratio(61, 217)],
            ratio(2600275875, 11144647808)
        )
    );
    for law in [Restitution::Newton, Restitution::Poisson] {
        assert_eq!(
            case(int(3), quarter.clone(), half.clone(), law),
            (ratio(75, 122), vec![], ratio(243975, 476288))
        );
    }
}
