"""The whole calibration job on LinuxCNC, driven by the plan's part program (issue 41).

As Renishaw CARTO's Capture → Explore → Compensate does by hand, in one run:

1. the ISO 230-2 plan's LinuxCNC program (:func:`axiscal.programs.write_program`) runs in AUTO mode
   on a headless LinuxCNC (:class:`~axiscal.instruments.linuxcnc_program.LinuxCNCProgramMachine`,
   the one-joint machine with a lagging drive);
2. the simulated laser records all the time: LinuxCNC's sampler gives the drive's position every
   servo period, and the laser reads where the simulated machine axis behind the drive is there,
   ``x + e(x, d)`` (its systematic deviation for the direction ``d`` it last moved, ISO 230-2
   §3.1; :meth:`~axiscal.machines.linear.LinearAxis.systematic_deviation`, on a rotary axis
   :meth:`~axiscal.machines.rotary.RotaryAxis.systematic_error`), with the axis's repeatability
   as one draw per approach and the instrument's noise on every reading; each test is dated the
   day it ran;
3. ``axiscal capture``'s stillness trigger (:func:`axiscal.procedures.capture.capture_test`)
   turns the record into the test's dataset;
4. :func:`axiscal.compensation.loop.run_compensation_loop` evaluates it (ISO 230-2), writes the
   LinuxCNC table, and this hook loads it as ``[JOINT_0] COMP_FILE`` and runs the program again.

:class:`ByProgram` is the loop's ``machine``; :func:`calibrate` runs the loop with it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from axiscal.errors import ConfigError

__all__ = ["ByProgram", "calibrate", "plan_rows"]


def plan_rows(plan):
    """The rows of ``plan.steps()`` (what :meth:`TestPlan.to_csv` writes, not via text), as
    the plan CSV's reader gives them (:class:`axiscal.procedures.capture.PlanRows`)."""
    from axiscal.procedures.capture import PlanRows

    s = plan.steps()
    kind = np.array([x.kind for x in s])
    return PlanRows(kind, np.array([x.position for x in s]), np.array([x.direction for x in s]),
                    np.array([x.run for x in s]), np.array([x.target_index for x in s]),
                    np.where(kind == "measure", plan.dwell, 0.0), plan.target_unit, plan.axis,
                    plan.axis_kind.value, "<plan>")


@dataclass
class ByProgram:
    """The loop's machine: each test is the plan's program run on LinuxCNC, recorded, captured.

    Attributes
    ----------
    dwell : float, s
        The program's dwell at each target (the plan's own is for a real machine's settling; the
        simulated drive settles in 0.1 s).
    feed : float, mm/min (deg/min on a rotary axis)
    progress : callable, optional
        ``progress(done, total)`` as LinuxCNC works through the program, over both runs (the
        program's lines: ``total`` is twice one program's).
    runs : list of dict
        What each run found: ``samples``, ``seconds`` (servo time), ``stops``, ``measurements``,
        ``gaps``, ``compensated``, ``travel`` (the lowest and highest position LinuxCNC's record
        holds, mm or deg).
    """

    dwell: float = 0.3
    feed: float = 12000.0
    #: Shortest stop capture takes, as a share of the dwell (``axiscal capture``'s default is
    #: 60 %). LinuxCNC times a dwell on the computer's clock while the sampler counts servo
    #: periods; on a loaded computer (load average 8 on 2 cores) the servo thread falls behind
    #: the clock, and a 0.3 s or 0.4 s dwell, less the drive's ~0.09 s of settling into the
    #: 1 µm (1″) window, has held fewer than 60 % (and fewer than 30 %) of its servo periods:
    #: rotary runs missed a stop in 4 of 6 attempts. A stop of 20 % (0.06 s at 0.3 s) is still
    #: hundreds of times longer than the drive's stillness at a reversal.
    stop_share = 0.2
    progress: object = None
    runs: list = field(default_factory=list)

    def measure(self, plan, axis, rng, measurement_sigma, controller_file):
        """Run ``plan``'s program through LinuxCNC on ``axis``; the captured dataset."""
        from dataclasses import replace

        from axiscal.instruments.linuxcnc_program import LinuxCNCProgramMachine
        from axiscal.procedures.capture import Record, capture_test
        from axiscal.programs import MachineOptions, write_program

        rotary = plan.target_unit == "deg"
        run_plan = replace(plan, dwell=self.dwell)
        letter = (plan.axis or ("C" if rotary else "X")).upper()
        if rotary:         # a turntable: the full turn and its overruns, no roll-over
            steps = [s.position for s in run_plan.steps()]
            lo, hi = (math.degrees(v) for v in axis.travel) if axis.travel else (
                min(steps), max(steps))
        else:
            lo, hi = (v * 1e3 for v in axis.travel)
        text = write_program(run_plan, "linuxcnc", MachineOptions(
            feed=self.feed, limits={letter: (lo, hi)}, trigger=self.stop_share * self.dwell))
        comp = None if controller_file is None else controller_file.text
        with LinuxCNCProgramMachine(axes={letter: (lo - 1.0, hi + 1.0)}, velocity=500.0,
                                    acceleration=20000.0, comp_file=comp,
                                    comp_file_type=1) as m:
            done = len(self.runs)

            def step(line, lines):
                if callable(self.progress):
                    self.progress(done * lines + line, 2 * lines)

            rec = m.run(text, timeout=self.timeout(run_plan), progress=step)
        si = math.pi / 180 if rotary else 1e-3            # deg or mm -> rad or m
        noise = measurement_sigma * (math.pi / 180 / 3600 if rotary else 1e-6)
        # the record from the program's first move to its last: the machine at rest before the
        # program starts (at home) and after it ends (at the safe start) is no stop of the plan,
        # and at a short stop share (stop_share) it could pass for one
        moving = np.flatnonzero(np.abs(np.diff(rec.positions[letter])) > 1e-4)   # 0.1 /s
        cut = slice(int(moving[0]), int(moving[-1]) + 2) if moving.size else slice(None)
        readings = self._laser(rec.positions[letter][cut] * si, axis, rng, noise, rotary) \
            - plan.targets[0] * si
        record = Record(rec.times[cut], readings, "rotary" if rotary else "linear",
                        sample_rate=1000.0)
        cap = capture_test(record, plan_rows(run_plan), window=1.0,
                           dwell=self.stop_share * self.dwell)
        x = rec.positions[letter]
        self.runs.append(dict(samples=int(rec.times.size), seconds=float(rec.times[-1]),
                              stops=len(cap.stops), measurements=len(cap.assigned),
                              gaps=rec.gaps, compensated=controller_file is not None,
                              travel=[float(x.min()), float(x.max())]))
        ds = cap.dataset
        import datetime

        return replace(ds, metadata=replace(ds.metadata, date=ds.metadata.date or str(
            datetime.date.today()), notes=ds.metadata.notes + (
            "; measured through a headless LinuxCNC running axiscal's part program"
            + (" with the compensation table loaded" if controller_file is not None else ""))))

    def timeout(self, plan) -> float:
        """How long a run may take, s: five times the program's dwells and its path at the
        feed, and a minute (a LinuxCNC that stalls is reported, not waited for)."""
        pos = np.array([s.position for s in plan.steps()])
        path = float(np.abs(np.diff(pos)).sum())
        return 60.0 + 5.0 * (plan.n_measurements * self.dwell + path / (self.feed / 60.0))

    @staticmethod
    def _laser(x, axis, rng, noise_si, rotary=False):
        """Where the simulated axis is (m, or rad on a rotary axis) at each sample of the drive's
        position ``x`` (m or rad): the systematic deviation for the direction it last moved, one
        repeatability draw per approach (from one stop to the next) and the instrument's noise
        (``noise_si``, m or rad) on each reading."""
        x = np.asarray(x, float)
        v = np.diff(x, prepend=x[0])
        # at rest below 0.1 mm/s (0.1 deg/s): the drive's settling tail
        moving = np.abs(v) > (math.radians(1e-4) if rotary else 1e-7)
        d = np.sign(np.where(moving, v, 0.0))
        idx = np.where(moving, np.arange(x.size), 0)
        np.maximum.accumulate(idx, out=idx)
        direction = np.where(d[idx] == 0, 1.0, d[idx])
        starts = moving & ~np.concatenate(([False], moving[:-1]))
        approach = np.cumsum(starts)
        rand = rng.normal(0.0, axis.repeatability_sigma, approach[-1] + 1)[approach] \
            if axis.repeatability_sigma > 0 else 0.0
        error = (axis.systematic_error(x, direction) if rotary
                 else axis.systematic_deviation(x, direction))
        reading = x + error + rand
        if noise_si > 0:
            reading = reading + rng.normal(0.0, noise_si, x.size)
        return reading


def calibrate(config: dict, seed: int = 1, *, dwell: float = 0.3, feed: float = 12000.0,
              progress=None, **overrides):
    """Plan → program → LinuxCNC → capture → ISO 230-2 → table → LinuxCNC → again.

    Returns ``(loop result, hook)``: :class:`~axiscal.compensation.loop.CompensationLoopResult`
    (``before``, ``after``, ``reduction``, the datasets) and the :class:`ByProgram` with what each
    run found. The controller is LinuxCNC (``COMP_FILE_TYPE`` 1, mm).
    """
    from axiscal.compensation.loop import run_compensation_loop

    if not (math.isfinite(dwell) and dwell >= 0.2):
        raise ConfigError(f"dwell {dwell!r} s: give 0.2 s or more (the drive settles in 0.1 s; "
                          "capture needs the rest)")
    hook = ByProgram(dwell=dwell, feed=feed, progress=progress)
    over = dict(overrides, controller="linuxcnc", options={"file_type": 1})
    r = run_compensation_loop(config, seed=seed, machine=hook, **over)
    return r, hook
