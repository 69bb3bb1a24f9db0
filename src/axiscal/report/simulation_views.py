"""The figure and the report of a run computed from a configuration or from raw readings
(:class:`axiscal.io.simulation_results.SimulationRun`), for the commands' ``--plot`` and
``--report`` and the public API's ``plot()`` and ``report()`` alike.

* ``scale-homing`` — the signals against position (``axiscal scale home``; Renishaw, "Laser
  scale axis referencing": events A, B, Z, C).
* ``gantry-homing`` — the skew X1 − X2 during homing with the skew limits (``axiscal scale
  gantry``; Renishaw, "Laser scale axis referencing", twin-axis sequence).
* ``five-dof`` — the five errors against angle, measured and true (``axiscal motion simulate``;
  Optics Express 2018, "Five-DOF motion errors of a rotary axis"), the report with ISO 230-7:2015.
* ``volumetric-map`` — the distorted grid and the |E| slices (``axiscal volumetric map``;
  ISO/TR 16907:2015 rigid-body model, body diagonals of ISO 230-6:2002).
* ``volumetric-compensation`` — each verified figure before and after the tables
  (``axiscal volumetric compensate --verify``; ISO 230-1:2012 errors, ISO 230-6:2002 diagonals).
* ``environment`` — the air and material over the test and the correction of each reading
  (``axiscal compensate-environment``; Ciddor 1996, ISO 1:2016).

``name`` is what the command names the run by: the configuration's or the raw file's name.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["simulation_figure", "write_simulation_report", "any_simulation_figure",
           "volumetric_map_record",
           "write_any_simulation_report", "MOUNTING_NOTE"]

#: Said beside a five-DOF simulation's measured-minus-true errors (terminal and report).
MOUNTING_NOTE = ("Measured minus truth is noise plus the mounting errors' crosstalk: an eccentric "
                 "or tilted reference axis shows as a once-per-turn term in δy, εx and εy (see "
                 "the crosstalk table), which ISO 230-7 removes as the fundamental.")

_SCALE_METHOD = ("Referencing of one axis through the environmental compensator: switch, "
                 "rephasing of the sine and cosine outputs and the reference mark at events A, B, "
                 "Z and C (Renishaw, Laser scale axis referencing).")
_GANTRY_METHOD = ("Homing of a gantry driven by two laser-scale axes through their environmental "
                  "compensators: each rephases at its own switch, the controller checks the skew "
                  "before synchronisation and deskews X2 (Renishaw, Laser scale axis "
                  "referencing).")
_GANTRY_CAPTION = ("Real skew X1 − X2 at each command step of the homing sequence, with the "
                   "controller's skew limit and the limit this configuration needs.")
_ENVIRONMENT_METHOD = ("Each raw reading corrected for the refractive index of the air at its "
                       "time (the equation named below) and the dead path, and the axis referred "
                       "to 20 °C by ISO 1:2016 with the material temperature at its time.")

_VOLUMETRIC_METHOD = ("Positioning and cross-axis tables computed from the 21 measured errors "
                      "(ISO 230-1:2012) in the order of Chapman, 'Calibration of machine "
                      "squareness', Appendix II, the squareness put on the receiving axis; "
                      "verified by re-measuring the simulated machine with the tables applied: "
                      "the volumetric map (ISO/TR 16907:2015) and the body diagonals "
                      "(ISO 230-6:2002).")


def any_simulation_figure(kind: str, test: Any, name: str = "") -> Any:
    """The figure of any :class:`axiscal.api.Simulation`: a positioning test's ISO 230-2 figure
    with the simulation's truth (the mean of both directions when bidirectional), a rotary
    calibration's error beside its truth and budget, or :func:`simulation_figure`."""
    if kind == "rotary-calibration":
        from axiscal.report.rotary import rotary_error_figure

        return rotary_error_figure(test)
    if kind != "positioning":
        return simulation_figure(test, name)
    from axiscal.report.plots import iso230_2_figure

    return iso230_2_figure(test.result, test.dataset, truth=_truth_line(test))


def _truth_line(test: Any) -> tuple:
    """(targets, systematic deviation) the simulation knew: the mean of both directions when
    bidirectional, as the ISO 230-2 figure draws it."""
    return (test.plan.targets, 0.5 * (test.truth_up + test.truth_down)
            if test.plan.bidirectional else test.truth_up)


def write_any_simulation_report(kind: str, test: Any, path: Any, name: str = "",
                                uncertainty: Any = None) -> Path:
    """The report of any :class:`axiscal.api.Simulation`, as its command's ``--report``; a
    positioning test's with its ISO 230-2:2014 Annex A uncertainty, the budget of its record
    (:func:`axiscal.store.kinds.with_uncertainty`) from ``uncertainty`` (default: the user
    configuration's inputs)."""
    if kind == "rotary-calibration":
        from axiscal.report.rotary import write_rotary_report

        return Path(write_rotary_report(path, test))
    if kind != "positioning":
        return write_simulation_report(test, path, name)
    from axiscal.report.html import positioning_report

    from axiscal.report.uncertainty import add_uncertainty
    from axiscal.store.kinds import inputs_from_config, positioning_record, with_uncertainty

    if uncertainty is None:
        from axiscal.io.user_config import load_user_config

        uncertainty = inputs_from_config("iso230-2", load_user_config(), test.dataset)
    rec = with_uncertainty(positioning_record(test.dataset, test.result, others=False),
                           uncertainty)
    rep = positioning_report(test.dataset, test.result, truth=_truth_line(test))
    rep.simulation = True
    add_uncertainty(rep, rec.budget, (), [p for p, v in test.result.parameters().items()
                                          if v is not None])
    add_truth_section(rep, test)
    return Path(rep.write(path))


def add_truth_section(rep: Any, sim: Any) -> None:
    """Add "evaluation beside the truth" to the report of a simulated positioning test: each
    ISO 230-2:2014 parameter measured beside the one the injected errors imply without noise."""
    from axiscal.report.html import _PARAM_LABEL, unit_label

    rep.add_heading("Evaluation beside the truth of the simulation")
    rep.add_text("The simulated axis's injected errors imply the figures below without noise; "
                 "the measured figures differ by the repeatability noise of a 5-run test.")
    rows = [[_PARAM_LABEL[k], sim.result.parameters()[k], v]
            for k, v in sim.truth.items() if k != "R_expected"]
    rows.append(["R (truth: 4σ + |b|)", sim.result.R, sim.truth.get("R_expected")])
    u = unit_label(sim.result.deviation_unit)
    rep.add_table(["Parameter", f"Measured [{u}]", f"Truth [{u}]"], rows, digits=2,
                  caption="σ: the simulated repeatability (standard deviation of a reading); "
                          "b: the simulated backlash; ISO 230-2:2014 clause 3 gives R as "
                          "max(2s↑ + 2s↓ + |B_i|, 4s↑, 4s↓).")


def simulation_figure(run: Any, name: str = "") -> Any:
    """The matplotlib Figure of a run, as its command's ``--plot`` draws it."""
    if run.kind == "scale-homing":
        from axiscal.report.scale_plot import referencing_figure

        return referencing_figure(run.record)
    if run.kind == "gantry-homing":
        from axiscal.report.scale_plot import gantry_figure

        return gantry_figure(run.record, run.json["required_skew_limit"])
    if run.kind == "five-dof":
        from axiscal.report.motion_plots import five_errors_figure

        return five_errors_figure([run.parts["measured"]], [run.record.truth],
                                  title=f"Five motion errors — {run.parts['machine'] or name}")
    if run.kind == "volumetric-compensation":
        return _verify_figure(run, name)
    if run.kind == "ballbar":
        from axiscal.report.evaluations import kind_figure
        from axiscal.store.kinds import evaluate_ballbar

        return kind_figure("ballbar", run.record, evaluate_ballbar(run.record))
    if run.kind == "volumetric-map":
        from axiscal.report.volumetric_plots import volumetric_figure

        return volumetric_figure(run.record, f"Volumetric error map — {run.parts['config'].name}")
    from axiscal.report.capture_plots import environment_figure

    return environment_figure(run.record, f"Environmental compensation of {name}")


def write_simulation_report(run: Any, path: Any, name: str = "") -> Path:
    """Write the HTML (or PDF) report of a run, as its command's ``--report``; returns the path."""
    from axiscal.report.html import write_result_report

    if run.kind == "five-dof":
        from axiscal.report.motion_report import motion_report

        p = run.parts
        return motion_report(f"Five motion errors — {p['machine'] or name}", result=p["result"],
                             runs=[p["measured"]], truth=[run.record.truth],
                             crosstalk=p["crosstalk"], resolutions=p["resolutions"],
                             metadata={"Configuration": name, "Axis": p["axis"],
                                       "Drift compensation": run.json["compensated"]},
                             notes=[MOUNTING_NOTE]).write(path)
    if run.kind == "ballbar":
        from axiscal.report.ballbar_plots import write_diagnosis_report
        from axiscal.store.kinds import evaluate_ballbar

        return write_diagnosis_report(path, run.record.runs, evaluate_ballbar(run.record),
                                      title=f"Ballbar diagnosis of a simulated test — {name}")
    if run.kind == "volumetric-map":   # with the budget of the record (as --json states it)
        from axiscal.report.volumetric_plots import volumetric_report

        cfg = run.parts["config"]
        return volumetric_report(run.record, run.parts["diagonals"], cfg.errors, name=cfg.name,
                                 truth=run.parts["truth"],
                                 budget=volumetric_map_record(run).budget).write(path)
    if run.kind == "volumetric-compensation":
        fig = _verify_figure(run, name) if run.parts["verify"] is not None else None
        return write_result_report(path, f"Volumetric compensation — {name}", run.json,
                                   figure=fig, simulation=fig is not None,
                                   method=_VOLUMETRIC_METHOD)
    fig = simulation_figure(run, name)
    if run.kind == "scale-homing":
        return write_result_report(path, f"Laser scale referencing — {name}", run.json,
                                   figure=fig, simulation=True, method=_SCALE_METHOD)
    if run.kind == "gantry-homing":
        return write_result_report(path, f"Twin-axis homing — {name}", run.json, figure=fig,
                                   simulation=True, caption=_GANTRY_CAPTION, method=_GANTRY_METHOD)
    return write_result_report(path, f"Environmental compensation of {name}", run.json,
                               figure=fig, method=_ENVIRONMENT_METHOD)


def _verify_figure(run: Any, name: str) -> Any:
    """Each figure of a volumetric compensation's verification before and after the tables
    (µm, as re-measured on the simulated machine)."""
    from axiscal.errors import InputError

    result = run.parts["verify"]
    if result is None:
        raise InputError("plot: a volumetric compensation has a figure when verified "
                         "(verify=True, a simulated configuration)")
    import numpy as np

    from axiscal.report._figures import pyplot

    plt = pyplot()
    names = [row[0] for row in result.rows]
    series = ([("before", "tab:red"), ("after the tables", "tab:blue")]
              if len(result.rows[0]) == 3 else     # through LinuxCNC: bare, tables, + 3-D
              [("bare", "tab:red"), ("tables alone", "tab:orange"),
               ("tables + 3-D correction", "tab:blue")])
    y = np.arange(len(names))
    width = 0.8 / len(series)
    fig, ax = plt.subplots(figsize=(8, 0.45 * len(names) + 1.4))
    for i, (label, color) in enumerate(series):
        ax.barh(y + 0.4 - width * (i + 0.5), [row[i + 1] * 1e6 for row in result.rows], width,
                label=label, color=color)
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlabel("µm (re-measured)")
    ax.grid(axis="x", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(f"Volumetric compensation for {getattr(result, 'controller', 'linuxcnc')} — "
                 f"{name}", fontsize=10)
    fig.tight_layout()
    return fig


def volumetric_map_record(run):
    """``axiscal volumetric map``'s run as the history's record of it
    (:func:`axiscal.store.kinds.volumetric_record`) with its budget
    (:func:`axiscal.store.kinds.with_uncertainty`) from the user configuration's
    ``[volumetric_uncertainty]`` (:func:`axiscal.store.kinds.inputs_from_config`): the one record
    its ``--json``, its text and its report state."""
    from axiscal.io.user_config import load_user_config
    from axiscal.store.kinds import inputs_from_config, volumetric_record, with_uncertainty

    return with_uncertainty(volumetric_record(run),
                            inputs_from_config("volumetric", load_user_config()))
