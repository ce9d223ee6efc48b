"""The counting commands: ``at``, ``table``, ``formula``, ``fit``, ``density``, ``schemes``,
``stats`` and ``verify``.

Each runs the command line's own command in this process (``_subcount.run_command``: the same
parsing, checks, JSON and messages as ``subcount COMMAND --format json``) and returns its JSON
as Python values; counts are ``int`` of any size. Keywords are the command line's flags with
dashes as underscores; a mesh is a path, a ``subcount.Mesh`` or ``(positions, faces)``.
"""

from __future__ import annotations

import json
import numbers
import operator
import os
import warnings
from typing import Any, Dict, List, Mapping, Optional, Sequence, Union

from . import _errors
from ._subcount import run_command

# The exception of each exit code of the command line.
_ERRORS = {
    1: _errors.MismatchError,
    2: _errors.UsageError,
    3: _errors.InputError,
    4: _errors.ResourceError,
}

# Python's int() refuses decimal strings beyond this many digits (CVE-2020-10735); longer
# counts are split in halves (subquadratic with Karatsuba products).
_INT_DIGITS = 4000


def _big_int(text: str) -> int:
    """A JSON integer of any length (``int(text)`` with no digit limit)."""
    if len(text) <= _INT_DIGITS:
        return int(text)
    if text[0] == "-":
        return -_big_int(text[1:])
    low = len(text) // 2
    return _big_int(text[:-low]) * 10**low + _big_int(text[-low:])


def _run(args: List[str], mesh: Any = None, text: bool = False) -> Any:
    """Runs ``subcount ARGS``: warns its notes, raises its error, returns its JSON (its text
    with ``text``)."""
    code, stdout, notes, error = run_command(args, mesh)
    for note in notes:
        warnings.warn(note, _errors.Warning, stacklevel=3)
    if text and code == 0:
        return stdout
    report = json.loads(stdout, parse_int=_big_int) if stdout.strip() and not text else None
    if code == 0:
        return report
    message = error or f"the command ended with exit code {code}"
    if code == 1:
        mismatch = _errors.MismatchError(message)
        mismatch.report = report  # verify's levels, the one that differs included
        raise mismatch
    raise _ERRORS.get(code, _errors.Error)(message)


def _levels(levels: Union[int, range], name: str = "levels") -> str:
    """``--levels``: an int N (0..=N) or a range of step 1."""
    if isinstance(levels, range):
        if levels.step != 1:
            raise _errors.UsageError(f"{name} must be a range of step 1, not {levels!r}")
        return f"{levels.start}..{levels.stop}"
    if isinstance(levels, bool) or not hasattr(levels, "__index__"):
        raise TypeError(f"{name} must be an int or a range, not {type(levels).__name__}")
    return str(operator.index(levels))


def _text(value: Any, name: str) -> str:
    """A number or a str as the command line writes it (bool refused)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, str, numbers.Number)):
        raise TypeError(f"{name} must be a number or a str, not {type(value).__name__}")
    if hasattr(value, "__index__") and not isinstance(value, str):
        return str(operator.index(value))  # numpy's integers too
    return str(value)


# The keywords of a command's recurrence and initial state (the command line's `Source`
# flags), taken by every counting command.
_SOURCE_KEYWORDS = (
    "scheme", "scheme_file", "matrix", "names", "init", "counts",
    "mesh", "base", "boundary", "crease_method", "triangle_rule", "ignore_tags",
)  # fmt: skip


def _source_of(arguments: Mapping[str, Any]) -> Dict[str, Any]:
    """The source keywords among a command's arguments (its ``locals()``)."""
    return {key: arguments[key] for key in _SOURCE_KEYWORDS}


def _source(
    args: List[str],
    *,
    scheme: Optional[str],
    scheme_file: Optional[Union[str, os.PathLike]],
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    **mesh_flags: Any,
) -> Any:
    """Appends the flags of a recurrence and its initial state; returns the in-memory mesh."""
    if scheme is not None:
        args += ["--scheme", scheme]
    if scheme_file is not None:
        args += ["--scheme-file", os.fspath(scheme_file)]
    if matrix is not None:
        text = matrix if isinstance(matrix, str) else json.dumps([[int(x) for x in row] for row in matrix])
        args += ["--matrix", text]
    if names is not None:
        args += ["--names", names if isinstance(names, str) else ",".join(names)]
    if init is not None:
        args += ["--init", init if isinstance(init, str) else ",".join(str(int(x)) for x in init)]
    if counts is not None:
        if isinstance(counts, str):
            text = counts
        else:
            text = ",".join(f"{k}={_text(v, f'counts[{k!r}]')}" for k, v in counts.items())
        args += ["--counts", text]
    return _mesh(args, **mesh_flags)


def _mesh(
    args: List[str],
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
) -> Any:
    """Appends the mesh flags; returns the mesh to hand over in memory (or None)."""
    memory = None
    if isinstance(mesh, (str, os.PathLike)):
        args += ["--mesh", os.fspath(mesh)]
    elif mesh is not None:
        memory = mesh
    if base is not None:
        args += ["--base", base]
    for flag, value in (
        ("--boundary", boundary),
        ("--crease-method", crease_method),
        ("--triangle-rule", triangle_rule),
    ):
        if value is not None:
            args += [flag, value]
    if ignore_tags:
        args.append("--ignore-tags")
    return memory


def at(
    level: int,
    *,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
    summary: bool = False,
    allow_large: bool = False,
) -> Dict[str, Any]:
    """Exact counts at one level, however large: ``subcount at --format json``.

    The state comes from ``counts`` (a dict such as ``{"V": 12, "E": 30, "F": 20}``),
    ``init``, ``mesh`` or ``base``; the recurrence from ``scheme``, ``scheme_file`` or
    ``matrix`` (with ``names``). With ``summary=True`` each count is
    ``{"digits": n, "leading": str, "trailing": str}``.

    >>> subcount.at(3, scheme="loop", counts={"V": 12, "E": 30, "F": 20})
    {'level': 3, 'V': 642, 'E': 1920, 'F': 1280}
    >>> subcount.at(10**5, scheme="loop", counts={"V": 12, "E": 30, "F": 20})["F"].bit_length()
    200005
    """
    args = ["at", "--level", _text(level, "level"), "--format", "json"]
    memory = _source(args, **_source_of(locals()))
    if summary:
        args.append("--summary")
    if allow_large:
        args.append("--allow-large")
    return _run(args, memory)


def table(
    levels: Union[int, range] = 8,
    *,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
) -> List[Dict[str, Any]]:
    """Counts per level, one dict per level: ``subcount table --format json``.

    ``levels`` is a ``range`` (step 1) or an int N meaning ``range(0, N + 1)``. Without a
    scheme or a matrix: the icosahedron under 4:1 subdivision. A mesh with texture
    coordinates adds a ``UV`` column.

    >>> subcount.table(2, scheme="catmull-clark", base="cube")[-1]
    {'level': 2, 'V': 98, 'IE': 192, 'BE': 0, 'F': 96, 'H': 384, 'E': 192}
    >>> [row["F"] for row in subcount.table(range(3, 5))]
    [1280, 5120]
    """
    args = ["table", "--levels", _levels(levels), "--format", "json"]
    memory = _source(args, **_source_of(locals()))
    return _run(args, memory)


_FORMULA_FORMATS = ("text", "latex", "rust", "json", "sympy")


def formula(
    *,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
    format: str = "text",
    allow_large: bool = False,
) -> Any:
    """Exact closed forms of the counts: ``subcount formula``.

    ``format``: "text", "latex" or "rust" return the command line's text; "json" its list of
    components (a scheme whose levels go in phases, as ``sqrt3-boundary``, or a composition:
    a list of phases, each with its ``forms``); "sympy" (needs SymPy) the same structure with
    each component's form as a SymPy expression in ``s`` (in ``t``, the step within a
    phase) and the initial counts ``V0``, ``E0``, ..., exact early levels as ``Piecewise``.

    >>> print(subcount.formula(scheme="loop"))
    V(s) = V0 + (4^s - 1)/3 * E0
    E(s) = 4^s * E0
    <BLANKLINE>
    >>> subcount.formula(scheme="loop", format="sympy")["E"]         # needs SymPy
    4**s*E0
    """
    if format not in _FORMULA_FORMATS:
        raise _errors.UsageError(
            f"invalid format {format!r}: expected one of {', '.join(map(repr, _FORMULA_FORMATS))}"
        )
    sympy = None
    if format == "sympy":
        import sympy  # type: ignore  # noqa: F811 (an optional, untyped dependency, imported when asked for)
    args = ["formula", "--format", "json" if format == "sympy" else format]
    memory = _source(args, **_source_of(locals()))
    if allow_large:
        args.append("--allow-large")
    report = _run(args, memory, text=format in ("text", "latex", "rust"))
    if sympy is None:
        return report
    if report and "phase" in report[0]:
        return [dict(p, forms=_sympy_forms(sympy, p["forms"], "t")) for p in report]
    return _sympy_forms(sympy, report, "s")


def _sympy_forms(sympy: Any, forms: List[Dict[str, Any]], step: str) -> Dict[str, Any]:
    """Each component's closed form as a SymPy expression in ``step``."""
    s = sympy.Symbol(step, integer=True, nonnegative=True)
    out = {}
    for form in forms:

        def combination(coefficients: Mapping[str, str]) -> Any:
            return sum(
                (sympy.sympify(c) * sympy.Symbol(f"{name}0") for name, c in coefficients.items()),
                sympy.Integer(0),
            )

        expr = sympy.Integer(0)
        for term in form["terms"]:
            base = sympy.sympify(term["eigenvalue"])
            expr += combination(term["coefficients"]) * base**s * s ** term["s_power"]
        early = [(combination(e["coefficients"]), sympy.Eq(s, e["level"])) for e in form["early_levels"]]
        out[form["component"]] = sympy.Piecewise(*early, (expr, True)) if early else expr
    return out


def fit(
    *,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
    max_vertices: Optional[int] = None,
    max_edges: Optional[int] = None,
    max_faces: Optional[int] = None,
    max_uv: Optional[int] = None,
    memory: Optional[Union[int, str]] = None,
    bytes_per_vertex: int = 12,
    bytes_per_edge: int = 0,
    bytes_per_face: int = 12,
    bytes_per_uv: Optional[int] = None,
) -> Dict[str, Any]:
    """The highest level within a budget: ``subcount fit --format json``.

    ``memory`` is bytes (an int) or a size such as ``"2GiB"``.

    >>> subcount.fit(scheme="loop", counts={"V": 12, "E": 30, "F": 20}, max_faces=100_000)
    {'level': 6, 'V': 40962, 'E': 122880, 'F': 81920}
    """
    args = ["fit", "--format", "json"]
    memory_mesh = _source(args, **_source_of(locals()))
    for flag, value in (
        ("--max-vertices", max_vertices),
        ("--max-edges", max_edges),
        ("--max-faces", max_faces),
        ("--max-uv", max_uv),
        ("--memory", memory),
        ("--bytes-per-uv", bytes_per_uv),
    ):
        if value is not None:
            args += [flag, _text(value, flag[2:].replace("-", "_"))]
    args += [
        "--bytes-per-vertex", _text(bytes_per_vertex, "bytes_per_vertex"),
        "--bytes-per-edge", _text(bytes_per_edge, "bytes_per_edge"),
        "--bytes-per-face", _text(bytes_per_face, "bytes_per_face"),
    ]  # fmt: skip
    return _run(args, memory_mesh)


def density(
    *,
    level: Optional[int] = None,
    target_area: Optional[float] = None,
    radius: float = 1.0,
    tau: Optional[float] = None,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    matrix: Optional[Union[str, Sequence[Sequence[int]]]] = None,
    names: Optional[Union[str, Sequence[str]]] = None,
    init: Optional[Union[str, Sequence[int]]] = None,
    counts: Optional[Union[str, Mapping[str, int]]] = None,
    mesh: Any = None,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
) -> Dict[str, Any]:
    """The mean co-volume area at a level, or the level for a target area (the paper's eq. (1)):
    ``subcount density --format json``.

    >>> subcount.density(level=2)
    {'level': 2, 'V': 162, 'radius': 1.0, 'mean_area': 0.07757018897752575}
    """
    args = ["density", "--format", "json", "--radius", _text(radius, "radius")]
    if level is not None:
        args += ["--level", _text(level, "level")]
    if target_area is not None:
        args += ["--target-area", _text(target_area, "target_area")]
    if tau is not None:
        args += ["--tau", _text(tau, "tau")]
    memory = _source(args, **_source_of(locals()))
    return _run(args, memory)


def schemes(name: Optional[str] = None) -> List[Dict[str, Any]]:
    """The built-in schemes (or the one named), as ``subcount schemes --format json``.

    >>> [s["name"] for s in subcount.schemes()][:3]
    ['loop', 'loop-boundary', 'loop-general']
    """
    args = ["schemes", "--format", "json"]
    if name is not None:
        args.append(name)
    return _run(args)


def stats(
    mesh: Any = None,
    *,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
) -> Dict[str, Any]:
    """A mesh's statistics and the schemes that apply to it: ``subcount stats --format json``.

    >>> s = subcount.stats(base="cube")
    >>> s["V"], s["E"], s["F"], s["genus"], s["applicable_schemes"][:2]
    (8, 12, 6, 0, ['catmull-clark-quad', 'catmull-clark'])
    """
    args = ["stats", "--format", "json"]
    memory = _mesh(args, mesh, base, boundary, crease_method, triangle_rule, ignore_tags)
    return _run(args, memory)


def verify(
    mesh: Any = None,
    *,
    scheme: Optional[str] = None,
    scheme_file: Optional[Union[str, os.PathLike]] = None,
    levels: Optional[int] = None,
    max_faces: int = 2_000_000,
    threads: int = 0,
    allow_large: bool = False,
    base: Optional[str] = None,
    boundary: Optional[str] = None,
    crease_method: Optional[str] = None,
    triangle_rule: Optional[str] = None,
    ignore_tags: bool = False,
) -> List[Dict[str, Any]]:
    """Subdivides for real and compares every count with the prediction: ``subcount verify
    --format json``, one dict per level. A mismatch raises ``subcount.MismatchError`` whose
    ``report`` attribute holds that list.

    >>> [row["match"] for row in subcount.verify(base="cube", scheme="catmull-clark", levels=2)]
    [True, True, True]
    """
    args = ["verify", "--format", "json", "--max-faces", _text(max_faces, "max_faces")]
    args += ["--threads", _text(threads, "threads")]
    if scheme is not None:
        args += ["--scheme", scheme]
    if scheme_file is not None:
        args += ["--scheme-file", os.fspath(scheme_file)]
    if levels is not None:
        args += ["--levels", _text(levels, "levels")]
    if allow_large:
        args.append("--allow-large")
    memory = _mesh(args, mesh, base, boundary, crease_method, triangle_rule, ignore_tags)
    return _run(args, memory)
