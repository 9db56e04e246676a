//! Exact runs: a frictionless sphere among planes under gravity, every impact time, velocity
//! and the accumulation time computed in an exact scalar type (rationals, or the radicals of
//! [`crate::scalar::symbolic`]) — no integration, no tolerance.
//!
//! **Why it is exact.** Between impacts the centre flies on its parabola,
//! x(τ) = x + v τ + ½ g τ², so the gap to plane i, g_i(τ) = N_i·(x(τ) − P_i) − r, is the
//! quadratic g_i + ġ_i τ + ½ a_i τ² with a_i = N_i·g. Its first root τ > 0 while approaching
//! is the next contact with that plane:
//!
//! ```text
//! g_i = 0, ġ_i > 0, a_i < 0:   τ_i = −2 ġ_i / a_i                      (a flight from the plane)
//! g_i > 0, a_i ≠ 0:            τ_i = (−ġ_i − √(ġ_i² − 2 a_i g_i)) / a_i   (the smaller positive root)
//! g_i > 0, a_i = 0, ġ_i < 0:   τ_i = −g_i / ġ_i
//! ```
//!
//! A flight from a plane back to it needs no root, so a ball bouncing on a floor stays in the
//! field of its first flight: dropped from height h, everything is in ℚ(√(2 g h)); launched from
//! the floor with a rational speed, everything is rational. A flight to another plane needs
//! √(ġ² − 2 a g) of the current state: exact while that radicand is rational (the first flight,
//! or planes the gravity does not reach); otherwise the run stops and says the time is a
//! nested radical ([`ExactError::NestedRadical`]).
//!
//! **The impact.** A frictionless sphere strikes one plane with the normal velocity
//! v_n = N·v < 0; every law of the toolkit gives the same one-contact answer
//! v_n⁺ = −k v_n (Newton's k = Poisson's for one contact; Stronge's energetic coefficient and
//! the LZB law's e for one frictionless contact are the same k — [`crate::impact::multiple`]):
//! v⁺ = v − (1 + k) v_n N. Its spin never changes (no friction, the normal through C).
//! Two planes struck at the same exact time are a multi-point impact this path does not solve
//! ([`ExactError::Simultaneous`]).
//!
//! **Zeno.** With one plane and 0 < k < 1, after the first impact the ball rises at
//! u₁ = −k v_n⁻, each flight lasts 2uₙ/|a| and uₙ₊₁ = k uₙ: the impacts accumulate at
//! t∞ = t₁ + 2u₁/(|a|(1 − k)), where the ball comes to rest on the plane. The run lists the
//! impacts up to its budget and reports t∞ exactly.

use crate::scalar::Scalar;

/// A vector of the exact type.
pub type V<T> = [T; 3];

/// A plane of an exact run.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactPlane<T: Scalar> {
    /// Its name.
    pub name: String,
    /// N, unit, out of the obstacle.
    pub normal: V<T>,
    /// A point P of it.
    pub point: V<T>,
    /// The coefficient of restitution of its contact.
    pub k: T,
}

/// A sphere among planes, exactly.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactSphere<T: Scalar> {
    /// r.
    pub radius: T,
    /// The centre at t = 0.
    pub x: V<T>,
    /// Its velocity at t = 0.
    pub v: V<T>,
    /// g.
    pub gravity: V<T>,
    /// The planes.
    pub planes: Vec<ExactPlane<T>>,
    /// The time simulated.
    pub duration: T,
    /// The most impacts listed.
    pub max_impacts: usize,
}

/// One impact of an exact run.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactImpact<T: Scalar> {
    /// t.
    pub t: T,
    /// The plane struck.
    pub plane: usize,
    /// The normal velocity before (negative) and after.
    pub before: T,
    /// After.
    pub after: T,
    /// The centre there.
    pub x: V<T>,
}

/// Why an exact run ended.
#[derive(Clone, Debug, PartialEq)]
pub enum ExactEnd<T: Scalar> {
    /// The duration was reached.
    Duration,
    /// The impact budget was spent.
    Impacts,
    /// The impacts accumulate at t∞ (one plane, 0 < k < 1), within the duration; the ball
    /// rests on the plane from there.
    Zeno {
        /// t∞.
        t_inf: T,
    },
    /// The ball came to rest on a plane (k = 0, or it started there at rest).
    Rest,
    /// No plane is ever reached.
    Escapes,
    /// The run left the exact path ([`ExactError`]).
    Stopped,
}

/// An exact run.
#[derive(Clone, Debug, PartialEq)]
pub struct ExactRun<T: Scalar> {
    /// The impacts, in order.
    pub impacts: Vec<ExactImpact<T>>,
    /// The accumulation time when one plane is struck with 0 < k < 1 (whether or not the
    /// budget or the duration ends the list first).
    pub zeno: Option<T>,
    /// Why it ended.
    pub end: ExactEnd<T>,
    /// When (for Duration, Impacts, Rest: the time reached; for Zeno: t∞).
    pub t_end: T,
    /// The centre and velocity there.
    pub x: V<T>,
    /// Velocity.
    pub v: V<T>,
}

/// Why an exact run stopped.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ExactError {
    /// The next contact time is the root of a radicand that is itself irrational.
    #[error(
        "the time of the next contact with \"{plane}\" after impact {after} is a nested radical \
         (√ of {radicand}): the exact path stops here; run it in f64"
    )]
    NestedRadical {
        /// The plane.
        plane: String,
        /// The impacts before.
        after: usize,
        /// The radicand, as text.
        radicand: String,
    },
    /// Two planes are struck at the same exact time.
    #[error(
        "\"{first}\" and \"{second}\" are struck at the same instant (impact {index}): a \
         multi-point impact, which the exact path does not solve; run it in f64"
    )]
    Simultaneous {
        /// One plane.
        first: String,
        /// The other.
        second: String,
        /// The impact's number.
        index: usize,
    },
}

fn dot<T: Scalar>(a: &V<T>, b: &V<T>) -> T {
    a[0].clone() * &b[0] + a[1].clone() * &b[1] + a[2].clone() * &b[2]
}

fn two<T: Scalar>() -> T {
    T::one() + T::one()
}

/// The first τ > 0 at which the sphere reaches plane `p` while approaching, from gap `g`, rate
/// `rate`, normal acceleration `a` (module docs); `None` when it never does.
fn contact_time<T: Scalar>(g: &T, rate: &T, a: &T) -> Result<Option<T>, T> {
    if g.is_zero() {
        // on the plane: it returns only from a flight away from it
        return Ok(
            (rate.signum_i8() > 0 && a.signum_i8() < 0).then(|| -(two::<T>() * rate) / a.clone())
        );
    }
    if a.is_zero() {
        return Ok((rate.signum_i8() < 0).then(|| -g.clone() / rate.clone()));
    }
    let disc = rate.clone() * rate - two::<T>() * a * g;
    if disc.signum_i8() < 0 {
        return Ok(None);
    }
    let Some(root) = disc.sqrt_exact() else {
        return Err(disc);
    };
    // roots (−ġ ± √D)/a; the smallest positive
    let mut best: Option<T> = None;
    for s in [T::one(), -T::one()] {
        let tau = (-rate.clone() + s * &root) / a.clone();
        if tau.signum_i8() > 0
            && best
                .as_ref()
                .is_none_or(|b| (tau.clone() - b).signum_i8() < 0)
        {
            best = Some(tau);
        }
    }
    Ok(best)
}

/// Run the sphere exactly (module docs).
///
/// # Errors
/// [`ExactError`]: a nested radical, or two planes struck at once.
pub fn run_exact<T: Scalar>(s: &ExactSphere<T>) -> Result<ExactRun<T>, ExactError> {
    match run_exact_history(s) {
        (run, None) => Ok(run),
        (_, Some(e)) => Err(e),
    }
}

/// Run the sphere exactly, keeping the impacts up to an error ([`ExactEnd::Stopped`]).
pub fn run_exact_history<T: Scalar>(s: &ExactSphere<T>) -> (ExactRun<T>, Option<ExactError>) {
    let mut t = T::zero();
    let mut x = s.x.clone();
    let mut v = s.v.clone();
    let mut impacts: Vec<ExactImpact<T>> = Vec::new();
    let single = s.planes.len() == 1;
    let mut zeno: Option<T> = None;
    let advance = |x: &mut V<T>, v: &mut V<T>, tau: &T| {
        let half_tau2 = tau.clone() * tau / two::<T>();
        for i in 0..3 {
            x[i] = x[i].clone() + v[i].clone() * tau + s.gravity[i].clone() * &half_tau2;
            v[i] = v[i].clone() + s.gravity[i].clone() * tau;
        }
    };
    let mut error = None;
    let end = 'run: loop {
        // the next contact
        let mut next: Option<(T, usize)> = None;
        let mut tie: Option<(usize, usize)> = None;
        let mut resting = false;
        for (p, plane) in s.planes.iter().enumerate() {
            let g = dot(&plane.normal, &x) - dot(&plane.normal, &plane.point) - s.radius.clone();
            let rate = dot(&plane.normal, &v);
            let a = dot(&plane.normal, &s.gravity);
            if g.is_zero() && rate.is_zero() && a.signum_i8() < 0 {
                resting = true;
            }
            let tau = match contact_time(&g, &rate, &a) {
                Ok(tau) => tau,
                Err(radicand) => {
                    error = Some(ExactError::NestedRadical {
                        plane: plane.name.clone(),
                        after: impacts.len(),
                        radicand: radicand
                            .exact_text()
                            .unwrap_or_else(|| format!("{:e}", radicand.to_f64())),
                    });
                    break 'run ExactEnd::Stopped;
                }
            };
            if let Some(tau) = tau {
                match &next {
                    Some((best, q)) => match (tau.clone() - best).signum_i8() {
                        -1 => {
                            next = Some((tau, p));
                            tie = None;
                        }
                        0 => tie = Some((*q, p)),
                        _ => {}
                    },
                    None => next = Some((tau, p)),
                }
            }
        }
        if resting {
            break ExactEnd::Rest;
        }
        let Some((tau, p)) = next else {
            break ExactEnd::Escapes;
        };
        if (t.clone() + &tau - &s.duration).signum_i8() > 0 {
            let rest = s.duration.clone() - &t;
            advance(&mut x, &mut v, &rest);
            t = s.duration.clone();
            break ExactEnd::Duration;
        }
        if impacts.len() >= s.max_impacts {
            break ExactEnd::Impacts;
        }
        if let Some((q, r)) = tie {
            error = Some(ExactError::Simultaneous {
                first: s.planes[q].name.clone(),
                second: s.planes[r].name.clone(),
                index: impacts.len() + 1,
            });
            break ExactEnd::Stopped;
        }
        advance(&mut x, &mut v, &tau);
        t += &tau;
        let plane = &s.planes[p];
        let vn = dot(&plane.normal, &v);
        let jump = -(T::one() + &plane.k) * &vn;
        for i in 0..3 {
            v[i] = v[i].clone() + jump.clone() * &plane.normal[i];
        }
        let after = dot(&plane.normal, &v);
        impacts.push(ExactImpact {
            t: t.clone(),
            plane: p,
            before: vn,
            after: after.clone(),
            x: x.clone(),
        });
        let a = dot(&plane.normal, &s.gravity);
        if single && impacts.len() == 1 && a.signum_i8() < 0 {
            let k = &plane.k;
            if k.signum_i8() > 0 && (T::one() - k).signum_i8() > 0 {
                // t∞ = t₁ + 2u₁/(|a|(1 − k))
                let t_inf = t.clone() + two::<T>() * &after / (-a.clone() * (T::one() - k));
                zeno = Some(t_inf);
            }
        }
        if let Some(t_inf) = &zeno
            && (t_inf.clone() - &s.duration).signum_i8() <= 0
            && impacts.len() >= s.max_impacts
        {
            // the budget is spent before the accumulation: report it, rest there
            let t_inf = t_inf.clone();
            rest_on(
                &mut x,
                &mut v,
                &s.planes[0],
                &s.gravity,
                &(t_inf.clone() - &t),
                &s.radius,
            );
            t = t_inf.clone();
            break ExactEnd::Zeno { t_inf };
        }
    };
    (
        ExactRun {
            impacts,
            zeno,
            end,
            t_end: t,
            x,
            v,
        },
        error,
    )
}

/// The state at the accumulation, `dt` after the last impact listed: normal motion at rest on
/// the plane (gap 0, normal velocity 0), the tangential motion ballistic along the plane.
fn rest_on<T: Scalar>(
    x: &mut V<T>,
    v: &mut V<T>,
    plane: &ExactPlane<T>,
    gravity: &V<T>,
    dt: &T,
    r: &T,
) {
    let n = &plane.normal;
    let gn = dot(n, gravity);
    let vn = dot(n, v);
    let half_dt2 = dt.clone() * dt / two::<T>();
    for i in 0..3 {
        let gt = gravity[i].clone() - gn.clone() * &n[i];
        let vt = v[i].clone() - vn.clone() * &n[i];
        x[i] = x[i].clone() + vt.clone() * dt + gt.clone() * &half_dt2;
        v[i] = vt + gt * dt;
    }
    // on the plane: remove the normal offset
    let g = dot(n, x) - dot(n, &plane.point) - r.clone();
    for i in 0..3 {
        x[i] = x[i].clone() - g.clone() * &n[i];
    }
}
