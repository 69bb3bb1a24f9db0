"""Results as data: a measured quantity with its value, expanded uncertainty, coverage factor,
unit and verdict, in one shape for every kind of test.

Every evaluation axiscal gives (a positioning test by any standard, a ballbar, straightness,
squareness, five-error test ...) names its results as :class:`Quantity` records, as GTC's
``ureal`` carries a value with its uncertainty. The same records are what ``--json`` writes
under ``quantities`` (:func:`quantities_json`, schema :data:`SCHEMA_VERSION`), what the history
stores and gives back, what the workbench's JSON serves and what an archive carries; a tidy
:class:`pandas.DataFrame` of them is :func:`quantities_frame`.

The block every ``--json`` object of an evaluation carries (schema 1): ``schema_version``
(1), ``quantities`` (name -> ``value``, ``U``, ``k``, ``unit``, ``symbol``, ``verdict``,
``tolerance``; null where not applicable, not estimated or not decided) and
``uncertainty_inputs`` (the inputs the budget was made with, by name, as given; absent ones
were assumed and are said in ``uncertainty_budget``). Keys of the older flat forms (``A``,
``uncertainty``, ``parameters``, ``backlash_x_um`` ...) stay for one release and are
deprecated: read ``quantities``.

Units are the code's short names (``um``, ``arcsec``, ``um/m``), as every ``unit`` key of the
JSON: :func:`axiscal.units.display` writes them as people do (µm, ″).

Examples
--------
>>> q = Quantity("E", 74.77, "um", U=0.66, k=2.0, symbol="E")
>>> str(q)
'E = 74.77 ± 0.66 µm (k = 2)'
>>> q.to_dict()["U"]
0.66
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Mapping

__all__ = ["SCHEMA_VERSION", "Quantity", "make_quantities", "quantities_json",
           "quantities_frame"]

#: Version of the ``quantities`` schema of ``--json``, the history, the workbench's JSON and
#: the archive (docs: "JSON output"). A new key keeps the version; a renamed or removed one
#: raises it, the old key kept one release and listed under ``deprecated``.
SCHEMA_VERSION = 1


@dataclass(frozen=True)
class Quantity:
    """One result of a test: value, expanded uncertainty, coverage factor, unit and verdict.

    Attributes
    ----------
    name : str
        The key (``E``, ``R_up``, ``jis-b6192:R``, ``squareness``), as ``history trend
        --parameter`` takes it.
    value : float or None, ``unit``
        None where the parameter does not apply (the other direction of a one-way test).
    unit : str
        ``um``, ``arcsec``, ``um/m`` ... (:mod:`axiscal.units`).
    U : float or None, ``unit``
        Expanded uncertainty (JCGM 100:2008 §6.2.1); None where the kind has no budget.
    k : float or None
        Coverage factor of ``U`` (JCGM 100:2008 §6.2.1); None without ``U``.
    symbol : str
        The document's symbol (ISO 230-2:2014 §3: ``R↑``), else the key in words.
    verdict : str or None
        The ISO 14253-1:2017 outcome against a tolerance (``conformance proven`` ...), None
        without a tolerance.
    tolerance : float or None, ``unit``
        The upper limit the verdict was decided against.
    """

    name: str
    value: float | None
    unit: str
    U: float | None = None
    k: float | None = None
    symbol: str = ""
    verdict: str | None = None
    tolerance: float | None = None

    def __float__(self) -> float:
        return float("nan") if self.value is None else float(self.value)

    def __str__(self) -> str:
        from axiscal import units
        from axiscal.standards.uncertainty_reporting import format_uncertainty

        u = units.display(self.unit)
        sym = self.symbol or self.name
        if self.value is None:
            return f"{sym}: n/a"
        text = f"{sym} = {self.value:.2f}" if abs(self.value) >= 0.01 or self.value == 0 \
            else f"{sym} = {self.value:.3g}"
        if self.U is not None:
            text += f" ± {format_uncertainty(self.U)} {u} (k = {self.k:g})"
        else:
            text += f" {u}"
        if self.verdict:
            text += f", {self.verdict}"
        return text

    def to_dict(self) -> dict[str, Any]:
        """The object of this quantity under ``quantities`` in every JSON."""
        return {"value": self.value, "U": self.U, "k": self.k, "unit": self.unit,
                "symbol": self.symbol or self.name, "verdict": self.verdict,
                "tolerance": self.tolerance}

    @classmethod
    def from_dict(cls, name: str, d: Mapping[str, Any]) -> "Quantity":
        """A quantity back from its JSON object (the history, an archive)."""
        return cls(name, d.get("value"), d.get("unit", ""), d.get("U"), d.get("k"),
                   d.get("symbol", ""), d.get("verdict"), d.get("tolerance"))


def make_quantities(parameters: Mapping[str, tuple], budget: Any = None,
                    verdicts: Iterable[Any] = ()) -> dict[str, Quantity]:
    """The quantities of an evaluation from its parameters, its budget and its verdicts.

    Parameters
    ----------
    parameters : mapping of str to (value, unit)
        The evaluation's named results (:attr:`axiscal.store.kinds.Evaluated.parameters`).
    budget : UncertaintyBudget, optional
        Its uncertainty budget (ISO 230-2:2014 Annex A; ISO/TR 230-9): U and k of every
        parameter it covers.
    verdicts : iterable of Decision
        ISO 14253-1:2017 decisions, by parameter.
    """
    from axiscal.standards.iso230_2 import PARAMETER_SYMBOLS

    by = {v.parameter: v for v in verdicts}
    out = {}
    for name, (value, unit) in parameters.items():
        U = budget.U(name) if budget is not None else None
        U = None if U is None or U != U else float(U)
        v = by.get(name)
        out[name] = Quantity(name, None if value is None else float(value), unit, U,
                             None if U is None else float(budget.k),
                             PARAMETER_SYMBOLS.get(name, name),
                             v.outcome.value if v is not None and v.outcome else None,
                             None if v is None else v.upper)
    return out


def quantities_json(quantities: Mapping[str, Quantity]) -> dict[str, Any]:
    """``{"schema_version": 1, "quantities": {name: {...}}}``: the block every JSON carries."""
    return {"schema_version": SCHEMA_VERSION,
            "quantities": {n: q.to_dict() for n, q in quantities.items()}}


def quantities_frame(quantities: Mapping[str, Quantity]) -> Any:
    """A tidy :class:`pandas.DataFrame` of the quantities: one row each, indexed by ``name``,
    columns ``symbol``, ``value``, ``U``, ``k``, ``unit``, ``verdict``, ``tolerance``."""
    import pandas as pd

    rows = [{"name": n, **q.to_dict()} for n, q in quantities.items()]
    cols = ["name", "symbol", "value", "U", "k", "unit", "verdict", "tolerance"]
    df = pd.DataFrame(rows, columns=cols).set_index("name")
    df.attrs["schema_version"] = SCHEMA_VERSION
    return df
