//! `verify`: really subdivide a mesh to every level and compare each count with the
//! scheme's prediction, UV values included (`UvCheck`: predicted by
//! [`schemes::uv::UvCounter`], measured as the distinct values the corners of a
//! [`halfedge::Refinement`] with UVs use at each level, or on the face-list path those of
//! `subdivide_polygons`' written UVs).

use halfedge::holes::HoleSet;
use halfedge::subdivide::{self as sub, LevelReport, SubdivideOptions};
use halfedge::uv::UvLayout;
use halfedge::{HalfEdgeMesh, PolygonMesh, Rule};
use num_bigint::BigInt;
use schemes::uv::UvCounter;
use schemes::{Budget, MeshCounts, Plan, Scheme};

use crate::error::{Error, Result};
use crate::guard::{guard_memory, uv_bytes};
use crate::mesh::LoadedMesh;
use crate::scheme::{choose, on_face_list, Chosen, SchemeChoice};
use crate::Notes;

/// The most levels [`highest_level_within`] picks.
pub const MAX_VERIFY_LEVELS: u64 = 64;

/// The highest level (at most [`MAX_VERIFY_LEVELS`]) whose face count under `plan` from the
/// initial state `x0` stays within `max_faces`.
///
/// # Errors
///
/// The search's errors ([`schemes::fit`]).
pub fn highest_level_within(plan: &Plan, x0: &[BigInt], max_faces: u64) -> Result<u32> {
    let budget = Budget {
        max_faces: Some(BigInt::from(max_faces)),
        ..Budget::default()
    };
    let fit = schemes::fit(plan, x0, &budget)?;
    Ok(fit.highest_level(MAX_VERIFY_LEVELS).unwrap_or(0) as u32)
}

/// What `verify` measured.
#[derive(Debug)]
pub struct Verified {
    /// One report per level, `0..=levels`.
    pub reports: Vec<LevelReport>,
    /// The scheme as it counts what is written.
    pub scheme: String,
    /// The last level.
    pub levels: u32,
}

/// A verification whose scheme is chosen: [`Verification::sizing`] and
/// [`Verification::initial_state`] tell the caller what the levels will count, before
/// [`Verification::run`].
#[derive(Debug)]
pub struct Verification<'m> {
    loaded: &'m LoadedMesh,
    chosen: Chosen,
    /// The rule's own scheme, which sizes the real subdivision of the whole mesh.
    sizing: Scheme,
    counts: MeshCounts,
    x0: Vec<BigInt>,
    custom: bool,
}

/// Starts verifying `choice` on `loaded`: the mesh checked, the scheme chosen ([`choose`]),
/// the mesh's notes handed to `notes`.
///
/// # Errors
///
/// [`Error::RepeatedVertex`], [`choose`]'s, a scheme that does not apply.
pub fn start<'m>(
    loaded: &'m LoadedMesh,
    choice: &SchemeChoice,
    notes: Notes<'_>,
) -> Result<Verification<'m>> {
    loaded.refuse_degenerate_faces()?;
    let counts = halfedge::stats::face_list_counts(&loaded.poly);
    let chosen = choose(choice, loaded, &counts)?;
    loaded.emit_notes(notes);
    // The rule's own scheme sizes the real subdivision of the whole mesh (a custom matrix may
    // be wrong); the scheme predicts what is written.
    let sizing = chosen.rule.scheme_for(&counts)?;
    let x0 = sizing
        .initial_state(&counts)
        .map_err(|e| loaded.not_applicable(e))?;
    Ok(Verification {
        loaded,
        chosen,
        sizing,
        counts,
        x0,
        custom: choice.is_custom(),
    })
}

impl Verification<'_> {
    /// The scheme that sizes the real subdivision (the rule's own).
    pub fn sizing(&self) -> &Scheme {
        &self.sizing
    }

    /// Its initial state on the mesh.
    pub fn initial_state(&self) -> &[BigInt] {
        &self.x0
    }

    /// Verifies to `levels` with `threads` (the memory guard lifted with `allow_large`):
    /// every count of every level, with the UV values when the mesh has a layout and the
    /// scheme counts them.
    ///
    /// # Errors
    ///
    /// The memory guard's refusal, an invalid mesh, the geometry's errors (a mismatch is in
    /// the reports, not an error).
    pub fn run(
        self,
        levels: u32,
        (threads, allow_large): (usize, bool),
        notes: Notes<'_>,
    ) -> Result<Verified> {
        let (loaded, counts, chosen) = (self.loaded, &self.counts, &self.chosen);
        let poly = &loaded.poly;
        let (scheme, rule) = (&chosen.scheme, chosen.rule);
        let face_list = on_face_list(scheme, rule, counts, self.custom);
        let need = if loaded.has_crease_rules(rule) && !face_list {
            halfedge::memory::predicted_peak_bytes_with_creases(rule, counts, levels, None)
        } else {
            halfedge::memory::predicted_peak_bytes(&self.sizing, counts, levels, None)
                .map_err(Into::into)
        };
        let uv_check = UvCheck::new(loaded, scheme, chosen.holes.as_ref(), notes)?;
        // The UV component refines the layout with the surface (a refinement with UVs per
        // level, the largest the last).
        let holes = chosen.holes.is_some();
        let need = match &uv_check {
            Some(_) => need.and_then(|need| Ok(need + uv_bytes(poly, rule, levels, 8, holes)?)),
            None => need,
        };
        let need = need.map(|need| need + halfedge::memory::read_extra_bytes(poly));
        guard_memory(need, self.sizing.name(), levels, allow_large)?;
        let mut opts = SubdivideOptions::default().with_threads(threads);
        if let Some(holes) = &chosen.holes {
            opts = opts.with_holes(holes);
        }
        let located = |e| Error::located(e, loaded);
        // The UV values measured at levels 1.., when there is a UV component.
        let mut uv_measured = None;
        let mut reports = if face_list {
            // The face-list subdividers place points linearly: no crease rules to follow.
            let reports = sub::verify_polygons(poly, scheme, levels, &opts).map_err(located)?;
            if let Some(check) = &uv_check {
                // The face-list subdividers refine the layout linearly with the faces: the
                // values their written UVs use.
                uv_measured = Some(check.measure_polygons(poly, rule, levels, &opts, loaded)?);
            }
            reports
        } else {
            let mesh = loaded.validate()?;
            let (sharpness, options) = loaded.crease_inputs(rule, &mesh, notes)?;
            let mut opts = opts.with_subdivision(options);
            if let Some(sharpness) = &sharpness {
                opts = opts.with_sharpness(sharpness);
            }
            let reports = sub::verify(&mesh, scheme, levels, &opts).map_err(located)?;
            if let Some(check) = &uv_check {
                uv_measured = Some(check.measure(&mesh, rule, levels, &opts)?);
            }
            reports
        };
        if let (Some(check), Some(measured)) = (&uv_check, &uv_measured) {
            check.extend(&mut reports, measured)?;
        }
        Ok(Verified {
            reports,
            scheme: scheme.name().to_owned(),
            levels,
        })
    }
}

/// The `UV` component of `verify`: the UV values a scheme predicts for the mesh's layout
/// ([`UvCounter`]), against those of the real face-varying subdivision.
struct UvCheck {
    /// The layout refined.
    layout: UvLayout,
    /// The prediction.
    counter: UvCounter,
    /// Level 0 as [`schemes::uv`] defines it: the `vt` entries the written corners use.
    used_vt: u64,
}

impl UvCheck {
    /// `None` for a mesh without a UV layout (no `vt`, or `vt` at only some corners: what is
    /// verified is then what it always was), and for a scheme that does not count UV values
    /// (one note, as `table` gives).
    fn new(
        loaded: &LoadedMesh,
        scheme: &Scheme,
        holes: Option<&HoleSet>,
        notes: Notes<'_>,
    ) -> Result<Option<UvCheck>> {
        let poly = &loaded.poly;
        let (Some(layout), Some(uvs)) = (poly.uv_layout(), poly.uvs()) else {
            return Ok(None);
        };
        let counts = match holes {
            Some(holes) => holes.written_uv_counts(poly),
            None => halfedge::stats::uv_counts(poly),
        };
        let Some(counts) = counts else {
            return Ok(None);
        };
        let counter = match UvCounter::new(&Plan::single(scheme.clone()), counts) {
            Ok(counter) => counter,
            Err(not) => {
                notes(format!("note: {not}: no UV rows"));
                return Ok(None);
            }
        };
        // Level 0, measured: the distinct `vt` of the written faces' corners.
        let offsets = poly.face_offsets();
        let mut used = vec![false; uvs.coords().len()];
        for f in (0..poly.n_faces()).filter(|&f| holes.map_or(true, |h| !h.contains(f as u32))) {
            for &t in &uvs.corners()[offsets[f]..offsets[f + 1]] {
                used[t as usize] = true;
            }
        }
        let used_vt = used.iter().filter(|&&u| u).count() as u64;
        Ok(Some(UvCheck {
            layout,
            counter,
            used_vt,
        }))
    }

    /// Refines the layout on `mesh` by `rule` to each level `1..=levels` (a
    /// [`halfedge::Refinement`] with UVs per level, under `opts`: holes, creases, options) and
    /// counts the distinct UV values its faces' corners use
    /// ([`halfedge::Refinement::write_uv_indices`]): the measured values of levels `1..`.
    fn measure(
        &self,
        mesh: &HalfEdgeMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
    ) -> Result<Vec<u64>> {
        let opts = opts.with_uvs(&self.layout);
        let mut measured = Vec::with_capacity(levels as usize);
        for level in 1..=levels {
            let r = halfedge::Refinement::new(mesh, rule, level, &opts)?;
            let mut corners = vec![0u32; r.n_corners(level)];
            r.write_uv_indices(&mut corners)?;
            let n = corners.iter().max().map_or(0, |&m| m as usize + 1);
            let mut used = vec![false; n];
            for &k in &corners {
                used[k as usize] = true;
            }
            measured.push(used.iter().filter(|&&u| u).count() as u64);
        }
        Ok(measured)
    }

    /// As [`UvCheck::measure`] on a raw face list: the distinct UV values the corners of
    /// each level `1..=levels` of [`sub::subdivide_polygons`] (with the layout) use.
    fn measure_polygons(
        &self,
        poly: &PolygonMesh,
        rule: Rule,
        levels: u32,
        opts: &SubdivideOptions<'_>,
        loaded: &LoadedMesh,
    ) -> Result<Vec<u64>> {
        let opts = opts.with_uvs(&self.layout);
        let mut measured = Vec::with_capacity(levels as usize);
        for level in 1..=levels {
            let out = sub::subdivide_polygons(poly, rule, level, &opts)
                .map_err(|e| Error::located(e, loaded))?;
            let uvs = out.uvs().ok_or(halfedge::Error::NoUvs)?;
            measured.push((uvs.coords().len() - uvs.unreferenced()) as u64);
        }
        Ok(measured)
    }

    /// Appends `("UV", predicted)` and `("UV", measured)` to every report, `measured` being
    /// the values of levels `1..` ([`UvCheck::measure`]).
    fn extend(&self, reports: &mut [LevelReport], measured: &[u64]) -> Result<()> {
        for r in reports.iter_mut() {
            let m = match r.level {
                0 => self.used_vt,
                s => match measured.get(s as usize - 1) {
                    Some(&m) => m,
                    None => continue,
                },
            };
            let p = self.counter.values_at(u64::from(r.level))?;
            r.predicted.push(("UV".to_owned(), p));
            r.measured.push(("UV".to_owned(), BigInt::from(m)));
        }
        Ok(())
    }
}
