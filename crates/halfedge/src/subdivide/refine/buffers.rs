//! The last level's index buffers, written into the caller's slices: triangles, quads,
//! polygons with offsets (numbered as `subdivide_to_face_list` numbers them).

use super::*;

impl Refinement {
    /// Writes the last level's triangles, 3 vertex indices per face (`3 * n_faces(levels)`
    /// entries), numbered as [`subdivide_to_face_list`](crate::subdivide::subdivide_to_face_list) numbers
    /// them.
    ///
    /// # Errors
    ///
    /// [`Error::FaceDegreeMismatch`] when a face of the last level is not a triangle;
    /// [`Error::BufferSize`].
    pub fn write_triangles(&self, out: &mut [u32]) -> Result<()> {
        self.write_uniform(out, 3, "triangles")
    }

    /// Writes the last level's quads, 4 vertex indices per face (`4 * n_faces(levels)`
    /// entries).
    ///
    /// # Errors
    ///
    /// [`Error::FaceDegreeMismatch`] when a face of the last level is not a quad;
    /// [`Error::BufferSize`].
    pub fn write_quads(&self, out: &mut [u32]) -> Result<()> {
        self.write_uniform(out, 4, "quads")
    }

    pub(super) fn write_uniform(
        &self,
        out: &mut [u32],
        degree: usize,
        what: &'static str,
    ) -> Result<()> {
        if self.face_degree != Some(degree) {
            let (face, found) = self.first_face_not_of(degree);
            return Err(Error::FaceDegreeMismatch {
                what,
                wanted: degree,
                face,
                degree: found,
            });
        }
        let nf = self.n_faces(self.levels);
        let what = if degree == 3 {
            "triangle indices"
        } else {
            "quad indices"
        };
        check_len(what, degree * nf, out.len())?;
        self.write_corners(out)
    }

    /// The first face of the last level whose degree is not `degree`, with its degree.
    pub(super) fn first_face_not_of(&self, degree: usize) -> (usize, usize) {
        if let Some(p) = &self.polygons {
            let found = p
                .offsets
                .windows(2)
                .map(|w| (w[1] - w[0]) as usize)
                .enumerate()
                .find(|&(_, d)| d != degree);
            return found.unwrap_or((0, degree));
        }
        // A direct rule: every face has the rule's degree.
        (0, self.face_degree.unwrap_or(0))
    }

    /// The face corners of the last level into `out` (exactly `n_corners(levels)` entries).
    pub(super) fn write_corners(&self, out: &mut [u32]) -> Result<()> {
        if let Some(p) = &self.polygons {
            out.copy_from_slice(&p.indices);
            return Ok(());
        }
        let parallel = self.threads != 1;
        let Some(t) = self
            .topology
            .last()
            .and_then(|l| l.topology.as_ref())
            .map(Connectivity::topo)
        else {
            return Ok(());
        };
        let expected = self.n_faces(self.levels);
        let template = self.template.as_ref();
        let written =
            self.run(|| crate::subdivide::to_faces::corners_after(&t, template, out, parallel));
        if written != expected {
            return Err(Error::PredictionMismatch {
                scheme: self.name.clone(),
                level: self.levels,
                what: "faces",
                predicted: expected.into(),
                actual: written as u64,
            });
        }
        Ok(())
    }

    /// Writes the last level's faces as polygons: `offsets` (`n_faces + 1` entries, face `f`
    /// is `indices[offsets[f]..offsets[f + 1]]`) and `indices` (`n_corners` entries).
    ///
    /// # Errors
    ///
    /// [`Error::BufferSize`]; [`Error::IndexOverflow`] when the corners do not fit `u32`
    /// offsets.
    pub fn write_polygons(&self, offsets: &mut [u32], indices: &mut [u32]) -> Result<()> {
        let nf = self.n_faces(self.levels);
        let nc = self.n_corners(self.levels);
        check_len("face offsets", nf + 1, offsets.len())?;
        check_len("face indices", nc, indices.len())?;
        if u32::try_from(nc).is_err() {
            return Err(Error::IndexOverflow {
                what: "face corners",
                count: nc as u128,
            });
        }
        match (&self.polygons, self.face_degree) {
            (Some(p), _) => offsets.copy_from_slice(&p.offsets),
            (None, Some(d)) => {
                for (f, o) in offsets.iter_mut().enumerate() {
                    // At most nc, which fits u32.
                    *o = (d * f) as u32;
                }
            }
            (None, None) => {}
        }
        self.write_corners(indices)
    }
}
