"""The settings of an EPICS camonitor log, one set for every front end.

A camonitor log (:mod:`axiscal.io.epics`) becomes a positioning test with six settings: the
setpoint PV whose steps are the stops, the reference PV read where it rests, the targets, the
line ``position = scale × reference + offset`` (ecmc's ``REF_GR`` and ``REF_OFF``,
``ecmcGetISO230DataFromCAFile.bash``) and the band the reference rests within. The command line
takes them as ``--setpoint-pv``, ``--reference-pv``, ``--targets``, ``--reference-scale``,
``--reference-offset`` and ``--rest-window`` (``axiscal iso230-2 LOG``, ``evaluate``,
``capture``); the workbench's measured upload takes them as form fields of the same names with
``_`` for ``-``. :func:`epics_options` turns what was given into the keyword arguments of
:func:`~axiscal.io.epics.capture_epics`, :func:`defaults_used` says each setting not given and
the default that acted in its place (shown beside the result), and :func:`capture_log` is the
one conversion both front ends call.
"""

from __future__ import annotations

from axiscal.errors import InputError

__all__ = ["SETTINGS", "epics_options", "defaults_used", "capture_log"]

#: Each setting: (name, command-line option, what acts when it is not given).
SETTINGS = (
    ("setpoint_pv", "--setpoint-pv", "found: of a log of two PVs, the one with fewer updates"),
    ("reference_pv", "--reference-pv", "found: the other PV of a log of two"),
    ("targets", "--targets", "the setpoint values passed through (turning points are "
                             "over-travel)"),
    ("reference_scale", "--reference-scale", "1 (ecmc's REF_GR)"),
    ("reference_offset", "--reference-offset", "0 (ecmc's REF_OFF)"),
    ("rest_window", "--rest-window", "1 µm (arcsec for a rotary axis) for 0.5 s at a stop"),
)
_KEYS = {"rest_window": "window"}        # capture_epics's name of a setting


def epics_options(setpoint_pv=None, reference_pv=None, targets=None, reference_scale=None,
                  reference_offset=None, rest_window=None, plan=None, dwell=None) -> dict:
    """The settings given, as :func:`axiscal.io.epics.capture_epics` takes them (none: ``{}``).

    Parameters
    ----------
    setpoint_pv, reference_pv : str, optional
        Blank text is not given.
    targets : str or sequence of float, target unit, optional
        Text is comma-separated numbers (``0,100,200``).
    reference_scale, reference_offset : float or str, optional
        ``position = scale × reference + offset``, target unit.
    rest_window : float or str, µm (arcsec rotary), optional
    plan : PlanRows, optional
        The plan the axis ran.
    dwell : float, s, optional

    Returns
    -------
    dict
        Keys of :func:`~axiscal.io.epics.capture_epics` (``window`` for ``rest_window``).

    Raises
    ------
    InputError
        Targets or a number that do not read as numbers, named by their option.

    Examples
    --------
    >>> epics_options(reference_pv="IOC:m1-PosAct", targets="0, 100,200", rest_window="2")
    {'reference_pv': 'IOC:m1-PosAct', 'window': 2.0, 'targets': [0.0, 100.0, 200.0]}
    """
    given = {"setpoint_pv": setpoint_pv, "reference_pv": reference_pv,
             "reference_scale": reference_scale, "reference_offset": reference_offset,
             "rest_window": rest_window, "dwell": dwell}
    d: dict = {}
    for name, value in given.items():
        if value is None or (isinstance(value, str) and not value.strip()):
            continue
        if name.endswith("_pv"):
            d[name] = value.strip()
        else:
            d[_KEYS.get(name, name)] = _number(name, value)
    if isinstance(targets, str) and targets.strip():
        try:
            d["targets"] = [float(x) for x in targets.split(",") if x.strip()]
        except ValueError:
            raise InputError(f"--targets {targets!r}: give numbers separated by commas, "
                             "e.g. 0,100,200") from None
    elif targets is not None and not isinstance(targets, str):
        d["targets"] = [float(x) for x in targets]
    if plan is not None:
        d["plan"] = plan
    return d


def defaults_used(options: dict) -> list[str]:
    """Each setting of :data:`SETTINGS` not in ``options`` with what acted in its place.

    Examples
    --------
    >>> for line in defaults_used({"reference_pv": "R", "setpoint_pv": "S", "window": 2.0}):
    ...     print(line)
    --targets not given: the setpoint values passed through (turning points are over-travel)
    --reference-scale not given: 1 (ecmc's REF_GR)
    --reference-offset not given: 0 (ecmc's REF_OFF)
    """
    out = []
    for name, option, default in SETTINGS:
        if _KEYS.get(name, name) in options or (name == "targets" and "plan" in options):
            continue
        out.append(f"{option} not given: {default}")
    return out


def capture_log(text: str, source: str, options: dict):
    """The positioning test of a camonitor log with the settings ``options`` (of
    :func:`epics_options`) and the words of what was found and assumed.

    Returns
    -------
    (EpicsCapture, str)
        The capture (:func:`axiscal.io.epics.capture_epics`) and its dataset's notes followed by
        :func:`defaults_used`.
    """
    from axiscal.io.epics import capture_epics

    cap = capture_epics(text, source=source, **options)
    words = "; ".join([cap.dataset.metadata.notes, *defaults_used(options)])
    return cap, words


def _number(name: str, value) -> float:
    import math

    try:
        v = float(str(value).strip().replace(",", ".")) if isinstance(value, str) else \
            float(value)
    except (TypeError, ValueError):
        raise InputError(f"--{name.replace('_', '-')} {value!r}: give a number") from None
    if not math.isfinite(v):
        raise InputError(f"--{name.replace('_', '-')} {value!r}: give a finite number")
    return v
