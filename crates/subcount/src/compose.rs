//! `verify` and `subdivide` of a composition (`--scheme loop:1,sqrt3`): the driver runs each
//! stage in turn ([`driver::compose`]); this module parses the flags and prints.

use std::io::Write;
use std::time::Instant;

use num_bigint::BigInt;
use schemes::Plan;

use crate::args::{Precision, SchemeChoice, SubdivideArgs, VerifyArgs};
use crate::failure::{scheme_failure, write_failure, Failure};
use crate::mesh::{
    print_note, real_levels, required_mesh, subdivide_job, timings_line, verify_levels,
    write_reports,
};

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

/// `verify --scheme A:k,B`: every level of the composition, really subdivided stage by stage,
/// against its prediction.
pub(crate) fn verify(args: VerifyArgs, plan: Plan, out: &mut impl Write) -> Result<u8, Failure> {
    let loaded = required_mesh(&args.mesh)?;
    let composition = driver::compose::start(&loaded, &plan, &mut print_note)?;
    let x0 = composition.initial_state()?;
    let levels = verify_levels(&args, composition.plan(), &x0)?;
    let verified = composition.verify(levels, args.threads, args.allow_large)?;
    write_reports(&verified, &args.mesh, args.format, out)
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
    crate::mesh::refuse_unwritten_format(args.output.as_deref())?;
    let first = &plan.stages()[0];
    if first.levels().is_some_and(|k| u64::from(levels) <= k) {
        args.scheme.scheme = Some(first.scheme().name().to_owned());
        return crate::mesh::subdivide(args, out);
    }
    if args.limit || args.normals == Some(crate::args::Normals::Limit) {
        let scheme = plan.name();
        return Err(driver::Error::LimitNotSupported { scheme }.into());
    }
    if args.frames > 0 || args.precision == Precision::F32 {
        let plan = plan.name();
        return Err(driver::Error::RefineOnceComposition { plan }.into());
    }
    let start = Instant::now();
    let loaded = required_mesh(&args.mesh)?;
    let composition = driver::compose::start(&loaded, &plan, &mut print_note)?;
    let job = subdivide_job(&args, levels);
    let load_s = start.elapsed().as_secs_f64();
    let composed = composition.subdivide(&job, args.output.as_deref(), &mut print_note)?;
    let last = &composed.mesh;
    let t2 = Instant::now();
    if let Some(path) = &args.output {
        let options = crate::mesh::write_options(&args, last.uvs().is_some());
        driver::output::write_polygon_mesh_file(last, path, &options)?;
    }
    let write_s = t2.elapsed().as_secs_f64();
    let c = halfedge::stats::face_list_counts(last);
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
        let peak: &BigInt = &composed.predicted_peak_bytes;
        timings_line(load_s, composed.time.as_secs_f64(), write_s, peak, "");
    }
    Ok(0)
}
