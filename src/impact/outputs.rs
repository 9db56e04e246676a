//! Which outputs a solve computes: the caller asks, and nothing else is built.
//!
//! A solve's outputs cost unequally (Example 3 in f64: the tangent frames and the tangential
//! inertances ĝ_ij,yx, ĝ_ij,zx are about a third of the assembly). [`Outputs`] names a set of
//! them; [`crate::impact::solve::Impact::assemble_for`] builds only what that set needs, and
//! [`crate::impact::solve::Impact::solve`] fills only those fields of the
//! [`crate::impact::solve::Outcome`] (the others are left empty, or as they were). Each output
//! is computed by the same operations in the same order whatever else is asked, so a requested
//! output is bit for bit the one [`Outputs::ALL`] gives (tested in every scalar type).
//!
//! What each output needs of the others is said once, in [`Outputs::needs`]: the energies are
//! formed from the twist change and the velocities along the normals (ΔE_c = ½ Σ P̂_i
//! (v̂⁰_ix + v̂_ix)) and the impulses; the constraint impulses from the twist change and the
//! impulses; the velocities along the normals, on the normal equations' route, from the
//! impulses. Those are computed when needed and not reported.

use std::fmt;
use std::ops::{BitOr, BitOrAssign};

/// A set of a solve's outputs.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Outputs(u8);

impl Outputs {
    /// P̂_i, and P̂_i^c for Poisson (eq. 20–23).
    pub const IMPULSES: Outputs = Outputs(1);
    /// {v} = [ω; v_C] after impact (eq. 24).
    pub const TWIST: Outputs = Outputs(1 << 1);
    /// v_ix after impact, along the normals (eq. 13).
    pub const NORMAL_VELOCITIES: Outputs = Outputs(1 << 2);
    /// The tangent axes y_i, z_i, the tangential inertances g_ij,yx and g_ij,zx (eq. 127–128)
    /// and the tangential velocities v_iy, v_iz before and after impact (eq. 8, 25–26), with
    /// their angle (eq. 27).
    pub const TANGENTIAL: Outputs = Outputs(1 << 3);
    /// E_p and ΔE_c (eq. 28, 32), and the kinetic energy before impact.
    pub const ENERGIES: Outputs = Outputs(1 << 4);
    /// The constraint impulses q (eq. 90–93; none for a free body).
    pub const CONSTRAINT_IMPULSES: Outputs = Outputs(1 << 5);
    /// No output: the assembly only (G, its factorization, Δ).
    pub const NONE: Outputs = Outputs(0);
    /// Every output: what [`crate::impact::solve::Impact::assemble`] computes.
    pub const ALL: Outputs = Outputs((1 << 6) - 1);

    /// Each output with the name the CLI and scenes use for it, in report order.
    pub const NAMED: [(&'static str, Outputs); 6] = [
        ("impulses", Outputs::IMPULSES),
        ("twist", Outputs::TWIST),
        ("normal-velocities", Outputs::NORMAL_VELOCITIES),
        ("tangential", Outputs::TANGENTIAL),
        ("energies", Outputs::ENERGIES),
        ("constraint-impulses", Outputs::CONSTRAINT_IMPULSES),
    ];

    /// Whether every output of `other` is in this set.
    pub const fn contains(self, other: Outputs) -> bool {
        self.0 & other.0 == other.0
    }

    /// Whether any output of `other` is in this set.
    pub const fn intersects(self, other: Outputs) -> bool {
        self.0 & other.0 != 0
    }

    /// Whether the set is empty.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// The set with what its outputs are computed from (module docs): what a solve computes
    /// to answer it.
    pub const fn needs(self) -> Outputs {
        let mut s = self.0;
        if self.intersects(Outputs::ENERGIES) {
            s |= Outputs::TWIST.0 | Outputs::NORMAL_VELOCITIES.0 | Outputs::IMPULSES.0;
        }
        if self.intersects(Outputs::CONSTRAINT_IMPULSES) {
            s |= Outputs::TWIST.0 | Outputs::IMPULSES.0;
        }
        if self.intersects(Outputs::TANGENTIAL) {
            // The tangential velocities after impact are v̂⁰_ia + {Ê_ia}ᵀ η Δv (one route) or
            // v̂⁰_ia − Σ_j ĝ_ij,ax P̂_j (the other).
            s |= Outputs::TWIST.0 | Outputs::IMPULSES.0;
        }
        if self.intersects(Outputs::NORMAL_VELOCITIES) {
            s |= Outputs::IMPULSES.0;
        }
        Outputs(s)
    }

    /// Every subset of [`Outputs::ALL`], the empty one first (for tests and benches).
    pub fn subsets() -> impl Iterator<Item = Outputs> {
        (0..=Outputs::ALL.0).map(Outputs)
    }

    /// Parse a list of names ([`Outputs::NAMED`], or `all`); the error names the unknown one.
    ///
    /// # Errors
    /// [`UnknownOutput`] for a name that is none of them.
    pub fn parse<'a>(names: impl IntoIterator<Item = &'a str>) -> Result<Outputs, UnknownOutput> {
        let mut set = Outputs::NONE;
        for name in names {
            let name = name.trim();
            set |= match name {
                "all" => Outputs::ALL,
                _ => Outputs::NAMED
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, o)| *o)
                    .ok_or_else(|| UnknownOutput(name.to_string()))?,
            };
        }
        Ok(set)
    }
}

impl Default for Outputs {
    fn default() -> Self {
        Outputs::ALL
    }
}

impl BitOr for Outputs {
    type Output = Outputs;
    fn bitor(self, rhs: Outputs) -> Outputs {
        Outputs(self.0 | rhs.0)
    }
}

impl BitOrAssign for Outputs {
    fn bitor_assign(&mut self, rhs: Outputs) {
        self.0 |= rhs.0;
    }
}

impl fmt::Display for Outputs {
    /// The names, comma-separated (`all` for every output).
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == Outputs::ALL {
            return f.write_str("all");
        }
        let names: Vec<&str> = Outputs::NAMED
            .iter()
            .filter(|(_, o)| self.contains(*o))
            .map(|(n, _)| *n)
            .collect();
        f.write_str(&names.join(","))
    }
}

/// An output name that is not one of [`Outputs::NAMED`].
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error(
    "unknown output '{0}': expected some of impulses, twist, normal-velocities, tangential, \
     energies, constraint-impulses, or all"
)]
pub struct UnknownOutput(pub String);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_parse_and_print_back() {
        let s = Outputs::parse(["impulses", " twist"]).unwrap();
        assert_eq!(s, Outputs::IMPULSES | Outputs::TWIST);
        assert_eq!(s.to_string(), "impulses,twist");
        assert_eq!(Outputs::parse(["all"]).unwrap(), Outputs::ALL);
        assert_eq!(Outputs::ALL.to_string(), "all");
        assert_eq!(
            Outputs::parse(["twist", "angles"]),
            Err(UnknownOutput("angles".into()))
        );
        assert_eq!(Outputs::subsets().count(), 64);
    }

    #[test]
    fn what_each_output_needs() {
        assert_eq!(Outputs::IMPULSES.needs(), Outputs::IMPULSES);
        assert_eq!(Outputs::TWIST.needs(), Outputs::TWIST);
        assert_eq!(
            Outputs::ENERGIES.needs(),
            Outputs::ENERGIES | Outputs::TWIST | Outputs::NORMAL_VELOCITIES | Outputs::IMPULSES
        );
        assert_eq!(Outputs::ALL.needs(), Outputs::ALL);
        for s in Outputs::subsets() {
            assert!(s.needs().contains(s) && s.needs().needs() == s.needs());
        }
    }
}
