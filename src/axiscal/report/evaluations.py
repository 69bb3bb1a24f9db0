"""The figure and the notebook view of one evaluation of any kind of test (public API).

:func:`kind_figure` draws what the kind's command draws with ``--plot`` (``ballbar analyze``,
``straightness``, ``squareness diagonal --file``, ``motion analyze``); :func:`notebook_html` is
the ``_repr_html_`` of :class:`axiscal.api.Evaluation`: its scalar results, then its figure.
"""

from __future__ import annotations

from typing import Any

__all__ = ["FIGURES", "kind_figure", "notebook_html"]


def kind_figure(kind: str, dataset: Any, result: Any) -> Any:
    """The matplotlib Figure of a ``ballbar``, ``straightness``, ``diagonal`` or ``motion``
    evaluation (:data:`FIGURES`)."""
    return FIGURES[kind](dataset, result)


def _ballbar_figure(data: Any, r: Any) -> Any:
    """Both directions: the diagnosis's polar plot and ranked terms; one: the ISO 230-4 plot."""
    if hasattr(r, "circular"):
        from axiscal.report.ballbar_plots import diagnosis_figure

        return diagnosis_figure(data.runs, r)
    from axiscal.report.squareness_plots import ballbar_figure

    return ballbar_figure(data.runs, r)


def _straightness_figure(data: Any, r: Any) -> Any:
    from axiscal.report.squareness_plots import straightness_figure

    return straightness_figure(data, r)


def _diagonal_figure(data: Any, r: Any) -> Any:
    from axiscal.report.squareness_plots import diagonal_figure

    return diagonal_figure(data, r)


def _motion_figure(data: Any, r: Any) -> Any:
    from axiscal.report.motion_plots import polar_figure

    return polar_figure(r)


#: The figure of each kind other than a positioning test: the one its command's --plot draws.
FIGURES = {"ballbar": _ballbar_figure, "straightness": _straightness_figure,
           "diagonal": _diagonal_figure, "motion": _motion_figure}


def notebook_html(kind: str, standard: str, d: dict, fig: Any) -> str:
    """A notebook's view: the scalar results as a table, then the figure (SVG)."""
    from html import escape

    from axiscal.report.html import figure_svg

    rows = "".join(f"<tr><th>{escape(str(k))}</th><td>{escape(_cell(v))}</td></tr>"
                   for k, v in d.items() if isinstance(v, (int, float, str)) or v is None)
    return (f"<div><p><b>{escape(kind)}</b> by {escape(standard)}</p>"
            f"<table>{rows}</table>{figure_svg(fig)}</div>")


def _cell(v: Any) -> str:
    return "—" if v is None else f"{v:.4g}" if isinstance(v, float) else str(v)
