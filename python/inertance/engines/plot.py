"""The report's plots as SVG text, written by hand (no plotting library: the same bytes from the
same numbers on every machine, and nothing to install for the CI part).

Two kinds: :func:`lines` (series of (x, y) points, optionally log–log: the convergence plots
and the random family's sorted errors) and :func:`dots` (one value per category and series:
the error and the energy ratio per scene and engine). On a log axis a value at or below
``floor`` (zero included) is drawn at ``floor`` with a hollow marker, and the axis says so.
"""

from __future__ import annotations

import math
from html import escape
from typing import Optional, Sequence

#: Series colours, in order (colour-blind-safe: Okabe–Ito), then markers if more are needed.
COLOURS = ("#0072B2", "#D55E00", "#009E73", "#CC79A7", "#E69F00", "#56B4E9", "#000000", "#F0E442")


def _fmt(v: float) -> str:
    if v == 0:
        return "0"
    e = math.floor(math.log10(abs(v)))
    if -3 <= e <= 3:
        return f"{v:g}"
    m = v / 10 ** e
    return f"1e{e}" if abs(m - 1) < 1e-9 else f"{m:g}e{e}"


class _Axis:
    def __init__(self, lo: float, hi: float, log: bool, floor: float):
        self.log, self.floor = log, floor
        if log:
            lo, hi = max(lo, floor), max(hi, floor)
            self.lo, self.hi = math.floor(math.log10(lo)), math.ceil(math.log10(hi))
            if self.hi == self.lo:
                self.hi += 1
        else:
            if hi == lo:
                lo, hi = lo - 0.5, hi + 0.5
            pad = 0.05 * (hi - lo)
            self.lo, self.hi = lo - pad, hi + pad

    def frac(self, v: float) -> float:
        if self.log:
            v = math.log10(max(v, self.floor))
        return (v - self.lo) / (self.hi - self.lo)

    def ticks(self) -> list:
        if self.log:
            step = max(1, math.ceil((self.hi - self.lo) / 8))
            return [10.0 ** k for k in range(int(self.lo), int(self.hi) + 1, step)]
        raw = (self.hi - self.lo) / 6
        mag = 10 ** math.floor(math.log10(raw))
        step = min((m * mag for m in (1, 2, 5, 10) if m * mag >= raw), default=mag)
        start = math.ceil(self.lo / step) * step
        return [start + k * step for k in range(int((self.hi - start) / step) + 1)]


def _frame(title: str, width: int, height: int, left: int, bottom: int) -> list:
    return [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
            f'viewBox="0 0 {width} {height}" font-family="sans-serif" font-size="11">',
            f'<rect width="{width}" height="{height}" fill="white"/>',
            f'<text x="{width / 2:.1f}" y="16" text-anchor="middle" font-size="13">{escape(title)}</text>']


def _legend(out: list, names: Sequence[str], x: float, y: float) -> None:
    for k, n in enumerate(names):
        c = COLOURS[k % len(COLOURS)]
        out.append(f'<circle cx="{x + 5:.1f}" cy="{y + 14 * k:.1f}" r="4" fill="{c}"/>'
                   f'<text x="{x + 14:.1f}" y="{y + 14 * k + 4:.1f}">{escape(n)}</text>')


def lines(series: dict, title: str, xlabel: str, ylabel: str, logx: bool = True, logy: bool = True,
          floor: float = 1e-16, width: int = 640, height: int = 400) -> str:
    """A line plot: ``series`` maps a name to ``[(x, y), …]`` (drawn in that order)."""
    pts = [p for s in series.values() for p in s]
    if not pts:
        raise ValueError(f"nothing to plot in {title!r}")
    left, right, top, bottom = 70, 150, 28, 46
    ax = _Axis(min(p[0] for p in pts), max(p[0] for p in pts), logx, floor)
    ay = _Axis(min(p[1] for p in pts), max(p[1] for p in pts), logy, floor)
    pw, ph = width - left - right, height - top - bottom
    X = lambda v: left + pw * ax.frac(v)
    Y = lambda v: top + ph * (1 - ay.frac(v))
    out = _frame(title, width, height, left, bottom)
    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>')
    for t in ax.ticks():
        out.append(f'<line x1="{X(t):.1f}" y1="{top}" x2="{X(t):.1f}" y2="{top + ph}" stroke="#ddd"/>'
                   f'<text x="{X(t):.1f}" y="{top + ph + 14}" text-anchor="middle">{_fmt(t)}</text>')
    for t in ay.ticks():
        out.append(f'<line x1="{left}" y1="{Y(t):.1f}" x2="{left + pw}" y2="{Y(t):.1f}" stroke="#ddd"/>'
                   f'<text x="{left - 4}" y="{Y(t) + 4:.1f}" text-anchor="end">{_fmt(t)}</text>')
    out.append(f'<text x="{left + pw / 2:.1f}" y="{height - 8}" text-anchor="middle">{escape(xlabel)}</text>')
    note = f" (≤ {_fmt(floor)} drawn at {_fmt(floor)}, hollow)" if logy else ""
    out.append(f'<text transform="translate(14 {top + ph / 2:.1f}) rotate(-90)" text-anchor="middle">'
               f'{escape(ylabel + note)}</text>')
    for k, (name, s) in enumerate(series.items()):
        c = COLOURS[k % len(COLOURS)]
        path = " ".join(f"{X(x):.1f},{Y(y):.1f}" for x, y in s)
        out.append(f'<polyline points="{path}" fill="none" stroke="{c}" stroke-width="1.5"/>')
        for x, y in s:
            hollow = logy and y <= floor
            out.append(f'<circle cx="{X(x):.1f}" cy="{Y(y):.1f}" r="3" '
                       + (f'fill="white" stroke="{c}"/>' if hollow else f'fill="{c}"/>'))
    _legend(out, list(series), left + pw + 10, top + 8)
    out.append("</svg>")
    return "\n".join(out) + "\n"


def dots(categories: Sequence[str], series: dict, title: str, ylabel: str, logy: bool = True,
         floor: float = 1e-16, reference: Optional[dict] = None, width: int = None, height: int = 420) -> str:
    """One column per category, one marker per series (``series[name][i]`` the value for
    ``categories[i]``, None: not graded); ``reference`` (a name and values) drawn as a black
    bar in each column (the exact answer's energy ratio)."""
    vals = [v for s in series.values() for v in s if v is not None]
    if reference:
        vals += [v for v in list(reference.values())[0] if v is not None]
    if not vals:
        raise ValueError(f"nothing to plot in {title!r}")
    n = len(categories)
    width = width or max(480, 34 * n + 240)
    left, right, top, bottom = 70, 150, 28, 130
    ay = _Axis(min(vals), max(vals), logy, floor)
    pw, ph = width - left - right, height - top - bottom
    col = pw / max(n, 1)
    Y = lambda v: top + ph * (1 - ay.frac(v))
    out = _frame(title, width, height, left, bottom)
    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#444"/>')
    for t in ay.ticks():
        out.append(f'<line x1="{left}" y1="{Y(t):.1f}" x2="{left + pw}" y2="{Y(t):.1f}" stroke="#ddd"/>'
                   f'<text x="{left - 4}" y="{Y(t) + 4:.1f}" text-anchor="end">{_fmt(t)}</text>')
    note = f" (≤ {_fmt(floor)} drawn at {_fmt(floor)}, hollow)" if logy else ""
    out.append(f'<text transform="translate(14 {top + ph / 2:.1f}) rotate(-90)" text-anchor="middle">'
               f'{escape(ylabel + note)}</text>')
    k = len(series)
    for i, cat in enumerate(categories):
        cx = left + col * (i + 0.5)
        out.append(f'<text transform="translate({cx + 3:.1f} {top + ph + 8}) rotate(60)" font-size="10">'
                   f'{escape(cat)}</text>')
        if reference:
            v = list(reference.values())[0][i]
            if v is not None:
                out.append(f'<line x1="{cx - col * 0.45:.1f}" y1="{Y(v):.1f}" x2="{cx + col * 0.45:.1f}" '
                           f'y2="{Y(v):.1f}" stroke="black" stroke-width="2"/>')
        for j, (name, s) in enumerate(series.items()):
            v = s[i]
            if v is None:
                continue
            c = COLOURS[j % len(COLOURS)]
            x = cx + col * 0.7 * ((j + 0.5) / k - 0.5)
            hollow = logy and v <= floor
            out.append(f'<circle cx="{x:.1f}" cy="{Y(v):.1f}" r="3" '
                       + (f'fill="white" stroke="{c}"/>' if hollow else f'fill="{c}"/>'))
    names = list(series)
    _legend(out, names, left + pw + 10, top + 8)
    if reference:
        y = top + 8 + 14 * len(names)
        out.append(f'<line x1="{left + pw + 10}" y1="{y}" x2="{left + pw + 20}" y2="{y}" stroke="black" '
                   f'stroke-width="2"/><text x="{left + pw + 24}" y="{y + 4}">{escape(list(reference)[0])}</text>')
    out.append("</svg>")
    return "\n".join(out) + "\n"
