//! The body's pose: the rotation R that takes body axes to world axes, written as an axis and
//! an angle, a quaternion, a rotation matrix, or a list of these applied in turn.
//!
//! ```text
//! axis a, angle θ (Rodrigues):  R = cos θ I + sin θ [k]ₓ + (1 − cos θ) k kᵀ,   k = a/|a|
//! quaternion (w, x, y, z):      R = 1/|q|² · [[w²+x²−y²−z², 2(xy−wz), 2(xz+wy)],
//!                                             [2(xy+wz), w²−x²+y²−z², 2(yz−wx)],
//!                                             [2(xz−wy), 2(yz+wx), w²−x²−y²+z²]]
//! matrix:                       R as written, by rows; RᵀR = I and det R = 1 are checked
//! ```
//!
//! A rational quaternion gives a rational R (every rational rotation has one); an angle whose
//! sine and cosine are radicals (`30 deg`) gives an exact R in the radical field; an angle
//! parameter stays a symbol for `derive`.

use toml_edit::{Item, Value};

use super::super::SceneError;
use super::super::read::{Reader, short};
use super::term::{Mat3, Term, Vec3, dot, identity, product, transpose};

impl Reader<'_> {
    /// `[body] pose`: R (body → world); the identity when absent.
    pub(super) fn pose(&self, item: Option<&Item>, prefix: &str) -> Result<Mat3, SceneError> {
        let Some(item) = item else {
            return Ok(identity());
        };
        if let Some(list) = item.as_array() {
            let mut r = identity();
            for (i, v) in list.iter().enumerate() {
                let step = self.rotation(v, &format!("{prefix}.pose[{i}]"))?;
                r = product(&step, &r);
            }
            return Ok(r);
        }
        let key = format!("{prefix}.pose");
        match item.as_value() {
            Some(v) => self.rotation(v, &key),
            None => match item.as_table_like() {
                Some(_) => self.rotation_table(item, &key),
                None => Err(self.pose_error(&key, short(item))),
            },
        }
    }

    fn pose_error(&self, key: &str, shown: String) -> SceneError {
        self.err(
            key,
            Some(shown),
            "must be a rotation: { axis = [x, y, z], angle = \"30 deg\" }, { quaternion = [w, x, y, z] }, \
             { matrix = [[…], […], […]] } (body axes to world axes), or a list of these applied in turn",
        )
    }

    fn rotation(&self, v: &Value, key: &str) -> Result<Mat3, SceneError> {
        match v.as_inline_table() {
            Some(_) => self.rotation_table(&Item::Value(v.clone()), key),
            None => Err(self.pose_error(key, v.to_string().trim().to_string())),
        }
    }

    fn rotation_table(&self, item: &Item, key: &str) -> Result<Mat3, SceneError> {
        let t = item
            .as_table_like()
            .ok_or_else(|| self.pose_error(key, short(item)))?;
        if let Some(q) = t.get("quaternion") {
            self.only_keys(t, key, &["quaternion"])?;
            return self.quaternion(q, &format!("{key}.quaternion"));
        }
        if let Some(m) = t.get("matrix") {
            self.only_keys(t, key, &["matrix"])?;
            return self.matrix(m, &format!("{key}.matrix"));
        }
        self.only_keys(t, key, &["axis", "angle"])?;
        let axis_key = format!("{key}.axis");
        let a = self.triple(self.get(t, "axis", key)?, &axis_key)?;
        self.nonzero(&a, &axis_key, "a rotation axis")?;
        let angle = self.number(self.get(t, "angle", key)?, &format!("{key}.angle"))?;
        self.observed
            .borrow_mut()
            .angles
            .push((format!("{key}.angle"), angle.clone()));
        let a: Vec3 = a.each_ref().map(Term::of);
        let theta = Term::of(&angle);
        let (c, s) = (theta.call("cos"), theta.call("sin"));
        let a2 = dot(&a, &a);
        let norm = self.root(&a2);
        let one_minus_c = &Term::int(1) - &c;
        let k = |i: usize| &a[i] / &norm;
        // Rodrigues: R = c I + s [k]× + (1 − c) a aᵀ/|a|².
        let skew = [
            [Term::int(0), -&k(2), k(1)],
            [k(2), Term::int(0), -&k(0)],
            [-&k(1), k(0), Term::int(0)],
        ];
        Ok(std::array::from_fn(|i| {
            std::array::from_fn(|j| {
                let diag = if i == j { c.clone() } else { Term::int(0) };
                let outer = &(&(&a[i] * &a[j]) / &a2) * &one_minus_c;
                &(&diag + &(&s * &skew[i][j])) + &outer
            })
        }))
    }

    /// √x as a term: exact when x is a rational square.
    pub(super) fn root(&self, x: &Term) -> Term {
        if let Term::Rat(q) = x
            && let (Some(n), Some(d)) = (
                crate::number::exact_root(q.numer(), 2),
                crate::number::exact_root(q.denom(), 2),
            )
        {
            return Term::Rat(num_rational::BigRational::new(n, d));
        }
        x.call("sqrt")
    }

    fn quaternion(&self, item: &Item, key: &str) -> Result<Mat3, SceneError> {
        let arr = item
            .as_array()
            .filter(|a| a.len() == 4)
            .ok_or_else(|| self.err(key, Some(short(item)), "must be four numbers [w, x, y, z]"))?;
        let mut q = Vec::with_capacity(4);
        for (i, v) in arr.iter().enumerate() {
            q.push(Term::of(&self.number_value(v, &format!("{key}[{i}]"))?));
        }
        let (w, x, y, z) = (&q[0], &q[1], &q[2], &q[3]);
        let n2 = &(&(&w.square() + &x.square()) + &y.square()) + &z.square();
        if self.decide_zero(&n2, key)? == Some(true) {
            return Err(self.err(key, Some(short(item)), "a quaternion must not be zero"));
        }
        let two = Term::int(2);
        let p = |a: &Term, b: &Term| &a.clone() * b;
        let twice = |a: Term| &two * &a;
        let m = [
            [
                &(&(&w.square() + &x.square()) - &y.square()) - &z.square(),
                twice(&p(x, y) - &p(w, z)),
                twice(&p(x, z) + &p(w, y)),
            ],
            [
                twice(&p(x, y) + &p(w, z)),
                &(&(&w.square() - &x.square()) + &y.square()) - &z.square(),
                twice(&p(y, z) - &p(w, x)),
            ],
            [
                twice(&p(x, z) - &p(w, y)),
                twice(&p(y, z) + &p(w, x)),
                &(&(&w.square() - &x.square()) - &y.square()) + &z.square(),
            ],
        ];
        Ok(m.map(|row| row.map(|e| &e / &n2)))
    }

    fn matrix(&self, item: &Item, key: &str) -> Result<Mat3, SceneError> {
        let m = self.matrix3(item, key)?;
        // RᵀR = I, exactly where the entries are exact, else to a few rounding errors.
        let rtr = product(&transpose(&m), &m);
        let id = identity();
        for i in 0..3 {
            for j in i..3 {
                let off = &rtr[i][j] - &id[i][j];
                if self.decide_zero(&off, key)? == Some(false) {
                    return Err(self.err(
                        key,
                        Some(short(item)),
                        format!(
                            "not a rotation: (RᵀR)[{i}][{j}] = {} instead of {}; write the entries exactly \
                             (\"cos(30 deg)\", fractions from a rational quaternion) or give the pose as \
                             {{ axis, angle }} or {{ quaternion }}",
                            self.approx(&rtr[i][j]),
                            id[i][j]
                        ),
                    ));
                }
            }
        }
        let det = dot(&m[0], &super::term::cross(&m[1], &m[2]));
        if self.sign(&det, key)? == Some(-1) {
            return Err(self.err(
                key,
                Some(short(item)),
                "det R = −1: a reflection, not a rotation (swap two rows, or negate one)",
            ));
        }
        Ok(m)
    }

    /// A 3×3 array of numbers, by rows.
    pub(super) fn matrix3(&self, item: &Item, key: &str) -> Result<Mat3, SceneError> {
        let rows = item.as_array().filter(|a| a.len() == 3).ok_or_else(|| {
            self.err(
                key,
                Some(short(item)),
                "must be three rows of three numbers",
            )
        })?;
        let mut m: Vec<Vec3> = Vec::with_capacity(3);
        for (i, row) in rows.iter().enumerate() {
            let path = format!("{key}[{i}]");
            let r = row.as_array().filter(|a| a.len() == 3).ok_or_else(|| {
                self.err(
                    &path,
                    Some(row.to_string().trim().to_string()),
                    "must be a row of three numbers",
                )
            })?;
            let mut out = Vec::with_capacity(3);
            for (j, v) in r.iter().enumerate() {
                out.push(Term::of(&self.number_value(v, &format!("{path}[{j}]"))?));
            }
            m.push([out[0].clone(), out[1].clone(), out[2].clone()]);
        }
        Ok([m[0].clone(), m[1].clone(), m[2].clone()])
    }
}
