//! A refinement kept for evaluations to come (refine once, evaluate many: OpenSubdiv's
//! `TopologyRefiner` with its `PrimvarRefiner`), prepared with the checks, guards, options and
//! notes of a run ([`crate::subdivide::prepare`] with [`SubdivideJob::keep_refinement`]).
//!
//! [`SubdivideJob::keep_refinement`]: crate::subdivide::SubdivideJob::keep_refinement

use halfedge::subdivide::SubdivideOptions;
use halfedge::Refinement;

use crate::error::{Error, Result};
use crate::subdivide::Prepared;
use crate::Notes;

/// A refinement of a mesh to its last level, and how its base relates to the mesh.
#[derive(Debug)]
pub struct KeptRefinement {
    /// The refinement (topology, weights, the UV channel when it refines UVs).
    pub refinement: Refinement,
    /// The mesh vertex (an index into the face list's positions) of each base vertex of the
    /// refinement: the half-edge mesh leaves out vertices that no face uses.
    pub base_vertices: Vec<u32>,
    /// The UV values the face-varying channel starts from (the mesh's layout), when the
    /// refinement refines UVs.
    pub base_uvs: Option<Vec<[f64; 2]>>,
    /// The scheme's name as it counts what is written.
    pub scheme: String,
}

impl Prepared<'_> {
    /// Refines the mesh to the job's last level and keeps the refinement, with the creases,
    /// holes and options a run would use. A rule without face-varying rules refines without
    /// UVs, with a note.
    ///
    /// # Errors
    ///
    /// [`Error::NoRefinement`] for a scheme on the raw face list (refused by
    /// [`crate::subdivide::prepare`] already when the job keeps its refinement); the
    /// refinement's errors, an error about a face naming the mesh ([`Error::InMesh`]).
    pub fn refinement(self, notes: Notes<'_>) -> Result<KeptRefinement> {
        let Some(mesh) = &self.mesh else {
            return Err(Error::NoRefinement {
                scheme: self.chosen.name().to_owned(),
            });
        };
        let (sharpness, options) = self.subdivision_inputs(notes)?;
        let mut opts = SubdivideOptions::default()
            .with_threads(self.job.threads)
            .with_subdivision(options)
            .with_limit(self.job.limit || self.job.limit_normals);
        if let Some(sharpness) = &sharpness {
            opts = opts.with_sharpness(sharpness);
        }
        if let Some(holes) = &self.holes {
            opts = opts.with_holes(holes);
        }
        let (rule, levels) = (self.rule, self.job.levels);
        let refined = match &self.layout {
            Some(layout) => match Refinement::new(mesh, rule, levels, &opts.with_uvs(layout)) {
                Err(e @ halfedge::Error::UvsNotSupported { .. }) => {
                    let label = self.loaded.label();
                    notes(format!("note: {label}: {e}: refining without UVs"));
                    Refinement::new(mesh, rule, levels, &opts)
                }
                result => result,
            },
            None => Refinement::new(mesh, rule, levels, &opts),
        };
        let refinement = refined.map_err(|e| Error::located(e, self.loaded))?;
        let base_uvs = match (&self.layout, refinement.has_uvs()) {
            (Some(layout), true) => Some(layout.values().iter().map(|v| [v.x, v.y]).collect()),
            _ => None,
        };
        Ok(KeptRefinement {
            refinement,
            base_vertices: self.loaded.poly.referenced_vertices(),
            base_uvs,
            scheme: self.chosen.name().to_owned(),
        })
    }
}
