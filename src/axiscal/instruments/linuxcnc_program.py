"""A live LinuxCNC running axiscal's part programs in AUTO mode, its axes sampled through HAL.

Issue 41, "Proven on LinuxCNC": :class:`LinuxCNCProgramMachine` is the one-joint driver's session
(:class:`~axiscal.instruments.linuxcnc_controller.LinuxCNC`: same start, lock, shutdown and
clean-up) on a simulated machine of several axes (``axiscal/data/linuxcnc/axiscal_program.ini``,
``axiscal_program_axis.ini``, ``axiscal_program.hal``, ``axiscal_program_drive.hal``):

* each joint's drive is a first-order lag (LinuxCNC's ``lowpass``: ``out += gain (in − out)``
  every servo period), its output fed back as ``joint.N.motor-pos-fb``: the position follows the command
  with a following error ``v τ`` at speed ``v`` (``τ ≈ period / gain``), as a servo does, and
  settles exponentially at a stop;
* LinuxCNC's ``sampler`` component records every joint's fed-back position and axiscal's count of
  the servo thread's runs (``axiscal-servo-clock``) every servo period into a FIFO that
  ``halsampler`` (LinuxCNC documentation, "halsampler") writes to a file: a continuous record in
  the servo thread's own time (one sample a run, however late a run comes on a loaded computer),
  checked for gaps by that count.

:meth:`LinuxCNCProgramMachine.run` loads a G-code file (``linuxcnc.command().program_open``),
starts sampling, runs it (``auto(AUTO_RUN)``), waits for the interpreter to go idle and the drive
to settle, and returns the :class:`ProgramRecord`. LinuxCNC documentation, "The LinuxCNC Python
module" (``mode(MODE_AUTO)``, ``program_open``, ``auto(AUTO_RUN, line)``, ``stat.interp_state``,
``error_channel``).
"""

from __future__ import annotations

import os
import signal
import subprocess
import tempfile
import time
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from string import Template

import numpy as np

from axiscal.errors import InputError, MeasurementError
from axiscal.instruments.linuxcnc_controller import LinuxCNC, _wait

__all__ = ["LinuxCNCProgramMachine", "ProgramRecord", "SERVO_PERIOD_S", "DRIVE_GAIN"]

#: The servo period of ``axiscal_program.ini`` (``[EMCMOT] SERVO_PERIOD``), s.
SERVO_PERIOD_S = 1e-3
#: ``lowpass.N.gain`` of the simulated drives: a time constant of −period / ln(1 − gain),
#: 9.5 ms.
DRIVE_GAIN = 0.1
#: Samples the sampler's FIFO holds (60 s of servo periods): halsampler may fall behind on a
#: loaded computer; a full FIFO loses samples, which the servo count would show.
FIFO_DEPTH = 60_000
#: Servo periods recorded after the program ends: the drive settles on the last position (ten
#: time constants), and the end stays shorter than a stop of a plan dwell of 0.2 s or more.
TAIL_PERIODS = 100


@dataclass(frozen=True, eq=False)
class ProgramRecord:
    """What the sampler recorded while LinuxCNC ran a program.

    Attributes
    ----------
    times : ndarray, s
        Servo-thread time from the first sample (runs × servo period).
    positions : dict of str to ndarray, mm or deg
        Each axis's fed-back position (``joint.N.motor-pos-fb``), machine units.
    servo_runs : ndarray
        The servo thread's count at each sample (consecutive: the record is continuous).
    """

    times: np.ndarray
    positions: dict
    servo_runs: np.ndarray

    @property
    def gaps(self) -> int:
        """Servo runs missing from the record (0 for a continuous record)."""
        d = np.diff(self.servo_runs)
        return int(np.sum(d[d > 1] - 1)) if d.size else 0


@dataclass
class LinuxCNCProgramMachine(LinuxCNC):
    """One headless LinuxCNC session on a simulated machine with ``axes`` (a context manager).

    Parameters
    ----------
    axes : dict of str to (float, float)
        Axis letter to its limits (mm, or deg for A, B, C: angular joints).
    velocity, acceleration : float, units per s and per s²
    comp_file, comp_file_type
        A ``COMP_FILE`` (text) for joint 0, the first of ``axes``, and its type (LinuxCNC
        documentation, "INI Configuration", ``[JOINT_n] COMP_FILE``).
    ferror : float, optional, machine units
        ``FERROR`` and ``MIN_FERROR`` of every joint (default twice the drive's lag at full speed,
        ``2 velocity τ``).
    """

    limits: tuple = (0.0, 0.0)
    axes: dict = field(default_factory=dict)
    velocity: float = 200.0
    acceleration: float = 5000.0
    ferror: float | None = None

    def __post_init__(self) -> None:
        super().__post_init__()
        if not self.axes or any(a not in "XYZABC" for a in self.axes):
            raise InputError(f"axes {list(self.axes)}: give distinct letters of XYZABC")

    def _write_config(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="axiscal-linuxcnc-"))
        os.chmod(self.folder, 0o1777)
        data = resources.files("axiscal.data") / "linuxcnc"
        axis_t = Template((data / "axiscal_program_axis.ini").read_text())
        drive_t = Template((data / "axiscal_program_drive.hal").read_text())
        blocks, drives = [], []
        tau = -SERVO_PERIOD_S / np.log(1 - DRIVE_GAIN)
        ferror = 2 * self.velocity * tau if self.ferror is None else self.ferror
        comp = ""
        if self.comp_file is not None:       # the first axis's joint (joint 0)
            (self.folder / "joint0.comp").write_text(self.comp_file)
            comp = f"COMP_FILE = joint0.comp\nCOMP_FILE_TYPE = {self.comp_file_type}"
        for j, (a, (lo, hi)) in enumerate(self.axes.items()):
            blocks.append(axis_t.substitute(comp_lines=comp if j == 0 else "",
                letter=a, joint=j, min_limit=repr(float(lo)), max_limit=repr(float(hi)),
                velocity=repr(float(self.velocity)), acceleration=repr(float(self.acceleration)),
                joint_type="ANGULAR" if a in "ABC" else "LINEAR", ferror=repr(float(ferror))))
            drives.append(drive_t.substitute(joint=j, gain=repr(DRIVE_GAIN)))
        n = len(self.axes)
        coords = "".join(self.axes)
        self.ini_text = Template((data / "axiscal_program.ini").read_text()).substitute(
            coordinates=coords, joints=n, velocity=repr(float(self.velocity)),
            axes="\n".join(blocks))
        (self.folder / "config.ini").write_text(self.ini_text)
        (self.folder / "axiscal_program.hal").write_text(Template(
            (data / "axiscal_program.hal").read_text()).substitute(
            joints=n, depth=FIFO_DEPTH, cfg="f" * (n + 1), clock_pin=n, drives="\n".join(drives)))
        (self.folder / "tool.tbl").write_text("")

    def _connect(self) -> None:
        comp = self._open_channels("axiscal-program")
        self._errors = self._channels.new("linuxcnc.error_channel")
        self._ready(comp, [])
        self._switch_on_and_home(len(self.axes))

    def run(self, program: str, timeout: float = 120.0, progress=None) -> ProgramRecord:
        """Run the G-code ``program`` (text) in AUTO mode and return the sampled record.

        ``progress(line, lines)``, if given, is called as LinuxCNC works through the program
        (``stat.motion_line``: the line whose motion is executing)."""
        import linuxcnc

        path = self.folder / f"program{int(time.monotonic_ns())}.ngc"
        path.write_text(program)
        c = self._cmd
        c.mode(linuxcnc.MODE_AUTO)
        c.wait_complete()
        c.program_open(str(path))
        c.wait_complete()
        out = self.folder / f"{path.stem}.samples"
        sampler = subprocess.Popen(["halsampler", "-t", str(out)], env=self._env(),
                                   stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
        try:
            self._halcmd("setp", "sampler.0.enable", "1")
            c.auto(linuxcnc.AUTO_RUN, 0)
            t0 = time.monotonic()
            self._wait_program(timeout, progress, program.count("\n"))
            self.last_run_s = time.monotonic() - t0
            self.wait_periods(TAIL_PERIODS)
            self._halcmd("setp", "sampler.0.enable", "0")
            _wait(lambda: self._halcmd("getp", "sampler.0.curr-depth").strip() == "0", 30.0,
                  "halsampler to empty the sampler's FIFO")
            time.sleep(0.1)        # halsampler's last read and write
        finally:
            sampler.send_signal(signal.SIGINT)
            try:
                sampler.wait(5)
            except subprocess.TimeoutExpired:
                sampler.kill()
                sampler.wait(5)
        c.mode(linuxcnc.MODE_MDI)
        c.wait_complete()
        return self._parse(out)

    def _wait_program(self, timeout: float, progress=None, lines: int = 0) -> None:
        import linuxcnc

        s = self._stat
        shown = [-1]

        def started():
            s.poll()
            return s.interp_state != linuxcnc.INTERP_IDLE

        def done():
            err = self._errors.poll()
            if err:
                raise MeasurementError(f"LinuxCNC stopped the program: {err[1]}")
            s.poll()
            if progress is not None and s.motion_line > shown[0]:
                shown[0] = s.motion_line
                progress(min(s.motion_line, lines), lines)
            return s.interp_state == linuxcnc.INTERP_IDLE and s.queue == 0

        _wait(started, 10.0, "LinuxCNC to start the program", poll=0.002)
        _wait(done, timeout, "LinuxCNC to finish the program", poll=0.01)

    def _halcmd(self, *args: str) -> str:
        return subprocess.run(["halcmd", *args], env=self._env(), check=True,
                              capture_output=True, text=True).stdout

    def _parse(self, path: Path) -> ProgramRecord:
        lines = path.read_text().splitlines()
        # halsampler says "overrun" where the sampler's count jumps: on its first line when the
        # FIFO's count goes on from an earlier program's samples (nothing lost), anywhere else
        # when samples were lost
        if lines and lines[0].strip() == "overrun":
            lines = lines[1:]
        if any(line.strip() == "overrun" for line in lines):
            raise MeasurementError("halsampler's record skips samples (the sampler's FIFO overran)")
        a = np.loadtxt(lines, ndmin=2)
        if a.shape[0] == 0:
            raise MeasurementError("halsampler recorded nothing")
        tags, values = a[:, 0], a[:, 1:]
        if np.any(np.diff(tags) != 1):
            raise MeasurementError("halsampler's record skips samples (its FIFO overran)")
        runs = np.rint(values[:, -1])
        times = (runs - runs[0]) * SERVO_PERIOD_S
        pos = {ax: values[:, j].copy() for j, ax in enumerate(self.axes)}
        return ProgramRecord(times, pos, runs)

    def move(self, *args, **kwargs):
        raise MeasurementError("LinuxCNCProgramMachine runs programs: use run")
