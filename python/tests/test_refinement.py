"""subcount.Refinement (refine once, evaluate many) and the Mesh tags under USD's names:
against subdivide() and the CLI to the bit, stencils, caller buffers, errors.
"""

import threading
import time
import warnings

import numpy as np
import pytest

import subcount
from test_mesh import CUBE, OCTAHEDRON, cli, grid, same_bits, write_obj

CASES = [
    ("loop", OCTAHEDRON, {}),
    ("catmull-clark", CUBE, {}),
    ("loop", grid(), {"boundary": "edge-and-corner"}),
    ("catmull-clark", grid(), {"boundary": "none"}),
    ("sqrt3", OCTAHEDRON, {}),
    ("doo-sabin", CUBE, {}),
]


def tagged_cube():
    """The cube with a crease chain (per-edge sharpness), a corner, a hole and its own options."""
    positions, faces = CUBE
    return subcount.Mesh(
        positions, [4] * 6, [i for f in faces for i in f],
        crease_indices=[0, 1, 2, 4, 5], crease_lengths=[3, 2], crease_sharpnesses=[1.5, 3.0, 0.5],
        corner_indices=[7], corner_sharpnesses=[2.0], hole_indices=[1],
        options={"crease_method": "chaikin"},
    )  # fmt: skip


@pytest.mark.parametrize("scheme,mesh,options", CASES)
@pytest.mark.parametrize("levels", [0, 1, 3])
def test_evaluate_equals_subdivide_to_the_bit(scheme, mesh, options, levels):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", subcount.Warning)
        r = subcount.Refinement(mesh, scheme=scheme, levels=levels, **options)
        out = subcount.subdivide(mesh, scheme=scheme, levels=levels, **options)
    positions = np.asarray(mesh[0], dtype=float)
    assert same_bits(r.evaluate(positions), out.positions)
    assert np.array_equal(r.face_vertex_counts, out.face_vertex_counts)
    assert np.array_equal(r.face_vertex_indices, out.face_vertex_indices)
    assert (r.n_vertices(), r.n_faces(), r.levels) == (out.n_vertices, out.n_faces, levels)


def test_tags_and_holes_reach_the_refinement_and_equal_the_cli(tmp_path):
    mesh = tagged_cube()
    r = subcount.Refinement(mesh, scheme="catmull-clark", levels=2)
    assert r.n_faces() == 5 * 16  # the hole's 16 faces are not written
    obj = tmp_path / "tagged.obj"
    subcount.write_mesh(mesh, tmp_path / "plain.obj")
    tags = "t crease 2/1/0 0 1 1.5\nt crease 2/1/0 1 2 3\nt crease 2/1/0 4 5 0.5\nt corner 1/1/0 7 2\n"
    tags += "t hole 1/0/0 1\nt creasemethod 0/0/1 chaikin\n"
    obj.write_text((tmp_path / "plain.obj").read_text() + tags)
    run = cli("subdivide", "--mesh", obj, "--scheme", "catmull-clark", "--levels", 2, "-o", tmp_path / "out.obj")
    assert run.returncode == 0, run.stderr
    theirs = subcount.read_mesh(tmp_path / "out.obj")
    assert same_bits(r.evaluate(mesh.positions), theirs.positions)
    assert np.array_equal(r.face_vertex_indices, theirs.face_vertex_indices)
    # The mesh's options are overridden by the keywords, as a file's tags by the flags.
    with pytest.warns(subcount.Warning, match="overrides"):
        uniform = subcount.Refinement(mesh, scheme="catmull-clark", levels=2, crease_method="uniform")
    assert not np.array_equal(uniform.evaluate(mesh.positions), r.evaluate(mesh.positions))


def test_tags_read_back_under_usd_names(tmp_path):
    mesh = tagged_cube()
    assert mesh.crease_indices.tolist() == [0, 1, 1, 2, 4, 5]
    assert mesh.crease_lengths.tolist() == [2, 2, 2]
    assert mesh.crease_sharpnesses.tolist() == [1.5, 3.0, 0.5]
    assert (mesh.corner_indices.tolist(), mesh.corner_sharpnesses.tolist()) == ([7], [2.0])
    assert mesh.hole_indices.tolist() == [1] and mesh.options == {"crease_method": "chaikin"}
    per_chain = subcount.Mesh(mesh.positions, mesh.face_vertex_counts, mesh.face_vertex_indices,
                              crease_indices=[0, 1, 2], crease_lengths=[3], crease_sharpnesses=[3.0])
    assert per_chain.crease_sharpnesses.tolist() == [3.0, 3.0]
    path = write_obj(tmp_path / "t.obj", *CUBE)
    path.write_text(path.read_text() + "t crease 2/1/0 0 3 4\nt interpolateboundary 1/0/0 1\n")
    read = subcount.read_mesh(path)
    assert read.crease_indices.tolist() == [0, 3] and read.options == {"boundary": "edge-and-corner"}
    plain = subcount.Mesh(*CUBE[:1], [4] * 6, [i for f in CUBE[1] for i in f])
    assert plain.crease_indices.size == 0 and plain.options == {}


@pytest.mark.parametrize(
    "keywords,error,match",
    [
        ({"crease_indices": [0, 9], "crease_lengths": [2], "crease_sharpnesses": [1]}, subcount.InputError, r"crease_indices\[1\] = 9"),
        ({"crease_indices": [0, 2], "crease_lengths": [2], "crease_sharpnesses": [1]}, subcount.InputError, "not an edge"),
        ({"crease_indices": [0, 1], "crease_lengths": [1], "crease_sharpnesses": [1]}, subcount.InputError, "at least 2"),
        ({"crease_indices": [0, 1, 2], "crease_lengths": [3], "crease_sharpnesses": [1, 2, 3]}, subcount.InputError, "one per chain"),
        ({"crease_indices": [0, 1], "crease_lengths": [2], "crease_sharpnesses": [-1]}, subcount.InputError, "not valid"),
        ({"crease_indices": [0, 1]}, subcount.UsageError, "go together"),
        ({"corner_indices": [0], "corner_sharpnesses": [1, 2]}, subcount.InputError, "one per corner"),
        ({"hole_indices": [6]}, subcount.InputError, r"hole_indices\[0\] = 6"),
        ({"hole_indices": [-1]}, subcount.InputError, "negative"),
        ({"options": {"boundary": "edgy"}}, subcount.UsageError, "edgy"),
        ({"options": {"speed": "fast"}}, subcount.UsageError, "unknown key"),
        ({"options": ["edge"]}, TypeError, "dict"),
        ({"crease_indices": [0.5, 1], "crease_lengths": [2], "crease_sharpnesses": [1]}, TypeError, "integers"),
    ],
)
def test_bad_tags_raise(keywords, error, match):
    positions, faces = CUBE
    with pytest.raises(error, match=match):
        subcount.Mesh(positions, [4] * 6, [i for f in faces for i in f], **keywords)


def test_stencils_are_the_evaluation():
    scipy = pytest.importorskip("scipy")
    import scipy.sparse
    positions = np.asarray(OCTAHEDRON[0], dtype=float)
    r = subcount.Refinement(OCTAHEDRON, scheme="loop", levels=3)
    s = r.stencils()
    assert s.shape == (r.n_vertices(), 6) and type(s) is scipy.sparse.csr_array
    assert np.allclose(s @ positions, r.evaluate(positions), rtol=0, atol=1e-14)
    assert np.allclose(s.sum(axis=1), 1.0)  # affine: every row's weights add up to 1
    # An unreferenced vertex is a column of zeros; its row in points is ignored.
    extra = np.vstack([positions, [[9.0, 9.0, 9.0]]])
    r2 = subcount.Refinement((extra, OCTAHEDRON[1]), scheme="loop", levels=1)
    assert r2.stencils().shape[1] == 7 and r2.stencils()[:, 6].nnz == 0
    assert same_bits(r2.evaluate(extra), subcount.subdivide((extra, OCTAHEDRON[1]), scheme="loop", levels=1).positions)
    with pytest.raises(subcount.InputError, match="not linear|linear"):
        subcount.Refinement(OCTAHEDRON, scheme="icosphere", levels=1).stencils()


def test_out_is_written_in_place_and_checked():
    positions = np.asarray(CUBE[0], dtype=float)
    r = subcount.Refinement(CUBE, scheme="catmull-clark", levels=2)
    buf = np.full((r.n_vertices(), 3), np.nan)
    assert r.evaluate(positions, out=buf) is buf and np.isfinite(buf).all()
    assert same_bits(buf, r.evaluate(positions))
    f32 = r.evaluate(positions.astype(np.float32))
    assert f32.dtype == np.float32 and np.abs(f32 - buf).max() < 1e-6
    for bad, error in [
        (np.empty((r.n_vertices() - 1, 3)), subcount.InputError),
        (np.empty((r.n_vertices(), 3), np.float32), TypeError),
        (np.empty((r.n_vertices(), 6))[:, ::2], subcount.InputError),
        (np.empty(3 * r.n_vertices()), subcount.InputError),
        ([[0.0] * 3] * r.n_vertices(), TypeError),
    ]:
        with pytest.raises(error):
            r.evaluate(positions, out=bad)
    with pytest.raises(subcount.InputError, match=r"points has 7 rows: expected one per vertex of the mesh \(8 rows\)"):
        r.evaluate(positions[:7])
    with pytest.raises(subcount.InputError, match=r"points\[2, 1\] is nan"):
        p = positions.copy()
        p[2, 1] = np.nan
        r.evaluate(p)
    with pytest.raises(TypeError):
        r.evaluate(positions.astype(str))
    with pytest.raises(subcount.InputError, match="rectangular"):
        r.evaluate([[0.0, 0.0, 0.0], [1.0, 2.0]])
    with pytest.raises(subcount.UsageError, match="not a level"):
        r.n_vertices(3)


def test_uvs_equal_subdivide():
    positions, faces = grid(4, 3)
    uvs = [[p[0] / 3.0, p[1] / 4.0] for p in positions]
    flat = [i for f in faces for i in f]
    mesh = subcount.Mesh(positions, [3] * len(faces), flat, uvs=uvs, uv_indices=flat)
    for scheme in ["loop", "catmull-clark"]:
        r = subcount.Refinement(mesh, scheme=scheme, levels=2, uv_interpolation="none")
        out = subcount.subdivide(mesh, scheme=scheme, levels=2, uv_interpolation="none")
        corner_uvs = r.evaluate_uvs()[r.uv_indices]
        assert same_bits(corner_uvs, out.uvs[out.uv_indices])
        assert r.n_uvs() == len(r.evaluate_uvs()) and r.base_uvs.shape[1] == 2
        moved = r.evaluate_uvs(r.base_uvs + 1.0)
        assert np.allclose(moved, r.evaluate_uvs() + 1.0, rtol=0, atol=1e-12)
    plain = subcount.Refinement(CUBE, scheme="catmull-clark", levels=1)
    assert plain.uv_indices is None and plain.base_uvs is None and plain.n_uvs() == 0
    with pytest.raises(subcount.UsageError, match="no UVs"):
        plain.evaluate_uvs()


def test_refusals():
    with pytest.raises(subcount.UsageError, match="raw face list"):
        subcount.Refinement(OCTAHEDRON, scheme="loop-general", levels=1)
    with pytest.raises(subcount.InputError):
        subcount.Refinement(OCTAHEDRON, scheme="catmull-clark-quad", levels=1)
    with pytest.raises(subcount.ResourceError):
        subcount.Refinement(OCTAHEDRON, scheme="loop", levels=14)
    with pytest.raises(subcount.UsageError):
        subcount.Refinement(OCTAHEDRON, scheme="loop", levels=-1)
    with pytest.raises(TypeError):
        subcount.Refinement(OCTAHEDRON, scheme="loop", levels="2")


def test_threads_give_the_same_bits_and_the_gil_is_released():
    positions, faces = grid(120, 120)
    positions = np.asarray(positions)
    results = [subcount.Refinement((positions, faces), scheme="loop", levels=2, threads=t).evaluate(positions) for t in (1, 2, 0)]
    assert same_bits(results[0], results[1]) and same_bits(results[0], results[2])
    r = subcount.Refinement((positions, faces), scheme="loop", levels=3, threads=1)
    ticks, done = [], threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.002)

    t = threading.Thread(target=tick)
    t.start()
    try:
        start = time.perf_counter()
        for _ in range(10):
            r.evaluate(positions)
        end = time.perf_counter()
    finally:
        done.set()
        t.join()
    assert len([x for x in ticks if start < x < end]) >= 3, end - start
