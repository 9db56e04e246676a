//! One step of Dormand and Prince's RK5(4) pair (the tableau of
//! [`crate::impact::friction::spatial`], rounded to f64 once), over the packed state of
//! [`super::body::State`]: the fifth-order solution and its embedded error estimate.

use crate::impact::friction::spatial::{A, E};

/// The tableau in f64: the rows of A (the seventh the fifth-order weights) and E.
pub struct Tableau {
    a: [[f64; 6]; 7],
    e: [f64; 7],
    c: [f64; 7],
}

impl Tableau {
    /// A and E rounded once.
    pub fn new() -> Tableau {
        let f = |(p, q): (i64, i64)| p as f64 / q as f64;
        let a: [[f64; 6]; 7] = std::array::from_fn(|i| std::array::from_fn(|j| f(A[i][j])));
        let e: [f64; 7] = std::array::from_fn(|i| f(E[i]));
        let c: [f64; 7] = std::array::from_fn(|i| a[i].iter().sum());
        Tableau { a, e, c }
    }
}

impl Default for Tableau {
    fn default() -> Self {
        Tableau::new()
    }
}

/// y(t + h) to fifth order from y(t), and the embedded error estimate of every component;
/// `f(t, y)` is the derivative, which may fail (the step is then abandoned).
pub fn step<const N: usize, Err>(
    tab: &Tableau,
    t: f64,
    y: &[f64; N],
    h: f64,
    mut f: impl FnMut(f64, &[f64; N]) -> Result<[f64; N], Err>,
) -> Result<([f64; N], [f64; N]), Err> {
    let mut g = |t: f64, y: &[f64]| -> Result<Vec<f64>, Err> {
        let y: &[f64; N] = y.try_into().expect("N components");
        f(t, y).map(Vec::from)
    };
    let (y5, err) = step_slice(tab, t, y, h, &mut g)?;
    let whole = |v: Vec<f64>| -> [f64; N] { v.try_into().expect("N components") };
    Ok((whole(y5), whole(err)))
}

/// The derivative f(t, y) of a state of any length, which may fail.
pub type Derivative<'a, Err> = dyn FnMut(f64, &[f64]) -> Result<Vec<f64>, Err> + 'a;

/// [`step`] over a state of any length (a system of bodies): the same arithmetic, in the same
/// order, so a fixed-size state gives the same numbers through either.
pub fn step_slice<Err>(
    tab: &Tableau,
    t: f64,
    y: &[f64],
    h: f64,
    f: &mut Derivative<'_, Err>,
) -> Result<(Vec<f64>, Vec<f64>), Err> {
    let n_y = y.len();
    let mut k: Vec<Vec<f64>> = Vec::with_capacity(7);
    for i in 0..7 {
        let mut yi = y.to_vec();
        for (j, kj) in k.iter().enumerate().take(i) {
            let a = tab.a[i][j];
            if a != 0.0 {
                for n in 0..n_y {
                    yi[n] += h * a * kj[n];
                }
            }
        }
        k.push(f(t + tab.c[i] * h, &yi)?);
    }
    // the seventh stage is evaluated at the fifth-order solution (FSAL)
    let mut y5 = y.to_vec();
    for (j, kj) in k.iter().enumerate().take(6) {
        let a = tab.a[6][j];
        for n in 0..n_y {
            y5[n] += h * a * kj[n];
        }
    }
    let mut err = vec![0.0; n_y];
    for (j, kj) in k.iter().enumerate() {
        for n in 0..n_y {
            err[n] += h * tab.e[j] * kj[n];
        }
    }
    Ok((y5, err))
}

/// The next step after a step `h` rejected with error ratio `ratio` > 1 (the error over its
/// tolerance): the fifth-root rule of a fifth-order pair with the safety factor 0.9, shrinking
/// at most fivefold.
pub fn shrink(h: f64, ratio: f64) -> f64 {
    h * (0.9 * ratio.powf(-0.2)).max(0.2)
}

/// The next step after a step `h` accepted with error ratio `ratio` ≤ 1: the same rule,
/// growing at most fivefold.
pub fn grow(h: f64, ratio: f64) -> f64 {
    h * (0.9 * ratio.max(1e-10).powf(-0.2)).min(5.0)
}

/// The shortest step the time resolves at `t`: 64 ε max(|t|, the output step).
pub fn floor(t: f64, output_step: f64) -> f64 {
    64.0 * f64::EPSILON * t.abs().max(output_step)
}
