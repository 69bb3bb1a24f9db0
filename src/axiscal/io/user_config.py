"""The user configuration: one place for company, operator, instruments and uncertainty defaults.

The file is ``config.toml`` in the user's configuration folder (platformdirs:
``~/.config/axiscal/config.toml`` on Linux), or the file named by ``AXISCAL_CONFIG``.
``axiscal config --init`` writes a commented template there. A job file (``--job FILE.toml``
on a command that writes a certificate) has the same tables and overrides the user file for one
test: customer, machine, test conditions, tolerances, specification.

:func:`config_problem` says why the user configuration cannot identify a laboratory (absent,
empty, still the template, or ``AXISCAL_CONFIG`` naming a file that does not exist): a
certificate names that reason among its missing items (ISO/IEC 17025:2017 §7.8.2.1 c).
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from axiscal.errors import ConfigError

__all__ = ["config_path", "load_user_config", "load_job", "merge", "logo_data_uri", "TEMPLATE",
           "TEMPLATE_COMPANY", "config_problem", "DEFAULT_NUMBER_PATTERN"]

#: The laboratory's certificate numbers when the configuration gives no pattern: the laboratory's
#: code, the year of issue and the register's counter.
DEFAULT_NUMBER_PATTERN = "{lab}-{year}-{counter:05d}"
#: The template's company name: a configuration that still holds it identifies no laboratory.
TEMPLATE_COMPANY = "Your Calibration Company Ltd"

TEMPLATE = """\
# axiscal user configuration: what every certificate carries.
# A job file (--job FILE.toml) with the same tables overrides these for one test.
# A certificate is issued (numbered in the register) only when every mandatory item of
# ISO/IEC 17025:2017 §7.8.2 and §7.8.4 is given; otherwise it is a DRAFT naming what is missing.

[company]
name = "Your Calibration Company Ltd"
address = ["1 Example Street", "Town, Postcode", "Country"]
code = "YCC"                          # the laboratory's code in certificate numbers
# logo = "/path/to/logo.png"          # PNG, JPEG or SVG
# accreditation = "Accredited calibration laboratory no. ..."

[operator]
name = "A. Operator"

[certificate]
paper = "A4"                          # or "Letter"
rule = "iso14253-1"                   # or "simple" (simple acceptance, stated on the certificate)
number_pattern = "{lab}-{year}-{counter:05d}"   # {lab} = [company] code, counter from the register
signatory = "B. Signatory"            # who authorises the certificate ...
signatory_role = "Head of laboratory" # ... and in which role

# The laboratory's authorised signatories: a certificate is issued only when one of them
# approves it (--approved-by NAME; the workbench's signed-in user), never the one who prepared it
# [[signatory]]
# name = "B. Signatory"
# role = "Head of laboratory"

[[instrument]]
name = "Laser interferometer"
serial = "..."
certificate = "..."
due = "YYYY-MM-DD"

# ISO 230-2:2014 Annex A inputs (see axiscal.standards.iso230_9); a number is in the unit the
# report shows, or text with its unit ("11.5 um/(m K)", "20.5 degC"). An input left out is
# assumed by a documented rule and shown as assumed beside U; give the values of your own
# instruments and set-up (the numbers below are the assumed defaults).
[uncertainty]
# reference = "laser"                 # or "encoder" (taken from the data file where it says so)
# laser_accuracy_ppm = 0.5            # from the laser's calibration certificate, expanded ...
# laser_accuracy_k = 2.0              # ... with this coverage factor
# encoder_accuracy = 5.0              # µm/m, ± bound of an encoder reference
# resolution = 0.001                  # µm
# beam_offset = 0.125                 # mm, lateral beam offset over the travel as aligned
# shop_temperature_min = 17.0         # °C, the shop's range when the material temperature ...
# shop_temperature_max = 23.0         # ... is not stated in the data file
# temperature_halfwidth = 0.1         # K, material sensor accuracy
# sensor_position_halfwidth = 0.2     # K, sensor place vs scale
# expansion_coefficient = 11.5        # µm/(m·K), α of the machine's scale (the data file's ...
# material_temperature = 20.0         # °C ... where it states them); or text: "293.15 K"
# expansion_coefficient_halfwidth = 1.15      # µm/(m·K) (default ±10 % of α)
# e_ve = 1.0                          # µm, environmental variation error: never assumed ...
# e_ve_source = "drift check"         # ... measured ("drift check") or "declared"
# Keys of the other kind's budget are ignored for a test (said in its notes). Per kind of axis:
# values for that kind only, and the laboratory's CMC per parameter (U is never stated below):
# [uncertainty.linear]
# cmc = { E = 1.0, A = 1.0, M = 1.0, R = 0.6, B = 0.6 }   # µm
# [uncertainty.rotary]
# resolution = 0.1                    # arcsec
# cmc = { E = 1.5, A = 1.5, R = 1.0, B = 1.0 }            # arcsec

# A straightness test's budget (ISO 230-1:2012 §8.2; axiscal.standards.iso230_9_straightness);
# its reading noise and slope fit are measured from the file (the numbers: the assumed defaults)
# [straightness_uncertainty]
# reference_u = 0.5                   # µm, the straightedge's or straightness optics' form, k = 1
# gain = 0.5                          # %, ± bound of the instrument's scale error
# resolution = 0.1                    # µm
# e_ve = 0.0                          # µm, the reading's range at rest over the test (air
#                                     # turbulence, gradients across a laser beam)
# reference_slope_u = 0.0             # µm/m, the reference's direction where it is calibrated
"""


def config_path() -> Path:
    """Where the user configuration lives (``AXISCAL_CONFIG`` overrides the platform folder)."""
    env = os.environ.get("AXISCAL_CONFIG")
    if env:
        return Path(env)
    import platformdirs

    return platformdirs.user_config_path("axiscal") / "config.toml"


def load_user_config(path: Path | None = None) -> dict[str, Any]:
    """The user configuration as a dict; an absent file is an empty configuration."""
    from axiscal.io._files import load_toml

    p = Path(path) if path is not None else config_path()
    if path is None and not p.exists():
        return {}
    return _plain_text(check_instruments(load_toml(p), str(p)), p)


#: The keys of an ``[[instrument]]`` entry (``name`` required).
INSTRUMENT_KEYS = ("name", "serial", "certificate", "due")


def check_instruments(cfg: dict[str, Any], source: str) -> dict[str, Any]:
    """Refuse ``[[instrument]]`` entries that are not tables with a ``name`` and known keys (an
    entry without ``name`` passed ``axiscal config`` and ended a certificate in a traceback:
    issue 39)."""
    from axiscal.errors import ConfigError

    inst = cfg.get("instrument", [])
    for n, t in enumerate(inst if isinstance(inst, list) else [inst], 1):
        if not isinstance(t, dict):
            raise ConfigError(f"{source}: [[instrument]] {n} is not a table; write [[instrument]] "
                              'then name = "...", serial = "..."')
        unknown = sorted(set(t) - set(INSTRUMENT_KEYS))
        if unknown:
            raise ConfigError(f"{source}: [[instrument]] {n}: unknown key(s) "
                              f"{', '.join(map(str, unknown))[:80]}; known: "
                              f"{', '.join(INSTRUMENT_KEYS)}")
        if not str(t.get("name", "")).strip():
            raise ConfigError(f"{source}: [[instrument]] {n} has no name; every instrument "
                              "needs name = \"...\"")
    return cfg


def config_problem(config: dict[str, Any] | None = None) -> str:
    """Why the user configuration identifies no laboratory ('' when it may).

    Absent (and where it was looked for), ``AXISCAL_CONFIG`` naming a file that does not exist,
    empty, or still the template :data:`TEMPLATE` (its company name unchanged).
    """
    p = config_path()
    if not p.exists():
        if os.environ.get("AXISCAL_CONFIG"):
            return f"AXISCAL_CONFIG names {p}, which does not exist"
        return f"no user configuration at {p} (write one with 'axiscal config --init')"
    cfg = load_user_config() if config is None else config
    if not cfg:
        return f"the user configuration {p} is empty"
    if cfg.get("company", {}).get("name") == TEMPLATE_COMPANY:
        return f"the user configuration {p} is still the template of 'axiscal config --init'"
    return ""


def load_job(path) -> dict[str, Any]:
    """A job file (same tables as the user configuration, for one test).

    Raises
    ------
    InputError
        A text holding a control character (ESC, BEL, NUL ...) or a bidirectional control
        (U+202E ...): it would be written into the certificate
        (:func:`axiscal.store.limits.checked_tables`, the rule of every text axiscal writes).
    """
    from axiscal.io._files import load_toml

    return _plain_text(check_instruments(load_toml(path), str(path)), path)


def _plain_text(cfg: dict[str, Any], path) -> dict[str, Any]:
    """``cfg`` if every text in it is free of control characters (one line where not an
    address, a note or a reason), else an InputError naming the file, the ``[table] key`` and
    the character."""
    from axiscal.store.limits import checked_tables

    return checked_tables(cfg, f"{Path(str(path)).name}:")


def merge(base: dict[str, Any], over: dict[str, Any]) -> dict[str, Any]:
    """``over`` on top of ``base``, table by table (a list such as ``[[instrument]]`` replaces)."""
    out = dict(base)
    for k, v in over.items():
        out[k] = merge(out[k], v) if isinstance(v, dict) and isinstance(out.get(k), dict) else v
    return out


def logo_data_uri(config: dict[str, Any], where: Path | None = None) -> str:
    """The ``[company] logo`` file as a ``data:`` URI ('' if none); a missing file is an error."""
    name = config.get("company", {}).get("logo")
    if not name:
        return ""
    p = Path(str(name)).expanduser()
    if not p.is_absolute() and where is not None:
        p = where.parent / p
    mime = {
        ".png": "image/png",
        ".jpg": "image/jpeg",
        ".jpeg": "image/jpeg",
        ".svg": "image/svg+xml",
    }.get(p.suffix.lower())
    if mime is None:
        raise ConfigError(f"[company] logo {p}: use a .png, .jpg or .svg file")
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise ConfigError(f"[company] logo {p}: {exc.strerror or exc}") from None
    import base64

    return f"data:{mime};base64,{base64.b64encode(data).decode('ascii')}"
