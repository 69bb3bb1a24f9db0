"""The interactive plots of the workbench as uPlot specs (JSON that ``static/axiscal.js`` draws):
an ISO 230-2 test's positioning deviations and a parameter's trend, in the units the pages write.

Shared by the history pages (:mod:`axiscal.web.history_pages`) and the sign-off
(:mod:`axiscal.web.signoff_pages`), which adds the ±2s bands, the readings and the tolerance
envelopes to the same spec.
"""

from __future__ import annotations

__all__ = ["COLORS", "positioning_plot", "trend_plot", "unit_text", "as_list"]

#: Colours of the series: up, down, bidirectional, fitted line.
COLORS = {"up": "#1f77b4", "down": "#d62728", "bi": "#2ca02c", "line": "#555"}


def positioning_plot(ev) -> dict:
    """uPlot spec of an ISO 230-2 test: x̄↑, x̄↓ and x̄ per target, every reading as points."""
    r, ds = ev.evaluation, ev.dataset
    unit = unit_text(r.deviation_unit)
    series = [{"label": "x̄↑", "values": as_list(r.mean_up), "color": COLORS["up"]},
              {"label": "x̄↓", "values": as_list(r.mean_down), "color": COLORS["down"]},
              {"label": "x̄ (bidirectional)", "values": as_list(r.mean_bi),
               "color": COLORS["bi"], "dash": True}]
    return {"title": f"ISO 230-2:2014 positioning deviations, {ds.metadata.axis or ''} axis",
            "x_label": f"target [{r.target_unit}]", "y_label": f"deviation [{unit}]",
            "x": as_list(r.targets), "series": series}


def trend_plot(tr, shown: str | None = None) -> dict:
    """uPlot spec of a trend on a date axis (x: seconds since 1970, UTC): the values (those
    without a date of their own apart, out of the fit), the fitted line (ISO/TS 28037:2010
    clause 6, as :func:`axiscal.store.trend` fits it) drawn on to the predicted crossing of the
    tolerance, the tolerance, and the crossing as a point. ``shown``: the parameter's name on
    the pages (its symbol; default the key)."""
    def seconds(d):
        import datetime as dt

        return (d if d.tzinfo else d.replace(tzinfo=dt.timezone.utc)).timestamp()

    shown = shown or tr.parameter
    x = [seconds(d) for d in tr.dates]
    values = [float(v) for v in tr.values]
    dated = [tr.is_dated(i) for i in range(len(values))]
    crossing = seconds(tr.crossing) if tr.crossing is not None else None
    if crossing is not None:          # one more x: the fitted line and the tolerance reach it
        x.append(crossing)
        values.append(None)
        dated.append(True)
    order = sorted(range(len(x)), key=x.__getitem__)
    x = [x[i] for i in order]
    series = [{"label": shown, "values": [values[i] if dated[i] else None for i in order],
               "color": COLORS["up"], "points": True}]
    if tr.undated:
        series.append({"label": "no date in the file (day stored; not in the fit)",
                       "values": [None if dated[i] else values[i] for i in order],
                       "color": COLORS["line"], "points": True})
    if tr.drift is not None:
        last = seconds(max(d for i, d in enumerate(tr.dates) if tr.is_dated(i)))
        # the level is the fitted value at the last test in the fit
        series.append({"label": "fitted drift", "values": [
            tr.level + tr.drift * (t - last) / (365.25 * 86400) for t in x],
            "color": COLORS["line"], "dash": True})
    if tr.tolerance is not None:
        series.append({"label": "tolerance", "values": [tr.tolerance] * len(x),
                       "color": COLORS["down"], "dash": True})
    if crossing is not None:
        series.append({"label": f"predicted crossing {tr.crossing:%Y-%m-%d}", "values": [
            tr.tolerance if t == crossing else None for t in x], "color": COLORS["down"],
            "points": True, "size": 11})
    return {"title": f"{shown} over time", "x_label": "date of the test (UTC)",
            "x_time": True, "y_label": f"{shown} [{unit_text(tr.unit)}]", "x": x,
            "series": series}


def unit_text(unit: str) -> str:
    """A unit as the pages write it: ``um`` (the store's spelling) as ``µm``, ``um/m`` as
    ``µm/m``."""
    return "µm" + unit[2:] if unit.startswith("um") else unit


def as_list(a) -> list:
    """Numbers as JSON can carry them: NaN (and None) as None."""
    import math

    return [None if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)
            for v in a]
