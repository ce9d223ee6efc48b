"""Exact subdivision counts and OpenSubdiv-grade subdivision (the Rust core of `subcount`)."""

import os
from collections.abc import Sequence
from typing import Any, Literal, Union, final, overload

import numpy as np
import numpy.typing as npt
from typing_extensions import TypeAlias

__all__ = [
    "__version__",
    "Mesh",
    "Refinement",
    "read_mesh",
    "write_mesh",
    "subdivide",
    "run_command",
]

__version__: str

# Stub-only aliases (not importable at runtime, hence the leading underscore).

#: A file name or path (``PathBuf`` on the Rust side: ``str`` or ``os.PathLike[str]``).
_Path: TypeAlias = Union[str, os.PathLike[str]]
#: The faces of ``(positions, faces)``: an ``(F, k)`` integer array, or a tuple
#: ``(face_vertex_counts, face_vertex_indices)``.
_Faces: TypeAlias = Union[npt.ArrayLike, tuple[npt.ArrayLike, npt.ArrayLike]]
#: A mesh argument: a path (read as ``read_mesh`` does), a ``Mesh`` or ``(positions, faces)``.
_MeshLike: TypeAlias = Union[str, os.PathLike[str], Mesh, tuple[npt.ArrayLike, _Faces]]
#: The command line's names of the options (``halfedge::tags``' enums; exact names only).
_Boundary: TypeAlias = Literal["edge", "edge-and-corner", "none"]
_CreaseMethod: TypeAlias = Literal["uniform", "chaikin"]
_TriangleRule: TypeAlias = Literal["catmark", "smooth"]
_UvInterpolation: TypeAlias = Literal[
    "none", "corners-only", "corners-plus1", "corners-plus2", "boundaries", "all"
]
_Precision: TypeAlias = Literal["f64", "f32"]
#: The floats of a mesh's arrays: float64, or float32 for ``subdivide(..., precision="f32")``.
_Floats: TypeAlias = npt.NDArray[Union[np.float64, np.float32]]

@final
class Mesh:
    """A polygon mesh: vertex positions and faces (a face list, 0-based), with the texture
    coordinates, vertex colors, materials and groups of its file."""

    def __new__(
        cls,
        positions: npt.ArrayLike,
        face_vertex_counts: npt.ArrayLike,
        face_vertex_indices: npt.ArrayLike,
        *,
        uvs: npt.ArrayLike | None = None,
        uv_indices: npt.ArrayLike | None = None,
        colors: npt.ArrayLike | None = None,
        crease_indices: npt.ArrayLike | None = None,
        crease_lengths: npt.ArrayLike | None = None,
        crease_sharpnesses: npt.ArrayLike | None = None,
        corner_indices: npt.ArrayLike | None = None,
        corner_sharpnesses: npt.ArrayLike | None = None,
        hole_indices: npt.ArrayLike | None = None,
        options: dict[str, str] | None = None,
    ) -> Mesh: ...
    @property
    def positions(self) -> _Floats:
        """Vertex positions, (N, 3) float64 (float32 for an f32 result)."""
    @property
    def face_vertex_counts(self) -> npt.NDArray[np.int32]:
        """The number of corners of each face, (F,) int32."""
    @property
    def face_vertex_indices(self) -> npt.NDArray[np.int32]:
        """The vertex of each corner, face after face, int32."""
    @property
    def uvs(self) -> _Floats | None:
        """Texture coordinates, (K, 2), or None."""
    @property
    def uv_indices(self) -> npt.NDArray[np.int32] | None:
        """The texture coordinate of each corner (an index into uvs), int32, or None."""
    @property
    def colors(self) -> _Floats | None:
        """Vertex colors, (N, 3), or None."""
    @property
    def materials(self) -> list[str | None] | None:
        """Each face's material (`usemtl`), a str or None, or None when the mesh has none."""
    @property
    def groups(self) -> list[str | None] | None:
        """Each face's groups (`g`, the names as written), a str or None, or None when the
        mesh has none."""
    @property
    def mtllib(self) -> list[str]:
        """The material files the OBJ file names (`mtllib`), in file order."""
    @property
    def crease_indices(self) -> npt.NDArray[np.int32]:
        """The crease edges' vertices, one 2-vertex chain per edge (USD's creaseIndices),
        int32."""
    @property
    def crease_lengths(self) -> npt.NDArray[np.int32]:
        """The vertices of each crease chain: 2 per crease edge (USD's creaseLengths), int32."""
    @property
    def crease_sharpnesses(self) -> npt.NDArray[np.float32]:
        """The sharpness of each crease edge (USD's creaseSharpnesses), float32."""
    @property
    def corner_indices(self) -> npt.NDArray[np.int32]:
        """The corner vertices (USD's cornerIndices), int32."""
    @property
    def corner_sharpnesses(self) -> npt.NDArray[np.float32]:
        """The sharpness of each corner (USD's cornerSharpnesses), float32."""
    @property
    def hole_indices(self) -> npt.NDArray[np.int32]:
        """The faces that are holes (USD's holeIndices), int32."""
    @property
    def options(self) -> dict[str, str]:
        """The mesh's own subdivision options (a file's tags), a dict of those it sets."""
    @property
    def n_vertices(self) -> int:
        """The number of vertices."""
    @property
    def n_faces(self) -> int:
        """The number of faces."""
    @property
    def timings(self) -> dict[str, float] | None:
        """With subdivide(..., timings=True): the seconds of each part of the call."""
    def __repr__(self) -> str: ...

@final
class Refinement:
    """A mesh's topology refined once to a level, to evaluate positions (and UVs) many
    times."""

    def __new__(
        cls,
        mesh: _MeshLike,
        *,
        scheme: str | None = None,
        levels: int,
        scheme_file: _Path | None = None,
        boundary: _Boundary | None = None,
        crease_method: _CreaseMethod | None = None,
        triangle_rule: _TriangleRule | None = None,
        uv_interpolation: _UvInterpolation | None = None,
        ignore_tags: bool = False,
        threads: int = 0,
        no_uv: bool = False,
        allow_large: bool = False,
        limit: bool = False,
    ) -> Refinement: ...
    @property
    def limit(self) -> bool:
        """Whether the refinement keeps the limit surface (made with limit=True)."""
    @property
    def levels(self) -> int:
        """The last level."""
    @property
    def scheme(self) -> str:
        """The scheme as it counts what is written ("loop-boundary" for "loop" on an open
        mesh)."""
    @property
    def face_vertex_counts(self) -> npt.NDArray[np.int32]:
        """The last level's face sizes, int32."""
    @property
    def face_vertex_indices(self) -> npt.NDArray[np.int32]:
        """The last level's corners (vertex indices, face after face), int32."""
    @property
    def uv_indices(self) -> npt.NDArray[np.int32] | None:
        """The UV value of each corner of the last level, int32, or None without UVs."""
    @property
    def base_uvs(self) -> npt.NDArray[np.float64] | None:
        """The UV values evaluate_uvs() starts from by default, (K, 2) float64, or None."""
    def n_vertices(self, level: int | None = None) -> int:
        """The vertices of a level (default: the last), those of holes included below the
        last."""
    def n_faces(self, level: int | None = None) -> int:
        """The faces of a level (default: the last; at the last, without holes)."""
    def n_uvs(self, level: int | None = None) -> int:
        """The UV values of a level (default: the last), 0 without UVs."""
    # evaluate() computes in float32 for float32 points (and then wants a float32 out), in
    # float64 for any other numbers.
    @overload
    def evaluate(
        self, points: npt.NDArray[np.float32], out: npt.NDArray[np.float32] | None = None
    ) -> npt.NDArray[np.float32]: ...
    @overload
    def evaluate(
        self, points: npt.ArrayLike, out: npt.NDArray[np.float64] | None = None
    ) -> npt.NDArray[np.float64]: ...
    # evaluate_uvs(limit=True): their limit (LimitFaceVarying).
    @overload
    def evaluate_uvs(
        self,
        uvs: npt.NDArray[np.float32],
        out: npt.NDArray[np.float32] | None = None,
        limit: bool = False,
    ) -> npt.NDArray[np.float32]: ...
    @overload
    def evaluate_uvs(
        self,
        uvs: npt.ArrayLike | None = None,
        out: npt.NDArray[np.float64] | None = None,
        limit: bool = False,
    ) -> npt.NDArray[np.float64]: ...
    # evaluate_limit() as evaluate(); with tangents=True, (positions, tangent1, tangent2).
    @overload
    def evaluate_limit(
        self,
        points: npt.NDArray[np.float32],
        out: npt.NDArray[np.float32] | None = None,
        tangents: Literal[False] = False,
    ) -> npt.NDArray[np.float32]: ...
    @overload
    def evaluate_limit(
        self,
        points: npt.ArrayLike,
        out: npt.NDArray[np.float64] | None = None,
        tangents: Literal[False] = False,
    ) -> npt.NDArray[np.float64]: ...
    @overload
    def evaluate_limit(
        self,
        points: npt.NDArray[np.float32],
        out: npt.NDArray[np.float32] | None = None,
        *,
        tangents: Literal[True],
    ) -> tuple[
        npt.NDArray[np.float32], npt.NDArray[np.float32], npt.NDArray[np.float32]
    ]: ...
    @overload
    def evaluate_limit(
        self,
        points: npt.ArrayLike,
        out: npt.NDArray[np.float64] | None = None,
        *,
        tangents: Literal[True],
    ) -> tuple[
        npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.float64]
    ]: ...
    def stencils(self) -> Any:
        """The last level's vertices as weighted sums of the mesh's vertices: a
        ``scipy.sparse.csr_array`` of shape (n_vertices(), N). (Typed ``Any``: SciPy is an
        optional dependency, imported when called.)"""
    def __repr__(self) -> str: ...

def read_mesh(path: _Path) -> Mesh:
    """Reads a mesh file (OBJ, OFF or PLY) with its texture coordinates, vertex colors,
    materials, groups and OpenSubdiv tags."""

def write_mesh(mesh: _MeshLike, path: _Path) -> None:
    """Writes a mesh as OBJ, or as binary PLY for a name ending in .ply."""

def subdivide(
    mesh: _MeshLike,
    *,
    scheme: str | None = None,
    levels: int,
    scheme_file: _Path | None = None,
    boundary: _Boundary | None = None,
    crease_method: _CreaseMethod | None = None,
    triangle_rule: _TriangleRule | None = None,
    uv_interpolation: _UvInterpolation | None = None,
    ignore_tags: bool = False,
    precision: _Precision = "f64",
    threads: int = 0,
    no_uv: bool = False,
    allow_large: bool = False,
    timings: bool = False,
    limit: bool = False,
) -> Mesh:
    """Subdivides a mesh as `subcount subdivide` does and returns the last level."""

def run_command(
    args: Sequence[str], mesh: _MeshLike | None = None
) -> tuple[int, str, list[str], str | None]:
    """Runs the command line `subcount ARGS` in this process: (exit_code, stdout, notes,
    error)."""
