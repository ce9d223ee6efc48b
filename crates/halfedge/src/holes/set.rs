//! The set of hole faces ([`HoleSet`]), apart from the counting and the meshes that read it
//! (`holes/mod.rs`), so that a mesh can carry one ([`crate::Descriptor`]) without naming them.

use crate::{Error, Result};

/// A set of hole faces of a mesh with a known number of faces: sorted, without repeats.
#[derive(Clone, Debug, PartialEq, Eq, Default)]
pub struct HoleSet {
    faces: Vec<u32>,
    n_faces: usize,
}

impl HoleSet {
    /// The holes among `n_faces` faces (repeats allowed, any order).
    ///
    /// # Errors
    ///
    /// [`Error::HoleOutOfRange`] for a face index `>= n_faces`.
    pub fn new(n_faces: usize, faces: impl IntoIterator<Item = u32>) -> Result<HoleSet> {
        let mut faces: Vec<u32> = faces.into_iter().collect();
        if let Some(&face) = faces.iter().find(|&&f| f as usize >= n_faces) {
            return Err(Error::HoleOutOfRange { face, n_faces });
        }
        faces.sort_unstable();
        faces.dedup();
        Ok(HoleSet { faces, n_faces })
    }

    /// The hole faces, ascending.
    pub fn faces(&self) -> &[u32] {
        &self.faces
    }

    /// `true` when there is no hole.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }

    /// Whether face `f` is a hole.
    pub fn contains(&self, f: u32) -> bool {
        self.faces.binary_search(&f).is_ok()
    }

    /// Checks that every hole is a face of a mesh with `n_faces` faces.
    pub(crate) fn check(&self, n_faces: usize) -> Result<()> {
        match self.faces.last() {
            Some(&face) if face as usize >= n_faces => Err(Error::HoleOutOfRange { face, n_faces }),
            _ => Ok(()),
        }
    }
}
