//! A file that is never left half-written: written beside its name and renamed into place
//! only when complete.

use std::fs::File;
use std::path::{Path, PathBuf};

use super::SweepError;

/// A file written as `FILE.tmp` and renamed to `FILE` on [`Staged::commit`]; removed if
/// dropped uncommitted.
pub(super) struct Staged {
    /// The file asked for.
    path: PathBuf,
    /// Where it is written until committed: `FILE.tmp`.
    pub(super) tmp: PathBuf,
    /// Whether it was renamed into place.
    done: bool,
}

impl Staged {
    /// Stage `path` (nothing is written until [`Staged::open`]).
    pub(super) fn create(path: &Path) -> Result<Staged, SweepError> {
        let mut tmp = path.as_os_str().to_owned();
        tmp.push(".tmp");
        Ok(Staged {
            path: path.to_path_buf(),
            tmp: PathBuf::from(tmp),
            done: false,
        })
    }

    /// Create the `.tmp` file to write.
    pub(super) fn open(&self) -> Result<File, SweepError> {
        File::create(&self.tmp).map_err(|e| SweepError::Io {
            path: self.path.clone(),
            message: format!(
                "cannot create {}: {e}; check that the directory exists and is writable",
                self.tmp.display()
            ),
        })
    }

    /// Rename the complete `.tmp` file to its name.
    pub(super) fn commit(mut self) -> Result<(), SweepError> {
        std::fs::rename(&self.tmp, &self.path).map_err(|e| SweepError::Io {
            path: self.path.clone(),
            message: format!("cannot rename {} to it: {e}", self.tmp.display()),
        })?;
        self.done = true;
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.done {
            let _ = std::fs::remove_file(&self.tmp);
        }
    }
}
