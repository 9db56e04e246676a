//! A row's CSV fields written into one buffer: a point writes two dozen numbers, and a
//! `String` per field cost as much as the solve. The text of each field is the one
//! [`super::text::num`] and the exact writers give, so the CSV is unchanged.

use std::fmt::Write;

/// The fields of one CSV row, in order, in one string.
#[derive(Clone, Debug, Default)]
pub(super) struct Cells {
    text: String,
    /// Where each field ends in `text`.
    ends: Vec<usize>,
}

impl Cells {
    /// Room for `fields` fields of about 20 bytes.
    pub(super) fn with_capacity(fields: usize) -> Cells {
        Cells {
            text: String::with_capacity(20 * fields),
            ends: Vec::with_capacity(fields),
        }
    }

    /// Add a field of text.
    pub(super) fn push(&mut self, s: &str) {
        self.text.push_str(s);
        self.ends.push(self.text.len());
    }

    /// Add an f64 with full round-trip precision, as [`super::text::num`] writes it.
    pub(super) fn push_f64(&mut self, x: f64) {
        // Writing into a String cannot fail.
        let _ = write!(self.text, "{x:?}");
        self.ends.push(self.text.len());
    }

    /// Add an integer.
    pub(super) fn push_usize(&mut self, n: usize) {
        let _ = write!(self.text, "{n}");
        self.ends.push(self.text.len());
    }

    /// Add `n` empty fields.
    pub(super) fn push_empty(&mut self, n: usize) {
        let end = self.text.len();
        self.ends.extend(std::iter::repeat_n(end, n));
    }

    /// The fields in order.
    pub(super) fn iter(&self) -> impl Iterator<Item = &str> {
        let starts = std::iter::once(0).chain(self.ends.iter().copied());
        starts.zip(&self.ends).map(|(a, &b)| &self.text[a..b])
    }
}

#[cfg(test)]
mod tests {
    use super::super::text::num;
    use super::*;

    /// Zeros of both signs, decimals, the edges of the exponent range, subnormals.
    const FLOATS: [f64; 8] = [
        0.0,
        -0.0,
        0.1,
        1e-7,
        1e16,
        123456789012.5,
        f64::MIN_POSITIVE,
        5e-324,
    ];

    #[test]
    fn fields_read_back_as_written() {
        let mut c = Cells::with_capacity(2);
        c.push_usize(17);
        c.push_empty(2);
        for x in FLOATS {
            c.push_f64(x);
        }
        c.push("1/3");
        c.push("");
        c.push("ok");
        let mut want = vec!["17".to_string(), String::new(), String::new()];
        want.extend(FLOATS.map(num));
        want.extend(["1/3".to_string(), String::new(), "ok".to_string()]);
        assert_eq!(c.iter().collect::<Vec<_>>(), want);
    }
}
