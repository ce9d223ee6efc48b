"""The counting commands (at, table, formula, fit, density, schemes, stats, verify) against the
CLI's `--format json` on every built-in scheme and the shared meshes, their errors and notes.

The CLI binary is $SUBCOUNT_BIN (as in test_mesh.py); the shared meshes
are $SUBCOUNT_MESHES (default: ../shared/meshes beside the repository).
"""

import json
import sys
import threading
import time
import warnings

import pytest

import subcount
from subcount._commands import _big_int
from test_mesh import SHARED_MESHES as MESHES
from test_mesh import cli

BASES = ["icosahedron", "cube", "mixed", "grid:3x2", "quad-grid:2x2", "icosahedron-holes:2"]
SCHEMES = [s["name"] for s in subcount.schemes()]
# Every shared mesh (the comparisons run every applicable scheme on each).
SHARED = sorted(p.name for p in MESHES.glob("*.obj")) if MESHES.is_dir() else []
ERRORS = {1: subcount.MismatchError, 2: subcount.UsageError, 3: subcount.InputError, 4: subcount.ResourceError}


def cli_json(*args):
    """The CLI's JSON (counts of any size), or its exit code and error line."""
    run = cli(*args, "--format", "json")
    if run.returncode != 0:
        return run.returncode, run.stderr.strip().splitlines()[-1].removeprefix("error: ")
    return json.loads(run.stdout, parse_int=_big_int)


def same_as_cli(call, *args):
    """`call()` returns the CLI's JSON, or raises the exception of its exit code with its message."""
    expected = cli_json(*args)
    if isinstance(expected, tuple):
        code, message = expected
        with pytest.raises(ERRORS[code]) as raised:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                call()
        assert str(raised.value) == message
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            assert call() == expected


def shared(name):
    path = MESHES / name
    if not path.exists():
        pytest.skip(f"no shared mesh {path} (set SUBCOUNT_MESHES)")
    return path


# --- every built-in scheme on generated meshes -------------------------------------------


@pytest.mark.parametrize("scheme", SCHEMES)
@pytest.mark.parametrize("base", BASES)
def test_table_equals_cli_on_every_scheme(scheme, base):
    same_as_cli(lambda: subcount.table(3, scheme=scheme, base=base), "table", "--levels", 3, "--scheme", scheme, "--base", base)


@pytest.mark.parametrize("scheme", SCHEMES)
def test_at_formula_fit_equal_cli_on_every_scheme(scheme):
    base = ["--base", "icosahedron" if "loop" in scheme or "sqrt3" in scheme or "tri" in scheme else "cube"]
    kw = {"scheme": scheme, "base": base[1]}
    same_as_cli(lambda: subcount.at(40, **kw), "at", "--level", 40, "--scheme", scheme, *base)
    same_as_cli(lambda: subcount.formula(format="json", **kw), "formula", "--scheme", scheme, *base)
    same_as_cli(lambda: subcount.fit(max_faces=10**9, **kw), "fit", "--max-faces", 10**9, "--scheme", scheme, *base)
    text = cli("formula", "--scheme", scheme, *base)
    assert text.returncode == 0, text.stderr
    assert subcount.formula(**kw) == text.stdout
    assert subcount.formula(format="latex", **kw) == cli("formula", "--scheme", scheme, *base, "--format", "latex").stdout
    same_as_cli(lambda: subcount.schemes(scheme), "schemes", scheme)


def test_schemes_and_density_equal_cli():
    same_as_cli(subcount.schemes, "schemes")
    same_as_cli(lambda: subcount.density(level=5), "density", "--level", 5)
    same_as_cli(lambda: subcount.density(target_area=0.001, radius=2.0, tau=0.5), "density", "--target-area", 0.001, "--radius", 2.0, "--tau", 0.5)


def test_the_issue_examples():
    counts = {"V": 12, "E": 30, "F": 20}
    at = subcount.at(10**6, scheme="loop", counts=counts)
    assert at["level"] == 10**6
    assert at["F"] == 20 * 4 ** (10**6) and at["E"] == 30 * 4 ** (10**6)  # 602,067 digits, exact
    rows = subcount.table(range(0, 6), scheme="catmull-clark", base="cube")
    assert [r["level"] for r in rows] == list(range(6)) and rows[5]["F"] == 6 * 4**5
    assert subcount.table(2) == subcount.table(range(0, 3))
    assert subcount.formula(scheme="loop", format="text").startswith("V(s) = V0 + (4^s - 1)/3 * E0")


def decimal_text(n):
    """`n` in decimal, without Python's limit on int-to-str conversions (4300 digits)."""
    set_limit = getattr(sys, "set_int_max_str_digits", None)
    if set_limit is None:  # an interpreter from before the limit
        return str(n)
    old = sys.get_int_max_str_digits()
    set_limit(0)
    try:
        return str(n)
    finally:
        set_limit(old)


def test_big_int_parses_any_length():
    for n in [0, 7, -12, 10**4000 - 1, 3**30000, -(7**20000) + 1]:
        text = decimal_text(n)
        assert _big_int(text) == n
    # Beyond Python's int() limit (4300 digits): 10^k - 1 and a digit pattern.
    assert _big_int("9" * 50_000) == 10**50_000 - 1
    assert _big_int("1" + "0" * 30_000 + "1") == 10**30_001 + 1


def test_sympy_forms_agree_with_table():
    sympy = pytest.importorskip("sympy")
    for scheme, base in [("loop", "icosahedron"), ("catmull-clark", "grid:3x2"), ("doo-sabin", "cube")]:
        forms = subcount.formula(scheme=scheme, base=base, format="sympy")
        rows = subcount.table(4, scheme=scheme, base=base)
        s = sympy.Symbol("s", integer=True, nonnegative=True)
        initial = {sympy.Symbol(f"{k}0"): v for k, v in rows[0].items() if k != "level"}
        for row in rows:
            for component, expr in forms.items():
                assert expr.subs(initial).subs(s, row["level"]) == row[component], (scheme, component, row)
    phased = subcount.formula(scheme="sqrt3-boundary", format="sympy")
    assert [p["phase"] for p in phased] == ["s = 2t", "s = 2t + 1"]
    assert str(phased[0]["forms"]["F"]) == "9**t*F0"


# --- meshes: files, Mesh objects, arrays ----------------------------------------------------


@pytest.mark.parametrize("name", SHARED or ["(no shared meshes)"])
def test_stats_table_verify_equal_cli_on_shared_meshes(name):
    path = shared(name)
    same_as_cli(lambda: subcount.stats(path), "stats", "--mesh", path)
    stats = cli_json("stats", "--mesh", path)
    schemes = stats["applicable_schemes"] if isinstance(stats, dict) else []
    # The file read once (a Mesh counts as its file: test_a_mesh_in_memory_counts_as_its_file).
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mesh = subcount.read_mesh(path)
    for scheme in schemes:
        same_as_cli(lambda: subcount.table(3, scheme=scheme, mesh=mesh), "table", "--levels", 3, "--scheme", scheme, "--mesh", path)
    # verify subdivides: one level, on the meshes under 1 MB (the big ones cost seconds each).
    if schemes and path.stat().st_size < 1_000_000:
        same_as_cli(lambda: subcount.verify(path, scheme=schemes[0], levels=1), "verify", "--levels", 1, "--scheme", schemes[0], "--mesh", path)


def test_a_mesh_in_memory_counts_as_its_file():
    path = shared("osd_catmark_pawn.obj")
    mesh = subcount.read_mesh(path)
    for call in [
        lambda m: subcount.stats(m),
        lambda m: subcount.table(3, scheme="catmull-clark", mesh=m),
        lambda m: subcount.verify(m, scheme="catmull-clark", levels=2),
        lambda m: subcount.fit(scheme="catmull-clark", mesh=m, max_faces=10**6),
        lambda m: subcount.formula(scheme="catmull-clark", mesh=m, format="json"),
    ]:
        assert call(mesh) == call(path) == call(str(path))
    arrays = (mesh.positions, (mesh.face_vertex_counts, mesh.face_vertex_indices))
    assert subcount.stats(arrays)["F"] == mesh.n_faces


def test_mesh_options_and_tags_reach_the_counts():
    grid = [[x, y, 0.0] for y in range(3) for x in range(3)]
    quads = [[y * 3 + x, y * 3 + x + 1, y * 3 + x + 4, y * 3 + x + 3] for y in range(2) for x in range(2)]
    counts = [4] * 4
    flat = [i for q in quads for i in q]
    holed = subcount.Mesh(grid, counts, flat, hole_indices=[0])
    plain = subcount.Mesh(grid, counts, flat)
    assert subcount.table(1, scheme="catmull-clark", mesh=holed)[0]["F"] == 3
    assert subcount.table(1, scheme="catmull-clark", mesh=plain)[0]["F"] == 4
    assert subcount.verify(holed, scheme="catmull-clark", levels=2)[-1]["match"]


# --- errors, notes, threads ---------------------------------------------------------------


def test_errors_are_the_cli_exit_codes_with_its_messages(tmp_path):
    same_as_cli(lambda: subcount.table(3, scheme="no-such-scheme"), "table", "--levels", 3, "--scheme", "no-such-scheme")
    same_as_cli(lambda: subcount.stats(tmp_path / "missing.obj"), "stats", "--mesh", tmp_path / "missing.obj")
    same_as_cli(lambda: subcount.at(10**12, scheme="loop", counts={"V": 12, "E": 30, "F": 20}), "at", "--level", 10**12, "--scheme", "loop", "--counts", "V=12,E=30,F=20")
    same_as_cli(lambda: subcount.table(3, scheme="loop", base="cube"), "table", "--levels", 3, "--scheme", "loop", "--base", "cube")
    with pytest.raises(subcount.UsageError, match="range of step 1"):
        subcount.table(range(0, 6, 2))
    with pytest.raises(subcount.UsageError, match="format"):
        subcount.formula(format="pdf")
    with pytest.raises(TypeError):
        subcount.table(2.5)
    with pytest.raises(TypeError):
        subcount.at(True, scheme="loop", counts={"V": 12, "E": 30, "F": 20})
    with pytest.raises(TypeError):
        subcount.stats(42)
    with pytest.raises(subcount.InputError, match="positions"):
        subcount.stats(([[0, 0, float("nan")], [1, 0, 0], [0, 1, 0]], [[0, 1, 2]]))
    assert issubclass(subcount.UsageError, ValueError) and issubclass(subcount.ResourceError, MemoryError)


def test_a_mismatch_raises_with_the_report(tmp_path):
    wrong = tmp_path / "wrong.toml"
    toml = cli("schemes", "loop", "--format", "toml").stdout.replace("[1, 1],", "[1, 2],").replace('name = "loop"', 'name = "wrong"')
    wrong.write_text(toml)
    run = cli("verify", "--base", "icosahedron", "--scheme-file", wrong, "--levels", 2, "--format", "json")
    assert run.returncode == 1
    with pytest.raises(subcount.MismatchError) as raised:
        subcount.verify(base="icosahedron", scheme_file=wrong, levels=2)
    assert raised.value.report == json.loads(run.stdout)
    assert [r["match"] for r in raised.value.report] == [True, False, False]


def test_notes_are_warnings(tmp_path):
    path = tmp_path / "partial.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n")
    with pytest.warns(subcount.Warning, match="no UV column"):
        rows = subcount.table(1, scheme="loop", mesh=path)
    assert "UV" not in rows[0]
    run = cli("table", "--levels", 1, "--scheme", "loop", "--mesh", path, "--format", "json")
    assert run.stderr.strip().endswith("no UV column") and json.loads(run.stdout) == rows


def test_the_gil_is_released_during_a_command():
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    t = threading.Thread(target=tick)
    t.start()
    try:
        start = time.perf_counter()
        subcount.at(4 * 10**5, scheme="loop", counts={"V": 12, "E": 30, "F": 20})
        end = time.perf_counter()
    finally:
        done.set()
        t.join()
    during = [x for x in ticks if start < x < end]
    assert end - start > 0.05, "the command was too quick to tell"
    assert len(during) >= 3, (len(during), end - start)


def test_numpy_integers_are_integers():
    import numpy as np

    assert subcount.table(np.int64(2)) == subcount.table(2)
    assert subcount.at(np.int32(3), scheme="loop", counts={"V": np.int64(12), "E": 30, "F": 20})["F"] == 1280
    out = subcount.subdivide(subcount.read_mesh(shared("osd_loop_icosahedron.obj")), scheme="loop", levels=np.int64(1))
    assert out.n_faces == 80
    assert subcount.density(level=2, base="icosahedron", boundary="edge")["V"] == 162
