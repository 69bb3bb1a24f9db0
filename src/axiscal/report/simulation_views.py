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
* ``environment`` — the air and material over the test and the correction of each reading
  (``axiscal compensate-environment``; Ciddor 1996, ISO 1:2016).

``name`` is what the command names the run by: the configuration's or the raw file's name.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

__all__ = ["simulation_figure", "write_simulation_report", "MOUNTING_NOTE"]

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
    if run.kind == "volumetric-map":
        from axiscal.report.volumetric_plots import volumetric_report

        cfg = run.parts["config"]
        return volumetric_report(run.record, run.parts["diagonals"], cfg.errors, name=cfg.name,
                                 truth=run.parts["truth"]).write(path)
    fig = simulation_figure(run, name)
    if run.kind == "scale-homing":
        return write_result_report(path, f"Laser scale referencing — {name}", run.json,
                                   figure=fig, simulation=True, method=_SCALE_METHOD)
    if run.kind == "gantry-homing":
        return write_result_report(path, f"Twin-axis homing — {name}", run.json, figure=fig,
                                   simulation=True, caption=_GANTRY_CAPTION, method=_GANTRY_METHOD)
    return write_result_report(path, f"Environmental compensation of {name}", run.json,
                               figure=fig, method=_ENVIRONMENT_METHOD)
