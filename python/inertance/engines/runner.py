"""Run adapters over catalogue scenes and write the grades as Markdown and JSON."""

from __future__ import annotations

import datetime
import json
import platform
import statistics
import time
import traceback
from typing import Iterable, Sequence

from .catalogue import CatalogueScene
from .grading import Grade, grade
from .scene import SceneUnsupported


def run(adapters: Sequence, scenes: Sequence[CatalogueScene], family: Sequence[CatalogueScene] = (),
        seed=None) -> dict:
    """Every adapter on every scene. Returns ``{"date", "python", "engines": [{name, version,
    settings}], "scenes": [{name, file, law, contacts}], "grades": [Grade.to_json() …],
    "not_applicable": [{scene, engine, reason}], "failures": [{scene, engine, error}]}``: an
    adapter that refuses a scene it cannot represent (:class:`SceneUnsupported`: a law or a
    coefficient its engine does not have) is listed with the reason; one that raises anything
    else is recorded as a failure with its message — neither is graded, neither is hidden.
    ``family``: the random family's scenes (:mod:`.random_family`, drawn from ``seed``), graded
    the same way, listed with ``"family": "random"`` and summarised (:func:`summaries`)."""
    grades, failures, refused = [], [], []
    everything = list(scenes) + list(family)
    random_names = {s.name for s in family}
    for a in adapters:
        for s in everything:
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
                    "bodies": len(s.engine.bodies), "symmetries": [x.name for x in s.symmetries],
                    "family": "random" if s.name in random_names else "catalogue",
                    "exact_energy_ratio": s.kinetic_energy_after / s.kinetic_energy_before} for s in everything],
        "random_seed": seed if family else None,
        "grades": grades,
        "not_applicable": refused,
        "failures": failures,
        "convergence": [],
    }


def summaries(report: dict, family: str = "random") -> list:
    """Per engine over the scenes of ``family``: how many were graded (n/a and failures apart),
    the median and the worst error (and its scene), and the fractions of graded scenes that
    gain energy (``+E``: above 0.1 %), break separation (``!sep``) and break a symmetry
    (``!sym``; random scenes are generically asymmetric); how many graded scenes determine the
    contact impulses (``impulses_determined``) and how many of those need a pull (``pulls``)."""
    names = {s["name"] for s in report["scenes"] if s.get("family", "catalogue") == family}
    out = []
    for e in report["engines"]:
        gs = [g for g in report["grades"] if g["engine"] == e["name"] and g["scene"] in names]
        na = sum(1 for f in report.get("not_applicable", []) if f["engine"] == e["name"] and f["scene"] in names)
        failed = sum(1 for f in report["failures"] if f["engine"] == e["name"] and f["scene"] in names)
        row = {"engine": e["name"], "scenes": len(names), "graded": len(gs), "not_applicable": na, "failed": failed}
        if gs:
            errs = sorted(g["error"] for g in gs)
            worst = max(gs, key=lambda g: g["error"])
            row.update({"median_error": float(statistics.median(errs)), "worst_error": worst["error"],
                        "worst_scene": worst["scene"],
                        "gains_energy": sum(g["energy_gain"] > ENERGY_FLAG for g in gs) / len(gs),
                        "breaks_separation": sum(not g["separation_ok"] for g in gs) / len(gs),
                        "breaks_symmetry": sum(not g["symmetry_ok"] for g in gs) / len(gs),
                        "impulses_determined": sum(g.get("pull") is not None for g in gs),
                        "pulls": sum(not g.get("pull_ok", True) for g in gs)})
        out.append(row)
    return out


#: The energy gain flagged ``+E`` (a fraction of the energy before impact).
ENERGY_FLAG = 1e-3


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
                 "`+E` an energy gain above 0.1 %; `!sym` a symmetric scene's answer whose reversed part "
                 "exceeds 0.1 % of the impact (the symmetries are in the scene table below); `!pull` an "
                 "answer whose twist change needs a contact to pull (a normal impulse below −0.1 % of the "
                 "impact's impulse scale, the impulse table below):")
    lines.append("")
    lines.append("| scene | law | " + " | ".join(engines) + " |")
    lines.append("|---|---|" + "---|" * len(engines))
    catalogue = [s for s in report["scenes"] if s.get("family", "catalogue") == "catalogue"]
    for s in catalogue:
        cells = []
        for e in engines:
            g = by.get((s["name"], e))
            if g is None:
                cells.append("failed" if (s["name"], e) in failed else "n/a" if (s["name"], e) in refused else "—")
                continue
            c = _fmt(g["error"])
            if not g["separation_ok"]:
                c += " !sep"
            if g["energy_gain"] > ENERGY_FLAG:
                c += " +E"
            if not g.get("symmetry_ok", True):
                c += " !sym"
            if not g.get("pull_ok", True):
                c += " !pull"
            cells.append(c)
        law = s["law"].split(" ")[0]
        lines.append(f"| {s['name']} | {law} | " + " | ".join(cells) + " |")
    lines += ["", "Kinetic energy after / before (inertance's exact answer in the second column):", ""]
    lines.append("| scene | inertance | " + " | ".join(engines) + " |")
    lines.append("|---|---|" + "---|" * len(engines))
    for s in catalogue:
        exact = s.get("exact_energy_ratio")
        cells = [_fmt(by[(s["name"], e)]["energy_ratio"]) if (s["name"], e) in by else "—" for e in engines]
        lines.append(f"| {s['name']} | {'—' if exact is None else _fmt(exact)} | " + " | ".join(cells) + " |")
    sym = [s for s in catalogue if s.get("symmetries")]
    if sym:
        lines += ["", "Symmetry broken: ‖ξ − Sξ‖_M / (2‖ξ* − ξ⁰‖_M), the largest over the scene's symmetries "
                  "(computed from the scene: mirrors through the centre of mass normal to x, y, z and "
                  "half-turns about those axes):", ""]
        lines.append("| scene | symmetries | " + " | ".join(engines) + " |")
        lines.append("|---|---|" + "---|" * len(engines))
        for s in sym:
            cells = []
            for e in engines:
                g = by.get((s["name"], e))
                cells.append("—" if g is None or g.get("symmetry_broken") is None else
                             _fmt(g["symmetry_broken"]) + ("" if g["symmetry_ok"] else " !sym"))
            lines.append(f"| {s['name']} | {', '.join(s['symmetries'])} | " + " | ".join(cells) + " |")
    lines += ["", "Pull: the normal impulses derived from the engine's twist change (least squares, "
              "W p = M Δξ, W the contact wrenches: the normal, and both tangents where μ > 0), the most "
              "negative over P, P the largest impulse that would stop one contact alone; 0 when every "
              "contact pushes, `n.d.` when W has not full column rank (the twist change does not "
              "determine the impulses). In brackets, where above 1 %: the fraction of the twist change "
              "that no impulse at the scene's contacts produces (another contact, friction where μ = 0, "
              "contact points that moved):", ""]
    lines.append("| scene | " + " | ".join(engines) + " |")
    lines.append("|---|" + "---|" * len(engines))
    for s in catalogue:
        cells = []
        for e in engines:
            g = by.get((s["name"], e))
            if g is None or "unexplained" not in g:
                cells.append("—")
                continue
            c = "n.d." if g.get("pull") is None else _fmt(-g["pull"] if g["pull"] else 0.0)
            if g.get("pull") is not None and not g["pull_ok"]:
                c += " !pull"
            if g["unexplained"] > 0.01:
                c += f" ({_fmt(g['unexplained'])})"
            cells.append(c)
        lines.append(f"| {s['name']} | " + " | ".join(cells) + " |")
    if any(s.get("family") == "random" for s in report["scenes"]):
        n = sum(1 for s in report["scenes"] if s.get("family") == "random")
        lines += ["", f"Random family (seed {report.get('random_seed')}, {n} scenes: boxes and cylinders, 1–4 "
                  "contacts, frictionless, the unilateral law; `inertance.engines.random_family`):", ""]
        lines.append("| engine | graded | median error | worst error (scene) | gains energy | breaks separation "
                     "| pulls (of determined) |")
        lines.append("|---|---|---|---|---|---|---|")
        for r in summaries(report):
            if not r["graded"]:
                lines.append(f"| {r['engine']} | 0 of {r['scenes']} ({r['not_applicable']} n/a, {r['failed']} failed) "
                             "| — | — | — | — | — |")
                continue
            extra = f" ({r['not_applicable']} n/a, {r['failed']} failed)" if r["not_applicable"] or r["failed"] else ""
            lines.append(f"| {r['engine']} | {r['graded']} of {r['scenes']}{extra} | {_fmt(r['median_error'])} | "
                         f"{_fmt(r['worst_error'])} ({r['worst_scene']}) | {100 * r['gains_energy']:.0f} % | "
                         f"{100 * r['breaks_separation']:.0f} % | {r['pulls']} of {r['impulses_determined']} |")
    if report.get("convergence"):
        from .convergence import markdown as convergence_markdown

        lines += ["", "Convergence (the error as each knob is refined from the engine's default; order: the "
                  "log–log slope over the three finest values, against h or 1/N):", ""]
        lines.append(convergence_markdown(report["convergence"]).rstrip("\n"))
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


def svgs(report: dict) -> dict:
    """The report's plots, ``{file name: SVG text}``: the error per catalogue scene and engine
    (log), the energy ratio (the exact one as a bar), the random family's errors sorted per
    engine, and the convergence plots (:func:`.convergence.svgs`)."""
    from .convergence import svgs as convergence_svgs
    from .plot import dots, lines

    engines = [e["name"] for e in report["engines"]]
    by = {(g["scene"], g["engine"]): g for g in report["grades"]}
    cat = [s["name"] for s in report["scenes"] if s.get("family", "catalogue") == "catalogue"]
    out = {}
    if cat and report["grades"]:
        out["error-per-scene.svg"] = dots(
            cat, {e: [by[(s, e)]["error"] if (s, e) in by else None for s in cat] for e in engines},
            "Error of the twist after impact per scene (0 exact, 1 no impact)", "error")
        out["energy-ratio.svg"] = dots(
            cat, {e: [by[(s, e)]["energy_ratio"] if (s, e) in by else None for s in cat] for e in engines},
            "Kinetic energy after / before", "energy ratio", logy=False,
            reference={"inertance (exact)": [next(x["exact_energy_ratio"] for x in report["scenes"] if x["name"] == s)
                                             for s in cat]})
    rnd = [s["name"] for s in report["scenes"] if s.get("family") == "random"]
    if rnd:
        series = {}
        for e in engines:
            errs = sorted(by[(s, e)]["error"] for s in rnd if (s, e) in by)
            if errs:
                series[e] = [((k + 0.5) / len(errs), x) for k, x in enumerate(errs)]
        if series:
            out["random-errors.svg"] = lines(series, f"Random family (seed {report.get('random_seed')}): errors, sorted",
                                             "fraction of the graded scenes", "error", logx=False)
    out.update(convergence_svgs(report.get("convergence", [])))
    return out


def html(report: dict, plots: Sequence[str]) -> str:
    """A page: the Markdown report's tables as HTML tables, its prose as paragraphs, then the plots."""
    from html import escape

    body, table = [], []

    def flush():
        if table:
            rows = [r for r in table if not set(r.replace("|", "").strip()) <= {"-"}]
            cells = [[c.strip() for c in r.strip().strip("|").split("|")] for r in rows]
            body.append("<table>" + "".join(
                "<tr>" + "".join(f"<{'th' if i == 0 else 'td'}>{escape(c)}</{'th' if i == 0 else 'td'}>" for c in row)
                + "</tr>" for i, row in enumerate(cells)) + "</table>")
            table.clear()

    for line in markdown(report).splitlines():
        if line.startswith("|"):
            table.append(line)
            continue
        flush()
        if line.strip():
            body.append(f"<p>{escape(line)}</p>")
    flush()
    imgs = "".join(f'<p><img src="{escape(p)}" alt="{escape(p)}"/></p>' for p in plots)
    style = ("body{font-family:sans-serif;max-width:80em;margin:auto}table{border-collapse:collapse;font-size:90%}"
             "td,th{border:1px solid #ccc;padding:2px 6px}")
    return (f"<!DOCTYPE html><html><head><meta charset=\"utf-8\"><title>Engine conformance</title>"
            f"<style>{style}</style></head><body><h1>How right is your physics engine?</h1>"
            + "".join(body) + imgs + "</body></html>\n")


def write(report: dict, out_dir) -> tuple:
    """``report.md``, ``report.json``, the plots (``*.svg``, :func:`svgs`) and ``report.html`` in
    ``out_dir``; returns the paths of the Markdown and the JSON."""
    from pathlib import Path

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    md, js = out / "report.md", out / "report.json"
    md.write_text(markdown(report))
    js.write_text(json.dumps(report, indent=1) + "\n")
    plots = svgs(report)
    for name, text in plots.items():
        (out / name).write_text(text)
    (out / "report.html").write_text(html(report, list(plots)))
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
        out.append({"step": h, "error": g.error, "energy_ratio": g.energy_ratio, "separation_ok": g.separation_ok,
                    "symmetry_broken": g.symmetry_broken})
    return out
