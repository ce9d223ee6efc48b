"""subcount: exact subdivision counts and OpenSubdiv-grade subdivision, numpy in and out.

>>> import subcount
>>> m = subcount.read_mesh("pawn.obj")
>>> out = subcount.subdivide(m, scheme="catmull-clark", levels=2)
>>> out.positions.shape, out.face_vertex_counts.dtype
((..., 3), dtype('int32'))
>>> subcount.write_mesh(out, "pawn-2.ply")

A mesh is a path, a ``subcount.Mesh`` or ``(positions, faces)`` (faces an ``(F, k)``
integer array or a tuple ``(face_vertex_counts, face_vertex_indices)``). Errors are
``subcount.Error`` subclasses named after the command line's exit codes; notes are
``subcount.Warning``.
"""

from ._errors import (
    Error,
    InputError,
    MismatchError,
    ResourceError,
    UsageError,
    Warning,
)
from ._commands import at, density, fit, formula, schemes, stats, table, verify
from ._subcount import Mesh, Refinement, __version__, read_mesh, subdivide, write_mesh

__all__ = [
    "Error",
    "InputError",
    "Mesh",
    "MismatchError",
    "Refinement",
    "ResourceError",
    "UsageError",
    "Warning",
    "__version__",
    "at",
    "density",
    "fit",
    "formula",
    "read_mesh",
    "schemes",
    "stats",
    "subdivide",
    "table",
    "verify",
    "write_mesh",
]
