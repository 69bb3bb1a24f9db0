"""Units checked on the way in (issue 37): every input of the ISO 230-2:2014 Annex A budgets is
typed in the unit the output shows beside it, or with its own unit, and refused outside its
plausible range. The trap the issue found: ``expansion_coefficient=11.5`` (as the table shows α,
11.5 µm/(m·K)) read as 11.5 /K gave U(A) = 210,000 µm."""

from __future__ import annotations

import json
from dataclasses import fields
from pathlib import Path

import pytest
from typer.testing import CliRunner

from axiscal.cli import app
from axiscal.errors import InputError
from axiscal.standards.iso230_9 import (
    LinearInputs,
    RotaryInputs,
    linear_budget,
    resolve_linear,
    resolve_rotary,
    rotary_budget,
)
from axiscal.standards.iso230_9_entry import LINEAR_ENTRY, ROTARY_ENTRY, entered
from axiscal.standards.iso230_9_inputs import input_table

ECMC = Path(__file__).resolve().parents[1] / "data" / "ecmc" / "sls_fat_sat_ISO230.dat"
TRAVEL_MM = 800.0

#: For each linear input: (a value as the output table shows it, the same with its unit, the
#: value inside LinearInputs, the other inputs that let it act on U).
LINEAR_TYPED = {
    "laser_accuracy_ppm": (1.5, "1.5 ppm", 1.5, {}),
    "laser_accuracy_k": (1.5, "1.5", 1.5, {}),
    "encoder_accuracy": (3.0, "0.003 mm/m", 3.0, {"reference": "encoder"}),
    "resolution": (0.01, "10 nm", 0.01, {}),
    "beam_offset": (0.5, "500 um", 0.5, {}),
    "expansion_coefficient": (8.0, "8e-6 1/K", 8e-6, {}),
    "expansion_coefficient_halfwidth": (0.5, "0.5 um/(m K)", 0.5e-6, {}),
    "material_temperature": (21.5, "294.65 K", 21.5, {}),
    "shop_temperature_min": (15.0, "59 degF", 15.0, {}),
    "shop_temperature_max": (24.5, "24.5 °C", 24.5, {}),
    "temperature_halfwidth": (0.3, "0.3 degC", 0.3, {}),   # a difference: 0.3 °C = 0.3 K
    "sensor_position_halfwidth": (0.5, "500 mK", 0.5, {}),
    "e_ve": (0.8, "0.0008 mm", 0.8, {}),
}
ROTARY_TYPED = {
    "calibrator_accuracy": (2.0, "2 arcsec", 2.0),
    "calibrator_k": (1.5, "1.5", 1.5),
    "resolution": (0.5, "0.5 arcsec", 0.5),
    "alpha": (2.0, "0.002 rad", 2.0),
    "beta": (3.0, "3 mrad", 3.0),
    "omega": (4.0, "4000 urad", 4.0),
    "e_ve": (1.5, "1.5 arcsec", 1.5),
}


def _U(budget) -> dict[str, float]:
    return {p: budget.U(p) for p in budget.combined}


def test_every_number_input_has_a_rule_and_a_typed_case():
    """No input escapes the check: each number field of LinearInputs and RotaryInputs has an
    entry rule and a case below."""
    text = {"reference", "e_ve_source"}
    assert set(LINEAR_ENTRY) == {f.name for f in fields(LinearInputs)} - text == set(LINEAR_TYPED)
    assert set(ROTARY_ENTRY) == {f.name for f in fields(RotaryInputs)} - text == set(ROTARY_TYPED)


@pytest.mark.parametrize("name", sorted(LINEAR_TYPED))
def test_linear_input_typed_as_shown_gives_the_internal_U(name):
    """Typed in the table's unit, or as text with another unit, an input gives the same U as
    the budget built with its internal value; and it moves U (so the check could fail)."""
    shown, text, inside, others = LINEAR_TYPED[name]
    internal = _U(linear_budget(TRAVEL_MM, LinearInputs(**others, **{name: inside})))
    for typed in (shown, text):
        inputs = resolve_linear({**others, name: typed})[0]
        assert getattr(inputs, name) == pytest.approx(inside, rel=1e-12)
        assert _U(linear_budget(TRAVEL_MM, inputs)) == pytest.approx(internal, rel=1e-12)
    assert _U(linear_budget(TRAVEL_MM, LinearInputs(**others))) != pytest.approx(internal)


@pytest.mark.parametrize("name", sorted(ROTARY_TYPED))
def test_rotary_input_typed_as_shown_gives_the_internal_U(name):
    shown, text, inside = ROTARY_TYPED[name]
    internal = _U(rotary_budget(RotaryInputs(**{name: inside})))
    for typed in (shown, text):
        inputs = resolve_rotary({name: typed})[0]
        assert getattr(inputs, name) == pytest.approx(inside, rel=1e-12)
        assert _U(rotary_budget(inputs)) == pytest.approx(internal, rel=1e-12)
    assert _U(rotary_budget(RotaryInputs())) != pytest.approx(internal)


@pytest.mark.parametrize("name, typed, message", [
    ("expansion_coefficient", 11.5e-6, "give 0, or 0.001 to 100 µm/(m·K)"),   # α in 1/K
    ("expansion_coefficient", 11.5e6, "give 0, or 0.001 to 100 µm/(m·K)"),
    ("expansion_coefficient", "11.5 1/K", "1.15e+07 µm/(m·K) is implausible"),
    ("material_temperature", 293.15, "293.15 °C is implausible: give 0 to 50 °C"),
    ("shop_temperature_max", 296.15, "give 0 to 50 °C"),
    ("beam_offset", 125.0, "give 0 to 25 mm"),                                 # µm typed as mm
    ("laser_accuracy_ppm", 0.5e-6, "give 0.01 to 100 ppm"),                    # a fraction
    ("temperature_halfwidth", 100.0, "give 0 to 10 K"),                        # mK typed as K
    ("e_ve", -1.0, "give 0 to 1000 µm"),
    ("resolution", float("nan"), "finite"),
    ("material_temperature", "20 mm", "cannot be converted to degC"),
    ("material_temperature", "warm", "write a number, then its unit"),
    ("beam_offset", True, "give a number in mm"),
])
def test_implausible_values_are_refused_naming_the_range(name, typed, message):
    with pytest.raises(InputError, match="uncertainty " + name) as e:
        resolve_linear({name: typed})
    assert message in str(e.value) and "\n" not in str(e.value)


def test_rotary_value_in_degrees_refused():
    """A calibrator's ±1 arcsec typed in degrees (0.000278) is below the plausible range."""
    with pytest.raises(InputError, match="give 0.001 to 100 arcsec"):
        resolve_rotary({"calibrator_accuracy": 1 / 3600})
    assert resolve_rotary({"calibrator_accuracy": "0.000278 deg"})[0].calibrator_accuracy == \
        pytest.approx(1.0008, rel=1e-9)


def test_the_issues_trap_is_gone():
    """``--uncertainty expansion_coefficient=11.5`` is steel's α (the default, 11.5e-6 /K): the
    same U as giving nothing, not U(A) = 210,000 µm; with its unit too; 1.15e-05 (α in 1/K
    without its unit) is refused naming the range; 293.15 as a material temperature is refused,
    '293.15 K' is 20 °C."""
    def run(*items):
        args = ["iso230-2", str(ECMC), "--json"]
        for item in items:
            args += ["--uncertainty", item]
        return CliRunner().invoke(app, args)

    base = json.loads(run().stdout)["uncertainty"]
    for item in ("expansion_coefficient=11.5", "expansion_coefficient=11.5 um/(m K)",
                 "expansion_coefficient=11.5 µm/(m·K)"):
        r = run(item)
        assert r.exit_code == 0, r.output
        assert json.loads(r.stdout)["uncertainty"] == pytest.approx(base, rel=1e-12)
    r = run("expansion_coefficient=1.15e-05")
    assert r.exit_code == 2 and "0.001 to 100 µm/(m·K)" in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and "Traceback" not in r.output
    r = run("material_temperature=293.15")
    assert r.exit_code == 2 and "give 0 to 50 °C" in r.stderr
    kelvin = json.loads(run("material_temperature=293.15 K").stdout)
    celsius = json.loads(run("material_temperature=20").stdout)
    assert kelvin["uncertainty"] == pytest.approx(celsius["uncertainty"], rel=1e-12)
    assert kelvin["uncertainty_budget"]["inputs"]["material_temperature"]["value"] == 20.0


def test_a_job_file_takes_text_with_units(tmp_path):
    """A job file's ``[uncertainty]`` table: the same reading as the option."""
    import axiscal

    job = tmp_path / "job.toml"
    job.write_text('[uncertainty]\nexpansion_coefficient = "8 um/(m K)"\n'
                   'material_temperature = "21.5 degC"\n', "utf-8")
    by_job = axiscal.evaluate(ECMC, job=job).to_dict()["uncertainty"]
    plain = axiscal.evaluate(ECMC, uncertainty={"expansion_coefficient": 8.0,
                                                "material_temperature": 21.5})
    assert by_job == pytest.approx(plain.to_dict()["uncertainty"], rel=1e-12)


def test_plain_numbers_never_load_pint():
    """pint is imported only for a value with its unit (start-up, issue 30)."""
    import subprocess
    import sys

    code = ("import sys; from axiscal.standards.iso230_9 import resolve_linear; "
            "resolve_linear({'expansion_coefficient': 11.5, 'material_temperature': '20.5'}); "
            "print('pint' in sys.modules); resolve_linear({'material_temperature': '20.5 degC'});"
            " print('pint' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.split()
    assert out == ["False", "True"]


def test_the_documented_table_lists_every_input():
    """One row per input of each budget, with the unit a number is typed in and its default
    in that unit (α: 11.5 µm/(m·K), as shown), and the rule of the default."""
    rows = input_table()
    assert {(r["budget"], r["name"]) for r in rows} == (
        {("linear", f.name) for f in fields(LinearInputs)}
        | {("rotary", f.name) for f in fields(RotaryInputs)})
    alpha = next(r for r in rows if r["name"] == "expansion_coefficient")
    assert (alpha["unit"], alpha["default"]) == ("µm/(m·K)", "11.5")
    assert entered("x", alpha["default"], LINEAR_ENTRY["expansion_coefficient"]) == 11.5e-6
    assert all(r["rule"] and r["range"] for r in rows)


#: For each input of a squareness budget: (typed as the output shows it, the same with another
#: unit, its value in the budget).
SQUARENESS_TYPED = {
    "length_x": (0.6, "600 mm", 0.6), "length_y": (0.9, "900 mm", 0.9),
    "optics_accuracy": (1.5, "0.0015 mm/m", 1.5), "optics_k": (1.5, "1.5", 1.5),
    "square_error": (1.5, "0.0015 mm", 1.5), "square_length": (0.3, "300 mm", 0.3),
    "probe_accuracy": (1.5, "1500 nm", 1.5), "slope_fit_x": (0.4, "0.4 um/m", 0.4),
    "slope_fit_y": (0.4, "0.4 ppm", 0.4), "e_ve": (0.8, "0.0008 mm", 0.8),
    "reposition": (1.5, "1.5 um", 1.5), "ballbar_radius": (0.1, "100 mm", 0.1),
    "transducer_accuracy": (1.5, "1.5 um", 1.5), "laser_ppm": (1.5, "1.5 ppm", 1.5),
    "diagonal_d1": (-20.0, "-0.02 mm", -20.0), "diagonal_d2": (15.0, "15 um", 15.0),
    "diagonal_length_u": (30.0, "0.03 mm", 30.0), "k": (3.0, "3", 3.0),
}


@pytest.mark.parametrize("name", sorted(SQUARENESS_TYPED))
def test_squareness_input_typed_as_shown_gives_the_internal_U(name):
    """The ``[squareness_uncertainty]`` table: as the ISO 230-2 inputs, for the first method
    whose budget reads the input (``square_error`` also as the optical square's arcsec)."""
    from axiscal.standards.iso230_9_geometry import (
        METHOD_INPUTS,
        squareness_budget,
        squareness_budget_with_inputs,
    )
    from axiscal.standards.iso230_9_entry import SQUARENESS_ENTRY

    assert set(SQUARENESS_TYPED) == set(SQUARENESS_ENTRY)
    method = next(m for m in ("square", "diagonal", "reversal", "ballbar", "optics")
                  if name in METHOD_INPUTS[m])
    shown, text, inside = SQUARENESS_TYPED[name]
    others = {"diagonal_d1": 20.0} if name == "diagonal_length_u" else {}   # u_D0 ∝ D1 − D2
    internal = squareness_budget(method, **others, **{name: inside}).U("squareness")
    for typed in (shown, text):
        U = squareness_budget_with_inputs(method, {**others, name: typed}).U("squareness")
        assert U == pytest.approx(internal, rel=1e-12)
    assert abs(squareness_budget(method, **others).U("squareness") - internal) > 1e-9 * internal
    if name == "square_error":
        got = squareness_budget_with_inputs("optics", {name: "0.5 arcsec"}).U("squareness")
        assert got == pytest.approx(squareness_budget("optics", square_error=0.5).U(
            "squareness"), rel=1e-12)


def test_squareness_values_in_another_unit_are_refused():
    """A travel typed in mm (600 for 0.6 m) is refused naming the range; every default lies in
    its range."""
    import inspect

    from axiscal.errors import ConfigError
    from axiscal.standards.iso230_9_entry import SQUARENESS_ENTRY
    from axiscal.standards.iso230_9_geometry import squareness_budget, squareness_budget_with_inputs

    with pytest.raises(ConfigError, match=r"\[squareness_uncertainty\] length_x = 600 m is "
                                          r"implausible: give 0.01 to 20 m"):
        squareness_budget_with_inputs("diagonal", {"length_x": 600})
    with pytest.raises(ConfigError, match="ballbar_radius = 150 m is implausible"):
        squareness_budget_with_inputs("ballbar", {"ballbar_radius": 150})
    defaults = {n: p.default for n, p in inspect.signature(squareness_budget).parameters.items()
                if n != "method"}
    for name, rule in SQUARENESS_ENTRY.items():
        assert rule.low <= defaults[name] <= rule.high or (rule.zero and defaults[name] == 0)
    for rules, cls in ((LINEAR_ENTRY, LinearInputs), (ROTARY_ENTRY, RotaryInputs)):
        for f in fields(cls):
            if f.name in rules and f.default is not None:
                r = rules[f.name]
                assert r.low <= f.default / r.scale <= r.high, f.name


def test_the_documented_table_lists_every_squareness_input():
    from axiscal.standards.iso230_9_geometry import SQUARENESS_INPUTS, squareness_input_table

    rows = squareness_input_table()
    assert [r["name"] for r in rows] == list(SQUARENESS_INPUTS)
    assert all(r["unit"] is not None and r["default"] and r["range"] and r["rule"] for r in rows)


def test_text_of_any_kind_is_a_number_or_one_input_error():
    """Arbitrary text given for an input ends as a number in range or an InputError, never
    another exception (CONVENTIONS habit 9: parsers raise only AxiscalError)."""
    from hypothesis import given, settings
    from hypothesis import strategies as st

    rule = LINEAR_ENTRY["material_temperature"]
    units = st.sampled_from(["", " K", " degC", " um", " (", " **", " 1/K", " m*m", " °F"])

    @settings(max_examples=30, deadline=None)
    @given(st.one_of(st.text(max_size=30), st.builds(
        lambda x, u: f"{x!r}{u}", st.floats(allow_nan=True, allow_infinity=True), units)))
    def check(text):
        try:
            value = entered("material_temperature", text, rule)
        except InputError as e:
            assert "\n" not in str(e)
        else:
            assert 0.0 <= value <= 50.0

    check()
