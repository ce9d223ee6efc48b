"""With SUBCOUNT_NO_SKIP=1 (as `.ci/run` sets it), a skipped test fails: in CI every input
(the CLI binary, the shared meshes, libigl, trimesh, usd-core, SciPy, SymPy, mypy) is there,
and a test that cannot find one must not pass untested."""

import os

import pytest

NO_SKIP = os.environ.get("SUBCOUNT_NO_SKIP") == "1"


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_makereport(item, call):
    outcome = yield
    report = outcome.get_result()
    if NO_SKIP and report.skipped:
        reason = report.longrepr[2] if isinstance(report.longrepr, tuple) else str(report.longrepr)
        report.outcome = "failed"
        report.longrepr = f"skipped under SUBCOUNT_NO_SKIP=1: {reason}"


@pytest.hookimpl(hookwrapper=True)
def pytest_make_collect_report(collector):
    """A module skipped as a whole (`pytest.importorskip` at its top) fails too."""
    outcome = yield
    report = outcome.get_result()
    if NO_SKIP and report.skipped:
        report.outcome = "failed"
