"""The report of a (simulated) rotary axis calibration: result beside the truth, set-up, budget.

Built with :class:`axiscal.report.html.Report`: the ISO 230-2 plot with the truth the simulation
knew, the measurement error per target against the stated budget and equation 1, the ISO 230-2
parameters measured and true, the per-target table, the set-up values, the optics calibration,
the error budget and, off axis, the alignment, the yaw correction and the start of the part
program.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from axiscal.report._figures import pyplot as _pyplot
from axiscal.report.html import Report, target_label
from axiscal.report.labels import fmt
from axiscal.standards.positioning_standards import parameter_label
from axiscal.units import ARCSEC

__all__ = ["rotary_report", "write_rotary_report", "rotary_error_figure", "common_offset"]

_PARAMS = ("A", "A_up", "A_down", "E", "E_up", "E_down", "M", "R", "R_up", "R_down", "B", "B_mean")


def rotary_error_figure(r):
    """Measured minus true per-target mean deviation (each direction), with the ± budget band and
    the equation-1 curve the true misalignments predict (both less their mean), arcsec."""
    from axiscal.physics.misalignment import misalignment_terms
    from axiscal.report.plots import DOWN_COLOR, UP_COLOR

    plt = _pyplot()

    t = r.plan.targets
    off = common_offset(r)
    fig, ax = plt.subplots(figsize=(10, 4.2), dpi=110)
    wc = r.budget.worst_case / ARCSEC
    ax.axhspan(-wc, wc, color="#27ae60", alpha=0.08, label=f"budget ± {fmt(wc, 'arcsec')} arcsec (worst case)")
    up = r.result.mean_up - r.truth_result.mean_up - off
    ax.plot(t, up, "o-", color=UP_COLOR, ms=3.5, lw=1.3, label="measured − true, positive ↑")
    shown = [up]
    if r.plan.bidirectional:
        down = r.result.mean_down - r.truth_result.mean_down - off
        ax.plot(t, down, "s-", color=DOWN_COLOR, ms=3.5, lw=1.3,
                label="measured − true, negative ↓")
        shown.append(down)
    dense = np.linspace(t[0], t[-1], 721)
    s = r.true_setup
    e = misalignment_terms(np.radians(dense), s.alpha, s.beam_tilt, s.reflector_twist, s.eta).total
    ax.plot(dense, (e - e.mean()) / ARCSEC, "--", color="#7f8c8d", lw=1.1,
            label="Renishaw eq. 1 for the true α, β, ω")
    ax.axhline(0, color="#888", lw=0.6)
    ax.set_xlabel("Target position [°]")
    ax.set_ylabel("Measurement error [arcsec]")
    ax.set_xlim(t[0] - 0.02 * (t[-1] - t[0]), t[-1] + 0.02 * (t[-1] - t[0]))
    if t[-1] - t[0] >= 90:
        ax.set_xticks(np.arange(np.ceil(t[0] / 45) * 45, t[-1] + 1e-9, 45))
    # the band sets the scale, but an error outside the budget must stay on the plot
    worst = float(np.nanmax(np.abs(np.concatenate(shown)))) if np.isfinite(shown[0]).any() else 0.0
    lim = 1.3 * max(wc, 0.1, worst)
    ax.set_ylim(-lim, lim)
    ax.grid(True, color="#e3e7ec", lw=0.7)
    ax.set_title(f"Measurement error per target: measured minus true mean deviation, less their "
                 f"mean ({fmt(off, 'arcsec', True)} arcsec)", loc="left", fontsize=10.5)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    fig.tight_layout()
    return fig


def common_offset(r) -> float:
    """Mean of measured minus true per-target mean deviations (both directions), arcsec.

    An angle calibration is defined up to a constant (the datum); no ISO 230-2 parameter depends
    on it, so the per-target errors are compared with the budget less this mean, as
    :attr:`~axiscal.procedures.rotary_calibration.RotaryCalibrationResult.mean_errors` does.
    """
    d = np.concatenate([r.result.mean_up - r.truth_result.mean_up,
                        r.result.mean_down - r.truth_result.mean_down])
    d = d[np.isfinite(d)]
    return float(d.mean()) if d.size else 0.0


def rotary_report(r, title: str | None = None) -> Report:
    """Build (without writing) the report of a :class:`RotaryCalibrationResult`."""
    from axiscal.report.plots import iso230_2_figure

    md = r.capture.dataset.metadata
    summary = r.summary()
    rep = Report(title or f"Rotary axis calibration — {md.machine or 'machine'} axis {r.plan.axis}",
                 subtitle="Angular interferometer with counter-rotating reference calibrator "
                          "(simulated), evaluated by ISO 230-2:2014",
                 metadata={"Machine": md.machine, "Axis": md.axis, "Operator": md.operator,
                           "Date": md.date, "Instrument": md.instrument, "Notes": md.notes,
                           "Plan": str(r.plan)}, simulation=True)
    rep.add_heading("Result beside the truth")
    verdict = "within" if summary["within_budget"] else "OUTSIDE"
    rep.add_text(
        f"Largest per-target error of the measured mean deviation against the truth: "
        f"{fmt(summary['max_mean_error_arcsec'], 'arcsec')} arcsec (single readings: "
        f"{fmt(summary['max_reading_error_arcsec'], 'arcsec')} arcsec), {verdict} the stated "
        f"budget of ±{fmt(r.budget.worst_case / ARCSEC, 'arcsec')} arcsec (worst case; RSS "
        f"±{fmt(r.budget.rss / ARCSEC, 'arcsec')} arcsec). The errors are taken less their "
        f"common mean ({fmt(common_offset(r), 'arcsec', True)} arcsec): an angle calibration is "
        "defined up to a constant "
        "and no ISO 230-2 parameter depends on it.")
    rows = []
    for k in _PARAMS:
        m, t = summary["measured"][k], summary["truth"][k]
        rows.append([parameter_label(k), m, t,
                     None if m is None or t is None else fmt(m - t, "arcsec", True)])
    rep.add_table(["Parameter", "Measured [arcsec]", "True [arcsec]", "Measured − true [arcsec]"],
                  rows, caption="ISO 230-2:2014 parameters of the measured and of the true "
                                "deviations (both relative to the datum at 0°).", digits=2)
    rep.add_warnings(list(r.result.warnings) + [f"set-up: {w}" for w in r.setup.warnings])
    truth_line = (r.plan.targets, r.truth_result.mean_bi if r.plan.bidirectional else r.truth_result.mean_up)
    rep.add_figure(iso230_2_figure(r.result, r.capture.dataset, truth=truth_line),
                   "Measured deviations (ISO 230-2 plot) with the true mean deviation the simulation "
                   "knew (dashed).")
    rep.add_figure(rotary_error_figure(r), "Measurement error per target (measured minus true "
                   "mean deviation, less their common mean) against the ± worst-case budget band, "
                   "with the misalignment error eq. 1 of Renishaw, Interferometric calibration of rotary axes, predicts for the true α, β, ω (less "
                   "its mean over the travel).")
    _per_target(rep, r)
    _setup_section(rep, r)
    _budget_section(rep, r)
    if r.offaxis is not None:
        _offaxis_section(rep, r)
    return rep


def write_rotary_report(path, r, title: str | None = None) -> Path:
    """Write the report atomically."""
    return rotary_report(r, title).write(path)


def _per_target(rep: Report, r) -> None:
    rep.add_heading("Per target (ISO 230-2)")
    rows = []
    for i, row in enumerate(r.result.target_table()):
        rows.append([target_label(row["target"]), row["mean_up"], row["mean_down"], row["mean_bi"], row["reversal"],
                     row["R_i"], float(r.truth_result.mean_bi[i]) if r.plan.bidirectional
                     else float(r.truth_result.mean_up[i])])
    rep.add_table(["Target [°]", "x̄↑ [arcsec]", "x̄↓ [arcsec]", "x̄ [arcsec]", "B_i [arcsec]",
                   "R_i [arcsec]", "true x̄ [arcsec]"], rows,
                  caption="Deviations actual − target; true x̄: the mean deviation the simulation "
                          "knew.", digits=2, css_class="targets")


def _setup_section(rep: Report, r) -> None:
    rep.add_heading("Set-up")
    rep.add_key_values(dict(r.setup.as_rows()), caption="Set-up checks (thresholds of Renishaw, Interferometric calibration of rotary axes)")
    s = r.true_setup
    items = {"α (true)": f"{s.alpha * 1e3:.3f} mrad at η = {np.degrees(s.eta):.1f}°",
             "β (true)": f"{s.beam_tilt * 1e3:.3f} mrad",
             "ω (true)": f"{s.reflector_twist * 1e3:.3f} mrad",
             "counter-rotation": "on" if s.counter_rotation else "off",
             "largest laser angle": f"{fmt(r.capture.max_laser_angle / ARCSEC, 'arcsec')} arcsec"}
    if r.optics is not None:
        items["optics self-calibration"] = str(r.optics).removeprefix("optics self-calibration ")
    else:
        items["optics self-calibration"] = "not done (K = 1, reflector not squared at the datum)"
    rep.add_key_values(items, caption="Misalignments the simulation used, and the optics calibration")


def _budget_section(rep: Report, r) -> None:
    rep.add_heading("Error budget")
    rows = [[i.name, i.value / ARCSEC, i.source] for i in r.budget.items]
    rows.append(["worst case (sum)", r.budget.worst_case / ARCSEC, ""])
    rows.append(["root sum of squares", r.budget.rss / ARCSEC, ""])
    rep.add_table(["Contribution", "± arcsec", "Source"], _arcsec(rows), css_class="params")
    from axiscal.standards.iso230_9 import chain_budget

    gum = chain_budget(r.budget)
    rows = [[c.name, c.u, c.distribution] for c in gum.contributors]
    rep.add_table(["Contribution", "u [arcsec]", "Distribution"], _arcsec(rows),
                  caption="The same budget in GUM form (ISO/TR 230-9): each ± bound a rectangular "
                          f"distribution, u = a/√3, combined with {gum.method}.", css_class="params")
    res = r.result.parameters()
    rows = [[k, res[k], gum.U_text(k)] for k in ("A", "E", "M", "R", "B")
            if res.get(k) is not None]
    rep.add_table(["Parameter", "Value [arcsec]", "U (k = 2) [arcsec]"], rows, digits=2,
                  caption="Expanded uncertainty of the ISO 230-2 parameters from this budget; "
                          "R and B carry the reading noise only.")


def _arcsec(rows):
    """Rows with every number in arcsec written with the decimals of arcsec (report.labels)."""
    return [[fmt(v, "arcsec") if isinstance(v, float) else v for v in row] for row in rows]


def _offaxis_section(rep: Report, r) -> None:
    o = r.offaxis
    rep.add_heading("Off-axis calibration")
    rep.add_key_values({
        "three-point alignment": str(o.alignment),
        "yaw profile": f"{o.profile.positions.size} points, moving optic {o.profile.moving_optic}, "
                       f"laser direction {o.profile.direction_sign:+d}",
        "yaw subtracted with sign": f"{o.sign:+d} (checked against both records)",
        "largest yaw correction": f"{fmt(o.yaw_removed / ARCSEC, 'arcsec')} arcsec",
    })
    head = "\n".join(o.program.splitlines()[:12])
    rep.add_html("<pre>" + _esc(head) + "\n…</pre>")


def _esc(text: str) -> str:
    import html

    return html.escape(text)


def budget_figure(data: dict):
    """The misalignment error of a rotary calibration over a turn, for ``axiscal rotary budget``.

    Each term of Renishaw, "Interferometric calibration of rotary axes", eq. 1 (α²/4 sin 2θ,
    αβ sin θ, αω cos θ) and their sum E(θ) in arcsec for the α, β, ω of ``data`` (the command's
    JSON result, mrad), with the expected accuracy (± arcsec, the more cautious of eq. 1 + base
    and the fitted Figure 22) as a band.
    """
    from axiscal.physics.misalignment import misalignment_terms

    plt = _pyplot()

    deg = np.linspace(0, 360, 721)
    a, b, w = (data[k] * 1e-3 for k in ("alpha_mrad", "beta_mrad", "omega_mrad"))
    terms = misalignment_terms(np.radians(deg), a, b, w)
    acc = data["expected_accuracy_arcsec"]
    fig, ax = plt.subplots(figsize=(10, 4.2), dpi=110)
    ax.axhspan(-acc, acc, color="#27ae60", alpha=0.08,
               label=f"expected accuracy ± {acc:.2f} arcsec")
    for name, label, style in (("quadratic", "α²/4 · sin 2θ", ":"), ("alpha_beta", "αβ · sin θ", "--"),
                               ("alpha_omega", "αω · cos θ", "-.")):
        ax.plot(deg, getattr(terms, name) / ARCSEC, style, lw=1.1, label=label)
    ax.plot(deg, terms.total / ARCSEC, "-", color="#2c3e50", lw=1.8, label="E(θ), eq. 1")
    ax.axhline(0, color="#888", lw=0.6)
    ax.set_xlabel("Axis position θ [°]")
    ax.set_ylabel("Misalignment error [arcsec]")
    ax.set_xlim(0, 360)
    ax.set_xticks(np.arange(0, 361, 45))
    ax.grid(True, color="#e3e7ec", lw=0.7)
    ax.set_title(f"Misalignment error over a turn: α = {data['alpha_mrad']:g}, β = "
                 f"{data['beta_mrad']:g}, ω = {data['omega_mrad']:g} mrad (Renishaw, "
                 "Interferometric calibration of rotary axes, eq. 1)", loc="left", fontsize=10)
    ax.legend(loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=8.5, frameon=False)
    fig.tight_layout()
    return fig
