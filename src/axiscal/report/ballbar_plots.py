"""Ballbar diagnosis figures: the polar plot a service engineer knows and the diagnostic bars.

Polar plot: both directions magnified about the nominal circle, the tolerance band (the larger
ISO 230-4:2005 circular deviation G, centred on the nominal circle), feed-direction arrows and the
start point of each run. Bar chart: each diagnosed term's effect on the radial deviation, ranked.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.report._figures import nice_step, polar_frame, polar_rings, pyplot, save_figure
from axiscal.report.labels import fmt

__all__ = ["RANKING_CAPTION", "RANKING_HEADERS", "diagnosis_figure", "ranking_rows",
           "save_diagnosis_plot", "write_diagnosis_report"]

_COLOURS = {"ccw": "tab:blue", "cw": "tab:red"}


def diagnosis_figure(runs, diagnosis, title: str = "Ballbar diagnosis"):
    """Polar plot (left) and ranked diagnostic bar chart (right)."""
    plt = pyplot()
    fig, (ax, bx) = plt.subplots(1, 2, figsize=(15, 7.4), gridspec_kw={"width_ratios": [1, 1.1]})
    _polar(ax, runs, diagnosis)
    _bars(bx, diagnosis)
    fig.suptitle(title, fontsize=13)
    fig.tight_layout()
    return fig


def save_diagnosis_plot(runs, diagnosis, path, title: str = "Ballbar diagnosis") -> Path:
    """Write :func:`diagnosis_figure` to ``path``."""
    return save_figure(diagnosis_figure(runs, diagnosis, title), path, dpi=110, tight=False)


def write_diagnosis_report(path, runs, diagnosis, title: str = "Ballbar diagnosis") -> Path:
    """An HTML report: summary, the figure, the ranked table with advice, warnings."""
    from axiscal.report.html import Report

    from axiscal.report.labels import label

    c = diagnosis.circular
    rep = Report(title, "ISO 230-4:2005 circular test; diagnosis after Renishaw, Calibration of "
                 "machine squareness, Method 4",
                 {"Radius": f"{fmt(c.radius * 1e3, 'mm')} mm", "Arc": f"{fmt(c.arc_deg, '°')}°",
                  "Feed": "—" if diagnosis.feed is None else
                  f"{fmt(diagnosis.feed * 6e4, 'mm/min')} mm/min"})
    rep.add_figure(diagnosis_figure(runs, diagnosis, title))
    rep.add_table(RANKING_HEADERS, ranking_rows(diagnosis), caption=RANKING_CAPTION,
                  css_class="params")   # the advice aligned left
    rep.add_table(["", ""], [[label(k), fmt(_um(v), "µm")] for k, v in
                             (("G_ccw_um", c.G_ccw), ("G_cw_um", c.G_cw), ("H_um", c.H),
                              ("residual_rms_um", diagnosis.residual_rms))],
                  caption="ISO 230-4:2005 §3 values", css_class="kv")
    _add_folded(rep, diagnosis)
    rep.add_warnings(diagnosis.warnings)
    return rep.write(path)


#: Columns and caption of the ranked diagnosis (the report and the workbench's test page).
RANKING_HEADERS = ["Rank", "Term", "Value", "Unit", "Effect [µm]", "Share of G [%]", "Advice"]
RANKING_CAPTION = ("Ranked diagnosis. Effect: the term's peak-to-valley on the radial deviation; "
                   "share: effect / G. The terms are not additive, so a share can exceed 100 %.")


def ranking_rows(diagnosis, number=fmt) -> list[tuple]:
    """The ranked diagnosis as rows of text under :data:`RANKING_HEADERS` (the order and the
    numbers ``ballbar analyze`` prints); ``number(value, unit)`` writes each value (by default
    with its unit's decimals, :func:`axiscal.report.labels.fmt`)."""
    axes = diagnosis.circular.squareness.axes
    return [(i, _term_label(t, axes), number(t.value, t.unit), t.unit, number(t.ptp * 1e6, "µm"),
             number(t.share * 100, "%"), t.advice) for i, t in enumerate(diagnosis.terms, 1)]


def _term_label(term, axes) -> str:
    """A diagnosed term as people name it (:mod:`axiscal.report.labels`): ``Backlash X``."""
    from axiscal.report.labels import quantity

    return quantity(term.key, axes=axes)[0]


def _add_folded(rep, diagnosis) -> None:
    """The statements of what the ISO 230-4 fit folds together, where the readings resolve it."""
    folds = diagnosis.folded_lines()
    if folds:
        rep.add_text("The ISO 230-4:2005 fit (squareness circular) cannot separate these terms; "
                     "what it folds in, against this diagnosis: "
                     + "; ".join(f.strip() for f in folds) + ".")


def _um(v):
    return None if v is None else v * 1e6


def _polar(ax, runs, d) -> None:
    c = d.circular
    devs = np.concatenate([r.deviations for r in runs])
    g = max(v for v in (c.G_ccw, c.G_cw, 1e-9) if v is not None)
    ring = nice_step(max(float(np.max(np.abs(devs))), g / 2, 1e-9))
    base, k, t = polar_rings(ax, ring)
    inner, outer = base - k * g / 2, base + k * g / 2
    ax.fill(np.r_[outer * np.cos(t), inner * np.cos(t[::-1])],
            np.r_[outer * np.sin(t), inner * np.sin(t[::-1])], color="tab:green", alpha=0.12,
            label=f"band G = {fmt(g * 1e6, 'µm')} µm")
    for r in runs:
        col = _COLOURS[r.direction]
        a, dv = r.angles, r.deviations            # in measuring order
        x, y = (base + k * dv) * np.cos(a), (base + k * dv) * np.sin(a)
        ax.plot(x, y, color=col, lw=1.3, label=r.direction.upper())
        ax.plot(x[0], y[0], "o", color=col, ms=7, mfc="white", mew=2)
        sense = 1.0 if r.direction == "ccw" else -1.0
        for i in np.linspace(0, a.size - 2, 5)[1:-1].astype(int):
            rr = base + k * dv[i] + (0.08 if sense > 0 else -0.08)
            p0 = np.array([rr * np.cos(a[i]), rr * np.sin(a[i])])
            tang = sense * np.array([-np.sin(a[i]), np.cos(a[i])]) * 0.15
            ax.annotate("", p0 + tang, p0, arrowprops=dict(arrowstyle="->", color=col, lw=1.5))
    polar_frame(ax, c.squareness.axes, (-1.7, 1.7), (-1.7, 1.7),
                f"({ring * 1e6:.3g} µm per dotted ring; ○ start point)")
    ax.legend(loc="upper right", fontsize=9)
    ax.set_title(f"R = {fmt(c.radius * 1e3, 'mm')} mm, {fmt(c.arc_deg, '°')}°, G ccw {_fmt(c.G_ccw)}, "
                 f"G cw {_fmt(c.G_cw)}, H {_fmt(c.H)}", fontsize=10)


def _bars(ax, d) -> None:
    terms = [t for t in d.terms][:12][::-1]
    y = np.arange(len(terms))
    eff = [t.ptp * 1e6 for t in terms]
    ax.barh(y, eff, color=["0.5" if t.key == "residual" else "tab:orange" for t in terms])
    axes = d.circular.squareness.axes
    ax.set_yticks(y, [f"{_term_label(t, axes)}  ({fmt(t.value, t.unit)} {t.unit})" for t in terms],
                  fontsize=9)
    for yi, t in zip(y, terms):
        ax.text(t.ptp * 1e6, yi, f" {fmt(t.share * 100, '%')} %", va="center", fontsize=8)
    ax.set_xlabel("effect on the radial deviation, peak-to-valley [µm] (share of G)")
    ax.set_title("Diagnosis, largest first")
    ax.grid(axis="x", alpha=0.3)


def _fmt(v):
    return "—" if v is None else f"{fmt(v * 1e6, 'µm')} µm"
