"""How :meth:`LinuxCNC.mdi` ends a line LinuxCNC 2.9's task lost track of.

The states are the ones seen on fresh-clone ``make test`` runs (CI log of stop 45: an approach
subroutine's MDI call with the interpreter READING and the task DONE for 60 s). LinuxCNC cannot
be made to lose a line on demand, so its two channels are stand-ins here that replay those states;
LinuxCNC itself runs the lines in ``test_linuxcnc_live.py``. No LinuxCNC is started: its
Python module is needed only for constants, which stand in where it is not installed.
"""

import sys
import types

import pytest

from axiscal.errors import MeasurementError
from axiscal.instruments.linuxcnc_controller import LinuxCNC, LinuxCNCRecovery

try:
    import linuxcnc
except ImportError:          # the constants LinuxCNC 2.9's Python module gives (emcmodule.cc)
    linuxcnc = types.ModuleType("linuxcnc")
    linuxcnc.INTERP_IDLE, linuxcnc.INTERP_READING = 1, 2
    linuxcnc.EXEC_DONE, linuxcnc.EXEC_WAITING_FOR_MOTION, linuxcnc.MODE_MDI = 2, 3, 3


@pytest.fixture(autouse=True)
def _module(monkeypatch):
    """``LinuxCNC.mdi`` imports ``linuxcnc`` for its constants: the real one, or the stand-in."""
    monkeypatch.setitem(sys.modules, "linuxcnc", linuxcnc)


class Task:
    """LinuxCNC's task as the two channels see it: ``behaviour`` per sending of the line,
    "done", "stall" (taken, interpreter READING, nothing running, for ever), "stall, a segment
    queued" (the same with a segment in the motion queue that does not move), "lost" (never
    taken) or "run" (taken, moving for ever)."""

    def __init__(self, *behaviour):
        self.behaviour = list(behaviour)
        self.serial = 0
        self.sent, self.aborts, self.modes = [], 0, []
        self.echo_serial_number, self.state = 0, 1
        self.interp_state, self.exec_state = linuxcnc.INTERP_IDLE, linuxcnc.EXEC_DONE
        self.queue, self.inpos, self.current_vel, self.position = 0, True, 0.0, (0.0,) * 9
        self.still = self.deaf = False
        self.alive = True

    # linuxcnc.command
    def mdi(self, line):
        self.serial += 1
        self.sent.append(line)
        how = self.behaviour.pop(0)
        if how == "lost":
            return
        self.echo_serial_number = self.serial
        if how == "stall":
            self.interp_state = linuxcnc.INTERP_READING
        elif how == "stall, a segment queued":    # the motion holds it "moving", going nowhere
            self.interp_state, self.queue, self.inpos = linuxcnc.INTERP_READING, 2, False
            self.current_vel, self.still = 1.0, True
        elif how == "run":
            self.interp_state, self.exec_state = (linuxcnc.INTERP_READING,
                                                  linuxcnc.EXEC_WAITING_FOR_MOTION)
            self.queue, self.inpos, self.current_vel = 1, False, 100.0

    def wait_complete(self, timeout=5.0):
        done = self.echo_serial_number == self.serial and self.interp_state == linuxcnc.INTERP_IDLE
        return 1 if done else -1

    def abort(self):
        self.aborts += 1
        if self.deaf:
            return
        self.interp_state, self.exec_state = linuxcnc.INTERP_IDLE, linuxcnc.EXEC_DONE
        self.queue, self.inpos, self.current_vel, self.still = 0, True, 0.0, False

    def mode(self, m):
        self.modes.append(m)

    # linuxcnc.stat
    def poll(self):
        if self.current_vel and not self.still:      # moving: the commanded position changes
            self.position = (self.position[0] + 1e-3,) + self.position[1:]


class Clock:
    """The servo thread's run count (``axiscal-servo-clock``): 500 runs between two looks."""

    def __init__(self):
        self.runs = 0.0

    def __getitem__(self, pin):
        self.runs += 500.0
        return self.runs


def _cnc(task):
    cnc = LinuxCNC((-10.0, 10.0))
    cnc._cmd = cnc._stat = task
    cnc._comp = Clock()
    cnc._task_alive = lambda: task.alive
    return cnc


def _quick(monkeypatch):
    """wait_complete's 0.5 s becomes instant: the stand-in answers at once."""
    import axiscal.instruments.linuxcnc_controller as m
    clock = iter(range(0, 10_000))
    monkeypatch.setattr(m.time, "monotonic", lambda: float(next(clock)))


@pytest.mark.parametrize("stall", ["stall", "stall, a segment queued"])
def test_a_stalled_subroutine_call_is_aborted_and_sent_again(monkeypatch, stall):
    _quick(monkeypatch)
    task = Task(stall, "done")
    cnc = _cnc(task)
    with pytest.warns(LinuxCNCRecovery, match=r"stalled \(processes: .*\); aborted and sent again"):
        cnc.mdi("o<axiscal_approach> call [3.01] [3] [60] [0]")
    assert task.aborts == 1 and task.modes == [linuxcnc.MODE_MDI]
    assert task.sent == ["o<axiscal_approach> call [3.01] [3] [60] [0]"] * 2
    assert cnc.recoveries == [(task.sent[0], "stalled")]


def test_a_lost_line_is_sent_again_without_abort(monkeypatch):
    _quick(monkeypatch)
    task = Task("lost", "done")
    cnc = _cnc(task)
    with pytest.warns(LinuxCNCRecovery, match=r"lost \(processes: .*\); sent again"):
        cnc.mdi("G0 X1")
    assert task.aborts == 0 and len(task.sent) == 2 and cnc.recoveries == [("G0 X1", "lost")]


def test_a_line_done_at_once_is_sent_once(monkeypatch):
    _quick(monkeypatch)
    task = Task("done")
    cnc = _cnc(task)
    cnc.mdi("G0 X1")
    assert task.sent == ["G0 X1"] and cnc.recoveries == [] and task.aborts == 0


def test_a_line_still_moving_is_an_error_naming_the_states(monkeypatch):
    _quick(monkeypatch)
    cnc = _cnc(Task("run"))
    with pytest.raises(MeasurementError, match=r"did not finish 'G0 X1' within 30 s "
                                               r"\(interpreter state 2, task 3, motion queue 1, "
                                               r"in position False, speed 100, servo thread "
                                               r"periods in the last look 500; processes: "):
        cnc.mdi("G0 X1")


def test_a_line_stalled_twice_is_an_error(monkeypatch):
    _quick(monkeypatch)
    task = Task("stall", "stall")
    cnc = _cnc(task)
    with pytest.raises(MeasurementError, match=r"sent twice \(stalled\)"), \
            pytest.warns(LinuxCNCRecovery):
        cnc.mdi("G0 X1")
    assert task.aborts == 2


def test_a_line_is_not_called_stalled_while_the_servo_thread_does_not_run(monkeypatch):
    """A computer so loaded that the servo thread did not run: nothing moves because nothing ran;
    the line is given its timeout, and the error says the thread did not run."""
    _quick(monkeypatch)
    task = Task("stall")
    cnc = _cnc(task)
    cnc._comp = {"servo-clock": 7.0}               # the count does not advance
    with pytest.raises(MeasurementError, match="servo thread periods in the last look 0"):
        cnc.mdi("G0 X1")
    assert task.aborts == 0 and cnc.recoveries == []


def test_a_task_that_does_not_answer_an_abort_is_an_error_saying_so(monkeypatch):
    """Seen once on CI (three workers): the task neither ended the call nor took the abort;
    the error says so and lists LinuxCNC's processes' states (here none run)."""
    _quick(monkeypatch)
    task = Task("stall")
    task.deaf = True
    with pytest.raises(MeasurementError, match="did not stop when aborted.*processes: "), \
            pytest.warns(LinuxCNCRecovery):
        _cnc(task).mdi("G0 X1")
    assert task.aborts == 1


def test_a_task_process_that_ended_means_linuxcnc_is_started_again(monkeypatch):
    """Seen on CI (three workers): LinuxCNC's ``milltask`` was gone from the processes (io,
    linuxcnc, linuxcncsvr and rtapi_app left) and the next line was never taken. The session
    starts LinuxCNC again and sends the line again; a second end is an error."""
    _quick(monkeypatch)
    task = Task("lost", "done")
    task.alive = False
    cnc = _cnc(task)
    restarts = []

    def restart():
        restarts.append(1)
        task.alive = True
    cnc._restart = restart
    with pytest.warns(LinuxCNCRecovery, match=r"milltask\) ended .* started again"):
        cnc.mdi("G0 X1")
    assert restarts == [1] and task.sent == ["G0 X1"] * 2
    assert cnc.recoveries == [("G0 X1", "task ended")]


def test_a_session_that_cannot_start_again_says_the_task_ended(monkeypatch):
    _quick(monkeypatch)
    task = Task("lost")
    task.alive = False
    cnc = _cnc(task)
    cnc.restartable = False
    with pytest.raises(MeasurementError, match=r"task process \(milltask\) ended while running "
                                               r"'G0 X1'"):
        cnc.mdi("G0 X1")
