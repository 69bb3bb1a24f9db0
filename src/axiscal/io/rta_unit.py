"""The ``.rta`` file's own unit kept beside the arcsec axiscal shows (Renishaw's rotary
export holds µrad): a module of its own, so that a result's ``--json`` can ask without loading
the Renishaw reader (``axiscal iso230-2 --json`` of a CSV loads no other format's reader)."""
from axiscal import units

#: The note of a ``.rta`` read in arcsec: its results' ``--json`` also gives them in the file's
#: µrad (:func:`file_unit_block`).
RTA_CONVERTED = ("deviations converted from the file's µrad to arcsec, the unit of every rotary "
                 "result in axiscal (read with deviation_unit=urad for the file's own numbers)")


def file_unit_block(notes: str, parameters: dict) -> dict | None:
    """The ISO 230-2 parameters in the ``.rta`` file's own unit, µrad, for ``--json`` beside the
    arcsec shown (``parameters`` in arcsec); None for a dataset not read from a ``.rta`` in
    arcsec (``notes``: the dataset's, which say :data:`RTA_CONVERTED`).

    1″ = π/648000 rad = 4.8481 µrad (ISO 80000-3 angle units; Read Laser Plot's 0.2063 ″/µrad
    is its inverse).
    """
    if RTA_CONVERTED not in (notes or ""):
        return None
    k = units.convert(1.0, "arcsec", "urad")
    return {"deviation_unit": "urad", "source": "the .rta file's unit",
            "parameters": {n: None if v is None else v * k for n, v in parameters.items()}}
