#!/usr/bin/env bash
# The Python bindings' tests, on a fresh machine (network: PyPI only): a virtual environment
# in the Cargo target directory, the build tools and test dependencies from PyPI, the package
# built and installed from this directory (a release build of the extension), then pytest.
# Run by the README's test command and by .ci/run after the cargo tests.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
target="${CARGO_TARGET_DIR:-$here/../target}"
venv="$target/python-test-venv"
python="${PYTHON:-python3}"
[ -x "$venv/bin/python" ] || "$python" -m venv "$venv"
# dask[distributed]: test_executor.py runs solve_batch and sweep on a Dask local cluster.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check maturin pytest numpy sympy "dask[distributed]"
# --no-build-isolation: build with the maturin just installed, in the same target directory
# as cargo (incremental), instead of a throwaway build environment.
PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$target" "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation --force-reinstall --no-deps "$here"
# From tests/, with the pytest script (not `python -m`, which would put the source package in
# python/ first on sys.path): the tests import the installed package.
cd "$here/tests"
status=0
"$venv/bin/pytest" -q -p no:cacheprovider || status=$?
# The guide's Python page runs too: its `>>>` examples are doctests, from the workspace root
# (their paths are the repository's).
cd "$here/.."
"$venv/bin/pytest" -q -p no:cacheprovider --doctest-glob='python.md' guide/python.md || status=$?
# pytest exits 5 when it collected no tests: a failure here, not a pass.
if [ "$status" -ne 0 ]; then
    echo "python tests failed (pytest exit status $status)" >&2
    exit 1
fi
