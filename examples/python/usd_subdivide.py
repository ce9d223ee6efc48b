#!/usr/bin/env python3
"""Subdivide a USD mesh with subcount: read a ``UsdGeom.Mesh``, write the refined mesh.

An example, not part of the subcount package. It needs ``usd-core`` (PyPI, ``from pxr import
Usd, UsdGeom``) and ``subcount``::

    python usd_subdivide.py IN.usda OUT.usda --levels 2 [--prim /World/Body]
        [--boundary edge|edge-and-corner|none] [--crease-method uniform|chaikin]
        [--triangle-rule catmark|smooth] [--uv-interpolation none|corners-only|...|all]
        [--threads N] [--no-uv]

Without ``--prim`` the first ``UsdGeom.Mesh`` of the stage (depth first) is read. Errors are
printed as ``error: ...`` with the command line's exit codes (2 usage, 3 input, 4 resource).

What is read, as OpenSubdiv does through USD (``pxOsd``), with the schema's fallbacks where an
attribute is not authored:

- ``subdivisionScheme``: ``catmullClark`` (fallback) is subcount's ``catmull-clark``, ``loop``
  is ``loop``; ``bilinear``, ``none`` and anything else raise ``subcount.InputError`` (subcount
  has no bilinear scheme, and a ``none`` mesh is not a subdivision surface).
- ``interpolateBoundary`` (fallback ``edgeAndCorner``: unlike subcount's own default ``edge``),
  ``faceVaryingLinearInterpolation`` (fallback ``cornersPlus1``) and
  ``triangleSubdivisionRule`` (fallback ``catmullClark``) become the mesh's own options
  (``subcount.Mesh(..., options=...)``, as an OBJ file's ``t interpolateboundary`` tags); the
  command line's flags override them, as the CLI's flags override a file's tags.
- ``creaseIndices``/``creaseLengths``/``creaseSharpnesses`` (chains of vertices; one sharpness
  per chain or one per edge), ``cornerIndices``/``cornerSharpnesses``, ``holeIndices``.
  Sharpness 10 or more is infinitely sharp.
- ``orientation = leftHanded``: each face is turned over as ``pxOsd`` does it, keeping its first
  corner and reversing the others (``a b c d`` becomes ``a d c b``), its ``st`` values with it;
  the output is ``rightHanded``.
- ``primvars:st`` (two components), ``faceVarying`` or ``vertex``, indexed or not. A vertex
  ``st`` (one value per point) is refined as a face-varying channel whose corners are the
  faces' vertices (``uv_indices = face_vertex_indices``). Any other interpolation raises
  ``subcount.InputError``. Other primvars (normals, displayColor, ...) are not carried.

What is written: a new stage holding one ``UsdGeom.Mesh`` at the input's path, with
``points``, ``faceVertexCounts``, ``faceVertexIndices``, ``extent``,
``subdivisionScheme = "none"`` (the result is the refined polygon mesh), ``orientation =
rightHanded``, ``primvars:st`` faceVarying and indexed when the result has UVs, and the input
prim's local-to-world transform as one ``xformOp:transform`` when that is not the identity
(the output's ancestors are plain prims), and the input's ``upAxis`` and ``metersPerUnit``
where it authors them. No crease, corner or hole attributes: holes are left
out of the refined faces, creases and corners are in the refined positions.

Precision: subcount computes in float64. ``points`` is ``point3f[]`` and ``primvars:st`` is
``texCoord2f[]`` (the schema's types, what every USD reader expects), so the written values are
the nearest float32 of subcount's result (``numpy.astype(float32)``). ``subdivide_usd`` returns
the float64 ``subcount.Mesh`` as well, for whoever needs every bit. USD's own float32 inputs
(points, st, sharpnesses) widen to float64 exactly.

Functions: ``mesh_from_usd(prim) -> (subcount.Mesh, scheme)``, ``mesh_to_usd(stage, path,
mesh)``, ``subdivide_usd(in_path, out_path, levels, prim_path=None, ...) -> subcount.Mesh``,
``find_mesh(stage, prim_path=None)`` and ``main(argv)``.
"""

import argparse
import sys

import numpy as np
from pxr import Gf, Sdf, Tf, Usd, UsdGeom, Vt

import subcount

# USD tokens -> subcount's names (the CLI's).
SCHEMES = {"catmullClark": "catmull-clark", "loop": "loop"}
BOUNDARY = {"none": "none", "edgeOnly": "edge", "edgeAndCorner": "edge-and-corner"}
FACE_VARYING = {
    "none": "none",
    "cornersOnly": "corners-only",
    "cornersPlus1": "corners-plus1",
    "cornersPlus2": "corners-plus2",
    "boundaries": "boundaries",
    "all": "all",
}
TRIANGLE_RULE = {"catmullClark": "catmark", "smooth": "smooth"}

ST_INTERPOLATIONS = (UsdGeom.Tokens.faceVarying, UsdGeom.Tokens.vertex)

# Exit codes of main(), the CLI's.
EXIT_CODES = ((subcount.UsageError, 2), (subcount.InputError, 3), (subcount.ResourceError, 4))


def _fail(prim, attribute, message):
    """A subcount.InputError naming the prim and the attribute."""
    where = f"{prim.GetPath()}" + (f".{attribute}" if attribute else "")
    return subcount.InputError(f"{where}: {message}")


def _token(prim, attr, table, time):
    """The value of a token attribute (authored or the schema's fallback), mapped by table."""
    value = str(attr.Get(time))
    if value not in table:
        known = ", ".join(f'"{k}"' for k in table)
        raise _fail(prim, attr.GetName(), f'"{value}" is not supported (expected {known})')
    return table[value]


def _ints(attr, time):
    value = attr.Get(time)
    return np.asarray(value if value is not None else [], dtype=np.int64)


def _floats(attr, time):
    value = attr.Get(time)
    # float32 from USD: widened to float64 exactly.
    return np.asarray(value if value is not None else [], dtype=np.float32).astype(np.float64)


def _flip_order(counts):
    """The corner permutation that turns every face over as pxOsd does (first corner kept,
    the others reversed): corner j of face f takes corner (n - j) % n of the face."""
    counts = np.asarray(counts, dtype=np.int64)
    starts = np.concatenate([[0], np.cumsum(counts)[:-1]])
    face_start = np.repeat(starts, counts)
    n = np.repeat(counts, counts)
    j = np.arange(int(counts.sum()), dtype=np.int64) - face_start
    return face_start + (n - j) % n


def find_mesh(stage, prim_path=None):
    """The prim at prim_path (a UsdGeom.Mesh), else the stage's first UsdGeom.Mesh."""
    if prim_path is not None:
        prim = stage.GetPrimAtPath(Sdf.Path(prim_path))
        if not prim or not prim.IsValid():
            raise subcount.InputError(f"{prim_path}: no such prim in {stage.GetRootLayer().identifier}")
        return prim
    for prim in stage.Traverse():
        if prim.IsA(UsdGeom.Mesh):
            return prim
    raise subcount.InputError(f"{stage.GetRootLayer().identifier}: no UsdGeom.Mesh in the stage")


def _st(prim, n_points, counts, indices, time):
    """(uvs, uv_indices) of primvars:st, before any flip, or None without st."""
    primvar = UsdGeom.PrimvarsAPI(prim).GetPrimvar("st")
    if not primvar or not primvar.HasAuthoredValue():
        return None
    name = primvar.GetAttr().GetName()
    interpolation = primvar.GetInterpolation()
    if interpolation not in ST_INTERPOLATIONS:
        raise _fail(
            prim, name, f'interpolation "{interpolation}" is not supported (faceVarying or vertex only)'
        )
    values = np.asarray(primvar.Get(time))
    if values.ndim != 2 or values.shape[1] != 2:
        type_name = primvar.GetTypeName()
        raise _fail(prim, name, f"has type {type_name}: texture coordinates of two components expected")
    uvs = values.astype(np.float64)
    if primvar.IsIndexed():
        st_indices = np.asarray(primvar.GetIndices(time), dtype=np.int64)
        bad = np.flatnonzero((st_indices < 0) | (st_indices >= len(uvs)))
        if bad.size:
            i = int(bad[0])
            raise _fail(
                prim, f"{name}:indices", f"[{i}] = {st_indices[i]} is out of range: {name} has {len(uvs)} values"
            )
    else:
        st_indices = np.arange(len(uvs), dtype=np.int64)
    n_corners = int(np.sum(counts))
    if interpolation == UsdGeom.Tokens.faceVarying:
        if len(st_indices) != n_corners:
            what = f"{name}:indices" if primvar.IsIndexed() else name
            raise _fail(
                prim, what, f"has {len(st_indices)} entries for {n_corners} face corners (faceVarying: one per corner)"
            )
        return uvs, st_indices
    # vertex: one value per point; the corners of a face use its vertices' values.
    if len(st_indices) != n_points:
        what = f"{name}:indices" if primvar.IsIndexed() else name
        raise _fail(prim, what, f"has {len(st_indices)} entries for {n_points} points (vertex: one per point)")
    return uvs, st_indices[indices]


def mesh_from_usd(prim, time=Usd.TimeCode.Default()):
    """A UsdGeom.Mesh prim as (subcount.Mesh, scheme name for subcount.subdivide).

    The mesh carries the prim's creases, corners, holes and options (authored or the
    schema's fallbacks); leftHanded faces are turned over. Raises subcount.InputError for
    anything this does not read (a prim that is not a mesh, no points, a scheme other than
    catmullClark or loop, a primvars:st that is neither faceVarying nor vertex, ...).
    """
    if not prim or not prim.IsValid():
        raise subcount.InputError("no prim given")
    if not prim.IsA(UsdGeom.Mesh):
        type_name = prim.GetTypeName() or "a typeless prim"
        raise _fail(prim, None, f"is {type_name}, not a UsdGeom.Mesh")
    mesh = UsdGeom.Mesh(prim)

    token = str(mesh.GetSubdivisionSchemeAttr().Get(time))
    if token not in SCHEMES:
        why = (
            "the mesh is not a subdivision surface"
            if token == "none"
            else "subcount has no such scheme"
        )
        raise _fail(prim, "subdivisionScheme", f'"{token}" is not supported ({why}; catmullClark or loop)')
    scheme = SCHEMES[token]

    points = mesh.GetPointsAttr().Get(time)
    if points is None or len(points) == 0:
        raise _fail(prim, "points", "has no value: a mesh needs points")
    positions = np.asarray(points, dtype=np.float32).astype(np.float64)
    counts = mesh.GetFaceVertexCountsAttr().Get(time)
    if counts is None or len(counts) == 0:
        raise _fail(prim, "faceVertexCounts", "has no value: a mesh needs faces")
    counts = np.asarray(counts, dtype=np.int64)
    indices = mesh.GetFaceVertexIndicesAttr().Get(time)
    if indices is None:
        raise _fail(prim, "faceVertexIndices", "has no value: a mesh needs faces")
    indices = np.asarray(indices, dtype=np.int64)
    if np.any(counts < 3):
        f = int(np.flatnonzero(counts < 3)[0])
        raise _fail(prim, "faceVertexCounts", f"[{f}] = {counts[f]}: a face has at least 3 corners")
    if int(counts.sum()) != len(indices):
        raise _fail(
            prim, "faceVertexIndices", f"has {len(indices)} entries, but faceVertexCounts add up to {int(counts.sum())}"
        )

    st = _st(prim, len(positions), counts, indices, time)

    orientation = str(mesh.GetOrientationAttr().Get(time))
    if orientation not in ("rightHanded", "leftHanded"):
        raise _fail(prim, "orientation", f'"{orientation}" is not supported (rightHanded or leftHanded)')
    if orientation == "leftHanded":
        order = _flip_order(counts)
        indices = indices[order]
        if st is not None:
            st = (st[0], st[1][order])

    options = {
        "boundary": _token(prim, mesh.GetInterpolateBoundaryAttr(), BOUNDARY, time),
        "uv_interpolation": _token(prim, mesh.GetFaceVaryingLinearInterpolationAttr(), FACE_VARYING, time),
        "triangle_rule": _token(prim, mesh.GetTriangleSubdivisionRuleAttr(), TRIANGLE_RULE, time),
    }
    tags = {
        "crease_indices": _ints(mesh.GetCreaseIndicesAttr(), time),
        "crease_lengths": _ints(mesh.GetCreaseLengthsAttr(), time),
        "crease_sharpnesses": _floats(mesh.GetCreaseSharpnessesAttr(), time),
        "corner_indices": _ints(mesh.GetCornerIndicesAttr(), time),
        "corner_sharpnesses": _floats(mesh.GetCornerSharpnessesAttr(), time),
        "hole_indices": _ints(mesh.GetHoleIndicesAttr(), time),
    }
    # Pass only the tags the prim has: an empty array says nothing.
    tags = {k: v for k, v in tags.items() if len(v)}

    uv_kwargs = {} if st is None else {"uvs": st[0], "uv_indices": st[1]}
    try:
        result = subcount.Mesh(positions, counts, indices, **uv_kwargs, **tags, options=options)
    except subcount.InputError as e:
        raise _fail(prim, None, str(e)) from e
    return result, scheme


def _int_array(values):
    return Vt.IntArray.FromNumpy(np.ascontiguousarray(values, dtype=np.int32))


def mesh_to_usd(stage, path, mesh, transform=None):
    """Defines a UsdGeom.Mesh at path holding mesh (a subcount.Mesh): the refined polygons,
    subdivisionScheme "none", rightHanded, primvars:st faceVarying indexed when the mesh has
    UVs, no crease, corner or hole attributes. points and st are float32 (the schema's
    types). transform: a Gf.Matrix4d authored as xformOp:transform unless None or identity."""
    usd_mesh = UsdGeom.Mesh.Define(stage, Sdf.Path(path))
    positions = np.ascontiguousarray(mesh.positions, dtype=np.float32)
    points = Vt.Vec3fArray.FromNumpy(positions)
    usd_mesh.CreatePointsAttr(points)
    usd_mesh.CreateFaceVertexCountsAttr(_int_array(mesh.face_vertex_counts))
    usd_mesh.CreateFaceVertexIndicesAttr(_int_array(mesh.face_vertex_indices))
    usd_mesh.CreateSubdivisionSchemeAttr(UsdGeom.Tokens.none)
    usd_mesh.CreateOrientationAttr(UsdGeom.Tokens.rightHanded)
    usd_mesh.CreateExtentAttr(UsdGeom.PointBased.ComputeExtent(points))
    if mesh.uvs is not None:
        primvar = UsdGeom.PrimvarsAPI(usd_mesh).CreatePrimvar(
            "st", Sdf.ValueTypeNames.TexCoord2fArray, UsdGeom.Tokens.faceVarying
        )
        primvar.Set(Vt.Vec2fArray.FromNumpy(np.ascontiguousarray(mesh.uvs, dtype=np.float32)))
        primvar.SetIndices(_int_array(mesh.uv_indices))
    if transform is not None and transform != Gf.Matrix4d(1.0):
        usd_mesh.AddTransformOp().Set(transform)
    return usd_mesh


def subdivide_usd(
    in_path,
    out_path,
    levels,
    prim_path=None,
    *,
    boundary=None,
    crease_method=None,
    triangle_rule=None,
    uv_interpolation=None,
    threads=0,
    no_uv=False,
    time=Usd.TimeCode.Default(),
):
    """Reads the mesh at prim_path (default: the first UsdGeom.Mesh) of the stage in_path,
    subdivides it levels times and writes it to a new stage out_path (same prim path). The
    keyword options override the mesh's own (its USD attributes). Returns the float64
    subcount.Mesh that was written."""
    try:
        stage = Usd.Stage.Open(str(in_path))
    except Tf.ErrorException as e:
        raise subcount.InputError(f"{in_path}: cannot open the stage: {str(e).strip()}") from e
    if stage is None:
        raise subcount.InputError(f"{in_path}: cannot open the stage")
    prim = find_mesh(stage, prim_path)
    mesh, scheme = mesh_from_usd(prim, time)
    result = subcount.subdivide(
        mesh,
        scheme=scheme,
        levels=levels,
        boundary=boundary,
        crease_method=crease_method,
        triangle_rule=triangle_rule,
        uv_interpolation=uv_interpolation,
        threads=threads,
        no_uv=no_uv,
    )
    # Built in memory and exported: the file is written whole, once, and only on success.
    out = Usd.Stage.CreateInMemory()
    for key in (UsdGeom.Tokens.upAxis, UsdGeom.Tokens.metersPerUnit):
        if stage.HasAuthoredMetadata(key):  # copied as authored, fallbacks left to USD
            out.SetMetadata(key, stage.GetMetadata(key))
    transform = UsdGeom.Xformable(prim).ComputeLocalToWorldTransform(time)
    mesh_to_usd(out, prim.GetPath(), result, transform)
    root = prim.GetPath().GetPrefixes()[0]
    out.SetDefaultPrim(out.GetPrimAtPath(root))
    # A file that cannot be written is exit code 3, as for the CLI's -o.
    try:
        written = out.GetRootLayer().Export(str(out_path))
    except Tf.ErrorException as e:
        raise subcount.InputError(f"{out_path}: cannot write the stage: {str(e).strip()}") from e
    if not written:
        raise subcount.InputError(f"{out_path}: cannot write the stage")
    return result


def main(argv=None):
    parser = argparse.ArgumentParser(
        description="Subdivide a UsdGeom.Mesh with subcount and write the refined mesh as USD."
    )
    parser.add_argument("input", help="a USD stage (.usda, .usdc, .usd)")
    parser.add_argument("output", help="the stage to write (created or overwritten)")
    parser.add_argument("--levels", type=int, required=True, help="subdivision levels")
    parser.add_argument("--prim", help="the mesh's prim path (default: the first UsdGeom.Mesh)")
    parser.add_argument("--boundary", choices=["edge", "edge-and-corner", "none"],
                        help="override interpolateBoundary")
    parser.add_argument("--crease-method", choices=["uniform", "chaikin"])
    parser.add_argument("--triangle-rule", choices=["catmark", "smooth"],
                        help="override triangleSubdivisionRule")
    parser.add_argument("--uv-interpolation", choices=list(FACE_VARYING.values()),
                        help="override faceVaryingLinearInterpolation")
    parser.add_argument("--threads", type=int, default=0, help="0: all cores")
    parser.add_argument("--no-uv", action="store_true", help="do not refine or write primvars:st")
    args = parser.parse_args(argv)
    try:
        result = subdivide_usd(
            args.input,
            args.output,
            args.levels,
            args.prim,
            boundary=args.boundary,
            crease_method=args.crease_method,
            triangle_rule=args.triangle_rule,
            uv_interpolation=args.uv_interpolation,
            threads=args.threads,
            no_uv=args.no_uv,
        )
    except subcount.Error as e:
        print(f"error: {e}", file=sys.stderr)
        return next((code for cls, code in EXIT_CODES if isinstance(e, cls)), 1)
    uv = "" if result.uvs is None else f", UV = {len(result.uvs)}"
    print(f"level {args.levels}: V = {result.n_vertices}, F = {result.n_faces}{uv}; wrote {args.output}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
