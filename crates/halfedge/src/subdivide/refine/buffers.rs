//! The last level's index buffers, written into the caller's slices: triangles, quads,
//! polygons with offsets (numbered as `subdivide_to_face_list` numbers them); the base face of
//! every face of a level (per-face data).

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

    /// The base face each face of level `level` comes from (`n_faces(level)` entries; with
    /// holes, the last level's written faces): OpenSubdiv's `GetFaceParentFace` chained to
    /// level 0, for per-face data such as materials and groups (`InterpolateFaceUniform`:
    /// face `g` takes `data[base_faces[g]]`). Under √3, Doo-Sabin and mid-edge, a face that
    /// comes from several faces (√3's flipped triangles, the dual rules' edge and vertex
    /// faces) takes the lowest-numbered base face it descends from. Computed on each call
    /// (4 bytes per face of the level).
    ///
    /// ```
    /// use halfedge::subdivide::SubdivideOptions;
    /// use halfedge::{shapes, HalfEdgeMesh, Refinement, Rule};
    ///
    /// let cube = HalfEdgeMesh::try_from(&shapes::cube())?;
    /// let r = Refinement::new(&cube, Rule::CatmullClark, 2, &SubdivideOptions::default())?;
    /// let base = r.base_faces(2)?;
    /// assert_eq!(base.len(), r.n_faces(2));
    /// assert!(base.iter().take(16).all(|&f| f == 0)); // face 0's 4 x 4 quads come first
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// # Errors
    ///
    /// [`Error::LevelOutOfRange`] unless `level <= levels`; [`Error::AllocationFailed`].
    pub fn base_faces(&self, level: u32) -> Result<Vec<u32>> {
        if level > self.levels {
            return Err(Error::LevelOutOfRange {
                level,
                first: 0,
                levels: self.levels,
            });
        }
        // The whole base level (with holes at `levels = 0`, `n_faces(0)` counts the written).
        let nf = match (&self.written, self.levels) {
            (Some(w), 0) => w.full.faces,
            _ => self.n_faces(0),
        };
        let faces = if self.split == Split::Quad && level > 0 {
            let degrees = self.base_degrees.iter().map(|&d| d as usize);
            crate::subdivide::uniform::nested_base_faces(self.split, degrees, level)?
        } else {
            let degrees = std::iter::repeat(3).take(nf);
            crate::subdivide::uniform::nested_base_faces(self.split, degrees, level)?
        };
        let mut faces = match faces {
            Some(faces) => faces,
            None => {
                // √3 and the dual rules keep every level's connectivity before the last.
                let mut values = crate::subdivide::alloc::with_capacity(nf, "base faces")?;
                values.extend(0..nf as u32);
                for s in 0..level as usize {
                    let t = self.topology.get(s).and_then(|l| l.topology.as_ref());
                    let Some(t) = t else {
                        return Err(Error::InvalidOutput {
                            scheme: self.name.clone(),
                            level: s as u32,
                            what: "no connectivity kept for the base faces".into(),
                        });
                    };
                    values =
                        crate::subdivide::uniform::child_faces(self.split, &t.topo(), &values)?;
                }
                values
            }
        };
        if let (Some(w), true) = (&self.written, level == self.levels) {
            faces.retain(|&f| !w.holes[f as usize]);
        }
        Ok(faces)
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
