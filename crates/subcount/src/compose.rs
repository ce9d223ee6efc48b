//! `verify` and `subdivide` of a composition (`--scheme loop:1,sqrt3`): each stage in turn on
//! what the stage before wrote ([`halfedge::subdivide::subdivide_stages`]), every level
//! checked against the composition's prediction, a memory guard before each stage.

use std::io::Write;
use std::time::Instant;

use halfedge::io::ObjWriteOptions;
use halfedge::subdivide::{self as sub, StageStart, SubdivideOptions};
use num_bigint::BigInt;
use schemes::Plan;

use crate::args::{Precision, SchemeChoice, SubdivideArgs, VerifyArgs};
use crate::failure::{scheme_failure, usage, write_failure, Failure, Kind};
use crate::mesh::{
    guard_failure, real_levels, required_mesh, uv_bytes, verify_levels, write_reports,
};
use crate::model::{mesh_label, not_applicable, refuse_degenerate_faces, LoadedMesh};

/// The composition `--scheme` names (two or more stages), if it names one.
///
/// # Errors
///
/// The plan's parse errors (an unknown stage, a bad level count): usage errors.
pub(crate) fn composition(choice: &SchemeChoice) -> Result<Option<Plan>, Failure> {
    match (&choice.scheme, &choice.scheme_file) {
        (Some(name), None) if name.contains(',') => {
            let plan = Plan::parse(name).map_err(scheme_failure)?;
            Ok((!plan.is_single()).then_some(plan))
        }
        _ => Ok(None),
    }
}

/// The mesh, checked for a composition: its plan applies, and it has no creases or corners
/// (which no stage after the first could follow) nor holes (refused by the library).
fn load(mesh: &crate::args::MeshSource, plan: &Plan) -> Result<(LoadedMesh, Plan), Failure> {
    let loaded = required_mesh(mesh)?;
    refuse_degenerate_faces(&loaded.poly, mesh)?;
    let counts = halfedge::stats::face_list_counts(&loaded.poly);
    let plan = plan.for_mesh(&counts);
    plan.initial_state(&counts)
        .map_err(|e| not_applicable(mesh, e))?;
    let tags = loaded.tags();
    let what = if !tags.sharp_edges().is_empty() || !tags.sharp_vertices().is_empty() {
        Some("creases and corners")
    } else if !tags.holes().is_empty() {
        Some("holes")
    } else {
        None
    };
    if let Some(what) = what {
        return Err(usage!(
            "{}: {}",
            mesh_label(mesh),
            halfedge::Error::NotComposable {
                scheme: plan.name(),
                what: what.into()
            }
        ));
    }
    loaded
        .holes(&counts, mesh, &plan.name(), &stage_rules(&plan))?
        .map_or(Ok(()), |_| {
            Err(usage!(
                "{}: {}",
                mesh_label(mesh),
                halfedge::Error::NotComposable {
                    scheme: plan.name(),
                    what: "the holes of boundary none".into()
                }
            ))
        })?;
    loaded.print_notes();
    Ok((loaded, plan))
}

/// Each stage's name and rule, as [`LoadedMesh::holes`] takes them.
fn stage_rules(plan: &Plan) -> Vec<(&str, Option<halfedge::Rule>)> {
    plan.stages()
        .iter()
        .map(|s| (s.scheme().name(), s.scheme().subdivision_rule()))
        .collect()
}

/// What the stages before a stage leave resident in the worker threads' heap arenas.
const STAGE_ARENA_BYTES: u64 = 4 << 20;

/// The memory guard of one stage, as `subdivide`'s of one scheme: the peak of subdividing
/// its mesh to a face list (the input, its half-edge build, the levels), the UV channel's
/// share when UVs are carried, the mesh as read (its file lines and `vt`), and from the
/// second stage on the mesh as read held beside the stage's own; the largest need of the
/// stages so far in `peak`.
fn guard_stage(
    stage: &StageStart<'_>,
    base: &halfedge::PolygonMesh,
    uvs: bool,
    allow_large: bool,
    peak: &mut BigInt,
) -> halfedge::Result<()> {
    let sizing = stage.rule.scheme_for(stage.counts)?;
    let last_faces = (!stage.face_list)
        .then(|| sub::direct_face_degree(stage.rule))
        .flatten();
    let mut need =
        halfedge::memory::predicted_peak_bytes(&sizing, stage.counts, stage.levels, last_faces)?;
    if !stage.face_list && last_faces.is_none() {
        need += halfedge::memory::face_list_copy_bytes(&sizing, stage.counts, stage.levels)?;
    }
    if uvs {
        need += uv_bytes(stage.mesh, stage.rule, stage.levels, 8, false)?;
    }
    need += halfedge::memory::read_extra_bytes(base);
    // The stage's input as a half-edge mesh, alive beside its levels.
    if !stage.face_list {
        let c = stage.counts;
        need += BigInt::from(halfedge::HalfEdgeMesh::bytes_for(
            c.vertices, c.edges, c.faces,
        ));
    }
    if stage.index > 0 {
        // The mesh as read, held beside the stage's own; and what the stages before leave
        // resident in the worker threads' heap arenas (1.9 to 3.1 MB measured on the icosahedron
        // and the charted cube at levels 7-8: a stage after the first peaked that much above
        // the same scheme run alone).
        need += BigInt::from(base.heap_bytes()) + BigInt::from(STAGE_ARENA_BYTES);
    }
    let limit = if allow_large {
        u128::MAX
    } else {
        halfedge::memory::peak_limit()
    };
    let need = halfedge::memory::within_limit(need, sizing.name(), stage.levels, limit)?;
    *peak = need.max(peak.clone());
    Ok(())
}

/// `verify --scheme A:k,B`: every level of the composition, really subdivided stage by stage,
/// against its prediction.
pub(crate) fn verify(args: VerifyArgs, plan: Plan, out: &mut impl Write) -> Result<u8, Failure> {
    let (loaded, plan) = load(&args.mesh, &plan)?;
    let counts = halfedge::stats::face_list_counts(&loaded.poly);
    let x0 = plan.initial_state(&counts).map_err(scheme_failure)?;
    let levels = verify_levels(&args, &plan, &x0)?;
    let opts = SubdivideOptions::default().with_threads(args.threads);
    let mut peak = BigInt::from(0);
    let mut guard =
        |s: &StageStart<'_>| guard_stage(s, &loaded.poly, false, args.allow_large, &mut peak);
    let run = sub::subdivide_stages(&loaded.poly, &plan, levels, &opts, true, &mut guard)
        .map_err(guard_failure)?;
    write_reports(
        &run.reports,
        &plan.name(),
        &args.mesh,
        levels,
        args.format,
        out,
    )
}

/// `subdivide --scheme A:k,B`: the stages in turn, UVs carried, the last level written. When
/// only the first stage runs (`--levels` within it) this is `subdivide` by that scheme, with
/// everything it supports (creases, holes, `--precision f32`, `--frames`).
pub(crate) fn subdivide(
    mut args: SubdivideArgs,
    plan: Plan,
    out: &mut impl Write,
) -> Result<u8, Failure> {
    let levels = real_levels(&args.levels)?;
    let first = &plan.stages()[0];
    if first.levels().is_some_and(|k| u64::from(levels) <= k) {
        args.scheme.scheme = Some(first.scheme().name().to_owned());
        return crate::mesh::subdivide(args, out);
    }
    if args.frames > 0 || args.precision == Precision::F32 {
        return Err(usage!(
            "--precision f32 and --frames refine one scheme once; {} is a composition: use --precision f64",
            plan.name()
        ));
    }
    let start = Instant::now();
    let (loaded, plan) = load(&args.mesh, &plan)?;
    if let Some(path) = &args.output {
        halfedge::io::check_output(path).map_err(|e| Failure::new(Kind::Input, e))?;
    }
    let label = mesh_label(&args.mesh);
    let layout = if args.no_uv {
        None
    } else {
        if let Some(partial) = loaded.poly.partial_uvs() {
            eprintln!("note: {label}: {partial}: writing without UVs");
        }
        loaded.poly.uv_layout()
    };
    let mut options = halfedge::tags::SubdivisionOptions::default();
    options.face_varying = args.uv_interpolation.unwrap_or(loaded.options.face_varying);
    let mut opts = SubdivideOptions::default()
        .with_threads(args.threads)
        .with_subdivision(options);
    if let Some(layout) = &layout {
        opts = opts.with_uvs(layout);
    }
    let load_s = start.elapsed().as_secs_f64();
    let t1 = Instant::now();
    let mut peak = BigInt::from(0);
    let uvs = layout.is_some();
    let mut guard =
        |s: &StageStart<'_>| guard_stage(s, &loaded.poly, uvs, args.allow_large, &mut peak);
    let run = sub::subdivide_stages(&loaded.poly, &plan, levels, &opts, false, &mut guard)
        .map_err(guard_failure)?;
    let subdivide_s = t1.elapsed().as_secs_f64();
    let last = run
        .mesh
        .ok_or_else(|| Failure::new(Kind::Mismatch, anyhow::anyhow!("no last level kept")))?;
    let t2 = Instant::now();
    if let Some(path) = &args.output {
        let options = ObjWriteOptions::default()
            .with_uvs(last.uvs().is_some())
            .with_normals(args.normals);
        halfedge::io::write_polygon_obj_file_with(&last, path, &options)
            .map_err(|e| Failure::new(Kind::Input, e))?;
    }
    let write_s = t2.elapsed().as_secs_f64();
    let c = halfedge::stats::face_list_counts(&last);
    let uv = last
        .uvs()
        .map_or_else(String::new, |u| format!(", UV = {}", u.coords().len()));
    let what = format!(
        "level {levels}: V = {}, E = {}, F = {}{uv}",
        c.vertices, c.edges, c.faces
    );
    match &args.output {
        Some(path) if path.as_os_str() == "-" => eprintln!("{what}; wrote standard output"),
        Some(path) => writeln!(out, "{what}; wrote {}", path.display()).map_err(write_failure)?,
        None => writeln!(out, "{what} (no -o: nothing written)").map_err(write_failure)?,
    }
    if args.timings {
        let resident = halfedge::memory::peak_resident_bytes()
            .map_or_else(|| "null".to_string(), |b| b.to_string());
        eprintln!(
            "timings: {{\"load_s\": {load_s:.6}, \"subdivide_s\": {subdivide_s:.6}, \"write_s\": {write_s:.6}, \"peak_bytes\": {resident}, \"predicted_peak_bytes\": {peak}}}"
        );
    }
    Ok(0)
}
