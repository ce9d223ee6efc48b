//! The options of a subdivision ([`SubdivideOptions`]) and what its progress callback hears
//! ([`LevelDone`]).

use super::*;

/// Options of [`subdivide`] and friends.
///
/// ```
/// use halfedge::subdivide::SubdivideOptions;
/// let opts = SubdivideOptions::default().with_threads(2);
/// assert_eq!(opts.threads, 2);
/// ```
#[derive(Clone, Copy)]
#[non_exhaustive]
pub struct SubdivideOptions<'a> {
    /// Threads for the geometry passes: 1 runs everything on the calling thread, 0 uses
    /// rayon's global pool, `n >= 2` a pool of `n` threads. Topology is built on one thread.
    pub threads: usize,
    /// Ignored: every run allocates each output array once from the predicted counts and
    /// checks its final size against the prediction. (Before issue 26, `false` built every
    /// level face by face into arrays growing on demand, a benchmark baseline; the one
    /// refinement has one way to build topology.)
    #[deprecated(note = "ignored: every run preallocates from the predicted counts")]
    pub preallocate: bool,
    /// Called after each level is built.
    pub progress: Option<&'a (dyn Fn(&LevelDone) + Sync)>,
    /// Creases and corners (Loop and Catmull-Clark, OpenSubdiv's rules: [`sdc`]); honoured by
    /// [`Refinement::new`](crate::Refinement::new) and by the one-shot [`subdivide`],
    /// [`subdivide_to_face_list`] and [`verify`] alike (the same weight tables: in `f64` the
    /// same positions to the bit). Other rules refuse a sharpness that is not smooth
    /// ([`Error::CreasesNotSupported`]); the face-list subdividers ([`subdivide_polygons`],
    /// [`verify_polygons`]) place points linearly and do not read it.
    pub sharpness: Option<&'a Sharpness>,
    /// Boundary interpolation, crease method and triangle rule of the crease rules
    /// ([`sdc`]), read wherever [`SubdivideOptions::sharpness`] is; the default is
    /// OpenSubdiv's `edge` / `uniform` / `catmark`, the rules' own kernels.
    pub subdivision: SubdivisionOptions,
    /// Faces that are holes ([`crate::holes`]), for the rules whose faces nest
    /// ([`schemes::holes::nests_faces`]; the others are refused with
    /// [`Error::HolesNeedNestedFaces`]): they are refined like any other face, so the surface
    /// around them is unchanged, but their descendants are not written, nor the vertices
    /// only they use (the others renumbered, in order). Honoured by
    /// [`subdivide_to_face_list`], [`subdivide_polygons`], [`verify`] and
    /// [`verify_polygons`] (which count what is written), [`subdivide`] (the written faces
    /// as a half-edge mesh, when they are one) and [`Refinement::new`](crate::Refinement::new)
    /// (index buffers and vertex data of the written part). `None` or an empty set changes
    /// nothing.
    pub holes: Option<&'a HoleSet>,
    /// The UV layout of the mesh ([`crate::uv::UvLayout`], from
    /// [`PolygonMesh::uv_layout`]) to refine as face-varying data
    /// ([`refine::face_varying`]): [`Refinement::new`](crate::Refinement::new) then refines it
    /// too ([`Refinement::evaluate_uvs`](crate::Refinement::evaluate_uvs)) and
    /// [`subdivide_to_face_list`] writes the refined UVs into its mesh. Loop and
    /// Catmull-Clark follow [`SubdivideOptions::subdivision`]'s
    /// [`face_varying`](crate::tags::SubdivisionOptions::face_varying) mode; Doo-Sabin and
    /// mid-edge, and √3, carry it corner by corner ([`refine::face_varying`]'s corner
    /// channel). [`subdivide_polygons`] refines it
    /// as a face list by the same linear per-face refinement as the positions and writes the
    /// UVs into its mesh. [`subdivide`] and [`verify`] (half-edge meshes, which carry no UVs)
    /// and [`verify_polygons`] do not read it.
    pub uvs: Option<&'a crate::uv::UvLayout>,
    /// Read what the mesh carries ([`HalfEdgeMesh::descriptor`]: its file's creases, corners,
    /// holes, options and UVs) where these options leave a value unset (`None`; for
    /// [`SubdivideOptions::subdivision`], the default), as the command line puts a flag over a
    /// tag (the rules: [`crate::descriptor`]). On by default; off, a subdivision reads these
    /// options alone.
    pub descriptor: bool,
    /// Give [`subdivide_to_face_list`]'s level the base face of each of its faces
    /// ([`FaceListLevel::base_faces`], 4 bytes a face; OpenSubdiv's
    /// `InterpolateFaceUniform`). Off by default.
    pub base_faces: bool,
    /// Keep the limit surface of the last level ([`Refinement::evaluate_limit`]: positions
    /// and tangents by OpenSubdiv's limit masks), Loop and Catmull-Clark only. Only
    /// [`Refinement::new`] reads it. Off by default.
    ///
    /// [`Refinement::new`]: crate::Refinement::new
    /// [`Refinement::evaluate_limit`]: crate::Refinement::evaluate_limit
    pub limit: bool,
}

impl Default for SubdivideOptions<'_> {
    #[allow(deprecated)]
    fn default() -> Self {
        SubdivideOptions {
            threads: 1,
            preallocate: true,
            progress: None,
            sharpness: None,
            subdivision: SubdivisionOptions::default(),
            holes: None,
            uvs: None,
            descriptor: true,
            base_faces: false,
            limit: false,
        }
    }
}

impl<'a> SubdivideOptions<'a> {
    with_setters! {
        /// Sets [`SubdivideOptions::threads`].
        with_threads(threads: usize);
        /// Sets [`SubdivideOptions::progress`].
        with_progress(progress: Some(&'a (dyn Fn(&LevelDone) + Sync)));
        /// Sets [`SubdivideOptions::sharpness`].
        with_sharpness(sharpness: Some(&'a Sharpness));
        /// Sets [`SubdivideOptions::subdivision`].
        with_subdivision(subdivision: SubdivisionOptions);
        /// Sets [`SubdivideOptions::uvs`].
        with_uvs(uvs: Some(&'a crate::uv::UvLayout));
        /// Sets [`SubdivideOptions::holes`].
        with_holes(holes: Some(&'a HoleSet));
        /// Sets [`SubdivideOptions::descriptor`].
        with_descriptor(descriptor: bool);
        /// Sets [`SubdivideOptions::base_faces`].
        with_base_faces(base_faces: bool);
        /// Sets [`SubdivideOptions::limit`].
        with_limit(limit: bool);
    }

    /// Sets [`SubdivideOptions::preallocate`], which is ignored.
    #[deprecated(note = "ignored: every run preallocates from the predicted counts")]
    #[must_use]
    #[allow(deprecated)]
    pub fn with_preallocate(mut self, preallocate: bool) -> Self {
        self.preallocate = preallocate;
        self
    }
}

impl std::fmt::Debug for SubdivideOptions<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SubdivideOptions")
            .field("threads", &self.threads)
            .field("progress", &self.progress.map(|_| "callback"))
            .field(
                "sharpness",
                &self
                    .sharpness
                    .map(|s| (s.n_sharp_edges(), s.n_sharp_vertices())),
            )
            .field("subdivision", &self.subdivision)
            .field("holes", &self.holes.map(|h| h.faces().len()))
            .field("uvs", &self.uvs.map(|u| u.n_values()))
            .field("descriptor", &self.descriptor)
            .field("base_faces", &self.base_faces)
            .field("limit", &self.limit)
            .finish()
    }
}

/// Passed to the progress callback after each level.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct LevelDone {
    /// The level just built (1-based).
    pub level: u32,
    /// The final level.
    pub levels: u32,
    /// Vertices of the level.
    pub vertices: usize,
    /// Edges of the level.
    pub edges: usize,
    /// Faces of the level.
    pub faces: usize,
}

impl<'a> SubdivideOptions<'a> {
    /// These options over what `mesh` carries for a subdivision by `rule` (the module docs
    /// of [`crate::descriptor`]); the options themselves when
    /// [`SubdivideOptions::descriptor`] is off or the mesh carries nothing.
    ///
    /// # Errors
    ///
    /// [`Error::CreasesNotSupported`] for the descriptor's boundary `none` on a mesh with
    /// boundary under a rule other than Loop and Catmull-Clark.
    pub(crate) fn over_descriptor<'m>(
        &self,
        mesh: &'m HalfEdgeMesh,
        rule: Option<Rule>,
    ) -> Result<SubdivideOptions<'m>>
    where
        'a: 'm,
    {
        let mut opts: SubdivideOptions<'m> = *self;
        let Some(d) = mesh.descriptor().filter(|_| self.descriptor) else {
            return Ok(opts);
        };
        let creases = matches!(rule, Some(Rule::Loop | Rule::CatmullClark));
        if creases {
            opts.sharpness = opts.sharpness.or(d.sharpness.as_ref());
            if opts.subdivision == SubdivisionOptions::default() {
                opts.subdivision = d.subdivision;
            }
        } else if d.subdivision.boundary == crate::tags::BoundaryInterpolation::None
            && !mesh.is_closed()
            && opts.holes.is_none()
        {
            return Err(Error::CreasesNotSupported {
                rule: rule.map_or_else(|| "this scheme".to_owned(), |r| r.to_string()),
                what: "the boundary none",
            });
        }
        opts.holes = opts.holes.or(d.holes.as_ref());
        opts.uvs = opts.uvs.or(d.uvs.as_ref());
        Ok(opts)
    }
}
