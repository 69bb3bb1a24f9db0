"""A live LinuxCNC controller running a simulated one-joint machine headless (issue 32).

The real driver beside the simulated machines: :class:`LinuxCNC` starts the controller LinuxCNC
ships (Debian ``linuxcnc-uspace`` 2.9) on a configuration axiscal writes from its package data
(``axiscal/data/linuxcnc/axiscal_sim.ini`` and ``axiscal_sim.hal``), homes it, moves it by MDI
and reads, through a HAL component of its own (``axiscal-laser``), the joint's
``pos-cmd`` (what the interpreter commanded) and ``motor-pos-cmd`` (what reaches the drive, the
compensation trim included). :class:`LinuxCNCAxis` puts a simulated machine axis behind the drive:
the axis's errors act on ``motor-pos-cmd``, and the simulated laser reads the result, so the
procedures drive the controller through the same interface as a simulated axis
(``name``, ``travel``, ``repeatability_sigma``, ``check_in_travel``, ``move``).

How LinuxCNC is run, as LinuxCNC documents and as tried on Debian 12 (issue 32's notes):

* as root it needs ``RTAPI_UID`` (an unprivileged uid, 65534 here) and ``RTAPI_FIFO_PATH``,
  the path of rtapi_app's socket, in a folder that uid can write (mode 1777);
* ``[DISPLAY] DISPLAY = dummy`` and ``linuxcnc -r config.ini`` with stdin a pipe: the dummy display
  waits for a line; closing stdin shuts LinuxCNC down (``/usr/bin/linuxcnc``, "dummy display just
  waits for <ENTER>", then its ``Cleanup``);
* the first ``linuxcnc.stat().poll()`` waits until the dummy display has started (polling earlier
  can break that process's NML connection for good);
* one LinuxCNC per computer: fixed shared-memory keys (the NML buffers 1001…1005 of
  ``linuxcnc.nml``, HAL's ``0x48414c32``, RTAPI's ``0x48484c34``) and ``/tmp/linuxcnc.lock``.
  axiscal takes an ``fcntl`` lock (:data:`SESSION_LOCK`) for the whole session, so two test
  processes (pytest-xdist) never run two at once; the lock dies with its holder, and the next
  session first removes what a killed one left (:func:`clean_leftovers`): every process carrying
  axiscal's marker in its environment, the lock file, and those segments when nothing is attached;
* a HAL component created in this process must ``exit()`` before LinuxCNC shuts down.

When LinuxCNC reports a move done, the joint's pins may not have reached the end yet: the planner
is done (``update_status``: in position once ``tpIsDone``) while its last points still pass through
the cubic interpolator on their way to ``joint.N.pos-cmd`` (``get_pos_cmds``: ``cubicAddPoint``,
``cubicInterpolate``; LinuxCNC ``src/emc/motion/control.c``). On a quiet computer the servo thread
has run many periods by the time the report arrives; in uspace without a realtime kernel its
thread is an ordinary one (scheduling class TS, tried), and on a loaded computer it runs late: a
reading taken at the report could be short of the target (tried at load average 9: a turntable
target read 0.00058° short, E after compensation 2.06″ instead of 0.89″), or hold ``pos-cmd`` of
one run and ``motor-pos-cmd`` of the run before (the thread can be preempted between writing
them). :meth:`LinuxCNC.read` therefore waits for :data:`SETTLE_PERIODS` runs of the servo
thread, counted by the thread itself (HAL ``integ`` as ``axiscal-servo-clock`` in
``axiscal_sim.hal``), never by the wall clock: the same moves read the same pins at any load.

With a ``COMP_FILE``, ``motor-pos-cmd = pos-cmd + trim`` (LinuxCNC ``src/emc/motion/control.c``,
``compute_screw_comp``): the forward trim while the joint moves +, the reverse trim while it moves
−, the last value held when stopped; :attr:`LinuxCNCAxis.log` keeps both pins at every reading.
"""

from __future__ import annotations

import fcntl
import os
import shutil
import signal
import subprocess
import tempfile
import time
import warnings
from contextlib import contextmanager
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path
from string import Template

import numpy as np

from axiscal.errors import InputError, MeasurementError
from axiscal.machines.seen_through import AxisSeenThrough

__all__ = ["LinuxCNC", "LinuxCNCAxis", "LinuxCNCRecovery", "Reading", "platform_reason", "unavailable_reason",
           "clean_leftovers", "running_processes", "leftover_segments", "session_lock", "SESSION_LOCK",
           "LINUXCNC_LOCK", "SETTLE_PERIODS"]

#: axiscal's own lock: one LinuxCNC session at a time on this computer (held with fcntl).
SESSION_LOCK = Path(tempfile.gettempdir()) / "axiscal-linuxcnc.session.lock"
#: LinuxCNC's lock file (``/usr/bin/linuxcnc``, ``LOCKFILE``).
LINUXCNC_LOCK = Path("/tmp/linuxcnc.lock")
#: Environment marker on every process axiscal starts (how leftovers are told from others').
MARKER = "AXISCAL_LINUXCNC_SESSION"
#: Shared-memory keys LinuxCNC creates: NML buffers (linuxcnc.nml), HAL ("HAL2"), RTAPI.
SHM_KEYS = (1001, 1002, 1003, 1004, 1005, 0x48414C32, 0x48484C34)
#: Process names of a LinuxCNC (the script, its servers, the realtime app, halcmd).
NAMES = ("linuxcnc", "linuxcncsvr", "milltask", "io", "rtapi_app", "halcmd", "realtime")
#: An unprivileged uid rtapi_app runs as when started by root.
RTAPI_UID = 65534
#: Table position unit (mm, or deg for a rotary joint) per machine unit.
_UNITS_MM = {"mm": 1.0, "inch": 25.4, "deg": 1.0}
#: SI (m or rad) per table position unit.
_SI = {"mm": 1e-3, "inch": 1e-3, "deg": np.pi / 180.0}
#: The final approach of :meth:`LinuxCNC.move` with ``approach``: distance (mm) and feed
#: (mm/min): 1 mm/s, a step of at most 1 µm per 1 ms servo period.
CREEP, CREEP_FEED = 0.01, 60.0
#: Runs of the servo thread between LinuxCNC reporting a move done and the reading. The joint
#: gets, each run, the way point (x0 + 4 x1 + x2) / 6 of the cubic interpolator's last four
#: planner points (LinuxCNC ``src/emc/motion/cubic.c``, ``cubicAddPoint``, ``wayPoint``), so the
#: planner's final point is on ``joint.N.pos-cmd`` 3 runs after the planner is done (tried: a
#: reading taken earlier was short by a sixth of the last step, 0.5 µm / 6); 5 leaves the trim's
#: rate limit (``compute_screw_comp``) its run and costs 5 ms a reading on a quiet computer.
SETTLE_PERIODS = 5
#: The HAL signal of ``axiscal-servo-clock.out``: the servo thread's runs so far.
SERVO_CLOCK = "axiscal-servo-clock"


def platform_reason() -> str | None:
    """Why this machine cannot host LinuxCNC at all (not Debian, not root), or None: what no
    install step can change. A Debian machine run as root that lacks the package is a missing
    install (``make linuxcnc``), said by :func:`unavailable_reason`."""
    if not Path("/etc/debian_version").exists():
        return "not Debian: axiscal runs LinuxCNC from Debian's linuxcnc-uspace package"
    if os.geteuid() != 0:
        return ("not root: axiscal starts LinuxCNC as root with RTAPI_UID (the way it was "
                "tried); run as root")
    return None


def unavailable_reason() -> str | None:
    """Why LinuxCNC cannot run here (one sentence), or None when it can."""
    if (why := platform_reason()) is not None:
        return why
    if shutil.which("linuxcnc") is None:
        return "linuxcnc-uspace is not installed: run 'make linuxcnc'"
    try:
        import hal  # noqa: F401
        import linuxcnc  # noqa: F401
    except ImportError as exc:
        return f"LinuxCNC's Python modules do not import ({exc}): run 'make linuxcnc'"
    return None


@contextmanager
def session_lock():
    """Hold axiscal's session lock (no LinuxCNC session starts meanwhile): to look at or clean
    what is left without racing another process's session."""
    with open(SESSION_LOCK, "w") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(f, fcntl.LOCK_UN)


def running_processes(marked_only: bool = True) -> list[int]:
    """Live (not zombie) LinuxCNC processes: those axiscal started, or any by name."""
    out = []
    for d in Path("/proc").iterdir():
        if not d.name.isdigit() or int(d.name) == os.getpid():
            continue
        try:
            stat = (d / "stat").read_text()
            if stat.rsplit(")", 1)[1].split()[0] == "Z":
                continue
            comm = stat[stat.index("(") + 1:stat.rindex(")")]
            env = (d / "environ").read_bytes() if marked_only else b""
        except (OSError, ValueError, IndexError):
            continue
        if (MARKER.encode() + b"=") in env or (not marked_only and comm in NAMES):
            out.append(int(d.name))
    return out


def process_states() -> str:
    """What LinuxCNC's processes are doing, for an error that says LinuxCNC stopped answering:
    ``name state wchan`` of each (``/proc/PID/stat`` state R running, S sleeping, D waiting on
    the disk; ``/proc/PID/wchan`` the kernel function it sleeps in)."""
    out = []
    for pid in running_processes(marked_only=False):
        try:
            stat = Path(f"/proc/{pid}/stat").read_text()
            wchan = Path(f"/proc/{pid}/wchan").read_text().strip() or "-"
        except OSError:
            continue
        comm = stat[stat.index("(") + 1:stat.rindex(")")]
        out.append(f"{comm} {stat.rsplit(')', 1)[1].split()[0]} {wchan}")
    return "; ".join(sorted(out)) or "none running"


def leftover_segments() -> list[int]:
    """LinuxCNC's shared-memory keys still present (``ipcs -m``)."""
    text = subprocess.run(["ipcs", "-m"], capture_output=True, text=True).stdout
    keys = []
    for line in text.splitlines():
        cells = line.split()
        if cells and cells[0].startswith("0x") and int(cells[0], 16) in SHM_KEYS:
            keys.append(int(cells[0], 16))
    return keys


def clean_leftovers() -> list[str]:
    """Remove what a killed session left: marked processes, the lock file, unattached segments.

    Returns what was removed (for the caller to say). Refuses, with :class:`MeasurementError`,
    when a LinuxCNC that axiscal did not start is running: one LinuxCNC per computer. Call it
    holding the session lock (:func:`session_lock`, or inside a session).
    """
    done = []
    for pid in running_processes():
        try:
            os.kill(pid, signal.SIGKILL)
            done.append(f"process {pid}")
        except ProcessLookupError:
            pass
    _wait(lambda: not running_processes(), 5.0, "leftover LinuxCNC processes to end")
    others = running_processes(marked_only=False)
    if others:
        raise MeasurementError(f"another LinuxCNC is running (pids {others}); LinuxCNC runs "
                               "once per computer: stop it first")
    for key in leftover_segments():
        if subprocess.run(["ipcrm", "-M", hex(key)], capture_output=True).returncode == 0:
            done.append(f"shared memory {hex(key)}")
    if LINUXCNC_LOCK.exists():
        LINUXCNC_LOCK.unlink()
        done.append(str(LINUXCNC_LOCK))
    return done


class LinuxCNCRecovery(UserWarning):
    """A line LinuxCNC lost, sent again, or its session started again (:meth:`LinuxCNC.mdi`)."""


@dataclass(frozen=True)
class Reading:
    """The joint's two HAL positions after a move, machine units.

    ``trim = motor_pos_cmd − pos_cmd`` is what the compensation added.
    """

    pos_cmd: float
    motor_pos_cmd: float

    @property
    def trim(self) -> float:
        """The compensation LinuxCNC applied, machine units."""
        return self.motor_pos_cmd - self.pos_cmd


@dataclass
class LinuxCNC:
    """One headless LinuxCNC session on a simulated one-joint machine (a context manager).

    Parameters
    ----------
    limits : (float, float), machine units
        The joint's ``MIN_LIMIT`` and ``MAX_LIMIT``.
    units : str
        ``[TRAJ] LINEAR_UNITS``: ``mm`` or ``inch``; ``deg`` for a rotary joint (``[JOINT_0]
        TYPE = ANGULAR``, ``[TRAJ] ANGULAR_UNITS = degree``).
    comp_file : str, optional
        Text of a ``COMP_FILE``; written beside the INI as ``[JOINT_0] COMP_FILE = x.comp``.
    comp_file_type : int
        ``[JOINT_0] COMP_FILE_TYPE`` (0 or 1).
    letter : str
        The axis letter (``[TRAJ] COORDINATES``).
    velocity, acceleration : float, machine units per s and per s²
        The joint's limits: high, so a test of hundreds of moves takes seconds (the simulated
        drive follows any command).
    take_lock : bool
        False only when the caller already holds :func:`session_lock` (a test that kills the
        session's process on purpose).
    """

    limits: tuple
    units: str = "mm"
    comp_file: str | None = None
    comp_file_type: int = 1
    letter: str = "X"
    velocity: float = 10000.0
    acceleration: float = 1.0e6
    ready_timeout: float = 30.0
    take_lock: bool = True
    folder: Path | None = field(default=None, init=False)
    ini_text: str = field(default="", init=False)
    _proc: object = field(default=None, init=False, repr=False)
    _lock: object = field(default=None, init=False, repr=False)
    _comp: object = field(default=None, init=False, repr=False)
    _channels: object = field(default=None, init=False, repr=False)
    #: MDI lines sent a second time, with what was seen (:meth:`mdi`).
    recoveries: list = field(default_factory=list, init=False, repr=False)
    #: Whether a session whose task process ended may be started again to go on (False where
    #: the session holds state a new start would lose: a thermal model's history).
    restartable = True
    _servo_seen: object = field(default=None, init=False, repr=False)

    def __post_init__(self) -> None:
        if self.units not in _UNITS_MM:
            raise InputError(f"LinuxCNC units {self.units!r}: use mm or inch (linear) or deg "
                             "(rotary)")
        if self.comp_file_type not in (0, 1):
            raise InputError(f"COMP_FILE_TYPE = {self.comp_file_type!r}; LinuxCNC knows 0 and 1")

    # -- session -------------------------------------------------------------------------------
    def __enter__(self) -> "LinuxCNC":
        why = unavailable_reason()
        if why:
            raise MeasurementError(f"LinuxCNC cannot run here: {why}")
        self._lock = open(SESSION_LOCK, "w")
        if self.take_lock:
            fcntl.flock(self._lock, fcntl.LOCK_EX)      # waits for another session to end
        try:
            clean_leftovers()
            self._write_config()
            self._start()
            self._connect()
        except BaseException:
            self.close()
            raise
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        """Shut LinuxCNC down (stdin closed; killed if it does not end) and clean up.

        The HAL component and the child process that holds the session's channels
        (:mod:`axiscal.instruments._nml`) end first, while LinuxCNC's shared memory still
        exists."""
        try:
            if self._comp is not None:
                try:
                    self._comp.exit()
                except MeasurementError:
                    pass                     # the channels' process has ended already
                self._comp = None
            self._release_channels()
            p = self._proc
            if p is not None and p.poll() is None:
                p.stdin.close()
                try:
                    p.wait(15)
                except subprocess.TimeoutExpired:
                    os.killpg(p.pid, signal.SIGKILL)
                    p.wait(5)
            self._proc = None
            if self._lock is not None:
                clean_leftovers()
        finally:
            if self.folder is not None:
                shutil.rmtree(self.folder, ignore_errors=True)
                self.folder = None
            if self._lock is not None:
                if self.take_lock:
                    fcntl.flock(self._lock, fcntl.LOCK_UN)
                self._lock.close()
                self._lock = None

    def _write_config(self) -> None:
        self.folder = Path(tempfile.mkdtemp(prefix="axiscal-linuxcnc-"))
        os.chmod(self.folder, 0o1777)                  # rtapi_app (RTAPI_UID) makes its socket here
        data = resources.files("axiscal.data") / "linuxcnc"
        comp = ""
        if self.comp_file is not None:
            (self.folder / "x.comp").write_text(self.comp_file)
            comp = f"COMP_FILE = x.comp\nCOMP_FILE_TYPE = {self.comp_file_type}"
        self.ini_text = Template((data / "axiscal_sim.ini").read_text()).substitute(
            letter=self.letter, velocity=repr(float(self.velocity)),
            acceleration=repr(float(self.acceleration)), min_limit=repr(float(self.limits[0])),
            max_limit=repr(float(self.limits[1])), comp_lines=comp,
            joint_type="ANGULAR" if self.units == "deg" else "LINEAR",
            linear_units="mm" if self.units == "deg" else self.units)
        (self.folder / "config.ini").write_text(self.ini_text)
        (self.folder / "axiscal_sim.hal").write_text((data / "axiscal_sim.hal").read_text())
        (self.folder / "axiscal_approach.ngc").write_text(Template(
            (data / "axiscal_approach.ngc").read_text()).substitute(letter=self.letter))
        (self.folder / "tool.tbl").write_text("")

    def _env(self) -> dict:
        return dict(os.environ, RTAPI_UID=str(RTAPI_UID), **{MARKER: str(os.getpid())},
                    RTAPI_FIFO_PATH=str(self.folder / "rtapi_fifo"))

    def _start(self) -> None:
        log = open(self.folder / "linuxcnc.log", "w")
        self._proc = subprocess.Popen(["linuxcnc", "-r", "config.ini"], cwd=self.folder,
                                      stdin=subprocess.PIPE, stdout=log, stderr=subprocess.STDOUT,
                                      env=self._env(), start_new_session=True)
        log.close()

        def ready():
            if self._proc.poll() is not None:
                raise MeasurementError(f"LinuxCNC ended while starting: {self._log_tail()}")
            return "DUMMY DISPLAY" in (self.folder / "linuxcnc.log").read_text(errors="replace")

        _wait(ready, self.ready_timeout, "LinuxCNC to start")

    def _release_channels(self) -> None:
        """End the child process that holds the session's channels (:mod:`._nml`)."""
        for n in ("_stat", "_cmd", "_errors"):
            setattr(self, n, None)
        if self._channels is not None:
            self._channels.close()
            self._channels = None

    def _open_channels(self, component: str):
        """Status and command channels and a HAL component named ``component``, all in a child
        process of this session's own (:mod:`axiscal.instruments._nml`: the NML library's
        process-wide state made a second session in one process crash)."""
        from axiscal.instruments._nml import ChannelProcess

        # the parent's environment without the session marker: the child is not LinuxCNC, and
        # clean_leftovers must not take it for one
        self._channels = ChannelProcess({k: v for k, v in os.environ.items() if k != MARKER})
        self._stat = self._channels.new("linuxcnc.stat")
        self._cmd = self._channels.new("linuxcnc.command")
        return self._channels.new("hal.component", component)

    def _log_tail(self, n: int = 3) -> str:
        try:
            text = (self.folder / "linuxcnc.log").read_text(errors="replace")
        except (OSError, TypeError):
            return "no log"
        return " | ".join(text.strip().splitlines()[-n:]) or "no output"

    def _connect(self) -> None:
        import hal

        comp = self._open_channels("axiscal-laser")
        for pin in ("motor-pos-cmd", "pos-cmd"):
            comp.newpin(pin, hal.HAL_FLOAT, hal.HAL_IN)
        self._ready(comp, [("j0-motor-pos-cmd", "axiscal-laser.motor-pos-cmd"),
                           ("j0-pos-cmd", "axiscal-laser.pos-cmd")])
        self._switch_on_and_home(1)

    def _ready(self, comp, nets: list) -> None:
        """Give ``comp`` (a ``hal.component`` with its pins) the servo clock's pin, make it ready
        and connect the ``nets`` (``halcmd net`` arguments)."""
        import hal

        comp.newpin("servo-clock", hal.HAL_FLOAT, hal.HAL_IN)
        comp.ready()
        self._comp = comp
        for net in [*nets, (SERVO_CLOCK, f"{comp.getprefix()}.servo-clock")]:
            subprocess.run(["halcmd", "net", *net], env=self._env(), check=True,
                           capture_output=True)

    def _switch_on_and_home(self, joints: int) -> None:
        """Out of e-stop, machine on, every joint homed in joint mode, then MDI (the order
        LinuxCNC's Python interface, ``linuxcnc.command``, takes them in)."""
        import linuxcnc

        c = self._cmd
        c.state(linuxcnc.STATE_ESTOP_RESET)
        c.state(linuxcnc.STATE_ON)
        c.wait_complete()
        c.mode(linuxcnc.MODE_MANUAL)
        c.wait_complete()
        c.teleop_enable(0)
        c.wait_complete()
        c.home(-1)

        def homed():
            self._stat.poll()
            return all(self._stat.homed[:joints])

        _wait(homed, 10.0, "LinuxCNC to home the joint" if joints == 1 else
              f"LinuxCNC to home the {joints} joints")

        def at_rest():                 # the homing's final move done: an MDI line sent during
            self._stat.poll()          # it can be lost (seen on the five-axis configuration)
            return bool(self._stat.inpos)

        _wait(at_rest, 10.0, "the joints to come to rest after homing")
        c.mode(linuxcnc.MODE_MDI)
        c.wait_complete()

    # -- use -----------------------------------------------------------------------------------
    def mdi(self, line: str, timeout: float = 30.0, stall: float = 3.0) -> None:
        """Run one MDI line and wait until it is done.

        LinuxCNC 2.9's task can lose track of an MDI line in three ways, each seen on loaded
        computers (about one line in several thousand of a ``make test``), each handled here:

        * ``wait_complete`` misses the end: the task took the line (``echo_serial_number`` at the
          command's ``serial``), the interpreter is idle and the task done: the line is done;
        * the line never reaches the task (not taken, the interpreter idle): it is sent again;
        * the interpreter stays "reading" an O-word subroutine call while nothing moves: the
          commanded position stands still while the servo thread runs (50 periods or more between
          two looks), for ``stall`` seconds, whatever the task, the motion queue and the reported
          speed say (seen: task DONE and queue empty; and a queue of 2 segments "moving" at the
          creep feed that never arrived). LinuxCNC's task (``emctaskmain.cc``,
          ``mdi_execute_hook``) ends an MDI call only when ``interp_list`` is empty, the task and
          the motion queue are done and its ``mdi_execute_wait``/``mdi_execute_next`` flags are
          clear, in one cycle; the state seen for 30 to 60 s on CI runs (interpreter READING,
          task DONE, also on the three-joint configuration with external offsets) is one where
          that no longer happens. The call is aborted (which clears the motion queue and returns
          the interpreter to idle, ``mdi_execute_abort``), MDI mode set again, and the line sent
          again.

        Sending a line again is safe: every line axiscal sends is absolute (G90 moves, dwells,
        the approach subroutines), so running it twice leaves the machine where once does. A line
        is sent at most twice; each recovery is kept in :attr:`recoveries` (line, what was seen).
        A line still running after ``timeout`` is an error that names the interpreter's, the
        task's and the motion's states.
        """
        import linuxcnc

        for attempt in range(2):
            self._cmd.mdi(line)
            serial = self._cmd.serial
            seen = self._await_mdi(serial, timeout, stall)
            if seen == "done":
                break
            if seen == "running":
                self._mdi_failed(line, f"{timeout:g} s")
            self.recoveries.append((line, seen))
            if not self._task_alive():
                log = self._log_tail(6)
                if not self.restartable or attempt:
                    raise MeasurementError(f"LinuxCNC's task process (milltask) ended while "
                                           f"running {line!r}; LinuxCNC's log ends: {log}")
                warnings.warn(f"LinuxCNC's task process (milltask) ended while running {line!r} "
                              f"(log: {log}); LinuxCNC started again and the line sent again",
                              LinuxCNCRecovery, stacklevel=2)
                self.recoveries[-1] = (line, "task ended")
                self._restart()
                continue
            warnings.warn(f"LinuxCNC: MDI line {line!r} {seen} (processes: {process_states()}); "
                          + ("aborted and sent again" if seen == "stalled" else "sent again"),
                          LinuxCNCRecovery, stacklevel=2)
            if seen == "stalled":
                self._cmd.abort()
                self._cmd.wait_complete(5.0)
                try:
                    _wait(lambda: (self._stat.poll(), self._stat.interp_state)[1]
                          == linuxcnc.INTERP_IDLE, 10.0, "LinuxCNC's interpreter to stop")
                except MeasurementError:
                    self._mdi_failed(line, f"{timeout:g} s, and did not stop when aborted")
                self._cmd.mode(linuxcnc.MODE_MDI)
                self._cmd.wait_complete(5.0)
        else:
            self._mdi_failed(line, f"{timeout:g} s, sent twice ({self.recoveries[-1][1]})")
        self._stat.poll()
        if self._stat.state != 1:        # linuxcnc.RCS_DONE
            raise MeasurementError(f"LinuxCNC refused {line!r} (state {self._stat.state})")

    def _await_mdi(self, serial: int, timeout: float, stall: float) -> str:
        """Wait for the MDI line ``serial``: "done", "lost" (never taken, the interpreter idle
        for ``stall`` s), "stalled" (taken, the interpreter not idle and the commanded position
        still while the servo thread runs, for ``stall`` s) or "running" (still going after
        ``timeout``); :meth:`mdi`."""
        import linuxcnc

        s = self._stat
        end = time.monotonic() + timeout
        since: dict[str, float] = {}
        last, runs = None, self._servo_runs_now()
        while True:
            if self._cmd.wait_complete(0.5) != -1:
                return "done"
            s.poll()
            now = time.monotonic()
            taken = s.echo_serial_number >= serial
            idle = s.interp_state == linuxcnc.INTERP_IDLE
            if taken and idle and s.state == 1:                  # linuxcnc.RCS_DONE
                return "done"                   # the task took the line and is done
            position, runs_before, runs = tuple(s.position), runs, self._servo_runs_now()
            ran = None if runs is None or runs_before is None else runs - runs_before
            self._servo_seen = ran
            # the controller runs (the servo thread did 50 periods or more since the last look)
            # and nothing moves: stalled, whatever the task and the motion queue say
            still = position == last and (ran is None or ran >= 50)
            last = position
            states = {"lost": idle and not taken, "stalled": taken and not idle and still}
            for what, now_so in states.items():
                if not now_so:
                    since.pop(what, None)
                elif now - since.setdefault(what, now) >= stall:
                    return what
            if now >= end:
                return "running"

    def _task_alive(self) -> bool:
        """Whether LinuxCNC's task process (``milltask``) runs."""
        for pid in running_processes():
            try:
                if Path(f"/proc/{pid}/comm").read_text().strip() == "milltask":
                    return True
            except OSError:
                continue
        return False

    def _restart(self) -> None:
        """Start this session's LinuxCNC again (its configuration written anew, homed, in MDI),
        keeping the session lock: what :meth:`mdi` does once when the task process ended."""
        lock, self._lock = self._lock, None          # close() neither cleans nor unlocks
        try:
            self.close()
        finally:
            self._lock = lock
        clean_leftovers()
        self._write_config()
        self._start()
        self._connect()

    def _servo_runs_now(self) -> float | None:
        """:meth:`servo_runs`, None before the HAL component is ready."""
        return None if self._comp is None else self.servo_runs()

    def _mdi_failed(self, line: str, what: str) -> None:
        self._stat.poll()
        s, ran = self._stat, self._servo_seen
        ran = "unknown" if ran is None else f"{ran:g}"
        raise MeasurementError(f"LinuxCNC did not finish {line!r} within {what} (interpreter "
                               f"state {s.interp_state}, task {s.exec_state}, motion queue "
                               f"{s.queue}, in position {bool(s.inpos)}, speed {s.current_vel:g}, "
                               f"servo thread periods in the last look {ran}; processes: "
                               f"{process_states()}; LinuxCNC's log ends: {self._log_tail(6)})")

    def move(self, position: float, dwell: float = 0.0, approach: int = 0) -> Reading:
        """G0 to ``position`` (machine units), dwell (G4, seconds), then read both pins.

        ``approach`` ±1: the last :data:`CREEP` mm at :data:`CREEP_FEED` mm/min (G1, in the
        machine's unit), arriving moving that way, in one MDI call of the subroutine
        ``axiscal_approach.ngc`` (package data). LinuxCNC holds, once the joint stops, the trim of
        the last servo period in which it moved (``compute_screw_comp`` takes the direction from
        the joint's velocity), computed one step short of the target: at full speed and a high
        acceleration that step is tenths of a millimetre and the held trim is off by the trim's
        slope times it; the creep keeps the step ≤ CREEP_FEED/60 × 1 ms (1 µm).
        """
        if approach:
            k = _UNITS_MM[self.units]
            self.mdi(f"o<axiscal_approach> call [{position - approach * CREEP / k:.9f}] "
                     f"[{position:.9f}] [{CREEP_FEED / k:.6g}] [{dwell:g}]", stall=3.0 + dwell)
            return self.read()
        self.mdi(f"G0 {self.letter}{position:.9f}")
        if dwell > 0:
            self.mdi(f"G4 P{dwell:g}")
        return self.read()

    def read(self) -> Reading:
        """The joint's ``pos-cmd`` and ``motor-pos-cmd`` (machine units), :data:`SETTLE_PERIODS`
        runs of the servo thread after now (the move's last points on the pins; module
        docstring)."""
        self.wait_periods(SETTLE_PERIODS)
        return Reading(float(self._comp["pos-cmd"]), float(self._comp["motor-pos-cmd"]))

    def wait_periods(self, n: int, timeout: float = 10.0) -> None:
        """Wait until the servo thread has run ``n`` more times (its own count, not the wall
        clock: late runs on a loaded computer count as what they are)."""
        start = self.servo_runs()
        _wait(lambda: self.servo_runs() - start > n - 0.5, timeout,
              f"LinuxCNC's servo thread to run {n} periods", poll=0.001)

    def servo_runs(self) -> float:
        """Runs of the servo thread so far (``axiscal-servo-clock``; a whole number)."""
        return float(self._comp["servo-clock"])


@dataclass
class LinuxCNCAxis(AxisSeenThrough):
    """A simulated machine axis driven by LinuxCNC: the procedures' axis interface.

    ``move`` commands the target through LinuxCNC, approaching from ``direction`` (from
    ``overrun`` beyond when the joint would not otherwise arrive moving that way, as
    ISO 230-2:2014 §3.1 and Figure 1 approach a target), reads ``motor-pos-cmd`` and returns the
    position the machine reaches there: ``motor-pos-cmd`` plus the axis's error at it, for the
    direction the joint last moved (its backlash), with its repeatability noise. Every reading is
    kept in :attr:`log` as ``(commanded mm, direction, Reading)``.

    Parameters
    ----------
    cnc : LinuxCNC
    axis : LinearAxis or RotaryAxis
        The machine behind the drive (SI: metres or radians).
    overrun : float, machine units
    dwell : float, seconds
        G4 after each move (the simulated drive settles at once; a real machine needs the plan's).
    """

    cnc: LinuxCNC
    axis: object
    overrun: float = 5.0
    dwell: float = 0.0
    log: list = field(default_factory=list)
    _here: float = field(default=0.0, init=False)
    _moving: int = field(default=1, init=False)

    def systematic_error(self, theta, direction, time: float = 0.0):
        """A rotary machine's error without noise (what the procedures ask a rotary axis)."""
        return self.axis.systematic_error(theta, direction, time)

    def move(self, position, direction, rng: np.random.Generator | None = None,
             time: float = 0.0):
        """Reach ``position`` (SI) moving in ``direction`` (±1); the actual position, SI."""
        to_m = _UNITS_MM[self.cnc.units] * _SI[self.cnc.units]     # SI per machine unit
        target = float(position) / to_m
        d = 1 if direction > 0 else -1
        if np.sign(target - self._here) != d:
            self._go(target - d * self.overrun)
        r = self._go(target, d)
        self.log.append((target * _UNITS_MM[self.cnc.units], d, r))
        actual = self.axis.move(r.motor_pos_cmd * to_m, self._moving, rng, time=time)
        return float(actual)

    def _go(self, target: float, approach: int = 0):
        r = self.cnc.move(target, self.dwell, approach)
        if target != self._here:
            self._moving = 1 if target > self._here else -1
        self._here = target
        return r


def _wait(ok, timeout: float, what: str, poll: float = 0.02) -> None:
    end = time.monotonic() + timeout
    while not ok():
        if time.monotonic() > end:
            raise MeasurementError(f"gave up waiting {timeout:g} s for {what}")
        time.sleep(poll)
