"""Convergence: does an engine approach the exact answer as its time step and its solver
iterations are refined, at what rate, or does it settle elsewhere?

:data:`SWEEPS` lists, per shipped engine adapter, the knobs refined and their values (each
from the adapter's default toward finer): the time step (MuJoCo, PyBullet, Rapier, Drake) and
the solver iterations (PyBullet's ``numSolverIterations``, Rapier's ``num_solver_iterations``;
MuJoCo's and Drake's solvers iterate to their own tolerance and have no fixed count in these
adapters). Pinocchio's ``impulseDynamics`` has neither (one linear solve): not swept.

:func:`sweep` grades the engine at each value; :func:`rate` reads the result: the **observed
order** p is the least-squares slope of log(error) against log(h) over the three finest
values (h the time step, or 1/N for N iterations), so error ∝ hᵖ there. The verdict:

* ``exact`` — every error below 10⁻¹² (nothing to refine);
* ``converges, order p`` — p ≥ 0.5 (the error at least shrinks by √2 when h halves) and the
  finest error is the smallest;
* ``settles at E`` — |p| < 0.2 over the finest values (the error changes by less than 15 % per
  halving of h): refining no longer helps; E is the finest error;
* ``diverges`` — p ≤ −0.5; else ``no clear trend``.

These thresholds are the reading, stated; the numbers beside them are what was measured.
"""

from __future__ import annotations

import math
from typing import Sequence

import numpy as np

from .catalogue import CatalogueScene
from .grading import grade

#: The scenes swept by default (issue 26: one contact, an edge, a flat face, the cradle).
SCENES = ("ball-floor-e05", "box-edge-30", "box-flat-e05", "cradle-3")


def _mujoco(**kw):
    from .mujoco_adapter import MuJoCoAdapter
    return MuJoCoAdapter(**kw)


def _pybullet(**kw):
    from .pybullet_adapter import PyBulletAdapter
    return PyBulletAdapter(**kw)


def _rapier(**kw):
    from .rapier_adapter import RapierAdapter
    return RapierAdapter(**kw)


def _drake(**kw):
    from .drake_adapter import DrakeAdapter
    return DrakeAdapter(**kw)


#: engine → [(knob, values, make(value) -> adapter)]; the values go from the default to finer.
SWEEPS = {
    "mujoco": [("timestep", [2e-3, 1e-3, 5e-4, 2.5e-4, 1.25e-4], lambda h: _mujoco(tuned=False, timestep=h))],
    "mujoco-calibrated": [("timestep", [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5],
                           lambda h: _mujoco(tuned=True, calibrated=True, timestep=h))],
    "pybullet": [("timestep", [1 / 240, 1 / 480, 1 / 960, 1 / 1920, 1 / 3840],
                  lambda h: _pybullet(timestep=h, max_steps=round(1 / h))),
                 ("iterations", [1, 2, 4, 10, 50, 200], lambda n: _pybullet(iterations=n))],
    "rapier": [("dt", [1 / 60, 1 / 120, 1 / 240, 1 / 480, 1 / 960, 1 / 1920], lambda h: _rapier(dt=h)),
               ("iterations", [1, 2, 4, 8, 16, 32], lambda n: _rapier(iterations=n))],
    "drake": [("time_step", [1e-3, 5e-4, 2.5e-4, 1.25e-4], lambda h: _drake(time_step=h))],
    "drake-tuned": [("time_step", [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5], lambda h: _drake(variant="tuned", time_step=h))],
    "drake-calibrated": [("time_step", [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5],
                          lambda h: _drake(variant="calibrated", time_step=h))],
    "drake-hydroelastic": [("time_step", [4e-4, 2e-4, 1e-4, 5e-5, 2.5e-5],
                            lambda h: _drake(variant="hydroelastic", time_step=h))],
}


def is_iterations(knob: str) -> bool:
    return "iteration" in knob


def sweep(engine: str, knob: str, values: Sequence, make, scene: CatalogueScene) -> dict:
    """``make(value)``'s adapter graded on ``scene`` at each value, with :func:`rate`'s reading."""
    points = []
    for v in values:
        a = make(v)
        g = grade(scene, a.name, a.run(scene.engine))
        points.append({"value": v, "error": g.error, "energy_ratio": g.energy_ratio,
                       "separation_ok": g.separation_ok, "symmetry_broken": g.symmetry_broken})
    h = [1 / p["value"] if is_iterations(knob) else p["value"] for p in points]
    order, verdict = rate(h, [p["error"] for p in points])
    return {"engine": engine, "knob": knob, "scene": scene.name, "points": points, "order": order,
            "verdict": verdict}


def rate(h: Sequence[float], errors: Sequence[float]) -> tuple:
    """(observed order p, verdict) of errors against a refinement measure h (module docstring)."""
    if max(errors) < 1e-12:
        return None, "exact"
    hs, es = np.log(np.asarray(h[-3:], float)), np.log(np.maximum(np.asarray(errors[-3:], float), 1e-300))
    p = float(np.polyfit(hs, es, 1)[0])
    if p >= 0.5 and errors[-1] <= min(errors):
        return p, f"converges, order {p:.2f}"
    if abs(p) < 0.2:
        return p, f"settles at {errors[-1]:.3g}"
    if p <= -0.5:
        return p, f"diverges (order {p:.2f})"
    return p, f"no clear trend (order {p:.2f})"


def run(engines: Sequence[str], scenes: Sequence[CatalogueScene]) -> list:
    """Every sweep of the named engines (those in :data:`SWEEPS`) on every scene."""
    out = []
    for e in engines:
        for knob, values, make in SWEEPS.get(e, []):
            for s in scenes:
                out.append(sweep(e, knob, values, make, s))
    return out


def _value(knob: str, v) -> str:
    if is_iterations(knob):
        return str(v)
    inv = 1 / v
    return f"1/{round(inv)}" if abs(inv - round(inv)) < 1e-6 * inv else f"{v:g}"


def markdown(results: Sequence[dict]) -> str:
    """The sweeps as a table: the error at each value, the observed order and the verdict."""
    if not results:
        return ""
    lines = ["| engine | knob: values | scene | error at each value | order | verdict |", "|---|---|---|---|---|---|"]
    for r in results:
        vals = ", ".join(_value(r["knob"], p["value"]) for p in r["points"])
        errs = ", ".join(f"{p['error']:.2e}" for p in r["points"])
        order = "—" if r["order"] is None else f"{r['order']:.2f}"
        lines.append(f"| {r['engine']} | {r['knob']}: {vals} | {r['scene']} | {errs} | {order} | {r['verdict']} |")
    return "\n".join(lines) + "\n"


def svgs(results: Sequence[dict]) -> dict:
    """Log–log plots: per scene, error against the time step (every engine), and error against
    the iterations (the engines that have a count). ``{file name: SVG text}``."""
    from .plot import lines

    out = {}
    for scene in dict.fromkeys(r["scene"] for r in results):
        for kind in ("step", "iterations"):
            rs = [r for r in results if r["scene"] == scene and is_iterations(r["knob"]) == (kind == "iterations")]
            if not rs:
                continue
            series = {f"{r['engine']}": [(p["value"], p["error"]) for p in r["points"]] for r in rs}
            if kind == "step":
                out[f"convergence-step-{scene}.svg"] = lines(
                    series, f"{scene}: error against the time step", "time step (s)", "error")
            else:
                out[f"convergence-iterations-{scene}.svg"] = lines(
                    series, f"{scene}: error against the solver iterations", "solver iterations", "error")
    return out
