"""The mesh side of the Python package: read/write, subdivide against the CLI, errors, notes.

The CLI binary is $SUBCOUNT_BIN (default: the repository's target/debug/subcount, under
$CARGO_TARGET_DIR when set, built by `cargo build -p subcount`); every input is generated here,
in tmp_path.
"""

import os
import re
import subprocess
import threading
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import subcount

REPO = Path(__file__).resolve().parents[2]
# The shared meshes: $SUBCOUNT_MESHES (relative to the repository root), else ../shared/meshes
# beside the repository.
SHARED_MESHES = Path(os.environ.get("SUBCOUNT_MESHES") or REPO.parent / "shared" / "meshes")
if not SHARED_MESHES.is_absolute():
    SHARED_MESHES = REPO / SHARED_MESHES
SUBCOUNT_BIN = os.environ.get("SUBCOUNT_BIN") or str(
    Path(os.environ.get("CARGO_TARGET_DIR") or REPO / "target") / "debug" / "subcount"
)

# An octahedron (closed triangles), a cube (closed quads), an open 3x2 triangle grid with a
# crease-free boundary, and a mixed triangle/quad mesh (a house: a cube with a roof).
OCTAHEDRON = (
    [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]],
    [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
)
CUBE = (
    [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [0, 0, 1], [1, 0, 1], [1, 1, 1], [0, 1, 1]],
    [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]],
)


def grid(w=3, h=2):
    """An open triangle grid of w x h squares, slightly bent so no coordinate is trivial."""
    positions = [[x * 0.7, y * 1.3, 0.1 * x * y + 0.05 * x * x] for y in range(h + 1) for x in range(w + 1)]
    faces = []
    for y in range(h):
        for x in range(w):
            a = y * (w + 1) + x
            b, c, d = a + 1, a + w + 2, a + w + 1
            faces += [[a, b, c], [a, c, d]]
    return positions, faces


def obj_text(positions, faces, extra_faces_text=None):
    lines = ["v " + " ".join(repr(float(c)) for c in p) for p in positions]
    lines += ["f " + " ".join(str(i + 1) for i in f) for f in faces]
    return "\n".join(lines) + "\n"


def write_obj(path, positions, faces):
    Path(path).write_text(obj_text(positions, faces))
    return path


def cli(*args):
    if not Path(SUBCOUNT_BIN).exists():
        pytest.skip(f"no CLI binary at {SUBCOUNT_BIN}: run `cargo build -p subcount` (or set SUBCOUNT_BIN)")
    return subprocess.run([SUBCOUNT_BIN, *map(str, args)], capture_output=True, text=True)


def cli_subdivide(mesh_path, out_path, *flags):
    run = cli("subdivide", "--mesh", mesh_path, *flags, "-o", out_path)
    assert run.returncode == 0, run.stderr
    return subcount.read_mesh(out_path)


def same_bits(a, b):
    a, b = np.asarray(a), np.asarray(b)
    assert a.shape == b.shape and a.dtype == b.dtype, (a.shape, b.shape, a.dtype, b.dtype)
    return np.array_equal(a.view(np.uint8), b.view(np.uint8))


def assert_same_mesh(ours, theirs):
    assert same_bits(ours.positions, theirs.positions)
    assert np.array_equal(ours.face_vertex_counts, theirs.face_vertex_counts)
    assert np.array_equal(ours.face_vertex_indices, theirs.face_vertex_indices)


# --- read and write --------------------------------------------------------------------


GROUPED_OBJ = """\
mtllib house.mtl
v 0 0 0 1 0 0
v 1 0 0 0 1 0
v 1 1 0 0 0 1
v 0 1 0 0.25 0.5 0.75
v 0.5 0.5 1 1 1 1
o house
g walls
usemtl red
f 1 2 5
f 2 3 5
usemtl blue
f 3 4 5
g roof
f 4 1 5
f 1 4 3 2
"""


def test_read_mesh_arrays_groups_and_colors(tmp_path):
    path = tmp_path / "house.obj"
    path.write_text(GROUPED_OBJ)
    m = subcount.read_mesh(path)
    assert m.positions.shape == (5, 3) and m.positions.dtype == np.float64
    assert m.face_vertex_counts.dtype == np.int32 and m.face_vertex_indices.dtype == np.int32
    assert m.face_vertex_counts.tolist() == [3, 3, 3, 3, 4]
    assert m.face_vertex_indices.tolist() == [0, 1, 4, 1, 2, 4, 2, 3, 4, 3, 0, 4, 0, 3, 2, 1]
    assert m.colors.tolist()[3] == [0.25, 0.5, 0.75]
    assert m.materials == ["red", "red", "blue", "blue", "blue"]
    assert m.groups == ["walls", "walls", "walls", "roof", "roof"]
    assert m.mtllib == ["house.mtl"]
    assert m.uvs is None and m.uv_indices is None
    assert (m.n_vertices, m.n_faces) == (5, 5)
    # The arrays are read-only copies.
    with pytest.raises(ValueError):
        m.positions[0, 0] = 7.0


@pytest.mark.parametrize("name", ["copy.obj", "copy.ply"])
def test_write_mesh_round_trip(tmp_path, name):
    path = tmp_path / "house.obj"
    path.write_text(GROUPED_OBJ)
    m = subcount.read_mesh(str(path))
    out = tmp_path / name
    if name.endswith(".ply"):
        with pytest.warns(subcount.Warning, match="materials and groups are not written to PLY"):
            subcount.write_mesh(m, out)
    else:
        subcount.write_mesh(m, str(out))
    back = subcount.read_mesh(out)
    assert_same_mesh(back, m)
    if name.endswith(".ply"):  # colors as uchar, materials and groups not written
        assert np.allclose(back.colors, np.round(m.colors * 255) / 255, rtol=0, atol=1e-15)
        assert back.materials is None
    else:
        assert same_bits(back.colors, m.colors)
        assert back.materials == m.materials and back.groups == m.groups
        assert back.mtllib == m.mtllib


def test_mesh_from_arrays_with_uvs_round_trips(tmp_path):
    positions, faces = CUBE
    counts = np.full(6, 4, dtype=np.int64)
    indices = np.asarray(faces, dtype=np.uint32).ravel()
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32)
    uv_indices = np.tile(np.arange(4), 6)
    colors = np.linspace(0, 1, 24).reshape(8, 3)
    m = subcount.Mesh(positions, counts, indices, uvs=uvs, uv_indices=uv_indices, colors=colors)
    assert m.positions.dtype == np.float64 and m.face_vertex_counts.tolist() == [4] * 6
    subcount.write_mesh(m, tmp_path / "cube.obj")
    back = subcount.read_mesh(tmp_path / "cube.obj")
    assert_same_mesh(back, m)
    assert same_bits(back.uvs, m.uvs) and np.array_equal(back.uv_indices, m.uv_indices)
    assert same_bits(back.colors, m.colors)
    assert "8 vertices, 6 faces" in repr(m)


# --- subdivide: the CLI's output to the bit --------------------------------------------


CASES = [
    ("loop", OCTAHEDRON),
    ("loop", grid()),
    ("catmull-clark", CUBE),
    ("catmull-clark", grid()),
    ("sqrt3", OCTAHEDRON),
]


@pytest.mark.parametrize("levels", [0, 1, 2])
@pytest.mark.parametrize("scheme,shape", CASES, ids=[f"{s}-{i}" for i, (s, _) in enumerate(CASES)])
def test_subdivide_equals_cli_to_the_bit(tmp_path, scheme, shape, levels):
    positions, faces = shape
    src = write_obj(tmp_path / "in.obj", positions, faces)
    expected = cli_subdivide(src, tmp_path / "cli.obj", "--scheme", scheme, "--levels", levels)
    # The three forms of the mesh argument: a path, a Mesh, arrays ((F, k) and the pair).
    by_path = subcount.subdivide(src, scheme=scheme, levels=levels)
    by_mesh = subcount.subdivide(subcount.read_mesh(src), scheme=scheme, levels=levels)
    by_array = subcount.subdivide((np.asarray(positions, float), np.asarray(faces)), scheme=scheme, levels=levels)
    counts = np.full(len(faces), len(faces[0]))
    by_pair = subcount.subdivide(
        (positions, (counts, np.ravel(faces))), scheme=scheme, levels=levels, threads=1
    )
    for ours in (by_path, by_mesh, by_array, by_pair):
        assert_same_mesh(ours, expected)




@pytest.mark.parametrize(
    "name,scheme",
    [
        ("osd_catmark_pawn.obj", "catmull-clark"),
        ("osd_catmark_bishop.obj", "catmull-clark"),
        ("fandisk_quads.obj", "catmull-clark"),
        ("3holes.obj", "loop"),
        ("eight_hole.obj", "loop"),
        ("osd_loop_toroidal_tet.obj", "loop"),
    ],
)
def test_subdivide_equals_cli_to_the_bit_on_shared_meshes(tmp_path, name, scheme):
    """Tags, UVs and groups as read: positions, faces and UVs equal `subdivide -o` to the bit."""
    path = SHARED_MESHES / name
    if not path.exists():
        pytest.skip(f"no shared mesh {path} (set SUBCOUNT_MESHES)")
    for levels in (1, 2):
        expected = cli_subdivide(path, tmp_path / "cli.obj", "--scheme", scheme, "--levels", levels)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", subcount.Warning)
            ours = subcount.subdivide(path, scheme=scheme, levels=levels)
        assert_same_mesh(ours, expected)
        if expected.uvs is not None:
            assert same_bits(ours.uvs, expected.uvs)
            assert np.array_equal(ours.uv_indices, expected.uv_indices)


def test_subdivide_options_and_f32_equal_cli(tmp_path):
    positions, faces = grid(4, 3)
    src = write_obj(tmp_path / "in.obj", positions, faces)
    flags = ["--scheme", "loop", "--levels", "2", "--boundary", "edge-and-corner", "--precision", "f32"]
    # PLY holds f32 as written: comparable to the bit.
    expected = cli_subdivide(src, tmp_path / "cli.ply", *flags)
    ours = subcount.subdivide(src, scheme="loop", levels=2, boundary="edge-and-corner", precision="f32")
    assert ours.positions.dtype == np.float32
    assert same_bits(ours.positions, expected.positions.astype(np.float32))
    assert np.array_equal(ours.face_vertex_indices, expected.face_vertex_indices)
    # Results do not depend on threads.
    one = subcount.subdivide(src, scheme="loop", levels=2, boundary="edge-and-corner", threads=1)
    two = subcount.subdivide(src, scheme="loop", levels=2, boundary="edge-and-corner", threads=2)
    assert_same_mesh(one, two)


SCHEME_FILES = Path(__file__).resolve().parents[2] / "examples" / "schemes"


def test_a_scheme_file_subdivides_as_the_cli(tmp_path):
    """scheme_file= is --scheme-file: alone or beside the file's own name, with the CLI's bits
    (subdivide and Refinement), and the CLI's refusals."""
    positions, faces = grid(3, 3)
    src = write_obj(tmp_path / "in.obj", positions, faces)
    triangles_cc = SCHEME_FILES / "catmull-clark-triangles.toml"
    loop_boundary = SCHEME_FILES / "loop-boundary.toml"
    for file, name in ((triangles_cc, None), (loop_boundary, "my-loop-boundary")):
        flags = ["--scheme-file", file, *(["--scheme", name] if name else []), "--levels", 2]
        expected = cli_subdivide(src, tmp_path / "cli.obj", *flags)
        ours = subcount.subdivide(src, scheme=name, scheme_file=file, levels=2)
        assert_same_mesh(ours, expected)
        r = subcount.Refinement(src, scheme_file=str(file), levels=2)
        assert same_bits(r.evaluate(np.asarray(positions, float)), expected.positions)
    # The name must be the file's, as --scheme with --scheme-file; one of the two is needed.
    cli_run = cli("subdivide", "--mesh", src, "--scheme", "loop", "--scheme-file", loop_boundary, "--levels", 1,
                  "-o", tmp_path / "no.obj")
    with pytest.raises(subcount.Error) as e:
        subcount.subdivide(src, scheme="loop", scheme_file=loop_boundary, levels=1)
    assert cli_run.returncode != 0 and str(e.value) in cli_run.stderr, (str(e.value), cli_run.stderr)
    assert isinstance(e.value, {2: subcount.UsageError, 3: subcount.InputError}[cli_run.returncode])
    with pytest.raises(subcount.UsageError, match="give scheme= .* or scheme_file="):
        subcount.subdivide(src, levels=1)
    with pytest.raises(subcount.InputError, match="nope.toml"):
        subcount.Refinement(src, scheme_file=tmp_path / "nope.toml", levels=1)
    with pytest.raises(TypeError, match="scheme_file must be"):
        subcount.subdivide(src, scheme_file=3, levels=1)


def test_subdivide_carries_groups_colors_and_uvs_as_the_cli(tmp_path):
    src = tmp_path / "house.obj"
    src.write_text(GROUPED_OBJ)
    expected = cli_subdivide(src, tmp_path / "cli.obj", "--scheme", "catmull-clark", "--levels", "2")
    ours = subcount.subdivide(src, scheme="catmull-clark", levels=2)
    assert_same_mesh(ours, expected)
    assert same_bits(ours.colors, expected.colors)
    assert ours.materials == expected.materials and ours.groups == expected.groups
    # UVs refined (a cube with a vt per corner).
    positions, faces = CUBE
    uvs = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], float)
    m = subcount.Mesh(positions, [4] * 6, np.ravel(faces), uvs=uvs, uv_indices=np.tile(np.arange(4), 6))
    subcount.write_mesh(m, tmp_path / "uv.obj")
    expected = cli_subdivide(tmp_path / "uv.obj", tmp_path / "uv-cli.obj", "--scheme", "catmull-clark", "--levels", "2")
    ours = subcount.subdivide(m, scheme="catmull-clark", levels=2)
    assert_same_mesh(ours, expected)
    assert same_bits(ours.uvs, expected.uvs) and np.array_equal(ours.uv_indices, expected.uv_indices)
    assert subcount.subdivide(m, scheme="catmull-clark", levels=1, no_uv=True).uvs is None


def test_the_gil_is_released_during_subdivide():
    positions, faces = OCTAHEDRON
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(1)
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    t.start()
    try:
        before = len(ticks)
        # 8 M faces, a few tenths of a second: without the GIL released, the other thread
        # could not run at all during the call.
        out = subcount.subdivide((positions, faces), scheme="loop", levels=10, threads=1)
        during = len(ticks) - before
    finally:
        done.set()
        t.join()
    assert out.n_faces == 8 * 4**10
    assert during > 20, during


# --- errors and notes -------------------------------------------------------------------


def test_exception_hierarchy():
    assert issubclass(subcount.UsageError, subcount.Error) and issubclass(subcount.UsageError, ValueError)
    assert issubclass(subcount.InputError, subcount.Error) and issubclass(subcount.InputError, ValueError)
    assert issubclass(subcount.ResourceError, subcount.Error)
    assert issubclass(subcount.ResourceError, MemoryError)
    assert issubclass(subcount.MismatchError, subcount.Error)
    assert issubclass(subcount.Warning, UserWarning)
    assert isinstance(subcount.__version__, str)


ATTRIBUTE = re.compile(r"^\s*#\[(?:pyo3::)?(pymethods|pyfunction)\b")
FN = re.compile(r"^(\s*)(?:pub(?:\([\w:]+\))?\s+)?(?:const\s+|async\s+|unsafe\s+|extern\s+\S+\s+)*fn\s+(\w+)")


def entry_points(source):
    """(name, body lines) of every `#[pyfunction]` and every fn of a `#[pymethods]` block in a
    Rust source of the bindings, as `cargo fmt` lays them out (`.ci/run` checks the layout):
    the signature ends with a line ending in `{`, the body closes at the fn's indentation."""
    lines = source.split("\n")
    found, block_indent, pending = [], None, False
    for i, line in enumerate(lines):
        attribute = ATTRIBUTE.match(line)
        if attribute and attribute.group(1) == "pymethods":
            block_indent = len(line) - len(line.lstrip())
            continue
        if attribute:
            pending = True
            continue
        if block_indent is not None and line == " " * block_indent + "}":
            block_indent = None
        start = FN.match(line)
        if not start or not (pending or block_indent is not None):
            continue
        pending = False
        indent = start.group(1)
        j = i
        while not lines[j].rstrip().endswith("{"):
            assert "}" not in lines[j].split("//")[0], f"a one-line fn body: {lines[j]!r}"
            j += 1
        k = j + 1
        while lines[k] != indent + "}":
            k += 1
        found.append((start.group(2), indent, lines[j + 1:k]))
    return found


def test_every_entry_point_raises_a_panic_as_error():
    """A Rust panic would be a bug; PyO3 would raise it as its `PanicException` (not an
    `Exception`), so the whole body of every function, method and getter Python can call is
    one `errors::entry(py, || ...)` expression, which raises it as `subcount.Error` with the
    panic's message."""
    src = Path(__file__).resolve().parents[1] / "src"
    checked = []
    for path in sorted(src.glob("*.rs")):
        for name, indent, body in entry_points(path.read_text()):
            where = f"{path.name}: {name}"
            assert body and body[0].startswith(indent + "    entry(py, ||"), f"{where} does not run in entry(): {body[:1]}"
            # One expression: nothing else at the body's own indentation.
            top = [line for line in body if line.startswith(indent + "    ") and not line.startswith(indent + "     ")]
            assert top == [body[0]] or top == [body[0], body[-1]], f"{where}: more than entry(): {top}"
            assert body[-1].rstrip().endswith(")"), f"{where}: more than entry(): {body[-1]}"
            checked.append(name)
    # read_mesh, write_mesh, subdivide, run_command, Mesh's and Refinement's methods and getters.
    assert len(checked) >= 41 and {"subdivide", "stencils", "positions", "__repr__"} <= set(checked), checked


def test_the_entry_point_check_sees_what_it_checks():
    """The parser above finds attribute forms and qualifiers it must not miss, and refuses a
    body that is more than one entry() expression."""
    source = """\
#[pyo3::pyfunction(signature = (a, *, b=None))]
pub(crate) fn one(py: Python<'_>, a: u32) -> PyResult<u32> {
    entry(py, || Ok(a))
}

#[pyfunction]
fn two(py: Python<'_>) -> PyResult<u32> {
    let x = 3;
    entry(py, || Ok(x))
}

#[pymethods]
impl Thing {
    #[staticmethod]
    fn three(
        py: Python<'_>,
    ) -> PyResult<u32> {
        entry(py, || {
            Ok(3)
        })
    }
}
"""
    found = {name: (indent, body) for name, indent, body in entry_points(source)}
    assert set(found) == {"one", "two", "three"}, found
    indent, body = found["two"]
    top = [line for line in body if line.startswith(indent + "    ") and not line.startswith(indent + "     ")]
    assert len(top) == 2 and not top[0].strip().startswith("entry("), top


def test_usage_errors(tmp_path):
    src = write_obj(tmp_path / "in.obj", *OCTAHEDRON)
    with pytest.raises(subcount.UsageError) as e:
        subcount.subdivide(src, scheme="no-such-scheme", levels=1)
    # The CLI's message, exit code 2.
    run = cli("subdivide", "--mesh", src, "--scheme", "no-such-scheme", "--levels", "1")
    assert run.returncode == 2 and run.stderr.strip() == f"error: {e.value}"
    with pytest.raises(subcount.UsageError, match="negative"):
        subcount.subdivide(src, scheme="loop", levels=-1)
    with pytest.raises(subcount.UsageError, match="boundary"):
        subcount.subdivide(src, scheme="loop", levels=1, boundary="sideways")
    with pytest.raises(subcount.UsageError, match="precision"):
        subcount.subdivide(src, scheme="loop", levels=1, precision="f16")
    with pytest.raises(subcount.UsageError, match="threads"):
        subcount.subdivide(src, scheme="loop", levels=1, threads=100000)
    with pytest.raises(subcount.UsageError, match="triangle"):
        subcount.subdivide(src, scheme="loop", levels=1, triangle_rule="smooth")
    with pytest.raises(subcount.UsageError, match="stl"):
        subcount.write_mesh(src, tmp_path / "out.stl")
    with pytest.raises(TypeError):
        subcount.subdivide(src, scheme="loop", levels=1.5)
    with pytest.raises(TypeError):
        subcount.subdivide(src, "loop", 1)  # options are keyword-only


def test_input_errors(tmp_path):
    positions, faces = OCTAHEDRON
    bad = np.array(positions, float)
    bad[4, 2] = np.nan
    with pytest.raises(subcount.InputError, match=r"positions\[4, 2\] is nan"):
        subcount.subdivide((bad, faces), scheme="loop", levels=1)
    bad[4, 2] = np.inf
    with pytest.raises(subcount.InputError, match=r"positions\[4, 2\] is inf"):
        subcount.Mesh(bad, [3] * 8, np.ravel(faces))
    out_of_range = np.array(faces)
    out_of_range[3, 1] = 6
    with pytest.raises(subcount.InputError, match=r"faces\[3, 1\] = 6 is out of range"):
        subcount.subdivide((positions, out_of_range), scheme="loop", levels=1)
    with pytest.raises(subcount.InputError, match=r"face_vertex_indices\[5\] = -2 is negative"):
        subcount.Mesh(positions, [3] * 8, [0, 2, 4, 2, 1, -2] + list(np.ravel(faces)[6:]))
    with pytest.raises(subcount.InputError, match=r"shape \(6, 2\)"):
        subcount.Mesh(np.zeros((6, 2)), [3], [0, 1, 2])
    with pytest.raises(subcount.InputError, match="empty"):
        subcount.Mesh(np.zeros((0, 3)), [3], [0, 1, 2])
    with pytest.raises(subcount.InputError, match="empty"):
        subcount.subdivide((positions, np.zeros((0, 3), int)), scheme="loop", levels=1)
    with pytest.raises(subcount.InputError, match=r"face_vertex_counts\[0\] = 2"):
        subcount.Mesh(positions, [2], [0, 1])
    with pytest.raises(subcount.InputError, match="add up to"):
        subcount.Mesh(positions, [3, 3], [0, 1, 2])
    with pytest.raises(subcount.InputError, match=r"face_vertex_counts\[1\] = -3 is negative"):
        subcount.Mesh(positions, [3, -3], [0, 1, 2])
    # The arrays beside the faces: UVs, their corners, colors, tags.
    counts, corners = [3] * 8, np.ravel(faces)
    uvs = np.zeros((4, 2))
    with pytest.raises(subcount.InputError, match=r"uv_indices has 23 entries for 24 corners"):
        subcount.Mesh(positions, counts, corners, uvs=uvs, uv_indices=np.zeros(23, int))
    with pytest.raises(subcount.InputError, match=r"uv_indices\[9\] = 4 is out of range: uvs has 4"):
        subcount.Mesh(positions, counts, corners, uvs=uvs, uv_indices=[0] * 9 + [4] + [0] * 14)
    with pytest.raises(subcount.InputError, match=r"uv_indices\[2\] = -1 is negative"):
        subcount.Mesh(positions, counts, corners, uvs=uvs, uv_indices=[0, 0, -1] + [0] * 21)
    nan_uvs = uvs.copy()
    nan_uvs[3, 1] = np.nan
    with pytest.raises(subcount.InputError, match=r"uvs\[3, 1\] is nan"):
        subcount.Mesh(positions, counts, corners, uvs=nan_uvs, uv_indices=np.zeros(24, int))
    with pytest.raises(subcount.InputError, match=r"colors has 5 rows for 6 vertices"):
        subcount.Mesh(positions, counts, corners, colors=np.zeros((5, 3)))
    with pytest.raises(subcount.InputError, match=r"colors\[0, 0\] is inf"):
        subcount.Mesh(positions, counts, corners, colors=[[np.inf, 0, 0]] + [[0, 0, 0]] * 5)
    for sharpness, what in ((np.nan, "nan"), (-1.0, "-1")):
        with pytest.raises(subcount.InputError, match=r"crease_sharpnesses\[0\]") as e:
            subcount.Mesh(positions, counts, corners, crease_indices=[0, 2], crease_lengths=[2],
                          crease_sharpnesses=[sharpness])
        assert what in str(e.value).lower(), str(e.value)
        with pytest.raises(subcount.InputError, match=r"corner_sharpnesses\[0\]"):
            subcount.Mesh(positions, counts, corners, corner_indices=[1], corner_sharpnesses=[sharpness])
    with pytest.raises(TypeError, match="positions"):
        subcount.Mesh([["a", "b", "c"]], [3], [0, 0, 0])
    with pytest.raises(TypeError, match="face_vertex_indices"):
        subcount.Mesh(positions, [3], [0.0, 1.0, 2.0])
    # The driver's input errors: a scheme that does not apply, a file that is not a mesh.
    src = write_obj(tmp_path / "quads.obj", *CUBE)
    with pytest.raises(subcount.InputError) as e:
        subcount.subdivide(src, scheme="loop", levels=1)
    run = cli("subdivide", "--mesh", src, "--scheme", "loop", "--levels", "1")
    assert run.returncode == 3 and run.stderr.strip() == f"error: {e.value}"
    (tmp_path / "broken.obj").write_text("v 0 0 0\nf 1 2 3\n")
    with pytest.raises(subcount.InputError):
        subcount.read_mesh(tmp_path / "broken.obj")
    with pytest.raises(subcount.InputError):
        subcount.read_mesh(tmp_path / "missing.obj")


def test_resource_errors(tmp_path):
    src = write_obj(tmp_path / "in.obj", *OCTAHEDRON)
    with pytest.raises(subcount.ResourceError) as e:
        subcount.subdivide(src, scheme="loop", levels=30)
    run = cli("subdivide", "--mesh", src, "--scheme", "loop", "--levels", "30")
    assert run.returncode == 4 and run.stderr.strip() == f"error: {e.value}"
    with pytest.raises(MemoryError):
        subcount.subdivide(src, scheme="loop", levels=10**30)


def test_notes_become_warnings(tmp_path):
    src = tmp_path / "tagged.obj"
    src.write_text(obj_text(*CUBE) + "t interpolateboundary 1/0/0 1\nt vertexedit 0/0/1 x\n")
    with pytest.warns(subcount.Warning) as record:
        subcount.subdivide(src, scheme="catmull-clark", levels=1, boundary="edge")
    messages = [str(w.message) for w in record]
    run = cli("subdivide", "--mesh", src, "--scheme", "catmull-clark", "--levels", "1", "--boundary", "edge")
    assert run.returncode == 0
    assert messages == run.stderr.strip().splitlines()
    assert any("vertexedit" in m for m in messages) and any("overrides" in m for m in messages)
    # A rule without crease rules says so; with ignore_tags, nothing is said.
    with pytest.warns(subcount.Warning) as record:
        subcount.subdivide(src, scheme="doo-sabin", levels=1, boundary="edge-and-corner")
    assert any("not applied by doo-sabin" in str(w.message) for w in record)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        subcount.subdivide(src, scheme="catmull-clark", levels=1, ignore_tags=True)


def test_a_warnings_filter_set_to_error_raises_the_note(tmp_path):
    src = tmp_path / "tagged.obj"
    src.write_text(obj_text(*CUBE) + "t vertexedit 0/0/1 x\n")
    with warnings.catch_warnings():
        warnings.simplefilter("error", subcount.Warning)
        with pytest.raises(subcount.Warning, match="vertexedit"):
            subcount.subdivide(src, scheme="catmull-clark", levels=1)


def test_a_result_goes_back_to_the_library(tmp_path):
    """A result hands its positions and corners to numpy without a copy; passed back (to
    subdivide, write_mesh, stats, Refinement) it is the same mesh."""
    once = subcount.subdivide(OCTAHEDRON, scheme="loop", levels=1)
    assert not once.positions.flags.writeable and not once.face_vertex_indices.flags.writeable
    twice = subcount.subdivide(once, scheme="loop", levels=1)
    subcount.write_mesh(once, tmp_path / "once.obj")
    assert_same_mesh(subcount.read_mesh(tmp_path / "once.obj"), once)
    assert_same_mesh(twice, subcount.subdivide(tmp_path / "once.obj", scheme="loop", levels=1))
    assert subcount.stats(once)["F"] == once.n_faces == 32
    r = subcount.Refinement(once, scheme="loop", levels=1)
    assert same_bits(r.evaluate(once.positions), twice.positions)
    # The same arrays on every access, and numpy refuses to make them (or their buffer's own
    # array) writable: the library reads them back.
    assert once.positions is once.positions
    for array in (once.positions, once.positions.base, once.face_vertex_indices, once.face_vertex_counts):
        with pytest.raises(ValueError):
            array.setflags(write=True)
    assert repr(once) == "subcount.Mesh(18 vertices, 32 faces)"


def test_hostile_arrays_and_arguments():
    positions = [[0, 0, 0], [1, 0, 0], [0, 1, 0]]
    # Counts whose sum wraps around 64 bits.
    with pytest.raises(subcount.InputError, match="add up"):
        subcount.Mesh(positions, np.array([2**64 - 1, 4], np.uint64), [0, 1, 2])
    # Empty lists are empty meshes, not a wrong dtype.
    with pytest.raises(subcount.InputError, match="empty"):
        subcount.Mesh(positions, [], [])
    with pytest.raises(subcount.InputError, match="faces"):
        subcount.subdivide((positions, []), scheme="loop", levels=1)
    # Tuples of tuples are faces; a (counts, corners) pair has lengths that differ.
    square = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
    two = subcount.stats((square, ((0, 1, 2), (0, 2, 3))))
    pair = subcount.stats((square, ((3, 3), (0, 1, 2, 0, 2, 3))))
    assert two == pair and two["F"] == 2
    # A mesh object and base= together, as --mesh and --base.
    with pytest.raises(subcount.UsageError, match="--base"):
        subcount.stats(subcount.Mesh(positions, [3], [0, 1, 2]), base="cube")
