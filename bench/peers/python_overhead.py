#!/usr/bin/env python3
"""What the Python bindings cost over the Rust work, and how they compare with Python peers
(not part of CI).

Usage (in a virtualenv where `import subcount, igl, trimesh` works):
    python3 bench/peers/python_overhead.py [--subcount PATH] [--meshes DIR] [--runs N]
                                           [--frames N] [--sphere-level K] [--json FILE]

Jobs: Loop levels 1-3 on the icosphere (`subcount subdivide --base icosahedron --scheme
icosphere --levels K -o FILE`, K = --sphere-level, 5 by default: 20,480 faces) and Loop levels
1-2 on armadillo.obj of --meshes when it is there (86,482 faces). Every subcount call runs with
threads=1 / --threads 1. Each figure is the median of --runs runs (each run its own process
where a row says "fresh process"); ratios and overheads are between medians of the same run of
this script, never across runs: the machine is shared (the load average at the start and the
end is printed with the tables).

1. Bindings over the Rust work, one-shot subdivide. `subcount.subdivide(m, scheme="loop",
   levels=L, threads=1)` on a `subcount.Mesh` read once (`read_mesh`, not timed), wall time of
   the call: (a) "fresh": the first call in a fresh Python process (one process per run), the
   state the command line's own figure is measured in (a new heap: every page of the result is
   a page fault); (b) "warm": repeated calls in this process after one untimed call (the
   allocator hands back pages already mapped). Against the command line's own
   `subdivide_s` (`subcount subdivide --mesh F --scheme loop --levels L --threads 1
   --timings`, one process per run). overhead = fresh - subdivide_s: the binding's work that
   the command line's timer does not see (the face list copied out of the Mesh, its checks,
   the half-edge mesh built for the scheme, the result turned into a face list), in ms, per
   output vertex and as a share of the Python call; the table's note fits overhead = a + b *
   V_out over the mesh's levels. The command line counts the half-edge build in its load_s,
   with the file's parsing: "CLI prepare" = load_s - the fresh process's read_mesh (the same
   parser) is that part, for comparison.
   `.positions` and `.face_vertex_indices` of the result are copies made on each access: one
   access of each, timed (in the fresh process: first access; and warm).
2. Per frame. `r = subcount.Refinement(m, scheme="loop", levels=L, threads=1)` (timed: against
   the CLI's refine_topology_s) and `r.evaluate(points, out=buf)` per frame, the points
   alternating between the base positions and a moved copy, buf reused: the median of --frames
   frames per run, the median of those over the runs, against the median over the runs of the
   CLI's `--frames N --timings` evaluate_s (itself the median of its N frames).
3. Peers, arrays in and arrays out: `subcount.subdivide((V, F), ...)` (its array checks
   included), and with the result's `.positions` and `.face_vertex_indices` read ("+ arrays",
   the fair comparison: the peers return arrays), `igl.loop(V, F, number_of_subdivs=L)` (libigl)
   and `trimesh.remesh.subdivide_loop(V, F, iterations=L)` on the same V (float64) and F (int64)
   arrays, each tool in its own worker process, all its runs in that process (load excluded).
   A run over 60 s is killed and reported as "> 60 s"; after a run over 10 s no more are made.
   cpu/wall is the process's CPU time over the wall time of the call (1.0: one thread busy):
   the workers run with OMP_NUM_THREADS = OPENBLAS_NUM_THREADS = MKL_NUM_THREADS = 1, and
   Threads (from /proc/self/status, after the calls) is printed. Not the same positions:
   trimesh's rule is subcount's (OpenSubdiv's Loop); igl.loop uses Warren's simplified beta
   (python/tests/test_peers.py has the measured deviations); the face counts are checked equal.
4. In-process against a process: `subcount.table(8, scheme="loop", mesh=m)` and
   `subcount.stats(m)` (m in memory; and with the file's path, so the file is read in-process
   too) against the wall time of the process `subcount table --levels 8 --scheme loop --mesh F
   --format json` and `subcount stats --mesh F --format json` (subprocess.run around it).

5. `--overhead` (alone): the issue's figure, (the Python wall time of `subdivide(...)` with the
   creation of its arrays `positions`, `face_vertex_counts`, `face_vertex_indices` - the Rust
   call's time) / the Rust call's time, where the Rust call's time is the library's work the
   call reports with `timings=True` (`rust_s`: the detached call, freeing included), on Loop L3 of the
   81,920-face icosphere and Loop L2 of armadillo, medians of --runs fresh processes.

Machine facts (CPU model from /proc/cpuinfo, cores, memory, kernel, `uptime` before and after,
UTC date, versions of Python, numpy, scipy, libigl, trimesh, subcount and the commit) are
printed above the tables and written to --json with every run's figure.
"""

import argparse
import datetime
import json
import os
import platform
import select
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Set before numpy, igl or trimesh is imported (here and in the workers): their thread pools,
# if any, start with one thread.
SINGLE_THREAD_ENV = {
    "OMP_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "RAYON_NUM_THREADS": "1",
}
os.environ.update(SINGLE_THREAD_ENV)

PEER_LIMIT_S = 60.0  # a peer's run that takes longer is killed: "> 60 s"
LONG_RUN_S = 10.0  # after a run this long, no more runs of that job (as compare.py)
WORKER_START_S = 180.0  # a worker's imports and loading
PEERS = ["subcount", "igl", "trimesh"]
SCHEME = "loop"
TABLE_LEVELS = 8


def load_average():
    return "%.2f %.2f %.2f" % os.getloadavg()


def uptime():
    try:
        return subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip()
    except OSError:
        return "load average: " + load_average()


def utc_now():
    return datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S UTC")


def import_subcount():
    """`import subcount`, retried for a few minutes: another engineer may be rebuilding it."""
    for attempt in range(6):
        try:
            import subcount

            return subcount
        except ImportError as e:
            if attempt == 5:
                raise
            print("import subcount failed (%s); retrying in 60 s" % e, file=sys.stderr)
            time.sleep(60)


def threads_now():
    """This process's threads (/proc/self/status)."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("Threads:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return None


def emit(obj):
    print(json.dumps(obj), flush=True)


# --------------------------------------------------------------------------------------------
# Worker side: a fresh process per fresh subcount call, one process per peer job.


def worker_fresh(path, levels):
    """The first subdivide call of a fresh process on a Mesh read from `path`, then the first
    access of each result array (numpy imported before, as a caller has it)."""
    import numpy  # noqa: F401  (the arrays' first access would import it otherwise)

    subcount = import_subcount()
    t0 = time.perf_counter()
    m = subcount.read_mesh(path)
    read_s = time.perf_counter() - t0
    c0, t0 = time.process_time(), time.perf_counter()
    out = subcount.subdivide(m, scheme=SCHEME, levels=levels, threads=1, timings=True)
    t1, c1 = time.perf_counter(), time.process_time()
    p = out.positions
    t2 = time.perf_counter()
    f = out.face_vertex_indices
    t3 = time.perf_counter()
    c = out.face_vertex_counts
    t4 = time.perf_counter()
    # The Rust call's own time: the library's work between the arguments' conversion and the
    # result (the "Rust time"); the rest of the wall time is the binding's.
    rust_s = out.timings["rust_s"]
    emit({"read_mesh_s": read_s, "call_s": t1 - t0, "cpu_s": c1 - c0, "positions_s": t2 - t1,
          "face_vertex_indices_s": t3 - t2, "face_vertex_counts_s": t4 - t3,
          "rust_s": rust_s, "timings": out.timings, "vertices": int(p.shape[0]),
          "faces": int(c.shape[0]), "threads": threads_now()})


def worker_peer(tool, arrays, levels, runs):
    """RUNS calls of one tool on the arrays of `arrays` (.npz: V float64, F int64), one JSON
    line per run (so the driver can stop a run that takes too long)."""
    import numpy as np

    data = np.load(arrays)
    v, f = np.ascontiguousarray(data["V"]), np.ascontiguousarray(data["F"])
    if tool == "subcount":
        subcount = import_subcount()

        def call():
            out = subcount.subdivide((v, f), scheme=SCHEME, levels=levels, threads=1)
            return out, out.n_vertices, out.n_faces
    elif tool == "igl":
        import igl

        def call():
            nv, nf = igl.loop(v, f, number_of_subdivs=levels)
            return None, int(nv.shape[0]), int(nf.shape[0])
    elif tool == "trimesh":
        from trimesh import remesh

        def call():
            nv, nf = remesh.subdivide_loop(v, f, iterations=levels)
            return None, int(nv.shape[0]), int(nf.shape[0])
    else:
        raise SystemExit("unknown tool %s" % tool)
    emit({"ready": True, "threads": threads_now()})
    for _ in range(runs):
        c0, t0 = time.process_time(), time.perf_counter()
        out, nverts, nfaces = call()
        t1, c1 = time.perf_counter(), time.process_time()
        row = {"call_s": t1 - t0, "cpu_s": c1 - c0, "vertices": nverts, "faces": nfaces,
               "threads": threads_now()}
        if out is not None:
            # What the peers hand back directly: the arrays.
            t2 = time.perf_counter()
            out.positions
            out.face_vertex_indices
            row["arrays_s"] = time.perf_counter() - t2
        del out
        emit(row)
        if t1 - t0 > LONG_RUN_S:
            break


# --------------------------------------------------------------------------------------------
# Driver side.


def run_streaming(args, runs, limit):
    """Runs a worker that prints a "ready" line then one JSON line per run; a run that does not
    report within `limit` seconds kills the worker. Returns (rows, error, timed_out)."""
    with tempfile.TemporaryFile(mode="w+") as err:
        p = subprocess.Popen(args, stdout=subprocess.PIPE, stderr=err, text=True,
                             env={**os.environ, **SINGLE_THREAD_ENV})
        rows, ready, timed_out, error = [], None, False, None
        deadline = time.monotonic() + WORKER_START_S
        while len(rows) < runs:
            left = deadline - time.monotonic()
            if left <= 0:
                if ready is None:
                    error = "no start within %d s" % WORKER_START_S
                else:
                    timed_out = True
                break
            r, _, _ = select.select([p.stdout], [], [], left)
            if not r:
                continue
            line = p.stdout.readline()
            if not line:
                break  # the worker ended: all runs made, a run over LONG_RUN_S, or a failure
            msg = json.loads(line)
            if msg.get("ready"):
                ready = msg
            else:
                rows.append(msg)
            deadline = time.monotonic() + limit
        killed = False
        if (timed_out or error) and p.poll() is None:
            p.kill()  # our own child, by its pid
            killed = True
        p.communicate()
        if not killed and p.returncode != 0:
            err.seek(0)
            error = (err.read().strip().splitlines() or ["exit code %s" % p.returncode])[-1]
    return rows, error, timed_out


def binding_overhead(rows):
    """The issue's overhead of one job: (the Python wall time of `subdivide(...)` including the
    creation of its arrays - the Rust call's time) / the Rust call's time, from the medians."""
    wall = med([r["call_s"] + r["positions_s"] + r["face_vertex_indices_s"]
                + r["face_vertex_counts_s"] for r in rows])
    rust = med([r["rust_s"] for r in rows])
    return wall, rust, (wall - rust) / rust


def overhead_only(args, subcount_bin, meshes_dir):
    """`--overhead`: the issue's two jobs only (Loop L3 of the 81,920-face icosphere, Loop L2
    of armadillo), fresh processes, a Markdown table."""
    tmp = tempfile.mkdtemp(prefix="subcount-python-overhead-")
    sphere = os.path.join(tmp, "icosphere6.obj")
    subprocess.run([subcount_bin, "subdivide", "--base", "icosahedron", "--scheme", "icosphere",
                    "--levels", "6", "-o", sphere], check=True, capture_output=True)
    print("%s; %s" % (utc_now(), uptime()))
    print()
    print("| job | Python wall (call + arrays) | Rust call | overhead |")
    print("|---|---:|---:|---:|")
    for name, path, level in [("icosphere 81,920 faces, Loop L3", sphere, 3),
                              ("armadillo, Loop L2", os.path.join(meshes_dir, "armadillo.obj"), 2)]:
        if not os.path.exists(path):
            print("| %s | (no %s) | | |" % (name, path))
            continue
        wall, rust, share = binding_overhead(run_fresh(path, level, args.runs))
        print("| %s | %s ms | %s ms | %.1f %% |" % (name, ms(wall), ms(rust), 100 * share))
    print()
    print("%s; %s; medians of %d fresh processes" % (utc_now(), uptime(), args.runs))


def run_fresh(mesh_path, levels, runs):
    rows = []
    for _ in range(runs):
        p = subprocess.run([sys.executable, os.path.abspath(__file__), "--worker", "fresh",
                            mesh_path, str(levels)], capture_output=True, text=True,
                           env={**os.environ, **SINGLE_THREAD_ENV})
        if p.returncode != 0:
            raise SystemExit("fresh worker failed: %s" % p.stderr.strip()[-400:])
        rows.append(json.loads(p.stdout.strip().splitlines()[-1]))
    return rows


def cli_timings(subcount_bin, args, runs):
    """The `timings: {...}` of RUNS `subcount subdivide --timings ARGS` processes, and the
    V and F of its summary line."""
    out = []
    for _ in range(runs):
        p = subprocess.run([subcount_bin, "subdivide", "--timings"] + args,
                           capture_output=True, text=True)
        if p.returncode != 0:
            raise SystemExit("subcount failed: %s" % p.stderr.strip())
        line = next(l for l in p.stderr.splitlines() if l.startswith("timings: "))
        t = json.loads(line[len("timings: "):])
        # "level 3: V = .., E = .., F = N (no -o: nothing written)"
        t["vertices"] = int(p.stdout.split("V = ")[1].split(",")[0])
        t["faces"] = int(p.stdout.split("F = ")[1].split()[0].rstrip(";"))
        out.append(t)
    return out


def process_walls(cmd, runs):
    walls = []
    for _ in range(runs):
        t0 = time.perf_counter()
        p = subprocess.run(cmd, capture_output=True, text=True)
        walls.append(time.perf_counter() - t0)
        if p.returncode != 0:
            raise SystemExit("%s failed: %s" % (" ".join(cmd), p.stderr.strip()))
    return walls


def timed(fn, runs):
    walls = []
    for _ in range(runs):
        t0 = time.perf_counter()
        fn()
        walls.append(time.perf_counter() - t0)
    return walls


def med(xs):
    return statistics.median(xs) if xs else None


def ms(s, digits=None):
    """Seconds as milliseconds, 3 significant figures (at least 2 decimals below 1 ms)."""
    if s is None:
        return "-"
    x = s * 1e3
    if digits is not None:
        return "%.*f" % (digits, x)
    if abs(x) >= 100:
        return "%.0f" % x
    if abs(x) >= 10:
        return "%.1f" % x
    if abs(x) >= 1:
        return "%.2f" % x
    return "%.3f" % x


def machine_facts(subcount_bin, subcount_mod):
    from importlib import metadata

    model = "?"
    with open("/proc/cpuinfo") as fh:
        for line in fh:
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    mem = "?"
    with open("/proc/meminfo") as fh:
        for line in fh:
            if line.startswith("MemTotal:"):
                mem = "%.1f GiB" % (int(line.split()[1]) / 2**20)
    versions = {"python": platform.python_version()}
    for name in ("numpy", "scipy", "libigl", "trimesh"):
        try:
            versions[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            versions[name] = None
    versions["subcount (package)"] = getattr(subcount_mod, "__version__", "?")
    cli = subprocess.run([subcount_bin, "--version"], capture_output=True, text=True)
    versions["subcount (CLI)"] = cli.stdout.strip()
    git = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"],
                         capture_output=True, text=True)
    so = getattr(getattr(subcount_mod, "_subcount", None), "__file__", None)

    def mtime(path):
        if not path or not os.path.exists(path):
            return None
        return datetime.datetime.fromtimestamp(os.path.getmtime(path), datetime.timezone.utc) \
            .strftime("%Y-%m-%d %H:%M UTC")

    return {
        "cpu": model,
        "cores": os.cpu_count(),
        "cores_usable": len(os.sched_getaffinity(0)),
        "memory": mem,
        "kernel": platform.release(),
        "versions": versions,
        "commit": git.stdout.strip() or None,
        "cli": subcount_bin,
        "cli_built": mtime(subcount_bin),
        "extension": so,
        "extension_built": mtime(so),
    }


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--worker":
        kind = sys.argv[2]
        if kind == "fresh":
            worker_fresh(sys.argv[3], int(sys.argv[4]))
        elif kind == "peer":
            worker_peer(sys.argv[3], sys.argv[4], int(sys.argv[5]), int(sys.argv[6]))
        else:
            raise SystemExit("unknown worker %s" % kind)
        return

    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    target = os.environ.get("CARGO_TARGET_DIR", os.path.join(REPO, "target"))
    ap.add_argument("--subcount", default=os.path.join(target, "release", "subcount"),
                    help="the command line (cargo build --release -p subcount)")
    meshes = os.environ.get("SUBCOUNT_MESHES") or os.path.join(REPO, "..", "shared", "meshes")
    ap.add_argument("--meshes", default=meshes,
                    help="folder of armadillo.obj (default: $SUBCOUNT_MESHES, else "
                         "../shared/meshes beside the repository)")
    ap.add_argument("--runs", type=int, default=7, help="runs per figure (medians; at least 5)")
    ap.add_argument("--frames", type=int, default=20, help="frames per run (at least 20)")
    ap.add_argument("--sphere-level", type=int, default=5,
                    help="the icosphere's level: 4 = 5,120 faces, 5 = 20,480 faces")
    ap.add_argument("--levels", default="1,2,3", help="Loop levels on the icosphere")
    ap.add_argument("--armadillo-levels", default="1,2", help="Loop levels on armadillo.obj")
    ap.add_argument("--json", help="also write every figure here")
    ap.add_argument("--overhead", action="store_true",
                    help="only the binding's overhead on the issue's two jobs (see binding_overhead)")
    args = ap.parse_args()
    if args.runs < 1 or args.frames < 1:
        ap.error("--runs and --frames must be positive")
    meshes_dir = args.meshes if os.path.isabs(args.meshes) else os.path.join(REPO, args.meshes)
    if args.overhead:
        overhead_only(args, args.subcount, meshes_dir)
        return

    subcount = import_subcount()
    import numpy as np

    facts = machine_facts(args.subcount, subcount)
    facts["start"] = utc_now()
    facts["uptime_before"] = uptime()
    facts["load_before"] = load_average()
    print("started %s; %s" % (facts["start"], facts["uptime_before"]), file=sys.stderr)

    tmp = tempfile.mkdtemp(prefix="subcount-python-overhead-")
    sphere = os.path.join(tmp, "icosphere%d.obj" % args.sphere_level)
    subprocess.run([args.subcount, "subdivide", "--base", "icosahedron", "--scheme", "icosphere",
                    "--levels", str(args.sphere_level), "-o", sphere],
                   check=True, capture_output=True)
    inputs = [("icosphere", sphere, [int(x) for x in args.levels.split(",") if x])]
    armadillo = os.path.join(meshes_dir, "armadillo.obj")
    if os.path.exists(armadillo):
        inputs.append(("armadillo", armadillo,
                       [int(x) for x in args.armadillo_levels.split(",") if x]))
    else:
        print("no %s: the armadillo jobs are skipped" % armadillo, file=sys.stderr)

    runs = args.runs
    results = {"machine": facts, "runs": runs, "frames": args.frames, "meshes": {}}
    try:
        for name, path, levels in inputs:
            m = subcount.read_mesh(path)
            base = {"vertices": m.n_vertices, "faces": m.n_faces, "path": path, "jobs": {}}
            results["meshes"][name] = base
            label0 = "%s (%s faces)" % (name, format(m.n_faces, ","))
            print("%s ..." % label0, file=sys.stderr)
            v = np.ascontiguousarray(m.positions, dtype=np.float64)
            f = np.ascontiguousarray(m.face_vertex_indices.reshape(-1, 3), dtype=np.int64)
            arrays = os.path.join(tmp, name + ".npz")
            np.savez(arrays, V=v, F=f)
            for levels_ in levels:
                job = {}
                base["jobs"][levels_] = job
                print("  L%d: command line" % levels_, file=sys.stderr)
                common = ["--mesh", path, "--scheme", SCHEME, "--levels", str(levels_),
                          "--threads", "1"]
                job["cli"] = cli_timings(args.subcount, common, runs)
                job["cli_frames"] = cli_timings(args.subcount, common + ["--frames", str(args.frames)], runs)

                print("  L%d: fresh processes" % levels_, file=sys.stderr)
                job["fresh"] = run_fresh(path, levels_, runs)

                print("  L%d: in-process" % levels_, file=sys.stderr)
                subcount.subdivide(m, scheme=SCHEME, levels=levels_, threads=1)  # untimed
                warm, pos, fvi = [], [], []
                for _ in range(runs):
                    t0 = time.perf_counter()
                    out = subcount.subdivide(m, scheme=SCHEME, levels=levels_, threads=1)
                    t1 = time.perf_counter()
                    out.positions
                    t2 = time.perf_counter()
                    out.face_vertex_indices
                    t3 = time.perf_counter()
                    warm.append(t1 - t0)
                    pos.append(t2 - t1)
                    fvi.append(t3 - t2)
                    del out
                job["warm"] = {"call_s": warm, "positions_s": pos, "face_vertex_indices_s": fvi}

                refine, frames, frame_cpu = [], [], []
                points = [v, np.ascontiguousarray(v * 1.001 + 1e-3)]
                for _ in range(runs):
                    t0 = time.perf_counter()
                    r = subcount.Refinement(m, scheme=SCHEME, levels=levels_, threads=1)
                    refine.append(time.perf_counter() - t0)
                    buf = np.empty((r.n_vertices(), 3))
                    per = []
                    c0 = time.process_time()
                    for k in range(args.frames):
                        t0 = time.perf_counter()
                        r.evaluate(points[k % 2], out=buf)
                        per.append(time.perf_counter() - t0)
                    frame_cpu.append((time.process_time() - c0) / sum(per))
                    frames.append(per)
                    del r, buf
                job["refinement"] = {"new_s": refine, "frames_s": frames,
                                     "frames_cpu_over_wall": frame_cpu}

                job["peers"] = {}
                for tool in PEERS:
                    print("  L%d: %s" % (levels_, tool), file=sys.stderr)
                    rows, error, timed_out = run_streaming(
                        [sys.executable, os.path.abspath(__file__), "--worker", "peer", tool,
                         arrays, str(levels_), str(runs)], runs, PEER_LIMIT_S)
                    job["peers"][tool] = {"runs": rows, "error": error, "timed_out": timed_out}

            # 4. The counting commands in-process against a process.
            print("  table and stats", file=sys.stderr)
            calls = {
                "table": (
                    lambda: subcount.table(TABLE_LEVELS, scheme=SCHEME, mesh=m),
                    lambda: subcount.table(TABLE_LEVELS, scheme=SCHEME, mesh=path),
                    [args.subcount, "table", "--levels", str(TABLE_LEVELS), "--scheme", SCHEME,
                     "--mesh", path, "--format", "json"],
                ),
                "stats": (
                    lambda: subcount.stats(m),
                    lambda: subcount.stats(path),
                    [args.subcount, "stats", "--mesh", path, "--format", "json"],
                ),
            }
            base["commands"] = {}
            for what, (in_memory, from_path, cmd) in calls.items():
                in_memory()  # untimed
                base["commands"][what] = {
                    "mesh_s": timed(in_memory, runs),
                    "path_s": timed(from_path, runs),
                    "process_s": process_walls(cmd, runs),
                }
    finally:
        for entry in os.listdir(tmp):
            os.remove(os.path.join(tmp, entry))
        os.rmdir(tmp)

    facts["end"] = utc_now()
    facts["uptime_after"] = uptime()
    facts["load_after"] = load_average()
    text = report(results, args)
    print(text)
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(results, fh, indent=1)


def report(results, args):
    import numpy as np

    facts = results["machine"]
    runs, frames = results["runs"], results["frames"]
    v = facts["versions"]
    lines = [
        "%s to %s, %s (%d cores, %d usable), %s RAM, Linux %s; load average %s at the start, "
        "%s at the end. subcount %s (CLI `%s`, built %s; extension built %s), commit %s; "
        "Python %s, numpy %s, scipy %s, libigl %s, trimesh %s. Medians of %d runs; "
        "subcount single-threaded (threads=1); workers with OMP/OPENBLAS/MKL_NUM_THREADS=1."
        % (facts["start"], facts["end"], facts["cpu"], facts["cores"], facts["cores_usable"],
           facts["memory"], facts["kernel"], facts["load_before"], facts["load_after"],
           v["subcount (package)"], v["subcount (CLI)"], facts["cli_built"],
           facts["extension_built"], facts["commit"], v["python"], v["numpy"], v["scipy"],
           v["libigl"], v["trimesh"], runs),
        "",
        "`uptime` before: %s" % facts["uptime_before"],
        "",
        "`uptime` after: %s" % facts["uptime_after"],
        "",
    ]

    # 1. One-shot subdivide: bindings over the command line's own time.
    lines += [
        "**1. `subcount.subdivide(m, scheme=\"loop\", levels=L, threads=1)` against the CLI's "
        "`subdivide_s`** (ms; fresh = first call of a fresh process, warm = repeated in-process; "
        "overhead = fresh - subdivide_s)",
        "",
        "| job | V out | Python fresh | Python warm | CLI subdivide_s | overhead | per out vertex "
        "| share of fresh | CLI prepare (load_s - read_mesh) | `.positions` fresh / warm "
        "| `.face_vertex_indices` fresh / warm |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    fits = []
    for name, mesh in results["meshes"].items():
        xs, ys = [], []
        for levels, job in mesh["jobs"].items():
            fresh = med([r["call_s"] for r in job["fresh"]])
            warm = med(job["warm"]["call_s"])
            cli = med([t["subdivide_s"] for t in job["cli"]])
            load = med([t["load_s"] for t in job["cli"]])
            read = med([r["read_mesh_s"] for r in job["fresh"]])
            nv = job["cli"][0]["vertices"]
            assert all(r["vertices"] == nv for r in job["fresh"]), "vertex counts differ"
            over = fresh - cli
            job["summary"] = {"fresh_s": fresh, "warm_s": warm, "cli_subdivide_s": cli,
                              "cli_load_s": load, "read_mesh_fresh_s": read,
                              "cli_prepare_s": load - read, "overhead_s": over,
                              "overhead_ns_per_vertex": over / nv * 1e9}
            xs.append(nv)
            ys.append(over)
            lines.append(
                "| %s L%s | %s | %s | %s | %s | %s | %.1f ns | %.0f %% | %s | %s / %s | %s / %s |"
                % (name, levels, format(nv, ","), ms(fresh), ms(warm), ms(cli), ms(over),
                   over / nv * 1e9, 100 * over / fresh, ms(load - read),
                   ms(med([r["positions_s"] for r in job["fresh"]])),
                   ms(med(job["warm"]["positions_s"])),
                   ms(med([r["face_vertex_indices_s"] for r in job["fresh"]])),
                   ms(med(job["warm"]["face_vertex_indices_s"]))))
        if len(xs) >= 2:
            b, a = np.polyfit(np.array(xs, float), np.array(ys, float), 1)
            mesh["overhead_fit"] = {"a_s": a, "b_s_per_vertex": b}
            fits.append("%s: overhead = %s ms + %.1f ns x V_out (least squares over levels %s)"
                        % (name, ms(a), b * 1e9, ", ".join(str(l) for l in mesh["jobs"])))
    lines += [""] + ["Fit, " + f for f in fits] + [""]

    # 2. Per frame.
    lines += [
        "**2. `subcount.Refinement(...)` and `r.evaluate(points, out=buf)` per frame against the "
        "CLI's `--frames %d --timings`** (ms; per frame: median of %d frames per run, median "
        "over the runs)" % (frames, frames),
        "",
        "| job | V out | `Refinement()` | CLI refine_topology_s | `evaluate` per frame | CLI "
        "evaluate_s | overhead per frame | per out vertex | share of the Python frame |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for name, mesh in results["meshes"].items():
        for levels, job in mesh["jobs"].items():
            rf = job["refinement"]
            new = med(rf["new_s"])
            frame = med([med(per) for per in rf["frames_s"]])
            cli_top = med([t["refine_topology_s"] for t in job["cli_frames"]])
            cli_eval = med([t["evaluate_s"] for t in job["cli_frames"]])
            nv = job["cli"][0]["vertices"]
            over = frame - cli_eval
            job["summary"].update({"refinement_new_s": new, "frame_s": frame,
                                   "cli_refine_topology_s": cli_top, "cli_evaluate_s": cli_eval,
                                   "frame_overhead_s": over})
            lines.append("| %s L%s | %s | %s | %s | %s | %s | %s | %.2f ns | %.0f %% |"
                         % (name, levels, format(nv, ","), ms(new), ms(cli_top), ms(frame),
                            ms(cli_eval), ms(over), over / nv * 1e9, 100 * over / frame))
    lines.append("")

    # 3. Peers.
    lines += [
        "**3. Peers, arrays in and out** (ms; each tool in its own process, the same V float64 "
        "and F int64; ratio = peer / subcount + arrays: above 1, subcount is faster; cpu/wall "
        "1.0 = one thread busy)",
        "",
        "| job | F out | subcount (V, F) | + arrays | igl.loop | trimesh subdivide_loop | igl / "
        "subcount | trimesh / subcount | cpu/wall subcount, igl, trimesh | threads |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]

    def peer(p):
        rs = p["runs"]
        if p["timed_out"] and not rs:
            return None, "> %d s" % PEER_LIMIT_S
        if p["error"] and not rs:
            return None, "error: " + p["error"][:40]
        t = med([r["call_s"] for r in rs])
        text = ms(t)
        if len(rs) < runs:
            text += " (%d run%s%s)" % (len(rs), "" if len(rs) == 1 else "s",
                                       ", then > %d s" % PEER_LIMIT_S if p["timed_out"] else "")
        return t, text

    for name, mesh in results["meshes"].items():
        for levels, job in mesh["jobs"].items():
            peers = job["peers"]
            sc = peers["subcount"]["runs"]
            nf = job["cli"][0]["faces"]
            call = med([r["call_s"] for r in sc]) if sc else None
            full = med([r["call_s"] + r["arrays_s"] for r in sc]) if sc else None
            cells, ratios, cpu, threads = [], [], [], []
            for tool in PEERS:
                p = peers[tool]
                t, text = peer(p)
                for r in p["runs"]:
                    if r["faces"] != nf:
                        text += " (F = %d!)" % r["faces"]
                        break
                if tool != "subcount":
                    cells.append(text)
                    if t is not None and full:
                        ratios.append("%.1fx" % (t / full))
                    elif p["timed_out"]:
                        ratios.append("> %.0fx" % (PEER_LIMIT_S / full) if full else "-")
                    else:
                        ratios.append("-")
                rs = p["runs"]
                cpu.append("%.2f" % med([r["cpu_s"] / r["call_s"] for r in rs]) if rs else "-")
                threads.append(str(rs[-1]["threads"]) if rs else "-")
            summary = job["summary"]
            summary.update({"subcount_arrays_call_s": call, "subcount_arrays_full_s": full})
            for tool in ("igl", "trimesh"):
                rs = peers[tool]["runs"]
                summary[tool + "_s"] = med([r["call_s"] for r in rs]) if rs else None
            lines.append("| %s L%s | %s | %s | %s | %s | %s | %s | %s | %s | %s |"
                         % (name, levels, format(nf, ","), ms(call), ms(full), cells[0],
                            cells[1], ratios[0], ratios[1], ", ".join(cpu), ", ".join(threads)))
    lines.append("")

    # 4. In-process against a process.
    lines += [
        "**4. The counting commands in-process against a process** (ms; ratio = process / "
        "in-process with the Mesh)",
        "",
        "| mesh | call | in-process, Mesh | in-process, path | `subcount` process | process / "
        "in-process |",
        "|---|---|---:|---:|---:|---:|",
    ]
    for name, mesh in results["meshes"].items():
        for what, c in mesh["commands"].items():
            a, b, p = med(c["mesh_s"]), med(c["path_s"]), med(c["process_s"])
            call = ("`subcount.table(%d, scheme=\"loop\", mesh=m)` / `subcount table --levels %d "
                    "--scheme loop --mesh F --format json`" % (TABLE_LEVELS, TABLE_LEVELS)
                    if what == "table" else
                    "`subcount.stats(m)` / `subcount stats --mesh F --format json`")
            lines.append("| %s (%s faces) | %s | %s | %s | %s | %.1fx |"
                         % (name, format(mesh["faces"], ","), call, ms(a), ms(b), ms(p), p / a))
    return "\n".join(lines)


if __name__ == "__main__":
    main()
