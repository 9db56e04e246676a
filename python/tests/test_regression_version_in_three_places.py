"""Regression: the version was written in three manifests and the package did not report it.
``inertance.__version__``, the wheel's metadata and ``inertance --version`` now all give
Cargo.toml's ``[workspace.package] version`` (tests/regression_version_in_three_places.rs)."""

import importlib.metadata
import re
import subprocess

import inertance
from conftest import ROOT


def workspace_version():
    """Cargo.toml's ``[workspace.package] version`` (read without tomllib, for Python 3.9)."""
    text = (ROOT / "Cargo.toml").read_text()
    table = text.split("[workspace.package]", 1)[1].split("\n[", 1)[0]
    return re.search(r'^version\s*=\s*"([^"]+)"', table, re.M).group(1)


def test_the_package_reports_the_crate_version():
    assert inertance.__version__ == workspace_version()
    assert importlib.metadata.version("inertance") == inertance.__version__


def test_the_cli_reports_the_same_version():
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--bin", "inertance", "--", "--version"],
        cwd=ROOT, capture_output=True, text=True, check=True,
    )
    assert out.stdout == f"inertance {inertance.__version__}\n"
