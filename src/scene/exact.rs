//! Why a scene cannot be solved exactly, named by what its author wrote.
//!
//! The exact solver holds rationals and the radicals of [`crate::scalar::symbolic`]; sines and
//! cosines are exact at multiples of 15°, not at 20°. A pose at 20° fails deep inside the lowering, on a computed entry of the inertia tensor
//! (`body.inertia[1][2] = (((cos((20 deg)))*(1/40))*…`); this module names the pose's angle —
//! or the parameter it was written as — says why, and what to do instead.

use crate::number::Number;
use crate::scalar::symbolic::symbolic;

use super::{Scene, SceneError};

impl Scene {
    /// The first pose angle whose sine or cosine has no exact form the solver holds, as the
    /// error to report in its place (`None` when every angle's has one).
    pub fn inexact_angle(&self) -> Option<SceneError> {
        self.angles.iter().find_map(|(key, n)| {
            let exact = |f: &str| symbolic(&format!("{f}({})", n.text), &n.symbols).is_ok();
            if exact("cos") && exact("sin") {
                return None;
            }
            let (key, value) = self.written_as(key, n);
            Some(SceneError {
                file: self.file.clone(),
                key,
                value: Some(value.clone()),
                message: format!(
                    "the exact solver cannot pose the body by this angle: cos and sin of {value} \
                     have no exact radical form it holds (it takes multiples of 15°, and rational \
                     rotations). Pose it by a multiple of 15°, by a rational rotation (`pose = {{ \
                     quaternion = [w, x, y, z] }}` or a `matrix` with rational entries), or solve \
                     in floating point (without `--exact`)"
                ),
            })
        })
    }

    /// The key and text an author wrote a value under: the parameter's when the value is a
    /// parameter's name.
    fn written_as(&self, key: &str, n: &Number) -> (String, String) {
        let written = n.source.as_deref().unwrap_or(&n.text).trim();
        match self.params.iter().find(|p| p.name == written) {
            Some(p) => (format!("params.{}", p.name), p.text.clone()),
            None => (key.to_string(), written.to_string()),
        }
    }
}
