"""Shared paths and the CLI the bindings are compared with."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BAR = ROOT / "examples" / "planar-bar.toml"
HARD = ROOT / "tests" / "hard_cases"


def cli_json(*args):
    """`inertance ARGS --json` from the workspace's CLI, parsed (the reference)."""
    out = subprocess.run(
        ["cargo", "run", "--quiet", "--bin", "inertance", "--", *map(str, args), "--json"],
        cwd=ROOT, capture_output=True, text=True, env=os.environ,
    )
    # 4: some model has no answer, the others are printed (guide/solving.md, "Exit status").
    assert out.returncode in (0, 4), out.stderr
    return json.loads(out.stdout)


@pytest.fixture(scope="session")
def bar():
    import inertance
    return inertance.Scene.load(BAR)
