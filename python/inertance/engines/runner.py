"""Run adapters over catalogue scenes and write the grades as Markdown and JSON."""

from __future__ import annotations

import datetime
import json
import platform
import time
import traceback
from typing import Iterable, Sequence

from .catalogue import CatalogueScene
from .grading import Grade, grade
from .scene import SceneUnsupported


def run(adapters: Sequence, scenes: Sequence[CatalogueScene]) -> dict:
    """Every adapter on every scene. Returns ``{"date", "python", "engines": [{name, version,
    settings}], "scenes": [{name, file, law, contacts}], "grades": [Grade.to_json() …],
    "not_applicable": [{scene, engine, reason}], "failures": [{scene, engine, error}]}``: an
    adapter that refuses a scene it cannot represent (:class:`SceneUnsupported`: a law or a
    coefficient its engine does not have) is listed with the reason; one that raises anything
    else is recorded as a failure with its message — neither is graded, neither is hidden."""
    grades, failures, refused = [], [], []
    for a in adapters:
        for s in scenes:
            t0 = time.perf_counter()
            try:
                twists = a.run(s.engine)
                g = grade(s, a.name, twists)
            except SceneUnsupported as e:
                refused.append({"scene": s.name, "engine": a.name, "reason": e.message})
                continue
            except Exception as e:  # an engine's failure is a result, reported
                failures.append({"scene": s.name, "engine": a.name, "error": f"{type(e).__name__}: {e}",
                                 "trace": traceback.format_exc(limit=3)})
                continue
            d = g.to_json()
            d["seconds"] = time.perf_counter() - t0
            grades.append(d)
    return {
        "date": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        "python": platform.python_version(),
        "engines": [{"name": a.name, "version": str(getattr(a, "version", "?")),
                     "settings": getattr(a, "settings", {})} for a in adapters],
        "scenes": [{"name": s.name, "file": str(s.path), "law": s.law, "contacts": len(s.engine.contacts),
                    "bodies": len(s.engine.bodies),
                    "exact_energy_ratio": s.kinetic_energy_after / s.kinetic_energy_before} for s in scenes],
        "grades": grades,
        "not_applicable": refused,
        "failures": failures,
    }


def _fmt(x: float) -> str:
    return f"{x:.2e}" if x != 0 and (abs(x) < 1e-3 or abs(x) >= 1e4) else f"{x:.3f}"


def markdown(report: dict) -> str:
    """The report as Markdown: one table of errors (scene × engine), one of energy ratios, the
    separation verdicts, the engines' versions and settings, the failures."""
    engines = [e["name"] for e in report["engines"]]
    by = {(g["scene"], g["engine"]): g for g in report["grades"]}
    failed = {(f["scene"], f["engine"]): f for f in report["failures"]}
    refused = {(f["scene"], f["engine"]): f for f in report.get("not_applicable", [])}
    lines = [f"Engine conformance — {report['date']}, Python {report['python']}", ""]
    lines.append("Error of the twist after impact, ‖ξ − ξ*‖_M / ‖ξ* − ξ⁰‖_M (0: exact; 1: as if no impact); "
                 "`!sep` marks a contact that should separate and does not, or the converse; "
                 "`+E` an energy gain above 0.1 %:")
    lines.append("")
    lines.append("| scene | law | " + " | ".join(engines) + " |")
    lines.append("|---|---|" + "---|" * len(engines))
    for s in report["scenes"]:
        cells = []
        for e in engines:
            g = by.get((s["name"], e))
            if g is None:
                cells.append("failed" if (s["name"], e) in failed else "n/a" if (s["name"], e) in refused else "—")
                continue
            c = _fmt(g["error"])
            if not g["separation_ok"]:
                c += " !sep"
            if g["energy_gain"] > 1e-3:
                c += " +E"
            cells.append(c)
        law = s["law"].split(" ")[0]
        lines.append(f"| {s['name']} | {law} | " + " | ".join(cells) + " |")
    lines += ["", "Kinetic energy after / before (inertance's exact answer in the second column):", ""]
    lines.append("| scene | inertance | " + " | ".join(engines) + " |")
    lines.append("|---|---|" + "---|" * len(engines))
    for s in report["scenes"]:
        exact = s.get("exact_energy_ratio")
        cells = [_fmt(by[(s["name"], e)]["energy_ratio"]) if (s["name"], e) in by else "—" for e in engines]
        lines.append(f"| {s['name']} | {'—' if exact is None else _fmt(exact)} | " + " | ".join(cells) + " |")
    lines += ["", "Engines:", ""]
    for e in report["engines"]:
        lines.append(f"- **{e['name']}** {e['version']}: " + ", ".join(f"{k} = {v}" for k, v in e["settings"].items()))
    if report.get("not_applicable"):
        lines += ["", "Not applicable (n/a: the engine's call cannot represent the scene):", ""]
        for f in report["not_applicable"]:
            lines.append(f"- {f['engine']} on {f['scene']}: {f['reason']}")
    if report["failures"]:
        lines += ["", "Failures:", ""]
        for f in report["failures"]:
            lines.append(f"- {f['engine']} on {f['scene']}: {f['error']}")
    return "\n".join(lines) + "\n"


def write(report: dict, out_dir) -> tuple:
    """``report.md`` and ``report.json`` in ``out_dir``; returns their paths."""
    from pathlib import Path

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    md, js = out / "report.md", out / "report.json"
    md.write_text(markdown(report))
    js.write_text(json.dumps(report, indent=1) + "\n")
    return md, js


def convergence(make_adapter, scene: CatalogueScene, steps: Sequence[float]) -> list:
    """One engine's grade on one scene as its time step is refined: ``make_adapter(step)`` builds
    the adapter at that step; returns ``[{"step", "error", "energy_ratio", "separation_ok"}]`` in
    the order given. Does the engine approach the exact answer as the step shrinks, and at what
    rate, or settle elsewhere? (The table of benches/engines/README.md.)"""
    out = []
    for h in steps:
        a = make_adapter(h)
        g = grade(scene, a.name, a.run(scene.engine))
        out.append({"step": h, "error": g.error, "energy_ratio": g.energy_ratio, "separation_ok": g.separation_ok})
    return out
