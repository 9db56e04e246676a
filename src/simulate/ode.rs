//! One step of Dormand and Prince's RK5(4) pair (the tableau of
//! [`crate::impact::friction::spatial`], rounded to f64 once), over the packed state of
//! [`super::body::State`] (or of a system's): the fifth-order solution, its embedded error
//! estimate and its continuous extension.

use crate::impact::friction::spatial::{A, E};

/// The tableau in f64: the rows of A (the seventh the fifth-order weights), E and the
/// dense-output weights D.
pub struct Tableau {
    a: [[f64; 6]; 7],
    e: [f64; 7],
    c: [f64; 7],
    d: [f64; 7],
}

impl Tableau {
    /// A, E and D rounded once.
    pub fn new() -> Tableau {
        let f = |(p, q): (i64, i64)| p as f64 / q as f64;
        let a: [[f64; 6]; 7] = std::array::from_fn(|i| std::array::from_fn(|j| f(A[i][j])));
        let e: [f64; 7] = std::array::from_fn(|i| f(E[i]));
        let c: [f64; 7] = std::array::from_fn(|i| a[i].iter().sum());
        let d: [f64; 7] = std::array::from_fn(|i| f(D[i]));
        Tableau { a, e, c, d }
    }
}

impl Default for Tableau {
    fn default() -> Self {
        Tableau::new()
    }
}

/// The derivative f(t, y) of a packed state, which may fail.
pub type Derivative<'a, Err> = dyn FnMut(f64, &[f64]) -> Result<Vec<f64>, Err> + 'a;

/// Hairer's dense-output weights of the pair (`dopri5`, Hairer, Nørsett and Wanner, *Solving
/// ODEs I*, §II.6): d₁, d₃, …, d₇ (d₂ = 0), as fractions.
const D: [(i64, i64); 7] = [
    (-12_715_105_075, 11_282_082_432),
    (0, 1),
    (87_487_479_700, 32_700_410_799),
    (-10_690_763_975, 1_880_347_072),
    (701_980_252_875, 199_316_789_632),
    (-1_453_857_185, 822_651_844),
    (69_997_945, 29_380_423),
];

/// The continuous extension of an accepted step from (t₀, y₀) over h, of fourth order
/// (Hairer's `contd5`): with θ = (t − t₀)/h, θ' = 1 − θ, Δ = y₁ − y₀, b = h k₁ − Δ,
///
/// ```text
/// y(t₀ + θh) = y₀ + θ (Δ + θ' (b + θ ((Δ − h k₇ − b) + θ' h Σ dᵢ kᵢ)))
/// ```
///
/// which is y₀ at θ = 0 and y₁ at θ = 1, with the derivatives k₁ and k₇ there.
#[derive(Clone, Debug, PartialEq)]
pub struct Dense {
    t0: f64,
    h: f64,
    y0: Vec<f64>,
    delta: Vec<f64>,
    b: Vec<f64>,
    c: Vec<f64>,
    d: Vec<f64>,
}

impl Dense {
    /// y(t), for t in [t₀, t₀ + h].
    pub fn at(&self, t: f64) -> Vec<f64> {
        let th = (t - self.t0) / self.h;
        let th1 = 1.0 - th;
        (0..self.y0.len())
            .map(|n| {
                self.y0[n]
                    + th * (self.delta[n] + th1 * (self.b[n] + th * (self.c[n] + th1 * self.d[n])))
            })
            .collect()
    }
}

/// y(t + h) to fifth order from y(t), the embedded error estimate of every component and the
/// step's continuous extension; `f(t, y)` is the derivative, which may fail (the step is then
/// abandoned). The seventh stage is evaluated at the fifth-order solution (FSAL).
pub fn step_dense<Err>(
    tab: &Tableau,
    t: f64,
    y: &[f64],
    h: f64,
    f: &mut Derivative<'_, Err>,
) -> Result<(Vec<f64>, Vec<f64>, Dense), Err> {
    let n_y = y.len();
    let mut k: Vec<Vec<f64>> = Vec::with_capacity(7);
    let mut yi = vec![0.0; n_y];
    for i in 0..7 {
        yi.copy_from_slice(y);
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
    // yi is now the fifth-order solution, where k₇ was evaluated
    let y5 = yi;
    let mut err = vec![0.0; n_y];
    let mut d = vec![0.0; n_y];
    for (j, kj) in k.iter().enumerate() {
        for n in 0..n_y {
            err[n] += h * tab.e[j] * kj[n];
            d[n] += h * tab.d[j] * kj[n];
        }
    }
    let delta: Vec<f64> = (0..n_y).map(|n| y5[n] - y[n]).collect();
    let b: Vec<f64> = (0..n_y).map(|n| h * k[0][n] - delta[n]).collect();
    let c: Vec<f64> = (0..n_y).map(|n| delta[n] - h * k[6][n] - b[n]).collect();
    let dense = Dense {
        t0: t,
        h,
        y0: y.to_vec(),
        delta,
        b,
        c,
        d,
    };
    Ok((y5, err, dense))
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A quartic y = t⁴ (y' = 4t³) is reproduced by the step and by its fourth-order continuous
    /// extension, to rounding, anywhere inside the step.
    #[test]
    fn dense_output_is_exact_on_a_quartic() {
        let tab = Tableau::new();
        let mut f = |t: f64, _y: &[f64]| -> Result<Vec<f64>, ()> { Ok(vec![4.0 * t * t * t]) };
        let (t0, h) = (0.5, 0.75);
        let (y5, _, dense) = step_dense(&tab, t0, &[t0.powi(4)], h, &mut f).unwrap();
        assert!((y5[0] - (t0 + h).powi(4)).abs() <= 8.0 * f64::EPSILON * y5[0]);
        for th in [0.0, 0.1, 0.3, 0.5, 0.9, 1.0] {
            let t = t0 + th * h;
            let y = dense.at(t)[0];
            assert!(
                (y - t.powi(4)).abs() <= 16.0 * f64::EPSILON * (t0 + h).powi(4),
                "{th}: {y}"
            );
        }
    }

    /// On y' = y the interpolant's error inside a step is O(h⁵): halving h divides it by about
    /// 32 (between 16 and 64 here, the next term's share).
    #[test]
    fn dense_output_is_of_fourth_order() {
        let tab = Tableau::new();
        let mut f = |_t: f64, y: &[f64]| -> Result<Vec<f64>, ()> { Ok(vec![y[0]]) };
        let error = |h: f64, f: &mut Derivative<'_, ()>| {
            let (_, _, dense) = step_dense(&tab, 0.0, &[1.0], h, f).unwrap();
            (dense.at(0.4 * h)[0] - (0.4 * h).exp()).abs()
        };
        let (e1, e2) = (error(0.2, &mut f), error(0.1, &mut f));
        assert!(e1 < 1e-7 && e2 > 0.0, "{e1} {e2}");
        let ratio = e1 / e2;
        assert!((16.0..64.0).contains(&ratio), "{ratio}");
    }
}
