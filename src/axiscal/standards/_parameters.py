"""How every positioning standard's result names and describes its parameters.

The one shape shared by :mod:`.jis_b6192`, :mod:`.vdi3441` and the registry of
:mod:`.positioning_standards`: name -> (value, unit, "description (source)"). It lives below all
three so that the registry can import the standards and the standards this helper without a circle.
"""

from __future__ import annotations

__all__ = ["described_parameters", "parameter_label"]


def parameter_label(name: str) -> str:
    """How a parameter name is shown: ``R_up`` -> ``R↑``, ``R_down`` -> ``R↓``, ``U_mean`` ->
    ``U mean``."""
    return name.replace("_up", "↑").replace("_down", "↓").replace("_mean", " mean")


def described_parameters(result, table: dict[str, tuple[str, str]]):
    """name -> (value, unit, "description (source)") of ``result``'s attributes named in ``table``
    (name -> (description, clause or source)), in the table's order and ``deviation_unit``."""
    return {name: (getattr(result, name), result.deviation_unit, f"{desc} ({src})")
            for name, (desc, src) in table.items()}
