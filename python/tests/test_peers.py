"""subcount's Loop against its peers: libigl's `igl.loop` and trimesh's `remesh.subdivide_loop`.

On closed triangle meshes, levels 1-3, all three give the same vertex and face counts (and the
counts of V' = V + E, E' = 2E + 3F, F' = 4F). Positions:

* subcount follows OpenSubdiv's Loop (Sdc): an edge (odd) vertex is 3/8 (a + b) + 1/8 (c + d);
  an interior vertex of valence n moves to (1 - n beta) v + beta * (sum of its neighbours)
  with Loop's beta(n) = (1/n) (5/8 - (3/8 + 1/4 cos(2 pi / n))^2).
* trimesh 5.2 (`remesh.py`) implements the same rule: the same odd weights
  (`0.375 * e_v0 + 0.375 * e_v1 + e_v2 / 8.0 + e_v3 / 8.0`) and the same beta, written as
  `(40 - (2 cos(2 pi / k) + 3)^2) / (64 k)`. On closed meshes its positions equal subcount's
  up to the vertex order: max deviation measured 2.3e-16 of the bounding-box diagonal (eight.obj,
  level 3); asserted < 1e-12, and the faces are the same once the vertices are matched.
  Where it does not: on a mesh with boundary, trimesh moves a boundary vertex by
  3/4 v + 1/8 (sum of *every* neighbour that is a boundary vertex), not only of the two joined
  to it by boundary edges, so a boundary vertex with an interior edge to another boundary vertex
  gets weights summing to 9/8 (the open grid below: 4 of its 12 vertices, moved by 1/8 of the
  extra neighbour's position); everything else there agrees with subcount's `boundary="edge"`.
* libigl 2.6.3's `igl.loop` (compiled; judged by its numbers, and it is the rule of libigl's
  `loop.cpp`) uses the same odd weights but Warren's simplified even weight:
  beta = 3/16 for n = 3, 3/(8n) otherwise. The two betas coincide for n = 3 (3/16) and n = 6
  (1/16) only, so igl.loop equals subcount to 1.9e-16 of the diagonal at levels 1-3 on meshes
  whose vertices all have valence 3 or 6 (tetrahedron, torus.obj), and elsewhere differs:
  at level 1 exactly at the original vertices of valence not 3 or 6, by
  (3/(8n) - beta_Loop(n)) * (sum of neighbours - n v); from level 2 on the difference spreads to
  every vertex. Max deviations from subcount, relative to the diagonal, levels 1/2/3:
  octahedron (n = 4) 3.2e-2/2.4e-2/2.0e-2, icosahedron (n = 5) 8.5e-3/7.1e-3/6.0e-3,
  osd_loop_toroidal_tet.obj (n = 6, 8) 5.2e-3/4.9e-3/4.3e-3, eight.obj (n = 6, 7, 8)
  1.7e-4/1.6e-4/1.4e-4. Those positions are compared with a numpy reference of Loop with
  Warren's beta instead, which igl.loop equals to 1e-12 of the diagonal.

Meshes: a tetrahedron, an octahedron, an icosahedron and two disjoint bodies (trimesh
subdivides each connected body separately) built here, and small closed triangle meshes from
$SUBCOUNT_MESHES (relative paths from the repository root; default ../shared/meshes beside
the repository): those cases are skipped, with the reason, when the folder or the file is
missing. Vertices are matched by position with a KD-tree (scipy, which libigl requires).
"""

import functools

import numpy as np
import pytest

import subcount

from test_mesh import SHARED_MESHES as MESHES

TOL = 1e-12  # relative to the bounding-box diagonal of the input mesh
LEVELS = [1, 2, 3]

_PHI = (1 + 5**0.5) / 2
INLINE = {
    "tetrahedron": (
        [[1, 1, 1], [1, -1, -1], [-1, 1, -1], [-1, -1, 1]],
        [[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
    ),
    "octahedron": (
        [[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]],
        [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
    ),
    "icosahedron": (
        [[-1, _PHI, 0], [1, _PHI, 0], [-1, -_PHI, 0], [1, -_PHI, 0],
         [0, -1, _PHI], [0, 1, _PHI], [0, -1, -_PHI], [0, 1, -_PHI],
         [_PHI, 0, -1], [_PHI, 0, 1], [-_PHI, 0, -1], [-_PHI, 0, 1]],
        [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4],
         [11, 10, 2], [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8],
         [3, 8, 9], [4, 9, 5], [2, 4, 11], [6, 2, 10], [8, 6, 7], [9, 8, 1]],
    ),
}
# A tetrahedron and a (scaled, moved) octahedron in one mesh.
INLINE["two_bodies"] = (
    INLINE["tetrahedron"][0] + [[2.5 * x + 4, 1.5 * y, z - 0.5] for x, y, z in INLINE["octahedron"][0]],
    INLINE["tetrahedron"][1] + [[a + 4, b + 4, c + 4] for a, b, c in INLINE["octahedron"][1]],
)
# Closed triangle meshes of $SUBCOUNT_MESHES under 5k faces: 20, 72, 2400 and 1536 faces.
FILES = ["osd_loop_icosahedron.obj", "osd_loop_toroidal_tet.obj", "torus.obj", "eight.obj"]
MESH_NAMES = list(INLINE) + FILES


def loop_beta(n):
    """Loop's (1987) even weight, OpenSubdiv's Sdc Loop for a smooth interior vertex."""
    n = np.asarray(n, dtype=float)
    return (5 / 8 - (3 / 8 + np.cos(2 * np.pi / n) / 4) ** 2) / n


def warren_beta(n):
    """Warren's simplified even weight: 3/16 for valence 3, else 3/(8n)."""
    n = np.asarray(n, dtype=float)
    return np.where(n == 3, 3 / 16, 3 / (8 * n))


# --- meshes ----------------------------------------------------------------------------------


def assert_closed_triangle_mesh(V, F):
    """Every directed edge once and its reverse once (closed, manifold edges, oriented), every
    vertex used, no face with a repeated vertex."""
    assert F.ndim == 2 and F.shape[1] == 3 and len(F) > 0
    assert (F[:, 0] != F[:, 1]).all() and (F[:, 1] != F[:, 2]).all() and (F[:, 2] != F[:, 0]).all()
    directed = np.stack([F.reshape(-1), np.roll(F, -1, axis=1).reshape(-1)], axis=1)
    assert len(np.unique(directed, axis=0)) == len(directed), "an edge is used twice in one direction"
    undirected, counts = np.unique(np.sort(directed, axis=1), axis=0, return_counts=True)
    assert (counts == 2).all(), f"{(counts == 1).sum()} boundary and {(counts > 2).sum()} non-manifold edges"
    assert np.array_equal(np.unique(F), np.arange(len(V))), "unused vertices"


@functools.lru_cache(maxsize=None)
def mesh(name):
    """(V, F): float64 (N, 3) and int64 (F, 3), read-only, checked closed."""
    if name in INLINE:
        V, F = (np.array(a, dtype=dt) for a, dt in zip(INLINE[name], (np.float64, np.int64)))
    else:
        if not MESHES.is_dir():
            pytest.skip(f"no meshes folder {MESHES} (set SUBCOUNT_MESHES)")
        path = MESHES / name
        if not path.is_file():
            pytest.skip(f"{path} not found")
        m = subcount.read_mesh(str(path))
        assert (m.face_vertex_counts == 3).all(), f"{name} is not a triangle mesh"
        V = np.array(m.positions, dtype=np.float64)
        F = np.array(m.face_vertex_indices, dtype=np.int64).reshape(-1, 3)
    assert_closed_triangle_mesh(V, F)
    V.flags.writeable = F.flags.writeable = False
    return V, F


def diagonal(V):
    return float(np.linalg.norm(V.max(axis=0) - V.min(axis=0)))


def counts(V, F):
    E = len(np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0))
    return len(V), E, len(F)


def valences(F, n):
    edges = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0)
    return np.bincount(edges.reshape(-1), minlength=n)


# --- the three subdivisions and a reference ----------------------------------------------------


@functools.lru_cache(maxsize=None)
def ours(name, levels):
    V, F = mesh(name)
    out = subcount.subdivide((V, F), scheme="loop", levels=levels)
    assert isinstance(out, subcount.Mesh)
    assert (out.face_vertex_counts == 3).all()
    assert out.positions.shape == (out.n_vertices, 3) and out.positions.dtype == np.float64
    assert out.face_vertex_indices.shape == (3 * out.n_faces,)
    return out.positions, out.face_vertex_indices.reshape(-1, 3).astype(np.int64)


@functools.lru_cache(maxsize=None)
def igl_loop(name, levels):
    igl = pytest.importorskip("igl")
    V, F = mesh(name)
    NV, NF = igl.loop(V, F, number_of_subdivs=levels)
    return np.asarray(NV, dtype=np.float64), np.asarray(NF, dtype=np.int64)


@functools.lru_cache(maxsize=None)
def trimesh_loop(name, levels):
    remesh = pytest.importorskip("trimesh.remesh")
    V, F = mesh(name)
    NV, NF = remesh.subdivide_loop(np.array(V), np.array(F), iterations=levels)
    return np.asarray(NV, dtype=np.float64), np.asarray(NF, dtype=np.int64)


def reference_loop(V, F, levels, beta):
    """Loop subdivision of a closed triangle mesh in numpy: odd 3/8, 3/8, 1/8, 1/8; even
    (1 - n beta(n)) v + beta(n) * (sum of neighbours). Evens first, in the input's order."""
    V, F = np.asarray(V, dtype=np.float64), np.asarray(F, dtype=np.int64)
    for _ in range(levels):
        n = len(V)
        a, b, c = (np.roll(F, -s, axis=1).reshape(-1) for s in range(3))  # edge a->b, opposite c
        edges, edge_of = np.unique(np.sort(np.stack([a, b], axis=1), axis=1), axis=0, return_inverse=True)
        edge_of = edge_of.reshape(-1)
        odd = 3 / 8 * (V[edges[:, 0]] + V[edges[:, 1]])
        np.add.at(odd, edge_of, V[c] / 8)
        k = np.bincount(edges.reshape(-1), minlength=n)
        ring = np.zeros_like(V)
        np.add.at(ring, edges[:, 0], V[edges[:, 1]])
        np.add.at(ring, edges[:, 1], V[edges[:, 0]])
        bk = beta(k)[:, None]
        even = (1 - k[:, None] * bk) * V + bk * ring
        e = n + edge_of.reshape(-1, 3)  # e[:, j]: the child of edge F[:, j] -> F[:, j + 1]
        F = np.concatenate([
            np.stack([F[:, 0], e[:, 0], e[:, 2]], axis=1),
            np.stack([F[:, 1], e[:, 1], e[:, 0]], axis=1),
            np.stack([F[:, 2], e[:, 2], e[:, 1]], axis=1),
            e,
        ])
        V = np.vstack([even, odd])
    return V, F


# --- matching ----------------------------------------------------------------------------------


def match(mine, theirs, tol):
    """perm with theirs[i] == mine[perm[i]] within tol (absolute), a bijection; returns (perm, max
    deviation). Asserts the points of `mine` are far enough apart for the match to be unique."""
    spatial = pytest.importorskip("scipy.spatial")
    assert mine.shape == theirs.shape, (mine.shape, theirs.shape)
    tree = spatial.cKDTree(mine)
    gap = tree.query(mine, k=2)[0][:, 1].min()
    assert gap > 1e3 * tol, f"points {gap} apart: a match within {tol} would be ambiguous"
    dist, perm = tree.query(theirs)
    assert dist.max() <= tol, f"max deviation {dist.max()} > {tol} at {np.count_nonzero(dist > tol)} vertices"
    assert len(np.unique(perm)) == len(mine), "not a one-to-one match"
    return perm, float(dist.max())


def distances_to(points, queries):
    """Distance from each query to the nearest of points."""
    spatial = pytest.importorskip("scipy.spatial")
    return spatial.cKDTree(points).query(queries)[0]


def canonical_faces(F):
    """Each triangle rotated to start at its smallest index (orientation kept), rows sorted."""
    F = np.asarray(F)
    r = np.argmin(F, axis=1)
    rotated = F[np.arange(len(F))[:, None], (r[:, None] + np.arange(3)) % 3]
    return rotated[np.lexsort(rotated.T[::-1])]


def assert_same_mesh_up_to_order(mine, theirs, tol):
    perm, dev = match(mine[0], theirs[0], tol)
    assert np.array_equal(canonical_faces(mine[1]), canonical_faces(perm[theirs[1]])), "different faces"
    return perm, dev


# --- counts ----------------------------------------------------------------------------------


@pytest.mark.parametrize("levels", LEVELS)
@pytest.mark.parametrize("name", MESH_NAMES)
def test_counts_equal_igl_and_trimesh(name, levels):
    V, F = mesh(name)
    nv, ne, nf = counts(V, F)
    for _ in range(levels):
        nv, ne, nf = nv + ne, 2 * ne + 3 * nf, 4 * nf
    mine = ours(name, levels)
    assert (len(mine[0]), len(mine[1])) == (nv, nf)
    assert counts(*mine)[1] == ne
    for peer in (igl_loop, trimesh_loop):
        NV, NF = peer(name, levels)
        assert NV.shape == (nv, 3) and NF.shape == (nf, 3), (peer.__name__, NV.shape, NF.shape)


# --- positions: trimesh ------------------------------------------------------------------------


@pytest.mark.parametrize("levels", LEVELS)
@pytest.mark.parametrize("name", MESH_NAMES)
def test_positions_equal_trimesh(name, levels):
    """Same rule on closed meshes: same positions and faces up to the vertex order."""
    V, F = mesh(name)
    tol = TOL * diagonal(V)
    assert_same_mesh_up_to_order(ours(name, levels), trimesh_loop(name, levels), tol)
    # ... and that rule is Loop's beta, not Warren's (they differ here unless all valences are 3 or 6).
    assert_same_mesh_up_to_order(ours(name, levels), reference_loop(V, F, levels, loop_beta), tol)


def grid(w=3, h=2):
    """The open triangle grid of test_mesh.py."""
    V = [[x * 0.7, y * 1.3, 0.1 * x * y + 0.05 * x * x] for y in range(h + 1) for x in range(w + 1)]
    F = []
    for y in range(h):
        for x in range(w):
            a = y * (w + 1) + x
            b, c, d = a + 1, a + w + 2, a + w + 1
            F += [[a, b, c], [a, c, d]]
    return np.array(V, dtype=np.float64), np.array(F, dtype=np.int64)


def test_trimesh_differs_at_boundary_vertices_joined_by_an_interior_edge():
    """Where trimesh's rule is not subcount's: boundary vertices (open grid, level 1)."""
    remesh = pytest.importorskip("trimesh.remesh")
    V, F = grid()
    n = len(V)
    tol = TOL * diagonal(V)
    out = subcount.subdivide((V, F), scheme="loop", levels=1, boundary="edge")
    mine = out.positions
    TV, TF = remesh.subdivide_loop(V.copy(), F.copy(), iterations=1)
    assert TV.shape == mine.shape and TF.shape == (4 * len(F), 3)

    # trimesh: the n even vertices first, in the input's order, then the odd ones: all of
    # those (3/8, 3/8, 1/8, 1/8 inside, midpoints on the boundary) are subcount's.
    assert distances_to(mine, TV[n:]).max() <= tol

    edges, cnt = np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1),
                           axis=0, return_counts=True)
    boundary_edges, interior_edges = edges[cnt == 1], edges[cnt == 2]
    on_boundary = np.zeros(n, dtype=bool)
    on_boundary[boundary_edges.reshape(-1)] = True
    k = np.bincount(edges.reshape(-1), minlength=n)

    def ring(es, i):
        return [b for a, b in es if a == i] + [a for a, b in es if b == i]

    crossed = set(interior_edges[on_boundary[interior_edges].all(axis=1)].reshape(-1).tolist())
    assert crossed == {2, 4, 7, 9}
    for i in range(n):
        if on_boundary[i]:  # subcount (boundary="edge"): 3/4 v + 1/8 (the two boundary-edge neighbours)
            b = ring(boundary_edges, i)
            assert len(b) == 2
            expected = 3 / 4 * V[i] + (V[b[0]] + V[b[1]]) / 8
        else:
            beta = loop_beta(k[i])
            expected = (1 - k[i] * beta) * V[i] + beta * V[ring(edges, i)].sum(axis=0)
        assert distances_to(mine, expected[None])[0] <= tol, i  # subcount has it
        if i in crossed:  # trimesh: 3/4 v + 1/8 (every neighbour on the boundary): 3 of them here
            nb = [j for j in ring(edges, i) if on_boundary[j]]
            assert len(nb) == 3
            assert np.abs(TV[i] - (3 / 4 * V[i] + V[nb].sum(axis=0) / 8)).max() <= tol
            assert np.linalg.norm(TV[i] - expected) > 1e-2 * diagonal(V)  # weights sum to 9/8
        else:
            assert np.abs(TV[i] - expected).max() <= tol, i


# --- positions: igl ----------------------------------------------------------------------------


def igl_against_ours(name, levels):
    """(subcount's positions, igl's positions), both in the vertex order of reference_loop: subcount
    matched (positions and faces) to the reference with Loop's beta, igl to the one with Warren's."""
    V, F = mesh(name)
    tol = TOL * diagonal(V)
    mine, theirs = ours(name, levels), igl_loop(name, levels)
    ref_loop = reference_loop(V, F, levels, loop_beta)
    ref_warren = reference_loop(V, F, levels, warren_beta)
    assert np.array_equal(ref_loop[1], ref_warren[1])
    p_ours, _ = assert_same_mesh_up_to_order(mine, ref_loop, tol)
    p_igl, _ = assert_same_mesh_up_to_order(theirs, ref_warren, tol)  # igl.loop is Warren's Loop
    return mine[0][p_ours], theirs[0][p_igl]


@pytest.mark.parametrize("levels", LEVELS)
@pytest.mark.parametrize("name", ["tetrahedron", "torus.obj"])
def test_positions_equal_igl_where_all_valences_are_3_or_6(name, levels):
    """Warren's beta is Loop's for n = 3 (3/16) and n = 6 (1/16): the same positions and faces."""
    V, F = mesh(name)
    assert set(valences(F, len(V)).tolist()) <= {3, 6}
    assert_same_mesh_up_to_order(ours(name, levels), igl_loop(name, levels), TOL * diagonal(V))


def test_the_two_betas_agree_for_valences_3_and_6_only():
    n = np.arange(3, 13)
    same = np.isclose(loop_beta(n), warren_beta(n), rtol=1e-15, atol=0)
    assert n[same].tolist() == [3, 6]
    assert loop_beta(3) == pytest.approx(3 / 16, abs=1e-16) and loop_beta(6) == pytest.approx(1 / 16, abs=1e-16)
    assert loop_beta(4) == pytest.approx(31 / 256, abs=1e-16)  # Warren: 3/32 = 24/256


@pytest.mark.parametrize("levels", LEVELS)
@pytest.mark.parametrize("name", MESH_NAMES)
def test_igl_is_loop_with_warren_beta(name, levels):
    """igl.loop equals Loop with Warren's beta (to 1e-12 of the diagonal) on every mesh; it
    differs from subcount wherever a valence is not 3 or 6 (by more than 1e-5 of the diagonal)."""
    V, F = mesh(name)
    mine, theirs = igl_against_ours(name, levels)
    deviation = np.linalg.norm(mine - theirs, axis=1).max() / diagonal(V)
    if set(valences(F, len(V)).tolist()) <= {3, 6}:
        assert deviation <= TOL
    else:
        assert deviation > 1e-5


@pytest.mark.parametrize("name", MESH_NAMES)
def test_igl_level_1_differs_at_even_vertices_of_valence_not_3_or_6_by_the_beta_difference(name):
    """Level 1: the odd vertices agree; igl's even vertex of v (valence n) is subcount's plus
    (beta_Warren(n) - beta_Loop(n)) * (sum of neighbours - n v), which is 0 for n = 3 and 6 only."""
    V, F = mesh(name)
    n = len(V)
    tol = TOL * diagonal(V)
    mine, theirs = igl_against_ours(name, 1)  # reference order: the n evens, then the odds
    assert np.abs(mine[n:] - theirs[n:]).max() <= tol
    k = valences(F, n)
    ring = np.zeros_like(V)
    for a, b in np.unique(np.sort(np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]]), axis=1), axis=0):
        ring[a] += V[b]
        ring[b] += V[a]
    expected = (warren_beta(k) - loop_beta(k))[:, None] * (ring - k[:, None] * V)
    assert np.abs((theirs[:n] - mine[:n]) - expected).max() <= tol
    moved = np.linalg.norm(theirs[:n] - mine[:n], axis=1)
    special = np.isin(k, [3, 6])
    assert (moved[special] <= tol).all()
    assert (moved[~special] > 1e-5 * diagonal(V)).all()
    assert special.all() == (name in ("tetrahedron", "torus.obj"))  # the meshes cover both cases
