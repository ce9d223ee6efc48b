"""The package is typed and documented: its stubs match the compiled module (mypy's stubtest),
type-check under ``mypy --strict``, every ``>>>`` example of every docstring runs, ``help()``
renders, and ``__version__`` is the crate's version."""

import doctest
import importlib.util
import io
import pydoc
import re
import subprocess
import sys
import textwrap
import types
from pathlib import Path

import numpy
import pytest

import subcount
import subcount._commands
import subcount._errors
import subcount._subcount

PYTHON_DIR = Path(__file__).resolve().parents[1]
PACKAGE_DIR = Path(subcount.__file__).resolve().parent

# Every module of the package: their docstrings and those of what they define.
MODULES = [subcount, subcount._subcount, subcount._commands, subcount._errors]
MODULE_NAMES = {m.__name__ for m in MODULES}

DOCTEST_FLAGS = doctest.ELLIPSIS | doctest.NORMALIZE_WHITESPACE

needs_mypy = pytest.mark.skipif(
    importlib.util.find_spec("mypy") is None,
    reason="mypy is not installed (pip install mypy): the stubs are not checked",
)


def run_mypy_module(args, cwd):
    """``python -m ARGS`` in `cwd`: (exit code, stdout and stderr)."""
    done = subprocess.run(
        [sys.executable, "-m", *args], cwd=cwd, capture_output=True, text=True, timeout=600
    )
    return done.returncode, done.stdout + done.stderr


# --- stubs -------------------------------------------------------------------------------


def test_the_package_ships_its_stubs_and_the_py_typed_marker():
    assert (PACKAGE_DIR / "py.typed").is_file()
    assert (PACKAGE_DIR / "_subcount.pyi").is_file()


@needs_mypy
def test_stubtest_finds_the_stubs_consistent_with_the_compiled_module(tmp_path):
    # From an empty directory: stubtest imports the installed package, not a source tree.
    code, output = run_mypy_module(["mypy.stubtest", "subcount"], tmp_path)
    assert code == 0, output


# Uses of the API that must type-check under --strict, with the types the stubs promise.
USES = """
    import pathlib
    from typing import Any, Optional, Union

    import numpy as np
    import numpy.typing as npt
    from typing_extensions import assert_type

    import subcount

    m = subcount.Mesh([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [3], [0, 1, 2], options={"boundary": "edge"})
    assert_type(subcount.read_mesh(pathlib.Path("a.obj")), subcount.Mesh)
    assert_type(m.positions, npt.NDArray[Union[np.float64, np.float32]])
    assert_type(m.face_vertex_indices, npt.NDArray[np.int32])
    assert_type(m.uv_indices, Optional[npt.NDArray[np.int32]])
    assert_type(m.crease_sharpnesses, npt.NDArray[np.float32])
    assert_type(m.materials, Optional[list[Optional[str]]])
    assert_type(m.options, dict[str, str])
    assert_type(m.n_faces, int)
    out = subcount.subdivide(
        (np.zeros((3, 3)), ([3], [0, 1, 2])), scheme="loop", levels=1, boundary="edge-and-corner",
        uv_interpolation="corners-plus1", precision="f32",
    )
    subcount.subdivide("a.obj", scheme="loop", levels=1)
    subcount.write_mesh(out, "a.ply")
    r = subcount.Refinement(m, scheme="loop", levels=2, crease_method="chaikin")
    assert_type(r.evaluate([[0.0, 0.0, 0.0]] * 3), npt.NDArray[np.float64])
    assert_type(r.evaluate(np.zeros((3, 3), np.float32)), npt.NDArray[np.float32])
    assert_type(r.evaluate_uvs(), npt.NDArray[np.float64])
    assert_type(r.n_vertices(1), int)
    assert_type(r.uv_indices, Optional[npt.NDArray[np.int32]])
    assert_type(r.stencils(), Any)
    assert_type(subcount.__version__, str)
    assert_type(subcount.table(range(2, 4))[0], dict[str, Any])
"""

# Misuses the stubs must refuse, each with the error code mypy gives.
MISUSES = """
    import subcount

    m = subcount.read_mesh("a.obj")
    subcount.subdivide(m, "loop", 2)  # E: call-arg
    subcount.subdivide(m, scheme="loop", levels=2, boundary="edge_and_corner")  # E: arg-type
    subcount.subdivide(m, scheme="loop", levels=2, precision="f16")  # E: arg-type
    m.positions = m.positions  # E: misc
    class Sub(subcount.Refinement): ...  # E: misc
"""


@needs_mypy
def test_the_stubs_type_check_uses_and_refuse_misuses_under_strict(tmp_path):
    (tmp_path / "uses.py").write_text(textwrap.dedent(USES))
    code, output = run_mypy_module(["mypy", "--strict", "--no-incremental", "uses.py"], tmp_path)
    assert code == 0, output

    misuses = textwrap.dedent(MISUSES)
    (tmp_path / "misuses.py").write_text(misuses)
    code, output = run_mypy_module(["mypy", "--strict", "--no-incremental", "misuses.py"], tmp_path)
    # The lines marked "# E:" and no other (the codes there are mypy's at the time of writing).
    expected = {n for n, line in enumerate(misuses.splitlines(), 1) if "# E: " in line}
    found = {int(n) for n in re.findall(r"^misuses\.py:(\d+): error: ", output, re.M)}
    assert found == expected, output
    assert code == 1, output


@needs_mypy
def test_the_stubs_themselves_pass_strict_mypy(tmp_path):
    code, output = run_mypy_module(
        # A copy: the installed file's folder is site-packages, which mypy would then take as
        # a source root beside the installed libraries (it refuses the shadowed modules).
        ["mypy", "--strict", "--no-incremental", str(stub_copy(tmp_path))], tmp_path
    )
    assert code == 0, output


def stub_copy(tmp_path):
    """The installed stub, copied into its own folder of `tmp_path`."""
    folder = tmp_path / "stub"
    folder.mkdir()
    copy = folder / "_subcount.pyi"
    copy.write_text((PACKAGE_DIR / "_subcount.pyi").read_text())
    return copy


# --- doctests ----------------------------------------------------------------------------

# The members of a class whose docstrings are the API's: methods, properties (PyO3's getters
# are getset descriptors, which doctest's finder passes over) and nested classes.
MEMBER_TYPES = (
    types.FunctionType,
    types.BuiltinFunctionType,
    types.MethodDescriptorType,
    types.GetSetDescriptorType,
    types.MemberDescriptorType,
    types.WrapperDescriptorType,
    types.ClassMethodDescriptorType,
    property,
    staticmethod,
    classmethod,
    type,
)


def documented_objects():
    """(name, object) for each module of the package, everything a module defines (classes
    of the compiled module say ``module = "subcount"``) and each member of its classes; each
    object once."""
    seen = set()
    for module in MODULES:
        found = [(module.__name__, module)]
        for name, obj in vars(module).items():
            if getattr(obj, "__module__", None) not in MODULE_NAMES:
                continue
            if not (isinstance(obj, type) or callable(obj)):
                continue
            found.append((f"{module.__name__}.{name}", obj))
            if isinstance(obj, type):
                for attr, member in vars(obj).items():
                    if isinstance(member, MEMBER_TYPES):
                        found.append((f"{module.__name__}.{name}.{attr}", member))
        for name, obj in found:
            if id(obj) not in seen:
                seen.add(id(obj))
                yield name, obj


def docstring_tests():
    """The doctests of every docstring of the package (fresh globals for each)."""
    parser = doctest.DocTestParser()
    tests = []
    for name, obj in documented_objects():
        doc = obj.__doc__ if isinstance(obj.__doc__, str) else None
        if not doc:
            continue
        globs = {"subcount": subcount, "numpy": numpy, "__name__": name}
        test = parser.get_doctest(doc, globs, name, None, None)
        if test.examples:
            tests.append(test)
    return tests


def test_the_walk_finds_every_docstring_doctests_finder_finds():
    """doctest.testmod's finder misses nothing the walk of the modules does not also find
    (the walk adds PyO3's getters, which the finder passes over)."""
    ours = {t.docstring for t in docstring_tests()}
    finder = doctest.DocTestFinder()
    for module in MODULES:
        for test in finder.find(module, extraglobs={"subcount": subcount, "numpy": numpy}):
            if test.examples:
                assert test.docstring in ours, test.name


# The file the examples read ("pawn.obj"): a closed quad mesh, a cube, in the test's folder.
PAWN = """\
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
"""


def test_every_docstring_example_runs(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "pawn.obj").write_text(PAWN)
    tests = docstring_tests()
    names = sorted(t.name for t in tests)
    # The Rust docstrings (classes of the compiled module) and the Python ones are all here.
    docstrings = {t.docstring for t in tests}
    for obj in (subcount, subcount.Mesh, subcount.Refinement, subcount.table, subcount.verify,
                subcount.read_mesh, subcount.subdivide):
        assert obj.__doc__ in docstrings, (obj, names)
    report = io.StringIO()
    runner = doctest.DocTestRunner(optionflags=DOCTEST_FLAGS)
    failed = attempted = 0
    for test in tests:
        result = runner.run(test, out=report.write)
        failed += result.failed
        attempted += result.attempted
    assert failed == 0, report.getvalue()
    assert attempted > 10, (attempted, names)
    # Nothing is skipped: every example runs (the package's own, read_mesh's, subdivide's).
    skipped = [t.name for t in tests for e in t.examples if e.options.get(doctest.SKIP)]
    assert not skipped, skipped
    assert (tmp_path / "pawn-2.ply").exists()


# --- help and version --------------------------------------------------------------------


def test_help_renders_the_package():
    text = pydoc.render_doc(subcount, renderer=pydoc.plaintext)
    for word in ("Refinement", "Mesh", "subdivide", "read_mesh", "write_mesh", "table", "at(",
                 "UsageError"):
        assert word in text, word
    assert f"VERSION\n    {subcount.__version__}\n" in text
    # The compiled classes and functions show their signatures.
    assert "subdivide(mesh, *, scheme=None, levels, scheme_file=None" in text
    assert "evaluate(self, /, points, out=None)" in text


def cargo_version():
    """The version in python/Cargo.toml's [package] table."""
    text = (PYTHON_DIR / "Cargo.toml").read_text()
    package = re.search(r"^\[package\]\s*$(.*?)(?=^\[)", text, re.M | re.S)
    assert package, "no [package] table in Cargo.toml"
    version = re.search(r'^version\s*=\s*"([^"]+)"', package.group(1), re.M)
    assert version, "no version in Cargo.toml's [package]"
    return version.group(1)


def test_version_is_the_crates():
    assert isinstance(subcount.__version__, str) and subcount.__version__
    assert subcount.__version__ == cargo_version()
    assert subcount._subcount.__version__ == subcount.__version__
    assert "__version__" in subcount.__all__
