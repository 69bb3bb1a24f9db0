"""The plans of the golden part programs (tests/data/programs/), one per plan kind, with the
machine options each is written for. ``python tests/programs/program_cases.py`` rewrites the
golden files (review the diff by hand before committing: they are the reference)."""

from pathlib import Path

from axiscal.procedures.circular_plan import plan_circular, plan_squareness, plan_straightness
from axiscal.procedures.positioning import plan_linear, plan_rotary
from axiscal.programs import CONTROLLERS, FiveAxisProgram, MachineOptions, extension, write_program

GOLDEN = Path(__file__).resolve().parents[1] / "data" / "programs"


def cases():
    """kind -> (plan, MachineOptions)."""
    return {
        "linear": (plan_linear(200.0, n_targets=5, runs=2, dwell=2.0, overrun=3.0, axis="X"),
                   MachineOptions(feed=2000.0, limits={"X": (-10.0, 210.0)})),
        "rotary": (plan_rotary(360.0, step=45.0, runs=1, dwell=2.0, overrun=5.0, axis="C"),
                   MachineOptions(feed=3600.0, limits={"C": (-10.0, 370.0)})),
        # the sign convention: the machine counts Y the other way from the test's +
        "pilgrim": (plan_linear(100.0, n_targets=5, irregularity=0.0, runs=2, cycle="pilgrim",
                                dwell=2.0, overrun=2.0, axis="Y"),
                    MachineOptions(feed=1000.0, limits={"Y": (-105.0, 5.0)}, sign={"Y": -1})),
        "circular": (plan_circular(100.0, (200.0, 150.0), feed=1000.0),
                     MachineOptions(feed=1000.0, limits={"X": (0.0, 400.0), "Y": (0.0, 300.0)})),
        "squareness": (plan_squareness("XY", 300.0, (50.0, 50.0), points=4, dwell=2.0,
                                       overrun=2.0),
                       MachineOptions(feed=2000.0, limits={"X": (0.0, 400.0), "Y": (0.0, 400.0)},
                                      safe={"X": 45.0, "Y": 45.0})),
        # a vertical line in inch: Z held at X, Y; the program's positions and feed in inch
        "straightness": (plan_straightness("Z", 254.0, -254.0, at={"X": 127.0, "Y": 63.5},
                                           points=3, dwell=2.0, overrun=2.54),
                         MachineOptions(feed=508.0, units="inch",
                                        limits={"Z": (-300.0, 10.0)})),
        # ISO 230-3 on the shipped thermal twin (a VMC), shortened: 5 cycles P1-P2-P1 of X
        "thermal_linear": (_thermal("linear", run_h=300 / 3600, duration_h=420 / 3600),
                           MachineOptions(limits={"X": (0.0, 800.0)}, max_feed=30000.0)),
        # the speed programme's steps repeated through the run, then the stop
        "thermal_spindle": (_thermal("spindle", run_h=0.5, duration_h=0.75,
                                     programme=((0.25, 10.0), (1.0, 5.0))),
                            MachineOptions(spindle=12000.0)),
        # 1.5 h at rest: two dwells of 45 min (HEIDENHAIN's Cycle 9 takes at most an hour)
        "drift_check": (_thermal("drift-check", duration_h=1.5, position_mm=400.0),
                        MachineOptions(limits={"X": (0.0, 800.0)})),
        # the shipped A/C example's R-test set-up, pose by pose (its probing set-ups named)
        "fiveaxis": (_fiveaxis("ac"),
                     MachineOptions(feed=1000.0, safe={"Z": 250.0},
                                    limits={"X": (-300.0, 300.0), "Y": (-300.0, 300.0),
                                            "Z": (-200.0, 400.0), "A": (-120.0, 30.0),
                                            "C": (-360.0, 360.0)})),
    }


def _thermal(test, **options):
    from axiscal.api._thermal import plan_thermal

    return plan_thermal(test, **options)


def _fiveaxis(machine):
    from importlib import resources

    from axiscal.api import fiveaxis
    from axiscal.api.fiveaxis import EXAMPLES
    from axiscal.io._files import load_toml

    key = {"ac": "A/C", "bc": "B/C"}[machine]
    planned = fiveaxis.plan(load_toml(resources.files("axiscal.data").joinpath(EXAMPLES[key])))
    return FiveAxisProgram(planned.plan, planned.machine, dwell=1.0, clearance=10.0)


def dwell(kind: str):
    """The dwell every measurement of ``kind``'s plan holds, s (None: several, or none)."""
    plan, _ = cases()[kind]
    if kind == "thermal_linear":
        return (1 - plan.duty) * plan.interval / 2
    return getattr(plan, "dwell", None)


def golden_path(kind: str, controller: str) -> Path:
    return GOLDEN / f"{kind}.{controller}{extension(controller)}"


def program(kind: str, controller: str) -> str:
    plan, options = cases()[kind]
    return write_program(plan, controller, options, name=f"AXISCAL_{kind.upper()}")


if __name__ == "__main__":
    GOLDEN.mkdir(parents=True, exist_ok=True)
    for kind in cases():
        for c in CONTROLLERS:
            golden_path(kind, c).write_text(program(kind, c))
