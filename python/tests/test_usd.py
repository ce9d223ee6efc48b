"""examples/python/usd_subdivide.py against the CLI: a UsdGeom.Mesh read with usd-core and
subdivided by subcount equals, to the bit, the CLI's run on an OBJ file holding the same data
as OpenSubdiv tags (the OBJ is written here from the raw USD data, independently of the
example's reader).

Precision: USD holds points, st and sharpnesses as float32; both sides widen them to float64
exactly (the OBJ gets the float64 value of each float32, written with repr). The example returns
subcount's float64 result, compared to the CLI's float64 OBJ to the bit; the written stage
holds point3f/texCoord2f (the schema's types), compared to the float32 cast of that result to
the bit.

The CLI binary is $SUBCOUNT_BIN (as in test_mesh.py); tests that need it
skip without it. Every input is generated in tmp_path.
"""

import importlib.util
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

pxr = pytest.importorskip("pxr")
from pxr import Gf, Sdf, Usd, UsdGeom, Vt  # noqa: E402

import subcount  # noqa: E402
from test_mesh import SUBCOUNT_BIN  # noqa: E402
from test_mesh import grid as tri_grid  # noqa: E402  (the open triangle grid)

EXAMPLE = Path(__file__).resolve().parents[2] / "examples" / "python" / "usd_subdivide.py"


def load_example():
    spec = importlib.util.spec_from_file_location("usd_subdivide", EXAMPLE)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


usd_subdivide = load_example()

# A cube with coordinates that are not round (nor exact in float32), quads facing outwards.
CUBE_POINTS = [
    [0.0, 0.0, 0.0], [1.1, 0.0, 0.05], [1.0, 1.2, 0.0], [0.0, 1.0, 0.1],
    [0.0, -0.1, 1.0], [1.0, 0.0, 0.9], [1.3, 1.0, 1.0], [0.0, 1.1, 1.0],
]
CUBE_FACES = [[0, 3, 2, 1], [4, 5, 6, 7], [0, 1, 5, 4], [1, 2, 6, 5], [2, 3, 7, 6], [3, 0, 4, 7]]
OCTAHEDRON_POINTS = [[1, 0, 0.1], [-1, 0, 0], [0, 1.2, 0], [0, -1, 0], [0, 0.1, 1], [0, 0, -0.9]]
OCTAHEDRON_FACES = [[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]]
# A cube with a roof: quads and triangles.
HOUSE_POINTS = CUBE_POINTS[:4] + [[0.5, 0.5, 1.7]]
HOUSE_FACES = [[0, 3, 2, 1], [0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]]


def quad_grid(w=3, h=3):
    points = [[x * 0.7, y * 1.3, 0.1 * x * y + 0.05 * x * x] for y in range(h + 1) for x in range(w + 1)]
    faces = []
    for y in range(h):
        for x in range(w):
            a = y * (w + 1) + x
            faces.append([a, a + 1, a + w + 2, a + w + 1])
    return points, faces


def layout(points, faces, seam_faces=()):
    """A UV layout: each corner's value from its vertex, offset on seam_faces (so there are
    seams); returns (values, indices) with the values deduplicated (an indexed primvar)."""
    corner_uvs = []
    for f, face in enumerate(faces):
        shift = 2.0 if f in seam_faces else 0.0
        for v in face:
            x, y, z = points[v]
            corner_uvs.append((0.9 * x + 0.3 * z + shift, 0.8 * y + 0.2 * z))
    values, indices = np.unique(np.asarray(corner_uvs, np.float32), axis=0, return_inverse=True)
    return values, indices.ravel()


# --- stages and OBJ files from the same data -------------------------------------------


class Spec:
    """The data of a mesh prim: what is authored (None: not authored, the fallback)."""

    def __init__(self, points, faces, **kw):
        self.points = points
        self.faces = faces
        self.scheme = kw.pop("scheme", None)
        self.interpolate_boundary = kw.pop("interpolate_boundary", None)
        self.fvar = kw.pop("fvar", None)
        self.triangle_rule = kw.pop("triangle_rule", None)
        self.orientation = kw.pop("orientation", None)
        self.creases = kw.pop("creases", None)  # (indices, lengths, sharpnesses)
        self.corners = kw.pop("corners", None)  # (indices, sharpnesses)
        self.holes = kw.pop("holes", None)
        self.st = kw.pop("st", None)  # (values, indices or None, interpolation)
        assert not kw, kw


def write_stage(path, spec, prim_path="/World/mesh"):
    stage = Usd.Stage.CreateNew(str(path))
    UsdGeom.Xform.Define(stage, Sdf.Path(prim_path).GetParentPath())
    mesh = UsdGeom.Mesh.Define(stage, prim_path)
    mesh.CreatePointsAttr([Gf.Vec3f(*p) for p in spec.points])
    mesh.CreateFaceVertexCountsAttr([len(f) for f in spec.faces])
    mesh.CreateFaceVertexIndicesAttr([v for f in spec.faces for v in f])
    if spec.scheme is not None:
        mesh.CreateSubdivisionSchemeAttr(spec.scheme)
    if spec.interpolate_boundary is not None:
        mesh.CreateInterpolateBoundaryAttr(spec.interpolate_boundary)
    if spec.fvar is not None:
        mesh.CreateFaceVaryingLinearInterpolationAttr(spec.fvar)
    if spec.triangle_rule is not None:
        mesh.CreateTriangleSubdivisionRuleAttr(spec.triangle_rule)
    if spec.orientation is not None:
        mesh.CreateOrientationAttr(spec.orientation)
    if spec.creases is not None:
        indices, lengths, sharpnesses = spec.creases
        mesh.CreateCreaseIndicesAttr(indices)
        mesh.CreateCreaseLengthsAttr(lengths)
        mesh.CreateCreaseSharpnessesAttr(sharpnesses)
    if spec.corners is not None:
        mesh.CreateCornerIndicesAttr(spec.corners[0])
        mesh.CreateCornerSharpnessesAttr(spec.corners[1])
    if spec.holes is not None:
        mesh.CreateHoleIndicesAttr(spec.holes)
    if spec.st is not None:
        values, indices, interpolation = spec.st
        primvar = UsdGeom.PrimvarsAPI(mesh).CreatePrimvar("st", Sdf.ValueTypeNames.TexCoord2fArray, interpolation)
        primvar.Set(Vt.Vec2fArray.FromNumpy(np.asarray(values, np.float32)))
        if indices is not None:
            primvar.SetIndices(Vt.IntArray([int(i) for i in indices]))
    stage.SetDefaultPrim(stage.GetPrimAtPath("/World"))
    stage.GetRootLayer().Save()
    return path


def f32(x):
    """The float64 value of x stored as float32, as OBJ text that reads back exactly."""
    return repr(float(np.float32(x)))


BOUNDARY_TAG = {"none": 0, "edgeAndCorner": 1, "edgeOnly": 2}
FVAR_TAG = {"none": 0, "cornersOnly": 1, "cornersPlus1": 2, "cornersPlus2": 3, "boundaries": 4, "all": 5}
TRIANGLE_TAG = {"catmullClark": "catmark", "smooth": "smooth"}


def write_obj(path, spec):
    """The spec as an OBJ file with OpenSubdiv tags, USD's fallbacks written out."""
    lines = ["v " + " ".join(f32(c) for c in p) for p in spec.points]
    flip = spec.orientation == "leftHanded"
    corner_uv = None
    if spec.st is not None:
        values, indices, interpolation = spec.st
        lines += ["vt " + " ".join(f32(c) for c in uv) for uv in values]
        per_value = list(indices) if indices is not None else list(range(len(values)))
        if interpolation == UsdGeom.Tokens.faceVarying:
            corner_uv = per_value
        else:  # vertex: a corner takes its vertex's value
            corner_uv = [per_value[v] for f in spec.faces for v in f]
    corner = 0
    for face in spec.faces:
        refs = []
        for v in face:
            refs.append(f"{v + 1}" if corner_uv is None else f"{v + 1}/{corner_uv[corner] + 1}")
            corner += 1
        if flip:  # pxOsd's flip: the first corner stays, the others reversed
            refs = refs[:1] + refs[1:][::-1]
        lines.append("f " + " ".join(refs))
    if spec.creases is not None:
        indices, lengths, sharpnesses = spec.creases
        per_edge = len(sharpnesses) != len(lengths)
        start, s = 0, 0
        for length in lengths:
            for j in range(length - 1):
                a, b = indices[start + j], indices[start + j + 1]
                lines.append(f"t crease 2/1/0 {a} {b} {f32(sharpnesses[s])}")
                s += per_edge
            s += not per_edge
            start += length
    if spec.corners is not None:
        for v, sharpness in zip(*spec.corners):
            lines.append(f"t corner 1/1/0 {v} {f32(sharpness)}")
    for face in spec.holes or []:
        lines.append(f"t hole 1/0/0 {face}")
    lines.append(f"t interpolateboundary 1/0/0 {BOUNDARY_TAG[spec.interpolate_boundary or 'edgeAndCorner']}")
    lines.append(f"t facevaryinginterpolateboundary 1/0/0 {FVAR_TAG[spec.fvar or 'cornersPlus1']}")
    lines.append(f"t smoothtriangles 0/0/1 {TRIANGLE_TAG[spec.triangle_rule or 'catmullClark']}")
    Path(path).write_text("\n".join(lines) + "\n")
    return path


def cli(*args):
    if not Path(SUBCOUNT_BIN).exists():
        pytest.skip(f"no CLI binary at {SUBCOUNT_BIN}: run `cargo build -p subcount` (or set SUBCOUNT_BIN)")
    return subprocess.run([SUBCOUNT_BIN, *map(str, args)], capture_output=True, text=True)


def same_bits(a, b):
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    assert a.shape == b.shape and a.dtype == b.dtype, (a.shape, b.shape, a.dtype, b.dtype)
    return np.array_equal(a.view(np.uint8), b.view(np.uint8))


TAG_ATTRIBUTES = [
    "creaseIndices", "creaseLengths", "creaseSharpnesses", "cornerIndices", "cornerSharpnesses",
    "holeIndices", "interpolateBoundary", "faceVaryingLinearInterpolation", "triangleSubdivisionRule",
]


def check_written(out_path, result, prim_path="/World/mesh"):
    """The written stage holds result: float32 points and st (to the bit), the faces, scheme
    none, rightHanded, and no tag attributes."""
    stage = Usd.Stage.Open(str(out_path))
    prim = stage.GetPrimAtPath(prim_path)
    assert prim and prim.IsA(UsdGeom.Mesh)
    mesh = UsdGeom.Mesh(prim)
    points = np.asarray(mesh.GetPointsAttr().Get())
    assert points.dtype == np.float32
    assert same_bits(points, result.positions.astype(np.float32))
    assert np.array_equal(np.asarray(mesh.GetFaceVertexCountsAttr().Get()), result.face_vertex_counts)
    assert np.array_equal(np.asarray(mesh.GetFaceVertexIndicesAttr().Get()), result.face_vertex_indices)
    assert mesh.GetSubdivisionSchemeAttr().HasAuthoredValue()
    assert mesh.GetSubdivisionSchemeAttr().Get() == "none"
    assert mesh.GetOrientationAttr().Get() == "rightHanded"
    for name in TAG_ATTRIBUTES:
        assert not prim.GetAttribute(name).HasAuthoredValue(), name
    text = stage.GetRootLayer().ExportToString()
    for word in ("crease", "corner", "hole"):
        assert word not in text
    st = UsdGeom.PrimvarsAPI(mesh).GetPrimvar("st")
    if result.uvs is None:
        assert not st
    else:
        assert st.GetInterpolation() == UsdGeom.Tokens.faceVarying and st.IsIndexed()
        values = np.asarray(st.Get())
        assert values.dtype == np.float32
        assert same_bits(values, result.uvs.astype(np.float32))
        assert np.array_equal(np.asarray(st.GetIndices()), result.uv_indices)
    # extent: the bounding box of the float32 points.
    extent = np.asarray(mesh.GetExtentAttr().Get())
    assert np.array_equal(extent, [points.min(axis=0), points.max(axis=0)])
    return stage


# --- the cases: example vs CLI ------------------------------------------------------------

CUBE_UV = layout(CUBE_POINTS, CUBE_FACES, seam_faces=(4, 5))
CUBE_UV_CORNERS = CUBE_UV[0][CUBE_UV[1]]  # the same layout, not indexed
CUBE_VERTEX_UV = np.asarray([[0.9 * x + 0.3 * z, 0.8 * y + 0.2 * z] for x, y, z in CUBE_POINTS], np.float32)
GRID = quad_grid()
TRI_GRID = tri_grid()
TRI_GRID_UV = layout(*TRI_GRID, seam_faces=(0, 1, 2))
FV = UsdGeom.Tokens.faceVarying
VERTEX = UsdGeom.Tokens.vertex

CASES = {
    # One sharpness per chain; a corner; every option unset (USD's fallbacks).
    "cube-crease-chain": Spec(CUBE_POINTS, CUBE_FACES, creases=([0, 1, 2], [3], [2.5]), corners=([6], [3.0])),
    # One sharpness per edge (3 edges over 2 chains), an infinitely sharp one; a hole: the
    # boundary mode matters, unset (edgeAndCorner) here, authored below.
    "cube-crease-per-edge-hole": Spec(
        CUBE_POINTS, CUBE_FACES, creases=([0, 1, 2, 4, 5], [3, 2], [1.3, 10.0, 0.7]), holes=[1]
    ),
    "cube-hole-edge-only": Spec(
        CUBE_POINTS, CUBE_FACES, creases=([3, 7], [2], [4.0]), holes=[1], interpolate_boundary="edgeOnly"
    ),
    "grid-boundary-unset": Spec(*GRID),
    "grid-boundary-edge-only": Spec(*GRID, interpolate_boundary="edgeOnly"),
    "grid-boundary-edge-and-corner": Spec(*GRID, interpolate_boundary="edgeAndCorner"),
    "grid-boundary-none": Spec(*GRID, interpolate_boundary="none"),
    "grid-corner-and-crease": Spec(*GRID, creases=([4, 5, 6, 7], [4], [1.5]), corners=([5, 10], [2.0, 10.0])),
    "cube-st-facevarying-indexed": Spec(CUBE_POINTS, CUBE_FACES, st=(CUBE_UV[0], CUBE_UV[1], FV)),
    "cube-st-facevarying-flat": Spec(CUBE_POINTS, CUBE_FACES, st=(CUBE_UV_CORNERS, None, FV)),
    "cube-st-fvar-all": Spec(CUBE_POINTS, CUBE_FACES, st=(CUBE_UV[0], CUBE_UV[1], FV), fvar="all"),
    "cube-st-fvar-none-creased": Spec(
        CUBE_POINTS, CUBE_FACES, st=(CUBE_UV[0], CUBE_UV[1], FV), fvar="none", creases=([0, 1, 2], [3], [3.0])
    ),
    "cube-st-vertex": Spec(CUBE_POINTS, CUBE_FACES, st=(CUBE_VERTEX_UV, None, VERTEX)),
    "cube-st-vertex-indexed": Spec(
        CUBE_POINTS, CUBE_FACES, st=(CUBE_VERTEX_UV[:4], [0, 1, 2, 3, 3, 2, 1, 0], VERTEX)
    ),
    "cube-left-handed": Spec(CUBE_POINTS, [f[::-1] for f in CUBE_FACES], orientation="leftHanded"),
    "cube-left-handed-st-crease-hole": Spec(
        CUBE_POINTS,
        [f[::-1] for f in CUBE_FACES],
        orientation="leftHanded",
        st=(CUBE_UV[0], CUBE_UV[1], FV),
        creases=([0, 1, 2], [3], [2.0]),
        corners=([7], [1.5]),
        holes=[2],
    ),
    "house-smooth-triangles": Spec(HOUSE_POINTS, HOUSE_FACES, triangle_rule="smooth", holes=[0]),
    "house-catmark-triangles": Spec(HOUSE_POINTS, HOUSE_FACES, triangle_rule="catmullClark"),
    "octahedron-loop": Spec(
        OCTAHEDRON_POINTS, OCTAHEDRON_FACES, scheme="loop", creases=([0, 2, 1], [3], [2.0]), corners=([4], [5.0])
    ),
    "tri-grid-loop-st": Spec(*TRI_GRID, scheme="loop", st=(TRI_GRID_UV[0], TRI_GRID_UV[1], FV)),
    "tri-grid-loop-edge-only-hole": Spec(*TRI_GRID, scheme="loop", interpolate_boundary="edgeOnly", holes=[3]),
    "tri-grid-loop-left-handed-st": Spec(
        TRI_GRID[0],
        [f[::-1] for f in TRI_GRID[1]],
        scheme="loop",
        orientation="leftHanded",
        st=(TRI_GRID_UV[0], TRI_GRID_UV[1], FV),
        fvar="cornersOnly",
    ),
}


def run_both(tmp_path, spec, levels=2, flags=(), **overrides):
    """The example's result (and its output path) and the CLI's on the OBJ twin."""
    src = write_stage(tmp_path / "in.usda", spec)
    obj = write_obj(tmp_path / "in.obj", spec)
    scheme = "loop" if spec.scheme == "loop" else "catmull-clark"
    run = cli("subdivide", "--mesh", obj, "--scheme", scheme, "--levels", levels, *flags, "-o", tmp_path / "cli.obj")
    assert run.returncode == 0, run.stderr
    expected = subcount.read_mesh(tmp_path / "cli.obj")
    out = tmp_path / "out.usda"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", subcount.Warning)  # the same notes as the CLI's stderr
        result = usd_subdivide.subdivide_usd(src, out, levels, **overrides)
    return result, expected, out


def assert_same(result, expected):
    assert result.positions.dtype == np.float64
    assert same_bits(result.positions, expected.positions)
    assert np.array_equal(result.face_vertex_counts, expected.face_vertex_counts)
    assert np.array_equal(result.face_vertex_indices, expected.face_vertex_indices)
    assert (result.uvs is None) == (expected.uvs is None)
    if result.uvs is not None:
        assert same_bits(result.uvs, expected.uvs)
        assert np.array_equal(result.uv_indices, expected.uv_indices)


@pytest.mark.parametrize("name", list(CASES))
def test_example_equals_cli_to_the_bit(tmp_path, name):
    spec = CASES[name]
    result, expected, out = run_both(tmp_path, spec)
    assert_same(result, expected)
    assert (result.uvs is not None) == (spec.st is not None)
    check_written(out, result)


@pytest.mark.parametrize(
    "overrides,flags",
    [
        ({"boundary": "edge"}, ["--boundary", "edge"]),
        ({"boundary": "none"}, ["--boundary", "none"]),
        ({"crease_method": "chaikin"}, ["--crease-method", "chaikin"]),
        ({"uv_interpolation": "all"}, ["--uv-interpolation", "all"]),
        ({"no_uv": True}, ["--no-uv"]),
    ],
    ids=["boundary-edge", "boundary-none", "chaikin", "uv-all", "no-uv"],
)
def test_overrides_equal_cli_flags(tmp_path, overrides, flags):
    spec = Spec(
        *GRID,
        creases=([4, 5, 6, 7], [4], [1.5, 0.5, 2.5]),
        corners=([10], [1.0]),
        st=layout(*GRID, seam_faces=(0, 4)) + (FV,),
    )
    result, expected, out = run_both(tmp_path, spec, 2, flags, **overrides)
    assert_same(result, expected)
    check_written(out, result)


def test_triangle_rule_override(tmp_path):
    spec = Spec(HOUSE_POINTS, HOUSE_FACES, triangle_rule="smooth")
    result, expected, _ = run_both(tmp_path, spec, 2, ["--triangle-rule", "catmark"], triangle_rule="catmark")
    assert_same(result, expected)
    unset, _, _ = run_both(tmp_path, Spec(HOUSE_POINTS, HOUSE_FACES), 2)
    assert same_bits(result.positions, unset.positions)


def test_usd_fallback_boundary_is_edge_and_corner_not_subcounts_edge(tmp_path):
    # Unset interpolateBoundary is USD's edgeAndCorner: the grid's corners stay put, unlike
    # subcount's own default (edge).
    spec = Spec(*GRID)
    result, _, _ = run_both(tmp_path, spec, 2)
    points, faces = GRID
    plain = subcount.subdivide(
        (np.asarray(points, np.float32).astype(float), np.asarray(faces)), scheme="catmull-clark", levels=2
    )
    corner = np.asarray(points[0], np.float32).astype(float)
    assert any(np.array_equal(p, corner) for p in result.positions)
    assert not any(np.array_equal(p, corner) for p in plain.positions)


# --- the reader ------------------------------------------------------------------------


def test_mesh_from_usd_reads_the_tags_and_flips(tmp_path):
    spec = CASES["cube-left-handed-st-crease-hole"]
    stage = Usd.Stage.Open(str(write_stage(tmp_path / "in.usda", spec)))
    mesh, scheme = usd_subdivide.mesh_from_usd(usd_subdivide.find_mesh(stage))
    assert scheme == "catmull-clark"
    # pxOsd's flip: first corner kept, the others reversed (back to CUBE_FACES' winding).
    flipped = [f[:1] + f[1:][::-1] for f in spec.faces]
    assert mesh.face_vertex_indices.tolist() == [v for f in flipped for v in f]
    values, indices, _ = spec.st
    corner_uvs = np.asarray(values)[np.asarray(indices)].reshape(-1, 4, 2)
    corner_uvs = np.concatenate([corner_uvs[:, :1], corner_uvs[:, :0:-1]], axis=1).reshape(-1, 2)
    assert same_bits(mesh.uvs[mesh.uv_indices], corner_uvs.astype(np.float64))
    # Creases read back as 2-vertex chains, one sharpness per edge.
    assert mesh.crease_indices.tolist() == [0, 1, 1, 2]
    assert mesh.crease_lengths.tolist() == [2, 2]
    assert mesh.crease_sharpnesses.tolist() == [2.0, 2.0]
    assert mesh.corner_indices.tolist() == [7] and mesh.corner_sharpnesses.tolist() == [1.5]
    assert mesh.hole_indices.tolist() == [2]
    options = dict(mesh.options)
    assert options["boundary"] == "edge-and-corner"
    assert options["uv_interpolation"] == "corners-plus1"
    assert options["triangle_rule"] == "catmark"


def test_find_mesh_takes_the_first_mesh_or_the_prim_asked(tmp_path):
    stage = Usd.Stage.CreateNew(str(tmp_path / "two.usda"))
    UsdGeom.Xform.Define(stage, "/World")
    UsdGeom.Cube.Define(stage, "/World/box")
    for name in ("a", "b"):
        m = UsdGeom.Mesh.Define(stage, f"/World/{name}")
        m.CreatePointsAttr([Gf.Vec3f(*p) for p in OCTAHEDRON_POINTS])
        m.CreateFaceVertexCountsAttr([3] * 8)
        m.CreateFaceVertexIndicesAttr([v for f in OCTAHEDRON_FACES for v in f])
        m.CreateSubdivisionSchemeAttr("loop")
    assert usd_subdivide.find_mesh(stage).GetPath() == Sdf.Path("/World/a")
    assert usd_subdivide.find_mesh(stage, "/World/b").GetPath() == Sdf.Path("/World/b")
    stage.GetRootLayer().Save()
    result = usd_subdivide.subdivide_usd(tmp_path / "two.usda", tmp_path / "out.usda", 1, "/World/b")
    assert result.n_faces == 32
    check_written(tmp_path / "out.usda", result, "/World/b")


def test_the_prims_transform_is_kept(tmp_path):
    spec = Spec(*GRID)
    src = write_stage(tmp_path / "in.usda", spec)
    stage = Usd.Stage.Open(str(src))
    UsdGeom.Xformable(stage.GetPrimAtPath("/World")).AddTranslateOp().Set(Gf.Vec3d(1, 2, 3))
    UsdGeom.Xformable(stage.GetPrimAtPath("/World/mesh")).AddScaleOp().Set(Gf.Vec3f(2, 2, 2))
    UsdGeom.SetStageUpAxis(stage, UsdGeom.Tokens.z)
    stage.GetRootLayer().Save()
    usd_subdivide.subdivide_usd(src, tmp_path / "out.usda", 1)
    out = Usd.Stage.Open(str(tmp_path / "out.usda"))
    prim = out.GetPrimAtPath("/World/mesh")
    world = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(Usd.TimeCode.Default())
    assert world == UsdGeom.Xformable(stage.GetPrimAtPath("/World/mesh")).ComputeLocalToWorldTransform(
        Usd.TimeCode.Default()
    )
    assert UsdGeom.GetStageUpAxis(out) == UsdGeom.Tokens.z
    assert not out.HasAuthoredMetadata(UsdGeom.Tokens.metersPerUnit)  # not authored in the input
    assert out.GetDefaultPrim().GetPath() == Sdf.Path("/World")


# --- errors ----------------------------------------------------------------------------


def stage_with(tmp_path, edit, spec=None):
    """A stage of a plain cube mesh at /World/mesh, changed by edit(stage, mesh)."""
    path = write_stage(tmp_path / "bad.usda", spec or Spec(CUBE_POINTS, CUBE_FACES))
    stage = Usd.Stage.Open(str(path))
    edit(stage, UsdGeom.Mesh(stage.GetPrimAtPath("/World/mesh")))
    stage.GetRootLayer().Save()
    return path


def set_st(interpolation, values=None, indices=None, type_name=Sdf.ValueTypeNames.TexCoord2fArray):
    def edit(stage, mesh):
        primvar = UsdGeom.PrimvarsAPI(mesh).CreatePrimvar("st", type_name, interpolation)
        primvar.Set(values if values is not None else CUBE_VERTEX_UV.tolist())
        if indices is not None:
            primvar.SetIndices(Vt.IntArray(indices))

    return edit


ERRORS = {
    "st-uniform": (
        set_st(UsdGeom.Tokens.uniform, [(0, 0)] * 6), r"/World/mesh\.primvars:st: interpolation \"uniform\""
    ),
    "st-constant": (set_st(UsdGeom.Tokens.constant, [(0, 0)]), r"primvars:st: interpolation \"constant\""),
    "st-varying": (set_st(UsdGeom.Tokens.varying), r"primvars:st: interpolation \"varying\""),
    "st-float3": (
        set_st(FV, [(0, 0, 0)] * 24, type_name=Sdf.ValueTypeNames.TexCoord3fArray),
        r"primvars:st: has type texCoord3f\[\]",
    ),
    "st-facevarying-count": (set_st(FV, [(0, 0)] * 23), r"primvars:st: has 23 entries for 24 face corners"),
    "st-indices-count": (set_st(FV, [(0, 0)], [0] * 20), r"primvars:st:indices: has 20 entries for 24"),
    "st-indices-range": (set_st(FV, [(0, 0)], [0] * 23 + [1]), r"primvars:st:indices: \[23\] = 1 is out of range"),
    "st-vertex-count": (set_st(VERTEX, [(0, 0)] * 7), r"primvars:st: has 7 entries for 8 points"),
    "scheme-none": (
        lambda s, m: m.CreateSubdivisionSchemeAttr("none"),
        r"/World/mesh\.subdivisionScheme: \"none\" is not supported \(the mesh is not a subdivision surface",
    ),
    "scheme-bilinear": (
        lambda s, m: m.CreateSubdivisionSchemeAttr("bilinear"),
        r"subdivisionScheme: \"bilinear\" is not supported \(subcount has no such scheme",
    ),
    "boundary-token": (
        lambda s, m: m.CreateInterpolateBoundaryAttr("sideways"),
        r"interpolateBoundary: \"sideways\" is not supported",
    ),
    "fvar-token": (
        lambda s, m: m.CreateFaceVaryingLinearInterpolationAttr("bilinear"),
        r"faceVaryingLinearInterpolation: \"bilinear\" is not supported",
    ),
    "no-points": (lambda s, m: m.GetPointsAttr().Clear(), r"/World/mesh\.points: has no value"),
    "no-faces": (lambda s, m: m.GetFaceVertexCountsAttr().Clear(), r"faceVertexCounts: has no value"),
    "face-indices-count": (
        lambda s, m: m.GetFaceVertexIndicesAttr().Set(list(range(8)) * 2 + [0]),
        r"faceVertexIndices: has 17 entries, but faceVertexCounts add up to 24",
    ),
}


@pytest.mark.parametrize("name", list(ERRORS))
def test_input_errors_name_the_prim_and_attribute(tmp_path, name):
    edit, message = ERRORS[name]
    src = stage_with(tmp_path, edit)
    with pytest.raises(subcount.InputError, match=message):
        usd_subdivide.subdivide_usd(src, tmp_path / "out.usda", 1)
    assert not (tmp_path / "out.usda").exists()


def test_a_prim_that_is_not_a_mesh(tmp_path):
    stage = Usd.Stage.CreateNew(str(tmp_path / "cube.usda"))
    UsdGeom.Xform.Define(stage, "/World")
    UsdGeom.Cube.Define(stage, "/World/box")
    stage.GetRootLayer().Save()
    with pytest.raises(subcount.InputError, match=r"/World/box: is Cube, not a UsdGeom.Mesh"):
        usd_subdivide.subdivide_usd(tmp_path / "cube.usda", tmp_path / "out.usda", 1, "/World/box")
    with pytest.raises(subcount.InputError, match=r"/World: is Xform, not a UsdGeom.Mesh"):
        usd_subdivide.subdivide_usd(tmp_path / "cube.usda", tmp_path / "out.usda", 1, "/World")
    with pytest.raises(subcount.InputError, match=r"/World/nothing: no such prim"):
        usd_subdivide.subdivide_usd(tmp_path / "cube.usda", tmp_path / "out.usda", 1, "/World/nothing")
    with pytest.raises(subcount.InputError, match=r"no UsdGeom.Mesh in the stage"):
        usd_subdivide.subdivide_usd(tmp_path / "cube.usda", tmp_path / "out.usda", 1)


# The tags' own errors come from subcount.Mesh, named after the prim.
TAG_ERRORS = {
    "crease-sharpness-count": Spec(CUBE_POINTS, CUBE_FACES, creases=([0, 1, 2], [3], [1.0, 2.0, 3.0])),
    "crease-lengths-sum": Spec(CUBE_POINTS, CUBE_FACES, creases=([0, 1, 2], [4], [1.0])),
    "crease-vertex-range": Spec(CUBE_POINTS, CUBE_FACES, creases=([0, 9], [2], [1.0])),
    "corner-count": Spec(CUBE_POINTS, CUBE_FACES, corners=([0, 1], [1.0])),
    "corner-range": Spec(CUBE_POINTS, CUBE_FACES, corners=([8], [1.0])),
    "hole-range": Spec(CUBE_POINTS, CUBE_FACES, holes=[6]),
    "negative-sharpness": Spec(CUBE_POINTS, CUBE_FACES, corners=([0], [-1.0])),
}


@pytest.mark.parametrize("name", list(TAG_ERRORS))
def test_tag_errors_are_input_errors_naming_the_prim(tmp_path, name):
    src = write_stage(tmp_path / "in.usda", TAG_ERRORS[name])
    with pytest.raises(subcount.InputError, match=r"^/World/mesh: ") as e:
        usd_subdivide.subdivide_usd(src, tmp_path / "out.usda", 1)
    print(name, "->", e.value)


# --- main ------------------------------------------------------------------------------


def test_main_writes_and_reports(tmp_path, capsys):
    src = write_stage(tmp_path / "in.usda", CASES["cube-st-facevarying-indexed"])
    assert usd_subdivide.main([str(src), str(tmp_path / "out.usda"), "--levels", "1"]) == 0
    assert "level 1: V = 26, F = 24, UV = " in capsys.readouterr().out
    stage = Usd.Stage.Open(str(tmp_path / "out.usda"))
    assert len(UsdGeom.Mesh(stage.GetPrimAtPath("/World/mesh")).GetFaceVertexCountsAttr().Get()) == 24


def test_main_exit_codes(tmp_path, capsys):
    src = stage_with(tmp_path, set_st(UsdGeom.Tokens.uniform, [(0, 0)] * 6))
    assert usd_subdivide.main([str(src), str(tmp_path / "out.usda"), "--levels", "1"]) == 3
    assert capsys.readouterr().err.startswith("error: /World/mesh.primvars:st: interpolation")
    good = write_stage(tmp_path / "good.usda", Spec(CUBE_POINTS, CUBE_FACES))
    assert usd_subdivide.main([str(good), str(tmp_path / "out.usda"), "--levels", "-1"]) == 2
    assert usd_subdivide.main([str(good), str(tmp_path / "out.usda"), "--levels", "40"]) == 4


def test_script_runs_from_the_command_line(tmp_path):
    src = write_stage(tmp_path / "in.usda", CASES["octahedron-loop"])
    run = subprocess.run(
        [sys.executable, str(EXAMPLE), str(src), str(tmp_path / "out.usda"), "--levels", "2"],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 0, run.stderr
    assert "level 2: V = 66, F = 128; wrote" in run.stdout
