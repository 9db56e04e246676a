//! The axes of a sweep: a varied input (`--vary PATH=START:STOP:COUNT`, [`Vary`]) and the
//! slice of the grid an array job solves (`--shard I/N`, [`Shard`]).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;

use super::SweepError;
use crate::number::parse_number;

/// One varied input: `PATH=START:STOP:COUNT` (COUNT ≥ 2 points, inclusive of both ends;
/// START/STOP are numbers as in scenes, read exactly: `0:1:101` gives 0, 1/100, …, 1 exactly).
/// A decreasing range is allowed; START = STOP is refused.
#[derive(Clone, Debug, PartialEq)]
pub struct Vary {
    /// The key path of the varied number, e.g. `contact[1].k`.
    pub path: String,
    /// The first value.
    pub start: BigRational,
    /// The last value.
    pub stop: BigRational,
    /// The number of values, ≥ 2.
    pub count: usize,
}

impl Vary {
    /// Parse `PATH=START:STOP:COUNT`; the path is checked against the scene by [`sweep`](super::sweep).
    pub fn parse(spec: &str) -> Result<Vary, SweepError> {
        let err = |reason: String| SweepError::Vary {
            spec: spec.to_string(),
            reason,
        };
        let (path, range) = spec.split_once('=').ok_or_else(|| {
            err("expected PATH=START:STOP:COUNT, e.g. contact[1].k=0:1:101".into())
        })?;
        let path = path.trim();
        if path.is_empty() {
            return Err(err(
                "the path before `=` is empty; name a number of the scene, e.g. contact[1].k"
                    .into(),
            ));
        }
        if path.contains(char::is_whitespace) {
            return Err(err(format!(
                "the path `{path}` contains whitespace; write it as in the scene, e.g. contact[1].k"
            )));
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        if parts.len() != 3 {
            return Err(err(format!(
                "expected START:STOP:COUNT after `=`, found `{range}` ({} part{}); e.g. {path}=0:1:101",
                parts.len(),
                if parts.len() == 1 { "" } else { "s" }
            )));
        }
        let number = |what: &str, text: &str| -> Result<BigRational, SweepError> {
            let n = parse_number(text).map_err(|e| err(format!("{what}: {e}")))?;
            n.exact.map_err(|why| {
                err(format!(
                    "{what} `{text}` is not rational ({why}); write it as a decimal or a fraction"
                ))
            })
        };
        let start = number("START", parts[0])?;
        let stop = number("STOP", parts[1])?;
        let count: usize = parts[2].parse().map_err(|_| {
            err(format!(
                "COUNT `{}` is not a whole number of points (≥ 2)",
                parts[2]
            ))
        })?;
        if count < 2 {
            return Err(err(format!(
                "COUNT is {count}: a sweep needs at least 2 points (both ends are included)"
            )));
        }
        if start == stop {
            return Err(err(format!(
                "START and STOP are equal ({}): nothing would vary",
                parts[0]
            )));
        }
        Ok(Vary {
            path: path.to_string(),
            start,
            stop,
            count,
        })
    }

    /// The i-th value, start + (stop − start)·i/(count − 1), exactly.
    ///
    /// Formed as one fraction over the common denominator, with start = a/b, stop = c/d and
    /// n = count − 1,
    ///
    /// ```text
    /// (a·d·(n − i) + c·b·i) / (b·d·n)
    /// ```
    ///
    /// and reduced once: the same rational, one gcd instead of the four of the sum of
    /// products (a sweep point of Example 3 spent a fifth of its time here).
    pub fn value(&self, i: usize) -> BigRational {
        if self.count < 2 {
            return self.start.clone();
        }
        let n = self.count - 1;
        let (a, b) = (self.start.numer(), self.start.denom());
        let (c, d) = (self.stop.numer(), self.stop.denom());
        if let Some(q) = small_value([a, b, c, d], n, i) {
            return q;
        }
        let (n, i) = (BigInt::from(n), BigInt::from(i));
        let numer = a * d * (&n - &i) + c * b * i;
        BigRational::new(numer, b * d * n)
    }
}

/// [`Vary::value`] in machine integers when a, b, c, d fit in 32 bits and n, i in 31 (the
/// usual grid, `0:1:100001`): the products then fit in `i128` and the reduction is one binary
/// gcd of two `u128`, with the same reduced fraction as [`BigRational::new`] (denominator
/// positive, gcd 1). `None` otherwise.
fn small_value([a, b, c, d]: [&BigInt; 4], n: usize, i: usize) -> Option<BigRational> {
    let small = |x: &BigInt| i32::try_from(x).ok().map(i128::from);
    let (a, b, c, d) = (small(a)?, small(b)?, small(c)?, small(d)?);
    let (n, i) = (
        i128::from(i32::try_from(n).ok()?),
        i128::from(i32::try_from(i).ok()?),
    );
    let numer = a * d * (n - i) + c * b * i;
    let denom = b * d * n;
    // num-integer's gcd of machine integers is Stein's binary algorithm
    let g = numer.unsigned_abs().gcd(&denom.unsigned_abs()) as i128;
    Some(BigRational::new_raw(
        BigInt::from(numer / g),
        BigInt::from(denom / g),
    ))
}

/// A slice of a sweep, `I/N` with 1 ≤ I ≤ N: 1-based, as Slurm's `--array=1-N` indices
/// (`--shard $SLURM_ARRAY_TASK_ID/N`). See the module docs for which points it takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// I, from 1.
    pub index: usize,
    /// N, ≥ 1.
    pub count: usize,
}

impl Shard {
    /// Parse `I/N`.
    pub fn parse(spec: &str) -> Result<Shard, SweepError> {
        let err = |reason: String| SweepError::Shard {
            spec: spec.to_string(),
            reason,
        };
        let (i, n) = spec
            .split_once('/')
            .ok_or_else(|| err("expected I/N, e.g. 1/4 (shard I of N, counted from 1)".into()))?;
        let whole = |what: &str, t: &str| -> Result<usize, SweepError> {
            t.trim().parse().map_err(|_| {
                err(format!(
                    "{what} `{}` is not a whole number; expected I/N, e.g. 1/4",
                    t.trim()
                ))
            })
        };
        let shard = Shard {
            index: whole("I", i)?,
            count: whole("N", n)?,
        };
        shard.check().map_err(err)?;
        Ok(shard)
    }

    /// The global points of a `points`-point grid this shard solves:
    /// `[⌊(I−1)·P/N⌋, ⌊I·P/N⌋)`. Assumes a valid shard (1 ≤ I ≤ N).
    pub fn range(&self, points: usize) -> std::ops::Range<usize> {
        let n = self.count.max(1) as u128;
        let at = |k: usize| ((k as u128 * points as u128) / n) as usize;
        at(self.index.saturating_sub(1))..at(self.index.min(self.count))
    }

    /// Whether 1 ≤ I ≤ N, and what to write instead when not.
    pub(super) fn check(&self) -> Result<(), String> {
        if self.count == 0 {
            Err("N is 0: there must be at least one shard".into())
        } else if self.index == 0 {
            Err(format!(
                "shards are numbered from 1 (as Slurm's --array=1-{n} with $SLURM_ARRAY_TASK_ID); use 1/{n} … {n}/{n}",
                n = self.count
            ))
        } else if self.index > self.count {
            Err(format!(
                "shard {} of {} does not exist; I must lie in 1 … {}",
                self.index, self.count, self.count
            ))
        } else {
            Ok(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tools::sweep::q;

    #[test]
    fn vary_parses_good_specs() {
        let v = Vary::parse("contact[1].k=0:1:101").unwrap();
        assert_eq!(v.path, "contact[1].k");
        assert_eq!(
            (v.start.clone(), v.stop.clone(), v.count),
            (q(0, 1), q(1, 1), 101)
        );
        for i in 0..=100 {
            assert_eq!(v.value(i), q(i as i64, 100), "point {i}");
        }
        // Decreasing ranges are allowed; fractions and decimals are exact.
        let d = Vary::parse("contact[1].k=1:0:5").unwrap();
        assert_eq!(d.value(1), q(3, 4));
        assert_eq!(d.value(4), q(0, 1));
        let f = Vary::parse(" body.mass = 1/3 : 0.7 : 3 ").unwrap();
        assert_eq!(
            (f.path.as_str(), f.start.clone(), f.stop.clone()),
            ("body.mass", q(1, 3), q(7, 10))
        );
        assert_eq!(f.value(1), q(31, 60));
        let e = Vary::parse("body.velocity[0]=-2:1e-1:2").unwrap();
        assert_eq!(e.start, q(-2, 1));
        assert_eq!(e.stop, q(1, 10));
    }

    /// The one-fraction form of [`Vary::value`] is start + (stop − start)·i/(count − 1).
    #[test]
    fn values_are_the_points_of_the_range() {
        for spec in [
            "k=0:1:101",
            "k=1:0:7",
            "k=1/3:0.7:13",
            "k=-2/7:5/3:10",
            "k=-1e-3:-4/9:6",
            "k=1e-30:1/3:7",
            "k=-2147483648:2147483647:5",
            "k=1/2147483647:-7/3:100001",
        ] {
            let v = Vary::parse(spec).unwrap();
            let n = BigRational::from_integer(BigInt::from(v.count - 1));
            for i in (0..v.count + 2).filter(|i| v.count < 1000 || i % 997 < 3) {
                let t = BigRational::from_integer(BigInt::from(i)) / &n;
                let want = &v.start + (&v.stop - &v.start) * t;
                // Equal as fractions written: reduced, the denominator positive.
                let got = v.value(i);
                assert_eq!(
                    (got.numer(), got.denom()),
                    (want.numer(), want.denom()),
                    "{spec}: point {i}"
                );
            }
        }
    }

    #[test]
    fn vary_refuses_bad_specs_naming_the_problem() {
        let reason = |spec: &str| match Vary::parse(spec) {
            Err(SweepError::Vary { spec: s, reason }) => {
                assert_eq!(s, spec);
                reason
            }
            other => panic!("{spec}: expected a Vary error, got {other:?}"),
        };
        assert!(reason("k=0:1").contains("START:STOP:COUNT"));
        assert!(reason("contact[1].k=0:1:1").contains("at least 2"));
        assert!(reason("contact[1].k=0:1:0").contains("at least 2"));
        assert!(reason("=0:1:3").contains("path"));
        assert!(reason("contact[1].k").contains("PATH=START:STOP:COUNT"));
        assert!(reason("contact[1].k=zero:1:3").contains("START"));
        assert!(reason("contact[1].k=0:1..2:3").contains("STOP"));
        assert!(reason("contact[1].k=0:1:many").contains("COUNT `many`"));
        assert!(reason("contact[1].k=0:1:-3").contains("COUNT"));
        assert!(reason("contact[1].k=0:sqrt(2):3").contains("not rational"));
        assert!(reason("contact[1].k=0.5:1/2:3").contains("equal"));
        assert!(reason("contact [1].k=0:1:3").contains("whitespace"));
    }

    #[test]
    fn shard_parses_and_refuses() {
        assert_eq!(Shard::parse("1/4").unwrap(), Shard { index: 1, count: 4 });
        assert_eq!(Shard::parse("4/4").unwrap(), Shard { index: 4, count: 4 });
        for (spec, needle) in [
            ("0/4", "numbered from 1"),
            ("5/4", "does not exist"),
            ("a/b", "not a whole number"),
            ("1/0", "at least one shard"),
            ("3", "expected I/N"),
            ("-1/4", "not a whole number"),
        ] {
            match Shard::parse(spec) {
                Err(e @ SweepError::Shard { .. }) => {
                    assert!(e.to_string().contains(needle), "{spec}: {e}");
                    assert_eq!(e.exit_code(), 2);
                }
                other => panic!("{spec}: {other:?}"),
            }
        }
    }

    #[test]
    fn shards_are_disjoint_and_cover() {
        for points in [0usize, 1, 2, 3, 7, 10, 11, 100, 101, 1000, 1023, 4097] {
            for n in 1..=17 {
                let mut next = 0;
                for i in 1..=n {
                    let r = Shard { index: i, count: n }.range(points);
                    assert_eq!(r.start, next, "P = {points}, {i}/{n}");
                    assert!(r.end >= r.start);
                    // Balanced: sizes differ by at most one.
                    assert!(r.len() <= points / n + 1);
                    next = r.end;
                }
                assert_eq!(next, points, "P = {points}, N = {n}");
            }
        }
        // Reproducible, and large grids do not overflow.
        let big = Shard { index: 3, count: 7 }.range(usize::MAX);
        assert_eq!(big, Shard { index: 3, count: 7 }.range(usize::MAX));
        assert!(big.start < big.end);
    }
}
