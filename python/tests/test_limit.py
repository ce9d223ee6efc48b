"""The limit surface from Python: subdivide(limit=True) is `subdivide --limit -o` to the bit,
Refinement(limit=True).evaluate_limit() is the same surface with its tangents (their cross
product the normals `--normals limit` writes), evaluate_uvs(limit=True) the limit UVs written,
and schemes without limit masks are refused as the CLI refuses them."""

import warnings

import numpy as np
import pytest

import subcount
from test_mesh import CUBE, OCTAHEDRON, SHARED_MESHES, assert_same_mesh, cli, cli_subdivide, same_bits, write_obj


@pytest.mark.parametrize("levels", [1, 2])
@pytest.mark.parametrize("scheme,shape", [("catmull-clark", CUBE), ("loop", OCTAHEDRON)])
def test_subdivide_limit_equals_cli_to_the_bit(tmp_path, scheme, shape, levels):
    src = write_obj(tmp_path / "in.obj", *shape)
    expected = cli_subdivide(src, tmp_path / "cli.obj", "--scheme", scheme, "--levels", levels, "--limit")
    ours = subcount.subdivide(src, scheme=scheme, levels=levels, limit=True)
    assert_same_mesh(ours, expected)
    r = subcount.Refinement(src, scheme=scheme, levels=levels, limit=True)
    assert r.limit
    assert same_bits(r.evaluate_limit(np.asarray(shape[0], float)), ours.positions)


def test_the_limit_of_a_tagged_mesh_with_uvs(tmp_path):
    path = SHARED_MESHES / "spot_control_mesh.obj"
    if not path.exists():
        pytest.skip(f"no shared mesh {path} (set SUBCOUNT_MESHES)")
    expected = cli_subdivide(path, tmp_path / "cli.obj", "--scheme", "catmull-clark", "--levels", 2, "--limit")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", subcount.Warning)
        ours = subcount.subdivide(path, scheme="catmull-clark", levels=2, limit=True)
        r = subcount.Refinement(path, scheme="catmull-clark", levels=2, limit=True)
    assert_same_mesh(ours, expected)
    assert same_bits(ours.uvs, expected.uvs)
    assert same_bits(r.evaluate_uvs(limit=True), expected.uvs)
    m = subcount.read_mesh(path)
    out = np.empty((r.n_vertices(), 3))
    assert r.evaluate_limit(m.positions, out=out) is not None
    assert same_bits(out, expected.positions)


def test_tangents_give_the_normals_the_cli_writes(tmp_path):
    src = write_obj(tmp_path / "in.obj", *CUBE)
    r = subcount.Refinement(src, scheme="catmull-clark", levels=2, limit=True)
    p, du, dv = r.evaluate_limit(np.asarray(CUBE[0], float), tangents=True)
    assert p.shape == du.shape == dv.shape == (r.n_vertices(), 3)
    out = tmp_path / "n.obj"
    run = cli("subdivide", "--mesh", src, "--scheme", "catmull-clark", "--levels", 2, "--limit", "--normals", "limit", "-o", out)
    assert run.returncode == 0, run.stderr
    vn = np.array([[float(x) for x in l.split()[1:]] for l in out.read_text().splitlines() if l.startswith("vn ")])
    n = np.cross(du, dv)
    n /= np.linalg.norm(n, axis=1)[:, None]
    # The cube is closed and convex: no normal is flipped or degenerate.
    assert np.allclose(n, vn, atol=1e-15)
    # float32 in, float32 out (tangents too).
    p32, du32, _ = r.evaluate_limit(np.asarray(CUBE[0], np.float32), tangents=True)
    assert p32.dtype == du32.dtype == np.float32
    assert np.allclose(p32, p, atol=1e-6)


def test_no_limit_is_refused_as_the_cli_refuses_it(tmp_path):
    src = write_obj(tmp_path / "in.obj", *CUBE)
    with pytest.raises(subcount.UsageError, match="loop, loop-boundary and catmull-clark"):
        subcount.subdivide(src, scheme="doo-sabin", levels=1, limit=True)
    with pytest.raises(subcount.UsageError, match="limit=True"):
        subcount.Refinement(src, scheme="catmull-clark", levels=1).evaluate_limit(np.asarray(CUBE[0], float))
    tri = write_obj(tmp_path / "tri.obj", *OCTAHEDRON)
    with pytest.raises(subcount.InputError, match="face 0 has 3 sides"):
        subcount.subdivide(tri, scheme="catmull-clark", levels=0, limit=True)
    with pytest.raises(TypeError, match="limit must be a bool"):
        subcount.subdivide(src, scheme="catmull-clark", levels=1, limit="yes")
