"""What a test's page shows of a five-axis kinematics test (a sphere probed at many rotary
poses, or an R-test; issue 43), in the generic kind template (``kind.html``).

The view lays out the history's one evaluation of the stored file
(:func:`axiscal.store.kinds.evaluate_file`, kind ``fiveaxis``: the location errors identified as
``axiscal fiveaxis identify`` identifies them): the axis lines in 3-D, magnified, beside the
nominal ones (:func:`axiscal.report.five_axis_plots.location_figure`), the location errors in
their ISO 230-1 / ISO 230-7 names with U (k = 2), what the set-up cannot see and which test
would, the residual and the convention. Nothing is computed here.
"""

from __future__ import annotations

__all__ = ["five_axis_view"]


def five_axis_view(ev, figure, fmt) -> dict:
    """The page's view (keys of :func:`axiscal.web.kind_pages.kind_view`); ``figure`` and
    ``fmt`` are that module's figure-to-image and number writers, passed in (so this module
    does not import its caller)."""
    from axiscal.physics.rotary_location import Geometry
    from axiscal.report.five_axis_plots import location_figure

    r, res = ev.evaluation, ev.result
    g = Geometry(res["tilt_axis"], tuple(v * 1e-3 for v in res["tilt_position_mm"]),
                 tuple(v * 1e-3 for v in res["c_position_mm"]))
    rows = [(e.name, f"{e.value_display:+.3f}", fmt(e.U_display), e.unit) for e in r.errors]
    unseen = [(u.name, u.reason) for u in r.unidentified]
    plan = r.plan
    fit = [("poses", str(plan.poses), ""), ("rank of the sensitivity matrix",
                                            f"{plan.rank} of {plan.columns}", ""),
           ("condition", f"{plan.condition:.3g}", ""),
           ("residual, rms", fmt(r.residual_rms * 1e6), "µm"),
           ("residual, largest", fmt(r.residual_max * 1e6), "µm"),
           ("chi² per degree of freedom", f"{r.chi2_per_dof:.3g}", "")]
    what = "sphere probed at many rotary poses" if res["kind_of_test"] == "probing" \
        else "R-test"
    return {"figure": figure(location_figure, g, r),
            "alt": "The rotary axes' lines in 3-D, nominal and identified (magnified), beside "
                   "the identified values with U",
            "source": "Location errors of the rotary axes, ISO 230-1:2012 and ISO 230-7:2015 "
                      "Clause 3; U (k = 2) from the residual and the instrument's calibration "
                      "(JCGM 100:2008)",
            "lead": f"{what} ({res['label']}), {res['tilt_axis']}/C table-table; convention: "
                    f"{res['convention']}",
            "tables": [("Location errors", "location-errors", ["error", "value", "U (k = 2)",
                                                               "unit"], rows),
                       ("Not identified by this set-up", "unidentified",
                        ["error", "why, and the test that would see it"], unseen),
                       ("The fit", "fit", ["quantity", "value", "unit"], fit)],
            "statements": [], "warnings": [r.unmodelled] if r.chi2_per_dof > 4 else []}
