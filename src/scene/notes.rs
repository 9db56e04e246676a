//! Notes on likely slips: a scene that reads, but probably not as its author meant. A note is
//! printed on stderr (`note: …`, Python's `Scene.notes`) and changes nothing: the scene is
//! solved as written.
//!
//! * **Radians beside degrees**: the scene writes angles in `deg` while another value applies
//!   sin, cos or tan to a bare number, or a pose turns by a bare number — read as radians
//!   (`sin(3)`, `angle = 20`: 20 rad = 1146°).
//! * **Units**: the toolkit takes SI units (m, kg, s). A shape given its mass whose density
//!   m / V is below that of air (1 kg/m³) or above any material's (10⁵ kg/m³; osmium is
//!   22 590) was probably written in millimetres or grams.

use crate::number::Number;
use crate::number::expr::{self, Kind, Node, Wording};

use super::Scene;

/// Densities outside this range (kg/m³) get the units note.
const PLAUSIBLE_DENSITY: (f64, f64) = (1.0, 1e5);

impl Scene {
    /// The notes on likely slips, each a line beginning `note: FILE:`.
    pub fn notes(&self) -> Vec<String> {
        // A bare pose angle is named once, by its own key, not through the numbers that the
        // rotation computes from it.
        let mut notes: Vec<String> = self
            .pose_radian_note()
            .or_else(|| self.radian_note())
            .into_iter()
            .collect();
        notes.extend(self.units_note());
        notes
    }

    /// A note when the scene writes angles both ways: some value uses `deg` while another
    /// applies sin, cos or tan to a bare number (read as radians) — `sin(3)` beside `30 deg`
    /// is likely a slip. Names the key and value.
    fn radian_note(&self) -> Option<String> {
        let numbers: Vec<(String, &Number)> = self.numbers().collect();
        if !numbers.iter().any(|(_, n)| n.text.contains("deg")) {
            return None;
        }
        numbers.iter().find_map(|(key, n)| {
            let t = &n.text;
            ["sin(", "cos(", "tan("].iter().find_map(|f| {
                let at = t.find(f)? + f.len();
                let inner = t[at..].split(')').next()?.trim();
                let bare = !inner.is_empty()
                    && inner
                        .chars()
                        .all(|c| c.is_ascii_digit() || c == '.' || c == '-' || c == '/');
                bare.then(|| {
                    format!(
                        "note: {}: `{key}` = \"{t}\" takes {} of {inner} radians, while the scene writes \
                         other angles in `deg`; write `{inner} deg` if degrees were meant",
                        self.file,
                        &f[..3]
                    )
                })
            })
        })
    }

    /// A pose angle written as a bare number (radians) while the scene writes other angles
    /// in `deg`: named by the key the author wrote it under (the pose's, or the parameter's).
    fn pose_radian_note(&self) -> Option<String> {
        let in_degrees = |t: &str| t.contains("deg");
        let elsewhere = self.params.iter().any(|p| in_degrees(&p.text))
            || self.angles.iter().any(|(_, n)| in_degrees(&n.text))
            || self.numbers().any(|(_, n)| in_degrees(&n.text));
        if !elsewhere {
            return None;
        }
        self.angles.iter().find_map(|(key, n)| {
            if n.approx == 0.0 || !bare_number(&n.text) {
                return None;
            }
            let written = n.source.as_deref().unwrap_or(&n.text).trim();
            let key = match self.params.iter().find(|p| p.name == written) {
                Some(p) => format!("params.{}", p.name),
                None => key.clone(),
            };
            let value = n.text.trim().trim_start_matches('(').trim_end_matches(')');
            Some(format!(
                "note: {}: `{key}` = {value} turns the body by {value} rad ({:.0}°), while the \
                 scene writes other angles in `deg`; write `{value} deg` if degrees were meant",
                self.file,
                n.approx.to_degrees()
            ))
        })
    }

    /// A shape whose mass gives an implausible density: lengths in millimetres, or a mass in
    /// grams.
    fn units_note(&self) -> Option<String> {
        let (low, high) = PLAUSIBLE_DENSITY;
        let (key, rho, hint) = self.density.iter().find_map(|(key, rho)| {
            let hint = if *rho < low {
                "lighter than air: were the lengths written in millimetres or centimetres?"
            } else if *rho > high {
                "denser than any material: was the mass written in grams, or the lengths in \
                 kilometres?"
            } else {
                return None;
            };
            Some((key, *rho, hint))
        })?;
        let whose = match &self.system {
            None => "the body's".to_string(),
            Some(_) => format!("`{key}`'s"),
        };
        Some(format!(
            "note: {}: {whose} mass over its shape's volume gives a density of {rho:.3e} kg/m³, \
             {hint} Lengths are in metres, masses in kilograms",
            self.file
        ))
    }
}

/// Whether `text` is a number with no unit and no π (a bare number of radians, if an angle).
fn bare_number(text: &str) -> bool {
    fn plain(n: &Node) -> bool {
        match &n.kind {
            Kind::Lit(_) => true,
            Kind::Neg(e) => plain(e),
            Kind::Chain(first, rest) => plain(first) && rest.iter().all(|(_, e)| plain(e)),
            Kind::Pow(b, e) => plain(b) && plain(e),
            Kind::Pi | Kind::NonFinite | Kind::Name(_) | Kind::Deg(_) | Kind::Call(..) => false,
        }
    }
    let wording = Wording {
        input: "value",
        operand: "a number",
    };
    expr::parse(text, &wording).is_ok_and(|root| plain(&root))
}
