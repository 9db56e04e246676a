#!/usr/bin/env bash
# The engine conformance suite on demand (benches/engines/README.md): a virtual environment in
# the Cargo target directory with the package and its engines from PyPI wheels (the `engines`
# extra: MuJoCo, PyBullet, Pinocchio, Rapier; Drake where its wheel installs), the engine tests
# of python/tests/test_engines.py (python/test.sh skips them without the engines), then the
# whole catalogue, the random family (seed $SEED, default 2026; $COUNT scenes, default 60) and
# the convergence sweeps graded by every installed engine (or by $ENGINES, comma-separated
# adapter names) into benches/engines/results/ (or the directory given as the first argument):
# report.md, report.json, the SVG plots, report.html and the family's scene files.
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$here/.."
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/python-engines-venv"
python="${PYTHON:-python3}"
out="${1:-$root/benches/engines/results}"
[ -x "$venv/bin/python" ] || "$python" -m venv "$venv"
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check maturin pytest numpy sympy mujoco pybullet pin rapier3d
# Drake (the `drake` extra) only where its wheel installs (manylinux_2_34, glibc ≥ 2.34)
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check drake || echo "drake did not install: its adapter and test are skipped" >&2
PATH="$venv/bin:$PATH" CARGO_TARGET_DIR="$target" "$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    --no-build-isolation --force-reinstall --no-deps "$here"
cd "$here/tests"
"$venv/bin/pytest" -q -p no:cacheprovider test_engines.py test_engine_grades.py
cd "$root"
status=0
"$venv/bin/python" -m inertance.engines --catalogue "$root/benches/engines/scenes" \
    ${ENGINES:+--engines "$ENGINES"} --random "${SEED:-2026}" --random-count "${COUNT:-60}" --convergence \
    --out "$out" || status=$?
"$venv/bin/python" - <<'PY'
import importlib.metadata as md
for p in ("mujoco", "pybullet", "pin", "rapier3d", "drake", "numpy"):
    try:
        print(f"{p} {md.version(p)}")
    except md.PackageNotFoundError:
        print(f"{p} not installed")
PY
exit "$status"
