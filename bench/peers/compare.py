#!/usr/bin/env python3
"""Times subcount's subdivision and exact counts against peers (not part of CI).

Usage:
    python3 bench/peers/compare.py [--subcount PATH] [--openmesh PATH] [--osd PATH]
                                   [--opensubdiv-rs PATH] [--frames N] [--no-accuracy]
                                   [--no-python] [--meshes DIR] [--venv DIR] [--reps N]
                                   [--json FILE]

What it does:
  1. creates a virtualenv (default /tmp/subcount-peers-venv) and pip-installs libigl,
     pymeshlab, trimesh, python-flint and numpy into it (skipped when they import already);
  2. writes the 81,920-face icosphere with
     `subcount subdivide --base icosahedron --scheme icosphere --levels 6 -o FILE`;
  3. for every job (scheme, levels, input) runs each tool in its own process, REPS times
     (once when a run takes more than 10 s): subcount through `subcount subdivide --timings`
     (the median of "subdivide_s", peak_bytes and predicted_peak_bytes; "subcount" with the
     default threads, i.e. every core, "subcount-1t" with --threads 1), OpenMesh through the
     driver built by bench/peers/openmesh/build.sh (skipped when it is missing), OpenSubdiv
     and opensubdiv-rs through their drivers (below), and the Python peers in-process in the
     virtualenv (wall time of the call only, loading excluded; peak RSS of the worker process,
     Python and numpy included);
  4. times python-flint's fmpz_mat power of the Catmull-Clark quad matrix at s = 10^6 and
     str() of the resulting count (~602,062 digits), next to the whole `subcount at` process
     and, in-process, `decimal::to_decimal` and num-bigint's `to_string` on the same number
     (criterion's samples from `cargo bench -p decimal --bench to_decimal`, group `decimal`;
     skipped with --no-cargo-bench);
  5. prints one table: median seconds, output faces per second, peak memory, and the ratio of
     each peer's median to subcount's median on the same job, all measured in the same run.

OpenSubdiv 3.5 (Debian's libosd-dev) runs through tools/osd-driver/osd_driver.cpp (built by
tools/osd-driver/build.sh when --osd is missing), the reference of the differential tests, in
its `--time` mode: Far::TopologyRefinerFactory::Create, RefineUniform with
fullTopologyInLastLevel = false, and Far::PrimvarRefinerReal<double>::Interpolate level by
level into a fresh buffer, each timed, VTX_BOUNDARY_EDGE_ONLY, single-threaded. Its main row is
RefineUniform + Interpolate (Create, the base level's topology, is in --json only); the rows
below it are RefineUniform alone, Interpolate in the one-shot run, and Interpolate per frame
(the median of --frames evaluations on a refiner built once, the base positions perturbed
before each, the buffer reused: the per-frame cost of animation). Peak memory is ru_maxrss.

opensubdiv-rs 0.5.0 (the Rust port on crates.io) runs through bench/peers/opensubdiv-rs, its own
cargo project (built with `cargo build --release` into TARGET/peers when --opensubdiv-rs is
missing), with the same rows; its refiner always builds full topology (it has no
fullTopologyInLastLevel) and its primvar weights are f32 (positions [f64; 3]). Unless
--no-accuracy, each of its jobs also writes OpenSubdiv's last level and reports the largest
distance between the two positions of a vertex (matched by position, faces checked as vertex
cycles), as a fraction of the bounding-box diagonal.

When `subcount subdivide --help` lists --frames, subcount also runs with --frames N --threads 1
and its "refine_topology_s" and "evaluate_s" are reported next to OpenSubdiv's RefineUniform and
per-frame Interpolate (ratios to them: above 1, subcount is faster). When it lists --limit too,
the Loop and Catmull-Clark jobs add the per-frame limit surface: OpenSubdiv's Interpolate +
PrimvarRefiner::Limit (positions and both tangents; `osd_driver --time ... limit`, the last level
refined with full topology) against `subcount subdivide --limit --normals limit --frames N`'s
evaluate_s, single thread.

The load average at the start and the end is printed with the table: on a shared machine wall
times are only comparable within one run.
"""

import argparse
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

PACKAGES = ["numpy", "libigl", "pymeshlab", "trimesh", "python-flint"]
REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# (label, subcount scheme, levels, input, peers). Input "icosphere" is the generated OBJ,
# other names are files of --meshes. trimesh's subdivide is the plain 4:1 midpoint split, so
# it is compared with subcount's `midpoint` on the same input.
JOBS = [
    ("loop L3 icosphere", "loop", 3, "icosphere", ["subcount-1t", "subcount-thp", "openmesh", "opensubdiv", "opensubdiv-rs", "igl", "pymeshlab"]),
    ("midpoint L3 icosphere", "midpoint", 3, "icosphere", ["subcount-1t", "trimesh"]),
    ("catmull-clark L3 icosphere", "catmull-clark", 3, "icosphere", ["subcount-1t", "subcount-thp", "openmesh", "opensubdiv", "opensubdiv-rs", "pymeshlab"]),
    ("sqrt3 L2 icosphere", "sqrt3", 2, "icosphere", ["subcount-1t", "openmesh"]),
    ("loop L2 armadillo", "loop", 2, "armadillo", ["subcount-1t", "openmesh", "opensubdiv", "opensubdiv-rs", "igl", "pymeshlab"]),
    ("catmull-clark L2 armadillo", "catmull-clark", 2, "armadillo", ["subcount-1t", "openmesh", "opensubdiv", "opensubdiv-rs", "pymeshlab"]),
    ("sqrt3 L2 armadillo", "sqrt3", 2, "armadillo", ["subcount-1t", "openmesh"]),
]

# The Catmull-Clark quad recurrence, state (V, E, F) on a closed quad mesh: each level
# V' = V + E + F, E' = 2E + 4F, F' = 4F.
CC_QUAD_MATRIX = [[1, 1, 1], [0, 2, 4], [0, 0, 4]]
# The cube: V = 8, E = 12, F = 6.
CC_QUAD_X0 = [8, 12, 6]
CC_LEVEL = 10**6


def load_average():
    return "%.2f %.2f %.2f" % os.getloadavg()


# --------------------------------------------------------------------------------------------
# Worker side: runs inside the virtualenv, one job per process.


def worker(tool, scheme, levels, path, reps):
    import numpy as np  # noqa: F401  (imported before timing, as every tool needs it)

    times = []
    faces = None
    if tool == "igl":
        import igl

        v, f = igl.read_triangle_mesh(path)
        for _ in range(reps):
            t0 = time.perf_counter()
            nv, nf = igl.loop(v, f, levels)
            times.append(time.perf_counter() - t0)
            faces = int(nf.shape[0])
            del nv, nf
            if times[-1] > 10:
                break
    elif tool == "trimesh":
        import trimesh
        from trimesh import remesh

        m = trimesh.load(path, process=False)
        v0, f0 = np.asarray(m.vertices), np.asarray(m.faces)
        for _ in range(reps):
            t0 = time.perf_counter()
            v, f = v0, f0
            for _ in range(levels):
                v, f = remesh.subdivide(v, f)
            times.append(time.perf_counter() - t0)
            faces = int(f.shape[0])
            del v, f
            if times[-1] > 10:
                break
    elif tool == "pymeshlab":
        import pymeshlab

        for _ in range(reps):
            ms = pymeshlab.MeshSet()
            ms.load_new_mesh(path)
            t0 = time.perf_counter()
            if scheme == "loop":
                # threshold 0: split every edge (the default only splits long edges).
                ms.meshing_surface_subdivision_loop(
                    iterations=levels, threshold=pymeshlab.PercentageValue(0.0)
                )
            else:
                for _ in range(levels):
                    ms.meshing_surface_subdivision_catmull_clark()
            times.append(time.perf_counter() - t0)
            faces = int(ms.current_mesh().face_number())
            del ms
            if times[-1] > 10:
                break
    else:
        raise SystemExit("unknown tool %s" % tool)
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024
    print(json.dumps({"times": times, "faces": faces, "peak_bytes": peak}))


def worker_flint(reps):
    import flint

    m = flint.fmpz_mat(CC_QUAD_MATRIX)
    x0 = flint.fmpz_mat([[x] for x in CC_QUAD_X0])
    power, render = [], []
    digits = None
    for _ in range(reps):
        t0 = time.perf_counter()
        x = (m**CC_LEVEL) * x0
        power.append(time.perf_counter() - t0)
        count = x[1, 0]  # E(s): 602,062 digits for the cube
        t0 = time.perf_counter()
        text = str(count)
        render.append(time.perf_counter() - t0)
        digits = len(text)
    print(json.dumps({"power": power, "render": render, "digits": digits}))


# --------------------------------------------------------------------------------------------
# Driver side.


def ensure_venv(venv):
    python = os.path.join(venv, "bin", "python")
    if not os.path.exists(python):
        subprocess.run([sys.executable, "-m", "venv", venv], check=True)
    probe = "import numpy, igl, pymeshlab, trimesh, flint"
    if subprocess.run([python, "-c", probe], capture_output=True).returncode != 0:
        subprocess.run([python, "-m", "pip", "install", "-q"] + PACKAGES, check=True)
    versions = subprocess.run(
        [python, "-m", "pip", "list", "--format=json"], capture_output=True, text=True, check=True
    )
    wanted = {p.lower() for p in PACKAGES}
    found = {
        p["name"].lower(): p["version"]
        for p in json.loads(versions.stdout)
        if p["name"].lower() in wanted
    }
    return python, found


def run_subcount(subcount, args, reps, env=None):
    """Median subdivide_s, peak_bytes and predicted_peak_bytes of `subcount subdivide`."""
    times, peak, predicted, faces = [], None, None, None
    for _ in range(reps):
        p = subprocess.run(
            [subcount, "subdivide", "--timings"] + args, capture_output=True, text=True,
            env=None if env is None else {**os.environ, **env},
        )
        if p.returncode != 0:
            raise SystemExit("subcount failed: %s" % p.stderr.strip())
        line = next(l for l in p.stderr.splitlines() if l.startswith("timings: "))
        t = json.loads(line[len("timings: "):])
        times.append(t["subdivide_s"])
        peak = max(peak or 0, t["peak_bytes"] or 0)
        predicted = t["predicted_peak_bytes"]
        # "level 3: V = .., E = .., F = N ..."
        faces = int(p.stdout.split("F = ")[1].split()[0].rstrip(";"))
        if t["subdivide_s"] > 10:
            break
    return {"times": times, "faces": faces, "peak_bytes": peak, "predicted": predicted}


# Peers run with an address-space cap and a time limit: pymeshlab's Catmull-Clark filter on
# the 81,920-triangle icosphere grew past 14 GB in two minutes on the first run of this script.
WORKER_MEMORY = 6 << 30
WORKER_TIMEOUT_S = 300


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (WORKER_MEMORY, WORKER_MEMORY))


def run_worker(python, tool, scheme, levels, path, reps):
    try:
        p = subprocess.run(
            [python, os.path.abspath(__file__), "--worker", tool, scheme, str(levels), path, str(reps)],
            capture_output=True,
            text=True,
            preexec_fn=limit_memory,
            timeout=WORKER_TIMEOUT_S,
        )
    except subprocess.TimeoutExpired:
        return {"error": "no result within %d s" % WORKER_TIMEOUT_S}
    if p.returncode != 0:
        return {"error": (p.stderr.strip().splitlines() or ["failed"])[-1]}
    return json.loads(p.stdout.strip().splitlines()[-1])


def run_openmesh(binary, scheme, levels, path, reps):
    p = subprocess.run([binary, scheme, str(levels), path, str(reps)], capture_output=True, text=True)
    if p.returncode != 0:
        return {"error": p.stderr.strip()}
    r = json.loads(p.stdout)
    return {"times": r["wall_s"], "faces": r["faces"], "peak_bytes": r["peak_rss_bytes"]}


# OpenSubdiv's name for each scheme compare.py gives both drivers.
OSD_SCHEMES = {"loop": "loop", "catmull-clark": "catmark"}


def run_osd_timing(command, scheme, levels, path, reps, frames, limit=False):
    """`osd_driver --time` or `opensubdiv-rs-peer time` (`command`): one process, REPS one-shot
    runs, then FRAMES evaluations on the last run's refiner (with `limit`, each followed by
    OpenSubdiv's Limit with both tangents: frame_limit_s)."""
    args = list(command)
    try:
        p = subprocess.run(args + [OSD_SCHEMES[scheme], str(levels), path, str(reps), str(frames)]
                           + (["limit"] if limit else []),
                           capture_output=True, text=True, timeout=WORKER_TIMEOUT_S)
    except subprocess.TimeoutExpired:
        return {"error": "no result within %d s" % WORKER_TIMEOUT_S}
    if p.returncode != 0:
        return {"error": (p.stderr.strip().splitlines() or ["failed"])[-1]}
    r = json.loads(p.stdout.strip().splitlines()[-1])
    # The main row: RefineUniform + Interpolate of each one-shot run.
    r["times"] = [a + b for a, b in zip(r["refine_s"], r["interpolate_s"])]
    r["peak_bytes"] = r["peak_rss_bytes"]
    return r


def run_osdrs_accuracy(osd, osdrs, scheme, levels, path, tmp):
    """The largest distance between opensubdiv-rs's and OpenSubdiv's positions of a vertex, as
    a fraction of the base mesh's bounding-box diagonal (opensubdiv-rs-peer compare)."""
    reference = os.path.join(tmp, "opensubdiv-reference.obj")
    try:
        with open(reference, "w") as out:
            p = subprocess.run([osd, OSD_SCHEMES[scheme], str(levels), path], stdout=out,
                               stderr=subprocess.PIPE, text=True)
        if p.returncode != 0:
            return {"error": p.stderr.strip()}
        p = subprocess.run([osdrs, "compare", OSD_SCHEMES[scheme], str(levels), path, reference],
                           capture_output=True, text=True)
        if p.returncode != 0:
            return {"error": p.stderr.strip()}
        return json.loads(p.stdout.strip().splitlines()[-1])
    finally:
        if os.path.exists(reference):
            os.remove(reference)


def subcount_has_flag(subcount, flag):
    """Whether this subcount's `subdivide` takes `flag` (--frames: refine_topology_s,
    evaluate_s; --limit: the limit surface)."""
    p = subprocess.run([subcount, "subdivide", "--help"], capture_output=True, text=True)
    return p.returncode == 0 and flag in p.stdout


def limit_rows(label, osd_limit, sub_limit, frames):
    """Per-frame limit surface: OpenSubdiv's Interpolate + Limit (positions and both tangents)
    on a refiner built once, against `subcount subdivide --limit --normals limit --frames N`'s
    evaluate_s (the levels and the limit table, positions and tangents), single thread."""
    out = []
    if "error" in osd_limit or "error" in sub_limit:
        err = osd_limit.get("error") or sub_limit.get("error")
        return [(label, "limit per frame", "error: " + err[:60], "", "", "", "")]
    both = [a + b for a, b in zip(osd_limit["frame_interpolate_s"], osd_limit["frame_limit_s"])]
    ours = statistics.median(sub_limit["evaluate_s"])
    for what, ts in (("opensubdiv Interpolate + Limit per frame", both),
                     ("opensubdiv Limit alone per frame", osd_limit["frame_limit_s"]),
                     ("subcount-1t --limit --normals limit evaluate_s", sub_limit["evaluate_s"])):
        med = statistics.median(ts)
        ratio = "%.2fx" % (med / ours) if ours > 0 else ""
        out.append((label, what + " (%d frames)" % frames, "%.4f" % med,
                    "%.4f-%.4f" % (min(ts), max(ts)), "%d vertices" % osd_limit["vertices"], "", ratio))
    return out


def run_subcount_frames(subcount, args, reps, frames):
    """Medians over REPS processes of `subcount subdivide --timings --frames N`: its
    refine_topology_s and evaluate_s (the median of its N evaluations)."""
    refine, evaluate = [], []
    for _ in range(reps):
        p = subprocess.run([subcount, "subdivide", "--timings", "--frames", str(frames)] + args,
                           capture_output=True, text=True)
        if p.returncode != 0:
            return {"error": p.stderr.strip()}
        line = next(l for l in p.stderr.splitlines() if l.startswith("timings: "))
        t = json.loads(line[len("timings: "):])
        refine.append(t["refine_topology_s"])
        evaluate.append(t["evaluate_s"])
    return {"refine_topology_s": refine, "evaluate_s": evaluate}


def ensure_built(path, build, what):
    """`path` when it exists, else the path `build()` prints (None when that fails)."""
    if os.path.exists(path):
        return path
    print("building %s ..." % what, file=sys.stderr)
    try:
        built = build()
    except (OSError, subprocess.CalledProcessError) as e:
        print("skipping %s: cannot build it (%s)" % (what, e), file=sys.stderr)
        return None
    return built if built and os.path.exists(built) else None


def criterion_rendering():
    """Seconds per call of decimal::to_decimal and num-bigint's to_string on the 602,062-digit
    count, one figure per criterion sample (group `decimal` of the decimal crate's to_decimal
    bench, which renders the same E = 12 4^(10^6) as flint's str() here)."""
    print("running cargo bench (decimal rendering) ...", file=sys.stderr)
    subprocess.run(
        ["cargo", "bench", "-p", "decimal", "--bench", "to_decimal", "--", "--noplot",
         "^decimal/catmull-clark-quad/.*/1000000$"],
        cwd=REPO, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    meta = json.loads(subprocess.run(["cargo", "metadata", "--format-version", "1", "--no-deps"],
                                     cwd=REPO, capture_output=True, text=True, check=True).stdout)
    out = {}
    for bench, label in (("to-decimal", "decimal::to_decimal (criterion)"),
                         ("num-bigint-to-string", "num-bigint to_string (criterion)")):
        path = os.path.join(meta["target_directory"], "criterion", "decimal",
                            "catmull-clark-quad_" + bench, "1000000", "new", "sample.json")
        with open(path) as fh:
            sample = json.load(fh)
        out[label] = [t / i / 1e9 for t, i in zip(sample["times"], sample["iters"])]
    return out


def osd_rows(label, tool, r, sub_frames):
    """The rows under an OpenSubdiv or opensubdiv-rs main row: its RefineUniform, its one-shot
    Interpolate and its per-frame Interpolate, each next to subcount's refine_topology_s and
    evaluate_s (`--frames`, single thread) when this subcount has them, and opensubdiv-rs's
    deviation from OpenSubdiv."""
    out = []

    def row(what, ts, ours=None, ours_name=None):
        if not ts:
            return
        med = statistics.median(ts)
        rate = "%d / %.1f M/s" % (r["faces"], r["faces"] / med / 1e6) if med > 0 else ""
        ratio = ""
        if ours:
            ratio = "%.2fx (%s %.3f)" % (med / statistics.median(ours), ours_name,
                                         statistics.median(ours))
        out.append((label, "%s %s" % (tool, what), "%.3f" % med,
                    "%.3f-%.3f" % (min(ts), max(ts)), rate, "", ratio))

    sf = sub_frames or {}
    row("RefineUniform", r["refine_s"], sf.get("refine_topology_s"), "refine_topology_s")
    row("Interpolate (one-shot)", r["interpolate_s"])
    row("Interpolate per frame", r.get("frame_interpolate_s"), sf.get("evaluate_s"), "evaluate_s")
    acc = r.get("accuracy")
    if acc:
        if "error" in acc:
            out.append((label, "%s positions vs opensubdiv" % tool, "error: " + acc["error"][:60],
                        "", "", "", ""))
        else:
            out.append((label, "%s positions vs opensubdiv" % tool,
                        "max %.2g of the diagonal" % acc["max_deviation"], "",
                        "%d vertices, same faces" % acc["vertices"], "", ""))
    return out


def osd_version():
    """Debian's libosd-dev version, when dpkg knows it."""
    p = subprocess.run(["dpkg-query", "-W", "-f", "${Version}", "libosd-dev"],
                       capture_output=True, text=True)
    return p.stdout.strip() if p.returncode == 0 and p.stdout.strip() else "(libosdCPU)"


def mib(b):
    return "-" if not b else "%.0f MiB" % (b / 2**20)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target"))
    ap.add_argument("--subcount", default=os.path.join(target, "release", "subcount"))
    ap.add_argument("--openmesh", default="/tmp/subcount-openmesh/subdivide_openmesh")
    ap.add_argument("--osd", default=os.path.join(target, "osd-driver", "osd_driver"),
                    help="OpenSubdiv's driver (built by tools/osd-driver/build.sh when missing)")
    ap.add_argument("--opensubdiv-rs", dest="osdrs",
                    default=os.path.join(target, "peers", "release", "opensubdiv-rs-peer"),
                    help="bench/peers/opensubdiv-rs's binary (built with cargo when missing)")
    ap.add_argument("--frames", type=int, default=10,
                    help="per-frame evaluations timed on one refinement (OpenSubdiv, "
                         "opensubdiv-rs, subcount --frames)")
    ap.add_argument("--no-python", action="store_true",
                    help="skip the virtualenv and the Python peers (libigl, pymeshlab, trimesh, "
                         "python-flint and the exact counts)")
    ap.add_argument("--no-accuracy", action="store_true",
                    help="skip comparing opensubdiv-rs's positions with OpenSubdiv's")
    ap.add_argument("--meshes", default=os.environ.get("SUBCOUNT_MESHES", os.path.join(REPO, "..", "shared", "meshes")))
    ap.add_argument("--venv", default=os.environ.get("SUBCOUNT_PEERS_VENV", "/tmp/subcount-peers-venv"))
    ap.add_argument("--reps", type=int, default=3)
    ap.add_argument("--only", default="", help="run only the jobs whose label contains this")
    ap.add_argument("--json", help="also write every raw figure to this file")
    ap.add_argument("--no-cargo-bench", action="store_true",
                    help="skip the in-process decimal rendering figures (criterion)")
    ap.add_argument("--worker", nargs="+", help=argparse.SUPPRESS)
    a = ap.parse_args()
    if a.worker:
        if a.worker[0] == "flint":
            return worker_flint(int(a.worker[1]))
        tool, scheme, levels, path, reps = a.worker
        return worker(tool, scheme, int(levels), path, int(reps))

    if not os.path.exists(a.subcount):
        raise SystemExit(
            "no subcount binary at %s: cargo build --release -p subcount (or --subcount PATH)" % a.subcount
        )
    python, versions = (None, {}) if a.no_python else ensure_venv(a.venv)
    have_openmesh = os.path.exists(a.openmesh)
    wanted = {t for job in JOBS if not a.only or a.only in job[0] for t in job[4]}
    osd = osdrs = None
    if "opensubdiv" in wanted:
        osd = ensure_built(a.osd, lambda: subprocess.run(
            [os.path.join(REPO, "tools", "osd-driver", "build.sh"), a.osd],
            check=True, capture_output=True, text=True).stdout.strip(), "the OpenSubdiv driver")
    if "opensubdiv-rs" in wanted:
        def build_osdrs():
            # Cargo's own layout: TARGET/release/NAME for --target-dir TARGET.
            target_dir = os.path.dirname(os.path.dirname(a.osdrs))
            subprocess.run(["cargo", "build", "--release", "--quiet", "--manifest-path",
                            os.path.join(REPO, "bench", "peers", "opensubdiv-rs", "Cargo.toml"),
                            "--target-dir", target_dir], check=True)
            return a.osdrs
        osdrs = ensure_built(a.osdrs, build_osdrs, "opensubdiv-rs-peer")
    frames_flag = subcount_has_flag(a.subcount, "--frames")
    limit_flag = frames_flag and subcount_has_flag(a.subcount, "--limit")
    start_load = load_average()
    started = time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime())
    tmp = tempfile.mkdtemp(prefix="subcount-peers-")
    ico = os.path.join(tmp, "icosphere.obj")
    subprocess.run(
        [a.subcount, "subdivide", "--base", "icosahedron", "--scheme", "icosphere", "--levels", "6", "-o", ico],
        check=True,
        capture_output=True,
    )
    rows, raw = [], []
    for label, scheme, levels, inp, peers in JOBS:
        if a.only and a.only not in label:
            continue
        path = ico if inp == "icosphere" else os.path.join(a.meshes, inp + ".obj")
        if not os.path.exists(path):
            print("skipping %s: %s is missing" % (label, path), file=sys.stderr)
            continue
        print("running %s ..." % label, file=sys.stderr)
        ours = run_subcount(a.subcount, ["--mesh", path, "--scheme", scheme, "--levels", str(levels)], a.reps)
        ours_med = statistics.median(ours["times"])
        results = [("subcount", ours)]
        for tool in peers:
            if tool == "subcount-1t":
                # The single-thread path (--threads 1); "subcount" is the default, rayon's
                # pool over every core.
                r = run_subcount(a.subcount, ["--mesh", path, "--scheme", scheme, "--levels", str(levels),
                                              "--threads", "1"], a.reps)
            elif tool == "subcount-thp":
                # The same binary with glibc's malloc asking for transparent huge pages
                # (fewer, larger page faults on the fresh output arrays).
                r = run_subcount(a.subcount, ["--mesh", path, "--scheme", scheme, "--levels", str(levels)],
                                 a.reps, env={"GLIBC_TUNABLES": "glibc.malloc.hugetlb=1"})
            elif tool == "openmesh":
                if not have_openmesh:
                    continue
                r = run_openmesh(a.openmesh, scheme, levels, path, a.reps)
            elif tool in ("opensubdiv", "opensubdiv-rs"):
                binary = osd if tool == "opensubdiv" else osdrs
                if binary is None:
                    continue
                command = [binary, "--time"] if tool == "opensubdiv" else [binary, "time"]
                r = run_osd_timing(command, scheme, levels, path, a.reps, a.frames)
                if tool == "opensubdiv-rs" and osd and not a.no_accuracy and "error" not in r:
                    r["accuracy"] = run_osdrs_accuracy(osd, osdrs, scheme, levels, path, tmp)
            elif python is None:
                continue
            else:
                r = run_worker(python, tool, scheme, levels, path, a.reps)
            results.append((tool, r))
        sub_frames = None
        if frames_flag and any(t.startswith("opensubdiv") for t, _ in results):
            sub_frames = run_subcount_frames(
                a.subcount, ["--mesh", path, "--scheme", scheme, "--levels", str(levels),
                             "--threads", "1"], a.reps, a.frames)
            raw.append({"job": label, "tool": "subcount-1t --frames", **sub_frames})
            if "error" in sub_frames:
                rows.append((label, "subcount-1t --frames", "error: " + sub_frames["error"][:60],
                             "", "", "", ""))
                sub_frames = None
        if limit_flag and osd and any(t == "opensubdiv" for t, _ in results):
            osd_limit = run_osd_timing([osd, "--time"], scheme, levels, path, 1, a.frames, limit=True)
            sub_limit = run_subcount_frames(
                a.subcount, ["--mesh", path, "--scheme", scheme, "--levels", str(levels),
                             "--threads", "1", "--limit", "--normals", "limit"], a.reps, a.frames)
            raw.append({"job": label, "tool": "opensubdiv limit", **osd_limit})
            raw.append({"job": label, "tool": "subcount-1t --limit", **sub_limit})
            limit_extra = limit_rows(label, osd_limit, sub_limit, a.frames)
        else:
            limit_extra = []
        for tool, r in results:
            raw.append({"job": label, "tool": tool, **r})
            if "error" in r:
                rows.append((label, tool, "error: " + r["error"][:60], "", "", "", ""))
                continue
            med = statistics.median(r["times"])
            spread = "%.3f-%.3f" % (min(r["times"]), max(r["times"]))
            rate = "%.1f M/s" % (r["faces"] / med / 1e6)
            peak = mib(r["peak_bytes"])
            if tool.startswith("subcount"):
                peak += " (pred. %s)" % mib(r["predicted"])
            ratio = "1" if tool == "subcount" else "%.2fx" % (med / ours_med)
            rows.append((label, tool, "%.3f" % med, spread, "%d / %s" % (r["faces"], rate), peak, ratio))
            if tool.startswith("opensubdiv"):
                rows.extend(osd_rows(label, tool, r, sub_frames))
        if sub_frames:
            # subcount's own figures of the --frames run, the ones the opensubdiv rows cite.
            for key, what in (("refine_topology_s", "refine_topology_s"),
                              ("evaluate_s", "evaluate_s (per frame)")):
                ts = sub_frames[key]
                med = statistics.median(ts)
                rate = "%.1f M/s" % (ours["faces"] / med / 1e6) if med > 0 else "-"
                rows.append((label, "subcount-1t --frames %d %s" % (a.frames, what), "%.3f" % med,
                             "%.3f-%.3f" % (min(ts), max(ts)), "%d / %s" % (ours["faces"], rate),
                             "", ""))
        rows.extend(limit_extra)

    if python is not None and (not a.only or a.only in "cc-quad counts flint"):
        print("running exact counts ...", file=sys.stderr)
        p = subprocess.run([python, os.path.abspath(__file__), "--worker", "flint", str(max(a.reps, 5))],
                           capture_output=True, text=True)
        def time_at(extra):
            ts = []
            for _ in range(max(a.reps, 5)):
                t0 = time.perf_counter()
                subprocess.run(
                    [a.subcount, "at", "--scheme", "catmull-clark-quad", "--counts", "V=8,E=12,F=6",
                     "--level", str(CC_LEVEL)] + extra,
                    check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                ts.append(time.perf_counter() - t0)
            return ts

        summary_times = time_at(["--summary"])
        at_times = time_at([])  # every digit of V, E and F, written to /dev/null
        at_med = statistics.median(at_times)
        rows.append(("cc-quad counts s=10^6", "subcount at --summary (process)",
                     "%.4f" % statistics.median(summary_times),
                     "%.4f-%.4f" % (min(summary_times), max(summary_times)), "", "",
                     "%.2fx" % (statistics.median(summary_times) / at_med)))
        rows.append(("cc-quad counts s=10^6", "subcount at, all digits of V, E, F (process)",
                     "%.4f" % at_med, "%.4f-%.4f" % (min(at_times), max(at_times)), "", "", "1"))
        rendering = {} if a.no_cargo_bench else criterion_rendering()
        if p.returncode == 0:
            fl = json.loads(p.stdout.strip().splitlines()[-1])
            raw.append({"job": "flint", **fl, "subcount_at": at_times, "subcount_at_summary": summary_times,
                        "criterion_rendering": rendering})
            ts = fl["power"]
            med = statistics.median(ts)
            rows.append(("cc-quad counts s=10^6", "flint fmpz_mat power", "%.4f" % med,
                         "%.4f-%.4f" % (min(ts), max(ts)), "", "", "%.2fx" % (med / at_med)))
            rendering["flint str() %d digits" % fl["digits"]] = fl["render"]
        else:
            rows.append(("cc-quad counts s=10^6", "flint", "error: " + p.stderr.strip()[-60:], "", "", "", ""))
        # Decimal rendering of E = 12 4^(10^6), in-process; ratios to decimal::to_decimal.
        ours_render = rendering.get("decimal::to_decimal (criterion)")
        for what, ts in rendering.items():
            med = statistics.median(ts)
            ratio = "%.2fx" % (med / statistics.median(ours_render)) if ours_render else ""
            rows.append(("cc-quad E s=10^6 to decimal", what, "%.4f" % med,
                         "%.4f-%.4f" % (min(ts), max(ts)), "", "", ratio))

    head = ("job", "tool", "median s", "min-max s", "faces / rate", "peak memory", "vs subcount")
    widths = [max(len(str(r[i])) for r in rows + [head]) for i in range(len(head))]
    print("started %s; load average at start %s, at end %s; reps %d" % (started, start_load, load_average(), a.reps))
    peers = ["%s %s" % kv for kv in sorted(versions.items())]
    peers.append("OpenMesh (sdist) C++ driver" if have_openmesh else "OpenMesh driver missing")
    peers.append("OpenSubdiv %s driver" % osd_version() if osd else "OpenSubdiv driver missing")
    peers.append("opensubdiv-rs 0.5.0" if osdrs else "opensubdiv-rs missing")
    print("peers: " + ", ".join(peers)
          + ("; subcount --frames %d" % a.frames if frames_flag else "; subcount has no --frames"))
    print("| " + " | ".join(h.ljust(w) for h, w in zip(head, widths)) + " |")
    print("|" + "|".join("-" * (w + 2) for w in widths) + "|")
    for r in rows:
        print("| " + " | ".join(str(c).ljust(w) for c, w in zip(r, widths)) + " |")
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(raw, fh, indent=1)


if __name__ == "__main__":
    main()
