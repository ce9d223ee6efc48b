//! What a mesh's file says about its subdivision, carried by the mesh: OpenSubdiv's
//! `Far::TopologyDescriptor` holds creases, corners, holes and face-varying data beside the
//! faces, and pmp-library's meshes keep their properties; a [`HalfEdgeMesh`] built from a
//! [`PolygonMesh`] (`HalfEdgeMesh::try_from`) keeps its file's tags and UVs the same way, in a
//! [`Descriptor`], and every subdivision of the mesh honours them unless its
//! [`SubdivideOptions`] say otherwise ([`SubdivideOptions::descriptor`]).
//!
//! What the descriptor holds, resolved once on construction:
//!
//! - the creases and corners as a [`Sharpness`] of the half-edge mesh (its vertices renumbered
//!   when the file has vertices in no face: [`Sharpness::from_tags_of`]);
//! - the options (`interpolateboundary`, `facevaryinginterpolateboundary`, `creasemethod`,
//!   `smoothtriangles`) over OpenSubdiv's defaults ([`SubdivisionOptions`]);
//! - the holes: the faces tagged `hole`, and under `interpolateboundary 0` (none) on a mesh
//!   with boundary the faces at the boundary as well ([`holes::holes_of`]),
//!   as `subcount subdivide` resolves them;
//! - the UV layout ([`PolygonMesh::uv_layout`]).
//!
//! How a subdivision reads it, exactly as the command line does (flag over tag over default,
//! the options being the flags): an option left unset (`None`; for
//! [`SubdivideOptions::subdivision`], the default) takes the descriptor's value. Creases,
//! corners and the options apply under Loop and Catmull-Clark only (the rules that have
//! crease rules; the others subdivide the mesh as if it had none, as the CLI does after its
//! note), holes under the rules whose faces nest (the others refuse them:
//! [`Error::HolesNeedNestedFaces`]), boundary `none` on a mesh with boundary under Loop and
//! Catmull-Clark only ([`Error::CreasesNotSupported`] elsewhere), the UVs under every rule.
//!
//! ```
//! use halfedge::subdivide::{subdivide_to_face_list, Rule, Sharpness, SubdivideOptions};
//! use halfedge::{io, HalfEdgeMesh, Refinement};
//!
//! // A cube with one infinitely sharp edge and texture coordinates, as OpenSubdiv's OBJ.
//! let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
//!            vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n\
//!            f 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\n\
//!            f 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\n\
//!            t crease 2/1/0 0 1 10\n";
//! let file = io::read_obj_from(obj.as_bytes(), "cube.obj")?;
//! let cube = HalfEdgeMesh::try_from(&file)?;
//! let carried = cube.descriptor().expect("the file has tags and UVs");
//! assert_eq!(carried.sharpness.as_ref().map(|s| s.n_sharp_edges()), Some(1));
//!
//! // The refinement honours the crease and refines the UVs without being told...
//! let opts = SubdivideOptions::default();
//! assert!(Refinement::new(&cube, Rule::CatmullClark, 2, &opts)?.has_uvs());
//! let level = subdivide_to_face_list(&cube, Rule::CatmullClark, 2, &opts)?;
//! // ... as if they had been given by hand.
//! let sharp = Sharpness::from_tags(&cube, file.tags())?;
//! let layout = file.uv_layout().expect("UVs");
//! let by_hand = opts.with_descriptor(false).with_sharpness(&sharp).with_uvs(&layout);
//! assert_eq!(level, subdivide_to_face_list(&cube, Rule::CatmullClark, 2, &by_hand)?);
//!
//! // Options override the descriptor, or leave it out.
//! let smooth = subdivide_to_face_list(&cube, Rule::CatmullClark, 2, &opts.with_descriptor(false))?;
//! assert_ne!(smooth.mesh.positions, level.mesh.positions);
//! assert!(smooth.mesh.uvs().is_none() && level.mesh.uvs().is_some());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! Refine once, evaluate many, on a tagged file (README.md's example; `write_quads` and
//! `evaluate_uvs` read the holes and the UVs the mesh carries):
//!
//! ```
//! # let path = std::env::temp_dir().join(format!("descriptor-doc-{}.obj", std::process::id()));
//! # std::fs::write(&path, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
//! #   vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 4/2 3/3 2/4\nf 5/1 6/2 7/3 8/4\nf 1/1 2/2 6/3 5/4\n\
//! #   f 2/1 3/2 7/3 6/4\nf 3/1 4/2 8/3 7/4\nf 4/1 1/2 5/3 8/4\nt crease 2/1/0 0 1 10\nt hole 1/0/0 1\n")?;
//! use halfedge::{io, subdivide::SubdivideOptions, HalfEdgeMesh, Refinement, Rule};
//!
//! let file = io::read_obj(&path)?;                  // OpenSubdiv's tags (creases, holes, options), vt
//! let mesh = HalfEdgeMesh::try_from(&file)?;          // carries them: mesh.descriptor()
//! let r = Refinement::new(&mesh, Rule::CatmullClark, 3, &SubdivideOptions::default())?;
//! let mut quads = vec![0u32; 4 * r.n_faces(3)];       // sizes known up front, holes left out
//! r.write_quads(&mut quads)?;
//! let base: Vec<[f32; 3]> = mesh.positions().iter().map(|p| p.as_vec3().to_array()).collect();
//! let mut positions = vec![[0f32; 3]; r.n_vertices(3)];
//! r.evaluator::<f32, 3>().evaluate(&base, &mut positions)?;     // per frame: no topology work
//! let layout = mesh.descriptor().and_then(|d| d.uvs.as_ref()).expect("vt lines");
//! let base_uvs: Vec<[f32; 2]> = layout.values().iter().map(|v| v.as_vec2().to_array()).collect();
//! let mut uvs = vec![[0f32; 2]; r.n_uvs(3)];
//! r.evaluate_uvs(&base_uvs, &mut uvs)?;
//! assert_eq!(r.n_faces(3), 5 * 64);                    // the hole's 64 faces are not written
//! # std::fs::remove_file(&path)?;
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

//!
//! [`HalfEdgeMesh`]: crate::HalfEdgeMesh
//! [`HalfEdgeMesh::descriptor`]: crate::HalfEdgeMesh::descriptor
//! [`PolygonMesh`]: crate::PolygonMesh
//! [`PolygonMesh::uv_layout`]: crate::PolygonMesh::uv_layout
//! [`SubdivideOptions`]: crate::subdivide::SubdivideOptions
//! [`SubdivideOptions::descriptor`]: crate::subdivide::SubdivideOptions::descriptor
//! [`SubdivideOptions::subdivision`]: crate::subdivide::SubdivideOptions::subdivision
//! [`Error::CreasesNotSupported`]: crate::Error::CreasesNotSupported
//! [`Error::HolesNeedNestedFaces`]: crate::Error::HolesNeedNestedFaces
//! [`holes::holes_of`]: crate::holes::holes_of
use crate::holes::set::HoleSet;
use crate::subdivide::sdc::sharpness::Sharpness;
use crate::tags::SubdivisionOptions;
use crate::uv::UvLayout;

/// The tags and UVs of a mesh's file, resolved on the half-edge mesh built from it
/// ([`HalfEdgeMesh::descriptor`](crate::HalfEdgeMesh::descriptor); the module docs say how a subdivision reads it).
#[derive(Clone, Debug, Default, PartialEq)]
#[non_exhaustive]
pub struct Descriptor {
    /// The creases and corners, `None` when no edge or vertex is sharp.
    pub sharpness: Option<Sharpness>,
    /// The file's options over OpenSubdiv's defaults.
    pub subdivision: SubdivisionOptions,
    /// The faces that are holes (tagged, and the boundary's under boundary `none`), `None`
    /// when there are none.
    pub holes: Option<HoleSet>,
    /// The UV layout, `None` without texture coordinates.
    pub uvs: Option<UvLayout>,
}
