//! The adaptive step both event loops take between events (one body, [`super::run`]; a sphere
//! system, [`super::system::run`]): its size (held below the gap horizon and the end of the
//! run, never below what t resolves), the Dormand–Prince RK5(4) pair ([`super::ode`]), the error
//! test on the scales of the motion, a step that would cross an open gap halved, and the dense
//! output of the accepted step, from which the output times inside it are sampled (the steps
//! are not cut at the output times).
//!
//! **Step control** (Hairer, Nørsett and Wanner, *Solving ODEs I*, §II.4): with the embedded
//! error e_k of component k, the step is accepted when max_k |e_k| / (tol · max(|y_k|, s_k)) ≤ 1
//! (s_k the scale of component k: a length, 1 for the quaternion, a speed, a rate); the next
//! step is h (0.9 ratio^(−1/5)), shrinking at most fivefold and growing at most fivefold.
//!
//! **Conservative advancement** ([`horizon`]): with M a bound on |g̈| over the step, an open gap
//! g(t + s) ≥ g + ġ s − ½ M s² stays positive for s < (ġ + √(ġ² + 2 M g))/M, written
//! 2g/(√(ġ² + 2 M g) − ġ) when ġ < 0, where the first form cancels (without gravity M is 0 and
//! the first form is 0/0 or 0).

use super::ode::{Dense, Derivative, Tableau, floor, grow, shrink, step_dense};

/// Whether a step took an open gap through its plane: it ends beyond the gap tolerance and
/// deeper than it began. A gap already beyond the tolerance at the step's start (a touching
/// feature the closed contacts' projection moved by rounding, or an impact left leaving) may
/// end the step where it is or shallower: refusing it would halve the step down to what t
/// resolves, and stall the run, while the feature leaves.
pub fn crossed(start: f64, end: f64, tolerance: f64) -> bool {
    end < -tolerance && end < start
}

/// How long an open gap g ≥ 0 approaching or leaving at ġ, its second derivative bounded by M,
/// surely stays open: the smallest positive root of g + ġ s − ½ M s², in the form that does not
/// cancel (∞ when nothing brings it to zero).
pub fn horizon(gap: f64, rate: f64, bound: f64) -> f64 {
    let reach = gap.max(0.0);
    let bound = bound.max(0.0);
    let root = (rate * rate + 2.0 * bound * reach).sqrt();
    if rate < 0.0 {
        2.0 * reach / (root - rate)
    } else if bound > 0.0 {
        (rate + root) / bound
    } else {
        f64::INFINITY
    }
}

/// The outcome of one attempt.
pub enum Advance<E> {
    /// Accepted: the state at `t` and the dense output over the step.
    Accepted {
        /// The time at the end of the step (the end of the run exactly when the step reached it).
        t: f64,
        /// The fifth-order state there.
        y: Vec<f64>,
        /// The continuous extension over the step.
        dense: Dense,
    },
    /// Rejected (error too large, or an open gap crossed): try again from the same state with
    /// the shorter step the stepper now holds.
    Retry,
    /// The derivative failed (a mode change inside the step) and the step is already at the
    /// resolution of t: the caller decides (switch the mode, or stall).
    Failed(E),
    /// The error estimate is not a finite number.
    NotFinite,
}

/// The step size and the counts of accepted and rejected steps.
pub struct Stepper {
    tab: Tableau,
    /// The step to try next.
    pub h: f64,
    /// Steps accepted, steps rejected.
    pub steps: (usize, usize),
    /// Where the current window of [`WINDOW`] attempts started: (attempts, t).
    window: (usize, f64),
    /// How the last window of [`WINDOW`] attempts stalled, if it did.
    stalled: Option<Stall>,
}

/// How a run stalled.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stall {
    /// A window of [`WINDOW`] attempts advanced t by less than a hundred resolutions of t per
    /// attempt.
    Resolution,
    /// At the pace of its last window the run would need more than [`PACE`] further attempts
    /// to reach its end.
    Pace {
        /// The attempts it would need.
        needed: f64,
    },
    /// The step budget is spent.
    Budget {
        /// The budget, in attempts.
        attempts: usize,
    },
}

impl std::fmt::Display for Stall {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Stall::Resolution => f.write_str(
                "its steps fell to what f64 resolves in t and stayed there (a stiff, singular or \
                 inconsistent contact phase)",
            ),
            Stall::Pace { needed } => write!(
                f,
                "at the pace of its last {WINDOW} attempts it would need {needed:.1e} more to \
                 reach its end (a contact phase chattering at the edge of a cone or of lift-off)"
            ),
            Stall::Budget { attempts } => write!(f, "it spent its budget of {attempts} attempts"),
        }
    }
}

/// The most further attempts a run's pace may call for: a window whose pace would take more
/// (ten times the step budget of [`super::run::MAX_STEPS`]) to reach the end of the run stops it
/// as stalled then, rather than after the budget — minutes later — with the same answer.
pub const PACE: f64 = 1.0e8;

/// The attempts over which a run's progress is judged: a run whose steps average less than
/// a hundred times the resolution of t over this many attempts is stalled — a motion that
/// moves on only at that resolution (a rim's contact point sweeping around a face landing
/// flat, a mode chattering) would take 10¹²–10¹⁵ steps to reach the end of the run, while the
/// few such steps an event needs (a gap crept onto, a mode switched) are far fewer.
pub const WINDOW: usize = 10_000;

impl Stepper {
    /// A first step of a tenth of the output step (or of the run, if shorter).
    pub fn new(output_step: f64, duration: f64) -> Stepper {
        Stepper {
            tab: Tableau::new(),
            h: (output_step.min(duration) / 10.0).max(f64::MIN_POSITIVE),
            steps: (0, 0),
            window: (0, 0.0),
            stalled: None,
        }
    }

    /// How the run has stalled, if it has: the last window of [`WINDOW`] attempts advanced t by
    /// less than a hundred resolutions of t per attempt, or at a pace that would need more than
    /// [`PACE`] further attempts; or `budget` attempts are spent.
    pub fn stall(&self, budget: usize) -> Option<Stall> {
        if self.attempts() >= budget {
            return Some(Stall::Budget { attempts: budget });
        }
        self.stalled
    }

    /// The total number of attempts.
    pub fn attempts(&self) -> usize {
        self.steps.0 + self.steps.1
    }

    /// One attempt from (t, y): the step is h, capped by the gap `horizon` and the `end` of the
    /// run, at least the resolution of t (a gap the step creeps onto at that resolution is
    /// taken as reached; a step the error would shrink below it is taken at it, so a motion
    /// faster than t resolves moves on to its error instead of stalling); `scales` the scale of each component, `f` the derivative and
    /// `crosses` whether a state has an open gap below its tolerance (the step is then halved,
    /// down to the resolution of t, where it is accepted).
    #[allow(clippy::too_many_arguments)]
    pub fn advance<E>(
        &mut self,
        t: f64,
        y: &[f64],
        horizon: f64,
        end: f64,
        output_step: f64,
        tolerance: f64,
        scales: &[f64],
        f: &mut Derivative<'_, E>,
        crosses: impl Fn(&[f64]) -> bool,
    ) -> Advance<E> {
        let cap = horizon.min(end - t);
        let mut hh = self.h.min(cap);
        let floor = floor(t, output_step);
        if hh < floor {
            // the end of the run within what t resolves is stepped to exactly; anything else
            // (a gap crept onto, a step the error shrank) at that resolution
            hh = if end - t < floor && end - t <= horizon {
                end - t
            } else {
                floor
            };
        }
        let attempts = self.attempts();
        if attempts >= self.window.0 + WINDOW {
            let advanced = t - self.window.1;
            let needed = (end - t) / advanced * WINDOW as f64;
            self.stalled = if advanced < 100.0 * WINDOW as f64 * floor {
                Some(Stall::Resolution)
            } else if needed > PACE {
                Some(Stall::Pace { needed })
            } else {
                None
            };
            self.window = (attempts, t);
        }
        let (y5, err, dense) = match step_dense(&self.tab, t, y, hh, f) {
            Ok(r) => r,
            Err(error) => {
                self.steps.1 += 1;
                self.h = hh / 4.0;
                if self.h < floor {
                    return Advance::Failed(error);
                }
                return Advance::Retry;
            }
        };
        let ratio = (0..y.len())
            .map(|k| err[k].abs() / (tolerance * y5[k].abs().max(scales[k])))
            .fold(0.0, f64::max);
        if !ratio.is_finite() {
            return Advance::NotFinite;
        }
        if ratio > 1.0 {
            self.steps.1 += 1;
            self.h = shrink(hh, ratio);
            return Advance::Retry;
        }
        if hh > floor && crosses(&y5) {
            self.steps.1 += 1;
            self.h = (hh / 2.0).max(floor);
            return Advance::Retry;
        }
        self.steps.0 += 1;
        if hh == self.h || ratio < 0.5 {
            self.h = grow(hh, ratio);
        }
        let t1 = if hh == end - t { end } else { t + hh };
        Advance::Accepted {
            t: t1,
            y: y5,
            dense,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A gap beyond the tolerance at the step's start (−6.5·10⁻¹² against 4.5·10⁻¹²: the box
    /// with μ = 0.9 under LZB, a corner struck while another one slid) may end the step as deep
    /// or shallower; one that goes deeper, or goes beyond from above, is crossed.
    #[test]
    fn a_gap_is_crossed_when_it_ends_beyond_the_tolerance_and_deeper() {
        let tol = 4.5e-12;
        assert!(!crossed(-6.5e-12, -6.5e-12, tol));
        assert!(!crossed(-6.5e-12, -6.0e-12, tol));
        assert!(crossed(-6.5e-12, -6.6e-12, tol));
        assert!(crossed(0.0, -4.6e-12, tol));
        assert!(crossed(1e-3, -1e-3, tol));
        assert!(!crossed(0.0, -4.4e-12, tol));
        assert!(!crossed(-4.4e-12, -4.5e-12, tol));
    }

    /// ġ < 0 without gravity: the gap closes at g/|ġ| (the first root form would give 0).
    #[test]
    fn horizon_without_gravity_is_the_gap_over_the_rate() {
        assert_eq!(horizon(2.0, -4.0, 0.0), 0.5);
        assert_eq!(horizon(2.0, 4.0, 0.0), f64::INFINITY);
        // with M: g + ġ s − ½ M s² = 0 at s = 1 for g = 1, ġ = 1, M = 4 (1 + 1 − 2 = 0)
        assert_eq!(horizon(1.0, 1.0, 4.0), 1.0);
        // approaching: g = 3, ġ = −1, M = 4: 3 − s − 2s² = 0 at s = 1
        assert_eq!(horizon(3.0, -1.0, 4.0), 1.0);
    }

    /// Steps of y' = 0 from t = 0.3, each capped by `horizon`, for two windows of attempts:
    /// whether the stepper then says the run stalled, and where t got to.
    fn two_windows(horizon: f64) -> (Option<Stall>, f64) {
        two_windows_to(horizon, 1.0)
    }

    /// As [`two_windows`], for a run that ends at `end`.
    fn two_windows_to(horizon: f64, end: f64) -> (Option<Stall>, f64) {
        let mut stepper = Stepper::new(0.01, end);
        let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ()> { Ok(vec![0.0; y.len()]) };
        let (mut t, y) = (0.3, vec![1.0]);
        for _ in 0..=2 * WINDOW {
            match stepper.advance(t, &y, horizon, end, 0.01, 1e-10, &[1.0], &mut f, |_| false) {
                Advance::Accepted { t: next, .. } => t = next,
                _ => panic!("y' = 0 has no error to reject a step for"),
            }
        }
        (stepper.stall(usize::MAX), t)
    }

    /// A gap crept onto at every step holds each step at the resolution of t (64 ε t): two
    /// windows of such steps advance t by 2 · 10⁴ resolutions, less than the hundred per
    /// attempt a moving run makes, and the stepper says the run stalled; so do steps of fifty
    /// resolutions.
    #[test]
    fn steps_held_near_the_resolution_of_t_are_a_stall() {
        let resolution = 64.0 * f64::EPSILON * 0.3;
        let (stall, t) = two_windows(0.0);
        assert_eq!(stall, Some(Stall::Resolution));
        assert!(
            t - 0.3 < 1.01 * (2 * WINDOW + 1) as f64 * resolution,
            "t = {t}"
        );
        assert_eq!(two_windows(50.0 * resolution).0, Some(Stall::Resolution));
    }

    /// Steps of a nanosecond are far above the resolution of t, but a run 1 s from its end
    /// would need 7 · 10⁸ more of them: stalled at its pace (10⁴ attempts advanced 10⁻⁵ s).
    #[test]
    fn steps_too_slow_to_reach_the_end_are_a_stall() {
        let (stall, _) = two_windows_to(1e-9, 1.0);
        let Some(Stall::Pace { needed }) = stall else {
            panic!("expected a stall at its pace, got {stall:?}");
        };
        assert!((needed - 0.69998 / 1e-9).abs() < 1e3, "needed {needed}");
    }

    /// Steps of a microsecond 0.7 s from the end need 7 · 10⁵ more, and steps of two hundred
    /// resolutions of t 5 · 10⁻⁵ s from the end 6 · 10⁷: no stall.
    #[test]
    fn steps_that_move_on_are_no_stall() {
        let resolution = 64.0 * f64::EPSILON * 0.3;
        assert_eq!(two_windows_to(200.0 * resolution, 0.30005).0, None);
        let (stall, t) = two_windows(1e-6);
        assert_eq!(stall, None);
        assert!(
            (t - 0.3 - (2 * WINDOW + 1) as f64 * 1e-6).abs() < 1e-9,
            "t = {t}"
        );
    }

    /// A run whose attempts reach the budget has stalled, whatever its pace.
    #[test]
    fn a_spent_budget_is_a_stall() {
        let mut stepper = Stepper::new(0.01, 1.0);
        let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ()> { Ok(vec![0.0; y.len()]) };
        let advance = stepper.advance(0.3, &[1.0], 1.0, 1.0, 0.01, 1e-10, &[1.0], &mut f, |_| {
            false
        });
        assert!(matches!(advance, Advance::Accepted { .. }));
        assert_eq!(stepper.stall(1), Some(Stall::Budget { attempts: 1 }));
        assert_eq!(stepper.stall(2), None);
    }
}
