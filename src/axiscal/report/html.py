"""Self-contained HTML reports: one file, inline SVG figures, no network.

:class:`Report` is a small page builder every report of axiscal uses; the specific reports
(:func:`write_positioning_report`, and those of the rotary, squareness and motion-error modules)
are short functions that add sections to it. The page is styled for print (A4) as well as screen,
so the same HTML turns into a PDF with a browser or weasyprint.

Examples
--------
>>> r = Report("Demo", subtitle="a test page")
>>> r.add_table(["a", "b"], [[1, 2.5]], caption="numbers")
>>> "<table" in r.html()
True
"""

from __future__ import annotations

import datetime as _dt
import html as _html
import io
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Iterable, Sequence

from axiscal import __version__
from axiscal.standards.iso230_2 import PARAMETER_SYMBOLS

__all__ = ["Report", "figure_svg", "write_positioning_report", "target_label"]

#: A table of more rows than this may continue on the next page (a shorter one is kept whole):
#: kept whole, a long table leaves the page before it half empty.
LONG_TABLE = 12


def figure_svg(fig) -> str:
    """Render a matplotlib figure as an inline ``<svg>`` string and close the figure."""
    import matplotlib.pyplot as plt

    import matplotlib

    buf = io.StringIO()
    with matplotlib.rc_context({"svg.hashsalt": "axiscal"}):   # same figure, same SVG ids
        fig.savefig(buf, format="svg", bbox_inches="tight", metadata={"Date": None})
    plt.close(fig)
    svg = buf.getvalue()
    start = svg.find("<svg")
    return svg[start:] if start >= 0 else svg


@dataclass
class Report:
    """An HTML report assembled section by section.

    Parameters
    ----------
    title : str
    subtitle : str, optional
    metadata : dict, optional
        Shown as a key/value table under the title (machine, axis, operator, date ...).
    reference : str, optional
        Report number, repeated in every printed page's margin.
    letterhead : str, optional
        Trusted HTML above the title (company name, logo, address of a certificate).
    paper : str
        ``A4`` or ``Letter``: the printed page size (PDF).
    simulation : bool
        Marks every page as a simulation report (simulation truth may appear only there).
    """

    title: str
    subtitle: str = ""
    metadata: dict[str, Any] = field(default_factory=dict)
    reference: str = ""
    letterhead: str = ""
    paper: str = "A4"
    simulation: bool = False
    _parts: list[str] = field(default_factory=list)

    def add_heading(self, text: str, level: int = 2) -> None:
        """A section heading (h2 by default)."""
        self._parts.append(f"<h{level}>{_esc(text)}</h{level}>")

    def add_text(self, text: str) -> None:
        """A paragraph of plain text (escaped; a standard's symbols such as ``B_i`` with their
        subscripts, :func:`axiscal.report.labels.symbol_html`)."""
        self._parts.append(f"<p>{_sym(text)}</p>")

    def add_truth(self, heading: str = "") -> None:
        """Start what shows a simulation's truth: marks every page of the report as a simulation
        report (the banner of ``templates/base.html``), then the heading if one is given. Every
        report that shows a truth calls this, so none can show it without the banner."""
        self.simulation = True
        if heading:
            self.add_heading(heading)

    def add_html(self, fragment: str) -> None:
        """A trusted HTML fragment (built by axiscal, never from user text)."""
        self._parts.append(fragment)

    def add_figure(self, fig, caption: str = "") -> None:
        """A matplotlib figure, inline as SVG (printed at most 118 mm high: a figure is drawn
        wider than tall, so that it fills the page's width)."""
        cap = f"<figcaption>{_esc(caption)}</figcaption>" if caption else ""
        self._parts.append(f"<figure>{figure_svg(fig)}{cap}</figure>")

    def add_table(self, headers: Sequence[str], rows: Iterable[Sequence[Any]], caption: str = "",
                  digits: int = 3, css_class: str = "", formulas: Sequence[int] = ()) -> None:
        """A table; floats are shown with ``digits`` decimals, None/NaN as a dash; the headers,
        the caption and the ``formulas`` columns (a standard's definitions) write symbols such as
        ``B_i`` with their subscripts."""
        head = "".join(f"<th>{_sym(h)}</th>" for h in headers)
        rows = list(rows)
        body = "".join("<tr>" + "".join(
            f"<td>{_sym(v) if i in formulas else _cell(v, digits)}</td>" for i, v in enumerate(row))
            + "</tr>" for row in rows)
        cap = f"<caption>{_sym(caption)}</caption>" if caption else ""
        css_class = f"{css_class} long".strip() if len(rows) > LONG_TABLE else css_class
        cls = f' class="{css_class}"' if css_class else ""
        self._parts.append(f"<table{cls}>{cap}<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>")

    def add_key_values(self, items: dict[str, Any], caption: str = "", digits: int = 4) -> None:
        """A two-column table of names and values."""
        self.add_table(["", ""], [[k, v] for k, v in items.items()], caption, digits, "kv")

    def add_warnings(self, warnings: Iterable[str]) -> None:
        """A highlighted list of warnings (nothing if there are none)."""
        items = "".join(f"<li>{_sym(w)}</li>" for w in warnings)
        if items:
            self._parts.append(f'<div class="warnings"><strong>Warnings</strong><ul>{items}</ul></div>')

    def html(self) -> str:
        """The complete page."""
        from jinja2 import Environment, PackageLoader, select_autoescape

        env = Environment(loader=PackageLoader("axiscal.report", "templates"),
                          autoescape=select_autoescape(["html"]))
        return env.get_template("base.html").render(
            title=self.title,
            subtitle=self.subtitle,
            metadata={k: _meta(v) for k, v in self.metadata.items() if v not in (None, "", [])},
            body="\n".join(self._parts),
            reference=self.reference,
            letterhead=self.letterhead,
            paper={"letter": "Letter"}.get(self.paper.lower(), "A4"),
            simulation=self.simulation,
            version=__version__,
            generated=_dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
        )

    def document(self, path) -> bytes:
        """The bytes :meth:`write` writes to ``path``: a PDF for a ``.pdf`` name (WeasyPrint,
        :mod:`axiscal.report.pdf`), else the page's HTML in UTF-8 (the certificate register keeps
        these bytes as issued)."""
        if Path(path).suffix.lower() == ".pdf":
            from axiscal.report.pdf import html_to_pdf

            return html_to_pdf(self.html())
        return self.html().encode("utf-8")

    def write(self, path) -> Path:
        """Write the page atomically (no half-written report is left on error).

        A ``.pdf`` name writes the same page as a PDF through WeasyPrint (:mod:`axiscal.report.pdf`).
        """
        if Path(path).suffix.lower() == ".pdf":
            from axiscal.report.pdf import write_pdf

            return write_pdf(self.html(), path)
        from axiscal.io._files import write_text_atomic

        return write_text_atomic(path, self.html())


def write_positioning_report(path, dataset, result, title: str | None = None, verdicts=()) -> Path:
    """Write the ISO 230-2 report of one positioning test: plot, tables, metadata, warnings."""
    return positioning_report(dataset, result, title, verdicts).write(path)


def positioning_report(dataset, result, title: str | None = None, verdicts=(), *,
                       truth=None) -> Report:
    """Build (without writing) the ISO 230-2 report of one positioning test; ``truth``
    (positions, systematic deviation) of a simulation is drawn in its figure as a dashed line."""
    from axiscal.report.plots import iso230_2_figure

    md = dataset.metadata
    env = md.environment
    axis = md.axis or ("rotary axis" if dataset.axis_kind.value == "rotary" else "linear axis")
    rep = Report(
        title or f"Positioning accuracy and repeatability — {md.machine or 'machine'} {axis}".strip(),
        subtitle="Evaluated by ISO 230-2:2014",
        metadata={
            "Machine": md.machine, "Axis": md.axis, "Operator": md.operator, "Date": md.date,
            "Instrument": md.instrument, "Notes": md.notes,
            "Air temperature [°C]": env.air_temperature,
            "Material temperature [°C]": ", ".join(f"{t:g}" for t in env.material_temperature),
            "Pressure [Pa]": env.pressure, "Humidity [%RH]": env.humidity,
            "Expansion coefficient [1/K]": env.expansion_coefficient,
        },
    )
    u = unit_label(result.deviation_unit)
    rep.add_heading("Result")
    params = result.parameters()
    rows = [[_PARAM_LABEL[k], v, _PARAM_MEANING[k]] for k, v in params.items()]
    for arrow, v in (("↑", result.closure_up), ("↓", result.closure_down)):
        if v is not None:   # a full turn: 0° and 360° stay two targets; their difference
            rows.append([f"Closure {arrow}", v, "Mean deviation at 360° minus that at 0° "
                         "(full turn; the turntable paper of Yüksel et al., Table 3)"])
    rep.add_table(["Parameter", f"Value [{u}]", "Meaning (ISO 230-2:2014)"], rows, digits=2,
                  css_class="params", formulas=(2,))
    if verdicts:
        add_acceptance(rep, verdicts, u, _PARAM_LABEL)
    rep.add_warnings(result.warnings)
    rep.add_figure(iso230_2_figure(result, dataset, truth=truth),
                   f"Mean deviation per direction with ±2s bands and every run's readings "
                   f"({u} against target in {unit_label(result.target_unit)})"
                   + ("; dashed: the mean deviation the simulation knew." if truth else "."))
    rep.add_heading("Per target")
    headers = [f"Target [{unit_label(result.target_unit)}]", "n↑",
               *(f"{h} [{u}]" for h in ("x̄↑", "s↑")), "n↓",
               *(f"{h} [{u}]" for h in ("x̄↓", "s↓", "x̄", "B_i", "R↑_i", "R↓_i", "R_i"))]
    rows = [[target_label(r["target"]), r["n_up"], r["mean_up"], r["s_up"], r["n_down"], r["mean_down"],
             r["s_down"], r["mean_bi"], r["reversal"], r["R_up_i"], r["R_down_i"], r["R_i"]]
            for r in result.target_table()]
    rep.add_table(headers, rows, caption=f"Deviations in {u}; n = readings used.", digits=2,
                  css_class="targets")
    rep.add_heading("How the figures are formed")
    rep.add_text(
        "Deviation = actual − target. x̄↑, x̄↓: mean deviation approaching in the positive and "
        "negative direction; s: the estimator of the standard uncertainty of positioning at a "
        "target (n − 1 in the denominator); B_i = x̄↑ − x̄↓ (positive when the positive approach "
        "stops further in +); R_i = max(2s↑ + 2s↓ + |B_i|, 4s↑, 4s↓); E, M, A, R, B as defined "
        "in ISO 230-2:2014 clause 3."
    )
    return rep


#: The symbols of ISO 230-2:2014 clause 3, from the one table every page and report reads.
_PARAM_LABEL = PARAMETER_SYMBOLS
_PARAM_MEANING = {
    "A": "Bidirectional accuracy of positioning", "A_up": "Unidirectional accuracy, positive",
    "A_down": "Unidirectional accuracy, negative",
    "E": "Bidirectional systematic positioning error", "E_up": "Unidirectional systematic error, positive",
    "E_down": "Unidirectional systematic error, negative",
    "M": "Range of mean bidirectional positioning error", "R": "Bidirectional repeatability",
    "R_up": "Unidirectional repeatability, positive", "R_down": "Unidirectional repeatability, negative",
    "B": "Reversal value (largest |B_i|)", "B_mean": "Mean reversal value (signed)",
}


def add_acceptance(rep: Report, decisions, unit_text: str, labels: dict | None = None) -> None:
    """The acceptance table of ISO 14253-1 decisions (:class:`~axiscal.standards.iso14253_1.
    Decision`): measured value, expanded uncertainty U (or "not estimated"), tolerance, outcome,
    with the decision rule in the caption."""
    from axiscal.standards.iso230_9 import format_uncertainty

    labels = labels or {}
    cls = {"PASS": "ok", "FAIL": "bad"}
    rows = []
    for d in decisions:
        state = "n/a" if d.outcome is None else d.outcome.short
        css = cls.get(state, "zone")
        u = "not estimated" if math.isnan(d.U) else format_uncertainty(d.U)
        rows.append(f"<tr><td>{_esc(labels.get(d.parameter, d.parameter))}</td>"
                    f"<td>{_cell(d.value, 2)}</td><td>{u}</td><td>{d.upper:g}</td>"
                    f'<td><span class="{css}">{state}</span></td></tr>')
    rule = decisions[0].rule.value
    how = ("ISO 14253-1:2017: conformance is proven when the value plus U is within the "
           "tolerance, non-conformance when the value minus U is beyond it, else ZONE"
           if rule == "iso14253-1" else
           "simple acceptance (ILAC-G8 §4.2.1): the measured value compared with the tolerance, "
           "without a guard band; no published budget gives U for these parameters")
    rep.add_html(f"<h3>Acceptance</h3><table><thead><tr><th>Parameter</th><th>Measured "
                 f"[{unit_text}]</th><th>U (k = 2) [{unit_text}]</th><th>Tolerance "
                 f"[{unit_text}]</th><th>Verdict</th></tr></thead><tbody>{''.join(rows)}</tbody>"
                 f"<caption>Decision rule: {_esc(how)}.</caption></table>")


def standards_report(dataset, results, title: str, decisions=()) -> Report:
    """The report of ``axiscal evaluate``: one test by one or every positioning standard.

    ``results`` are the (Standard, StandardResult or reason) pairs of
    :func:`axiscal.standards.positioning_standards.evaluate_all`. Every parameter keeps its
    standard's name and source; a parameter or standard axiscal does not evaluate is listed with
    the reason. The figure is the per-target one every standard starts from.
    """
    from axiscal.report.plots import standard_figure, standards_figure
    from axiscal.standards.positioning_standards import parameter_label, table_rows

    md = dataset.metadata
    evaluated = [(std, r) for std, r in results if not isinstance(r, str)]
    rep = Report(title, subtitle="Evaluated by " + ", ".join(std.title for std, _ in evaluated),
                 metadata={"Machine": md.machine, "Axis": md.axis, "Operator": md.operator,
                           "Date": md.date, "Instrument": md.instrument, "Notes": md.notes})
    u = unit_label(dataset.deviation_unit)
    rep.add_heading("Result")
    rows = [row[:4] for std, r in evaluated for row in table_rows(std, r)]
    rep.add_table(["Standard", "Parameter", f"Value [{u}]", "Meaning (source)"], rows, digits=2,
                  css_class="params standards", formulas=(3,))
    if decisions:
        add_acceptance(rep, decisions, u, {d.parameter: parameter_label(d.parameter)
                                           for d in decisions})
    rep.add_warnings(f"{std.title}: {w}" for std, r in evaluated for w in r.warnings)
    skipped = [(std, r) for std, r in results if isinstance(r, str)]
    if skipped:
        rep.add_heading("Not evaluated")
        rep.add_table(["Standard", "Why"],
                      [[std.title, _why(why, std.title)] for std, why in skipped],
                      css_class="text")
    units = f"{u} against target in {unit_label(dataset.target_unit)}"
    if len(evaluated) == 1 and evaluated[0][0].key != "iso230-2:2014":
        std, r = evaluated[0]
        band = (f"with the ±{std.band:g}s band of its definitions" if std.band else
                "without a band: its scatter factor is not public")
        rep.add_figure(standard_figure(dataset, std, r),
                       f"Mean deviation per direction and every run's readings, {band} ({units}).")
    elif evaluated:
        std = evaluated[0][0]
        rep.add_figure(standards_figure(dataset, results),
                       f"The readings every standard starts from: mean deviation per direction "
                       f"and every run's readings, drawn as {std.title} does"
                       + (f" with ±{std.band:g}s bands" if std.band else "") + f" ({units}).")
    rep.add_heading("Sources")
    rep.add_table(["Standard", "Definitions taken from"],
                  [[std.title, std.source] for std, _ in evaluated], css_class="text")
    return rep


def _why(reason: str, title: str) -> str:
    """Why a standard was not evaluated, for a customer: without its title (the row names it) and
    without the pointer to axiscal's own documentation (the terminal keeps it)."""
    return reason.removeprefix(f"{title}: ").replace(" (see docs/standards.md)", "")


def target_label(value: float) -> str:
    """A target position as planned: up to 4 decimals, trailing zeros dropped (34.736, 45, 0.5).

    Rounding a target to the table's two decimals would show 34.74 mm for a 34.736 mm target.
    """
    text = f"{float(value):.4f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def unit_label(unit: str) -> str:
    """How a unit is written for people: µm for um, ° for deg, otherwise as it is."""
    return {"um": "µm", "deg": "°"}.get(unit, unit)


def _meta(v: Any) -> Any:
    """A metadata value as a reader wants it: yes/no rather than True/False."""
    return ("yes" if v else "no") if isinstance(v, bool) else v


def _esc(text: Any) -> str:
    return _html.escape(str(text))


def _sym(text: Any) -> str:
    """Escaped text with a standard's symbols subscripted (:func:`~axiscal.report.labels.
    symbol_html`)."""
    from axiscal.report.labels import symbol_html

    return symbol_html(str(text))


def _cell(v: Any, digits: int) -> str:
    """A table cell: a number to ``digits`` decimals (:func:`axiscal.report.labels.fixed`),
    text escaped."""
    from axiscal.report.labels import fixed

    if isinstance(v, (str, bytes)) or not (v is None or isinstance(v, (int, float))
                                           or hasattr(v, "dtype")):
        return _esc(v)
    return fixed(v, digits)


def result_rows(result: dict, unit: str = "", axes=("X", "Y")) -> list[list[str]]:
    """A command's JSON result as ``[label, value]`` rows of text: each scalar under its label
    with unit (:func:`axiscal.report.labels.label`) and its unit's decimals; a short list of
    numbers inline, a long one counted (``--json`` holds it whole). Nested objects and lists of
    objects are left to :func:`result_tables`."""
    from axiscal.report.labels import label, quantity, split_key

    rows: list[list[str]] = []
    for key, value in result.items():
        if key == "warnings" or isinstance(value, dict) or _records(value):
            continue
        name, u = quantity(key, unit, axes)
        shown = f"{name} [{u}]" if u else name
        if isinstance(value, str):   # a text naming another figure of the result by its key
            value = re.sub(r"\b[a-z0-9]+(?:_[a-z0-9]+)+\b", lambda m: label(m[0], unit, axes)
                           if m[0] in result else m[0], value)
        if value is not None:
            rows.append([shown, _uncertainty_text(value) if split_key(key)[0] == "U"
                         else _shown(value, u)])
    return rows


def _uncertainty_text(U) -> str:
    """An expanded uncertainty U as the terminal shows it: two significant digits, rounded up
    (JCGM 100:2008 §7.2.6; :func:`axiscal.standards.uncertainty_reporting.format_uncertainty`),
    not to its unit's decimals (a report said 2.72 µm/m where the terminal said 2.8)."""
    from axiscal.standards.uncertainty_reporting import format_uncertainty

    return format_uncertainty(U) if isinstance(U, (int, float)) else _shown(U, "")


def _record_cell(key: str, value, unit: str, axes) -> str:
    """One cell (``<td>``) of a result that is a table: a name with a standard's subscripts, an
    object as its labelled values, text aligned left and numbers right."""
    from axiscal.report.labels import fmt, quantity, symbol_html

    u = quantity(key, unit, axes)[1]
    if isinstance(value, dict):
        parts = "; ".join(f"{quantity(k, unit, axes)[0]} {fmt(v, unit, True)}"
                          for k, v in value.items())
        return f'<td class="t">{_esc(parts)}</td>'
    shown = _shown(value, u)
    text = symbol_html(shown) if key.rsplit(".", 1)[-1] in ("name", "") else _esc(shown)
    return f'<td class="t">{text}</td>' if isinstance(value, str) else f"<td>{text}</td>"


def _shown(value, unit: str) -> str:
    """A result's value as text with its unit's decimals; a short list inline, a long one
    counted (``--json`` holds it whole)."""
    from axiscal.report.labels import fmt

    if not isinstance(value, (list, tuple)):
        return fmt(value, unit)
    if len(value) > 6:
        return f"{len(value)} values (in --json)"
    return ", ".join(fmt(v, unit) for v in value) or "—"


def result_tables(result: dict, unit: str = "", axes=("X", "Y")) -> list[tuple[str, list, list]]:
    """The nested parts of a command's result as (caption, headers, rows) tables: an object as a
    table of its own, an object of objects or a list of objects as one row per entry."""
    from axiscal.report.labels import label, quantity, split_key

    out = []
    for key, value in result.items():
        caption = quantity(key, unit, axes)[0]
        if isinstance(value, dict) and value and all(isinstance(v, dict) for v in value.values()):
            value = [{"": quantity(k, unit, axes)[0], **v} for k, v in value.items()]
        if _records(value) and all("statement" in v for v in value):
            out.append((caption, [], [[_esc(v["statement"])] for v in value]))
        elif _records(value):
            keys = list(dict.fromkeys(k for v in value for k in v))
            own = "unit" in keys   # each row in its own unit, shown in its unit column
            rows = [[_record_cell(f"{key}.{k}", v.get(k), v.get("unit") if own else unit, axes)
                     for k in keys] for v in value]
            out.append((caption, [label(f"{key}.{k}", "" if own else unit, axes) if k else ""
                                  for k in keys], rows))
        elif isinstance(value, dict):   # its values in the unit its key names (terms_arcsec)
            inner = split_key(key)[1] or unit
            rows = [[_esc(r[0]), _esc(r[1])] for r in result_rows(value, inner, axes)]
            out.append((caption, ["", ""], rows))
            out.extend((f"{caption}: {c}", h, r) for c, h, r in result_tables(value, inner, axes))
    return out


def _records(value) -> bool:
    """A non-empty list of objects (a result that is itself a table)."""
    return isinstance(value, (list, tuple)) and bool(value) and all(isinstance(v, dict)
                                                                     for v in value)


def write_result_report(path, title: str, result: dict, *, figure=None, caption: str = "",
                        method: str = "", subtitle: str = "", notes=(), simulation: bool = False,
                        metadata: dict | None = None, tables=()) -> Path:
    """A report of one command's result: the method (with its document and clause), the plot,
    and every figure of the ``--json`` result as a table.

    Used by the commands whose result is a handful of figures and one plot (straightness, the
    squareness tests, scale referencing, capture, history comparisons and trends, the rotary
    budget); ``tables`` adds (caption, headers, rows) for a result that is itself a table;
    ``simulation`` marks every page as a simulation report.
    """
    rep = Report(title, subtitle=subtitle, metadata=metadata or {}, simulation=simulation)
    if method:
        rep.add_text(method)
    rep.add_warnings(list(notes) + list(result.get("warnings") or ()))
    if figure is not None:
        rep.add_figure(figure, caption)
    rep.add_heading("Results")
    unit = result.get("unit") or result.get("deviation_unit") or ""
    axes = tuple(result.get("axes") or ("X", "Y"))
    rep.add_table(["", ""], result_rows(result, unit, axes), css_class="kv")
    for caption_, headers, rows in result_tables(result, unit, axes):
        rep.add_html(_html_table(caption_, headers, rows))
    for caption_, headers, rows in tables:  # (caption, headers, rows): a result that is a table
        rep.add_table(headers, rows, caption=caption_, digits=2)
    return rep.write(path)


def _html_table(caption: str, headers, rows) -> str:
    """A table of cells already written as HTML (a key/value table when its headers are empty)."""
    if not headers:   # statements: one sentence each
        items = "".join(f"<li>{row[0]}</li>" for row in rows)
        return f'<h3>{_esc(caption)}</h3><ul class="statements">{items}</ul>'
    kv = not any(headers)
    head = "".join(f"<th>{_esc(h)}</th>" for h in headers)
    body = "".join("<tr>" + "".join(c if c.startswith("<td") else f"<td>{c}</td>" for c in row)
                   + "</tr>" for row in rows)
    cls = ("kv" if kv else "records") + (" long" if len(rows) > LONG_TABLE else "")
    return (f'<h3>{_esc(caption)}</h3><table class="{cls}">'   # a heading stays with its table
            f"<thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>")
