"""The example scripts run (the notebook-style Example 3 and the timing script's calls)."""

import pathlib
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[1] / "examples"


def test_example3_runs_and_prints_the_papers_values(tmp_path):
    out = subprocess.run([sys.executable, EXAMPLES / "example3.py"], cwd=tmp_path,
                         capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    assert "Fraction(329, 90), Fraction(89, 450)" in out.stdout
    assert "closest at k2 = 0.30" in out.stdout
    assert "at Example 3: 91/25 = 91/25" in out.stdout


def test_the_scale_out_timing_runs_and_checks_its_results(tmp_path):
    # A small sweep (the script asserts each executor's result equals the in-process one).
    pytest.importorskip("dask.distributed")
    out = subprocess.run([sys.executable, EXAMPLES / "scale_out.py", "200", "2"], cwd=tmp_path,
                         capture_output=True, text=True, timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.count("in-process ÷ this") == 4, out.stdout
