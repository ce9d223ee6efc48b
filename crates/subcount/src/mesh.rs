//! `stats`, `verify` and `subdivide`: real meshes and real subdivision.
//!
//! The meshes are the driver's ([`driver::load`]), and so are the runs
//! ([`driver::subdivide`], [`driver::verify`]): this module parses the flags into them and
//! prints what they return.

use std::io::Write;
use std::time::Instant;

use halfedge::io::ObjWriteOptions;
use halfedge::PolygonMesh;
use num_bigint::BigInt;
use num_traits::ToPrimitive;
use schemes::Plan;
use serde_json::{json, Value};

use crate::args::{
    MeshSource, Precision, ReportFormat, SchemeChoice, StatsArgs, SubdivideArgs, VerifyArgs,
};
use crate::failure::{usage, write_failure, Failure, Kind};
use crate::levels::parse_levels_count;
use crate::model::{load_mesh, print_notes, LoadedMesh};
use schemes::output::json_text;

pub(crate) fn required_mesh(mesh: &MeshSource) -> Result<LoadedMesh, Failure> {
    load_mesh(mesh)?.ok_or_else(|| usage!("give a mesh: --mesh FILE or --base NAME"))
}

pub(crate) fn stats(args: StatsArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let loaded = required_mesh(&args.mesh)?;
    print_notes(&loaded);
    let poly = &loaded.poly;
    // Present only when the file has tags: an untagged mesh's output is what it always was.
    let tags = poly.has_tags().then(|| tag_summary(loaded.tags(), poly));
    let report = halfedge::stats::face_list_report(poly);
    // The half-edge mesh is built only for the message of a mesh the scan shows invalid.
    let validation = if report.is_valid() {
        None
    } else {
        loaded.validate().err()
    };
    let halfedge::stats::FaceListReport {
        counts, problems, ..
    } = report;
    // A face that repeats a vertex is refused on every path, so no scheme applies.
    let applicable = if problems.faces_with_repeated_vertex > 0 {
        Vec::new()
    } else {
        loaded
            .applicable_schemes(&counts, validation.is_none())
            .iter()
            .map(|s| s.name().to_owned())
            .collect()
    };
    let genus = if validation.is_none() {
        halfedge::stats::genus(&counts)
    } else {
        None
    };
    // Present only when the file has texture coordinates (a layout, or `vt` at only some
    // corners: one line, `"uv": null`): a mesh without `vt` prints what it always printed.
    let uv = halfedge::stats::uv_counts(poly);
    let c = &counts;
    let text = match args.format {
        ReportFormat::Json => {
            let degrees: serde_json::Map<String, Value> = c
                .faces_by_degree
                .iter()
                .map(|(d, n)| (d.to_string(), Value::from(*n)))
                .collect();
            let mut object = json!({
                "V": c.vertices,
                "E": c.edges,
                "IE": c.interior_edges,
                "BE": c.boundary_edges,
                "NME": c.nonmanifold_edges,
                "F": c.faces,
                "H": c.corners,
                "faces_by_degree": degrees,
                "boundary_loops": c.boundary_loops,
                "components": c.components,
                "euler_characteristic": c.euler_characteristic,
                "genus": genus,
                "unreferenced_vertices": c.unreferenced_vertices,
                "manifold": validation.is_none(),
                "problems": {
                    "faces_with_repeated_vertex": problems.faces_with_repeated_vertex,
                    "duplicate_faces": problems.duplicate_faces,
                    "nonmanifold_edges": problems.nonmanifold_edges,
                    "nonmanifold_vertices": problems.nonmanifold_vertices,
                    "inconsistently_oriented_edges": problems.inconsistently_oriented_edges,
                },
            });
            if let (Some(tags), Value::Object(map)) = (&tags, &mut object) {
                map.insert("tags".to_owned(), tags.to_json());
            }
            if let Value::Object(map) = &mut object {
                match (&uv, poly.partial_uvs()) {
                    (Some(uv), _) => {
                        map.insert("uv".to_owned(), json!(uv));
                    }
                    (None, Some(_)) => {
                        map.insert("uv".to_owned(), Value::Null);
                    }
                    (None, None) => {}
                }
            }
            if let Value::Object(map) = &mut object {
                if poly.colors().is_some() {
                    map.insert("colors".to_owned(), json!(3));
                }
                map.insert("applicable_schemes".to_owned(), json!(applicable));
            }
            json_text(&object)
        }
        ReportFormat::Text => {
            let degrees: Vec<String> = c
                .faces_by_degree
                .iter()
                .map(|(d, n)| format!("{n} of degree {d}"))
                .collect();
            let mut t = format!(
                "V = {} (vertices used by faces; {} unreferenced)\nE = {} (IE = {} interior, BE = {} boundary, NME = {} non-manifold)\nF = {} ({})\nH = {} (sum of face degrees)\nboundary loops = {}\ncomponents = {}\nEuler characteristic = {}\n",
                c.vertices,
                c.unreferenced_vertices,
                c.edges,
                c.interior_edges,
                c.boundary_edges,
                c.nonmanifold_edges,
                c.faces,
                degrees.join(", "),
                c.corners,
                c.boundary_loops,
                c.components,
                c.euler_characteristic,
            );
            if let Some(g) = genus {
                t.push_str(&format!("genus = {g}\n"));
            }
            match &validation {
                None => t.push_str("manifold, consistently oriented\n"),
                Some(e) => t.push_str(&format!("not a valid half-edge mesh: {e}\n")),
            }
            if let Some(tags) = &tags {
                t.push_str(&format!("{}\n", tags.to_text()));
            }
            match (&uv, poly.partial_uvs()) {
                (Some(uv), _) => t.push_str(&format!("{}\n", uv_layout_text(uv))),
                (None, Some(partial)) => t.push_str(&format!("{partial}\n")),
                (None, None) => {}
            }
            match (poly.colors(), poly.partial_colors()) {
                (Some(_), _) => t.push_str("vertex colors: 3 channels\n"),
                (None, Some(partial)) => t.push_str(&format!("{partial}\n")),
                (None, None) => {}
            }
            t.push_str(&format!("applicable schemes: {}", applicable.join(", ")));
            t
        }
    };
    writeln!(out, "{text}").map_err(write_failure)?;
    Ok(0)
}

/// The UV layout line of `stats`: `UV layout: V = 267, E = 438, BE = 144, seam edges = 72,
/// boundary loops = 13, charts = 13, unreferenced = 0`.
fn uv_layout_text(uv: &schemes::uv::UvCounts) -> String {
    format!(
        "UV layout: V = {}, E = {}, BE = {}, seam edges = {}, boundary loops = {}, charts = {}, unreferenced = {}",
        uv.values,
        uv.edges,
        uv.boundary_edges,
        uv.seam_edges,
        uv.boundary_loops,
        uv.charts,
        uv.unreferenced
    )
}

/// What a file's tags hold, for `stats`: distinct sharp edges and vertices (sharpness > 0),
/// distinct hole faces, the options the tags set, and the tags not read.
struct TagSummary {
    crease_edges: usize,
    corners: usize,
    holes: usize,
    /// `(key, value)`: `boundary`, `face_varying`, `crease_method`, `triangle_rule`, each only
    /// when a tag sets it, valued by its command-line name.
    options: Vec<(&'static str, &'static str)>,
    /// Tag names not read, with their number of lines.
    ignored: Vec<(String, u64)>,
}

fn tag_summary(tags: &halfedge::tags::Tags, poly: &PolygonMesh) -> TagSummary {
    let o = &tags.options;
    let options = [
        ("boundary", o.boundary.map(|v| v.name())),
        ("face_varying", o.face_varying.map(|v| v.name())),
        ("crease_method", o.crease_method.map(|v| v.name())),
        ("triangle_rule", o.triangle_rule.map(|v| v.name())),
    ]
    .into_iter()
    .filter_map(|(k, v)| v.map(|v| (k, v)))
    .collect();
    TagSummary {
        crease_edges: tags.sharp_edges().len(),
        corners: tags.sharp_vertices().len(),
        holes: tags.hole_faces().len(),
        options,
        ignored: poly
            .ignored_tags()
            .iter()
            .map(|t| (t.name.clone(), t.count))
            .collect(),
    }
}

impl TagSummary {
    fn to_json(&self) -> Value {
        let options: serde_json::Map<String, Value> = self
            .options
            .iter()
            .map(|&(k, v)| (k.to_owned(), Value::from(v)))
            .collect();
        let mut object = json!({
            "crease_edges": self.crease_edges,
            "corners": self.corners,
            "holes": self.holes,
            "options": options,
        });
        if let (false, Value::Object(map)) = (self.ignored.is_empty(), &mut object) {
            let ignored: serde_json::Map<String, Value> = self
                .ignored
                .iter()
                .map(|(k, n)| (k.clone(), Value::from(*n)))
                .collect();
            map.insert("ignored".to_owned(), ignored.into());
        }
        object
    }

    fn to_text(&self) -> String {
        let mut t = format!(
            "tags: {} crease edges, {} corners, {} holes",
            self.crease_edges, self.corners, self.holes
        );
        let options: Vec<String> = self
            .options
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        let ignored: Vec<String> = self
            .ignored
            .iter()
            .map(|(k, n)| format!("{k} ({n})"))
            .collect();
        for (label, items) in [("options", options), ("ignored", ignored)] {
            if !items.is_empty() {
                t.push_str(&format!("; {label}: {}", items.join(", ")));
            }
        }
        t
    }
}

/// The last level of a real subdivision: at most 64, refused (exit 4) before any count is
/// computed, since every rule at least doubles the faces per level and level 65 could not be
/// indexed by 32-bit integers (and its exact counts would take long to compute).
pub(crate) fn real_levels(text: &str) -> Result<u32, Failure> {
    let levels = parse_levels_count(text)?;
    match driver::limits::levels_refusal(levels.into()) {
        Some(why) => Err(Failure::new(
            Kind::Guard,
            anyhow::anyhow!("--levels {levels}: {why}"),
        )),
        None => Ok(levels),
    }
}

/// The last level `verify` checks: `--levels`, or the highest level whose predicted face
/// count under `plan` from `x0` stays within `--max-faces` (at most 64).
pub(crate) fn verify_levels(args: &VerifyArgs, plan: &Plan, x0: &[BigInt]) -> Result<u32, Failure> {
    match &args.levels {
        Some(t) => real_levels(t),
        None => Ok(driver::verify::highest_level_within(
            plan,
            x0,
            args.max_faces,
        )?),
    }
}

/// The scheme of `--scheme` or `--scheme-file` ([`driver::SchemeChoice`]).
pub(crate) fn scheme_choice(choice: &SchemeChoice) -> Result<driver::SchemeChoice, Failure> {
    driver::SchemeChoice::from_options(choice.scheme.clone(), choice.scheme_file.clone())
        .ok_or_else(|| usage!("give --scheme NAME or --scheme-file FILE"))
}

pub(crate) use crate::failure::print_note;

pub(crate) fn verify(args: VerifyArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let loaded = required_mesh(&args.mesh)?;
    let choice = scheme_choice(&args.scheme)?;
    let verification = driver::verify::start(&loaded, &choice, &mut print_note)?;
    let plan = Plan::single(verification.sizing().clone());
    let levels = verify_levels(&args, &plan, verification.initial_state())?;
    let verified = verification.run(levels, (args.threads, args.allow_large), &mut print_note)?;
    write_reports(&verified, &args.mesh, args.format, out)
}

/// Writes `verify`'s reports (text or JSON) and returns its exit code: 0 when every level
/// matches, [`Kind::Mismatch`] otherwise.
pub(crate) fn write_reports(
    verified: &driver::verify::Verified,
    mesh: &MeshSource,
    format: ReportFormat,
    out: &mut impl Write,
) -> Result<u8, Failure> {
    let (reports, name, levels) = (&verified.reports, &verified.scheme, verified.levels);
    let all_match = reports.iter().all(|r| r.is_match());
    let text = match format {
        ReportFormat::Json => {
            // Counts of a mesh in memory fit in u64; a larger one would be written as a string.
            let object = |pairs: &[(String, BigInt)]| -> Value {
                pairs
                    .iter()
                    .map(|(k, v)| {
                        let v = v.to_u64().map_or_else(|| v.to_string().into(), Value::from);
                        (k.clone(), v)
                    })
                    .collect::<serde_json::Map<_, _>>()
                    .into()
            };
            let rows: Vec<String> = reports
                .iter()
                .map(|r| {
                    json_text(&json!({
                        "level": r.level,
                        "match": r.is_match(),
                        "predicted": object(&r.predicted),
                        "measured": object(&r.measured),
                    }))
                })
                .collect();
            format!("[\n{}\n]", rows.join(",\n"))
        }
        ReportFormat::Text => {
            let mut t = format!(
                "{} on {} levels 0..={levels}\n",
                name,
                match (&mesh.memory, &mesh.mesh) {
                    (Some(memory), _) => memory.1.clone(),
                    (None, Some(path)) => path.display().to_string(),
                    (None, None) => mesh.base.clone().unwrap_or_default(),
                }
            );
            t.push_str("level  component  predicted  measured\n");
            for r in reports {
                for ((name, p), (_, m)) in r.predicted.iter().zip(&r.measured) {
                    let flag = if p == m { "" } else { "  MISMATCH" };
                    t.push_str(&format!(
                        "{:>5}  {name:>9}  {p:>9}  {m:>8}{flag}\n",
                        r.level
                    ));
                }
            }
            t.push_str(if all_match {
                "all counts match the prediction"
            } else {
                "MISMATCH: the prediction is wrong"
            });
            t
        }
    };
    writeln!(out, "{text}").map_err(write_failure)?;
    if all_match {
        Ok(0)
    } else {
        Err(Failure::new(
            Kind::Mismatch,
            anyhow::anyhow!("{}: real subdivision disagrees with the prediction", name),
        ))
    }
}

/// OBJ text in a file named for another mesh format would mislead whatever opens it (`.ply`
/// is written as PLY): refused before any work, for one scheme and compositions alike.
pub(crate) fn refuse_unwritten_format(output: Option<&std::path::Path>) -> Result<(), Failure> {
    if let Some(path) = output {
        if let Some(format) = driver::output::unwritten_mesh_format(path) {
            return Err(usage!(
                "-o {}: subdivide does not write {} files; it writes OBJ and PLY (name the output .obj or .ply, or anything that is not another mesh format's extension)",
                path.display(),
                format.to_ascii_uppercase()
            ));
        }
    }
    Ok(())
}

/// How `subdivide` writes its output: UVs when `uvs`, normals with `--normals`, formatted on
/// `--threads`.
pub(crate) fn write_options(args: &SubdivideArgs, uvs: bool) -> ObjWriteOptions {
    ObjWriteOptions::default()
        .with_uvs(uvs)
        .with_normals(args.normals.is_some())
        .with_threads(args.threads)
}

pub(crate) fn subdivide(args: SubdivideArgs, out: &mut impl Write) -> Result<u8, Failure> {
    let levels = real_levels(&args.levels)?;
    refuse_unwritten_format(args.output.as_deref())?;
    let start = Instant::now();
    let loaded = required_mesh(&args.mesh)?;
    let choice = scheme_choice(&args.scheme)?;
    let job = subdivide_job(&args, levels);
    let prepared = driver::subdivide::prepare(
        &loaded,
        &choice,
        &job,
        args.output.as_deref(),
        &mut print_note,
    )?;
    let load_s = start.elapsed().as_secs_f64();
    let predicted = prepared.predicted_peak_bytes().clone();
    let bar = (prepared.final_faces() >= 1_000_000).then(|| {
        let bar = indicatif::ProgressBar::new(u64::from(levels));
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{msg} [{bar:30}] level {pos}/{len} ({elapsed})",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        bar.set_message(format!("subdividing with {}", prepared.scheme_name()));
        bar
    });
    let progress = |level: u32| {
        if let Some(bar) = &bar {
            bar.set_position(u64::from(level));
        }
    };
    let result = prepared.run(&progress, &mut print_note)?;
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let t2 = Instant::now();
    if let Some(path) = &args.output {
        // UVs only when refined (a level-0 copy of the face list keeps the file's).
        result.write(path, &write_options(&args, result.uvs().is_some()))?;
    }
    let write_s = t2.elapsed().as_secs_f64();
    let [v, e, f] = result.counts();
    let uv = result
        .uvs()
        .map_or_else(String::new, |(n, _)| format!(", UV = {n}"));
    let message = match &args.output {
        Some(path) => format!(
            "level {levels}: V = {v}, E = {e}, F = {f}{uv}; wrote {}",
            path.display()
        ),
        None => format!("level {levels}: V = {v}, E = {e}, F = {f}{uv} (no -o: nothing written)"),
    };
    // With `-o -` the mesh is standard output: the summary goes to stderr.
    if args.output.as_deref() == Some(std::path::Path::new("-")) {
        eprintln!("{}", message.replace("wrote -", "wrote standard output"));
    } else {
        writeln!(out, "{message}").map_err(write_failure)?;
    }
    if args.timings {
        let frames = match result.refine_times() {
            Some((topology, median)) if args.frames > 0 => format!(
                ", \"refine_topology_s\": {:.6}, \"evaluate_s\": {:.6}",
                topology.as_secs_f64(),
                median.unwrap_or_default().as_secs_f64()
            ),
            _ => String::new(),
        };
        let uv_s = result.uvs().map_or_else(String::new, |(_, s)| {
            format!(", \"uv_s\": {:.6}", s.as_secs_f64())
        });
        let subdivide_s = result.time().as_secs_f64();
        timings_line(load_s, subdivide_s, write_s, &predicted, &(frames + &uv_s));
    }
    Ok(0)
}

/// The `timings: {...}` line of `subdivide --timings` on stderr; `extra` is appended inside
/// the object (`, "uv_s": ...`).
pub(crate) fn timings_line(
    load_s: f64,
    subdivide_s: f64,
    write_s: f64,
    predicted: &BigInt,
    extra: &str,
) {
    let peak =
        driver::system::peak_resident_bytes().map_or_else(|| "null".to_string(), |b| b.to_string());
    eprintln!(
        "timings: {{\"load_s\": {load_s:.6}, \"subdivide_s\": {subdivide_s:.6}, \"write_s\": {write_s:.6}, \"peak_bytes\": {peak}, \"predicted_peak_bytes\": {predicted}{extra}}}"
    );
}

/// The driver's job of `subdivide`'s flags.
pub(crate) fn subdivide_job(args: &SubdivideArgs, levels: u32) -> driver::subdivide::SubdivideJob {
    let mut job = driver::subdivide::SubdivideJob::new(levels);
    job.threads = args.threads;
    job.allow_large = args.allow_large;
    job.precision = match args.precision {
        Precision::F32 => driver::refined::Precision::F32,
        Precision::F64 => driver::refined::Precision::F64,
    };
    job.frames = args.frames;
    job.uvs = !args.no_uv;
    job.uv_interpolation = args.uv_interpolation;
    job.limit = args.limit;
    job.limit_normals = args.normals == Some(crate::args::Normals::Limit);
    job
}
