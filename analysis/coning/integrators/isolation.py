"""A user's integrator run in a child process: a hang, a crash or a segfault becomes one clear error.

Code handed to ``strapdown identify`` is code the package does not control: it
may loop forever, call a C function that ignores Ctrl-C, dereference a null
pointer, or call ``sys.exit`` when it is imported.  :class:`Isolated` loads the
integrator ``FILE.py:NAME`` (:func:`~.adapters.load_integrator`) in a child
Python process and returns an :class:`~.interface.Integrator` whose every call
goes to that child over a pipe:

* the child is started once per run (its start, about the import of numpy, is
  paid once, not per probe) and serves calls until it is closed;
* every call waits at most until the run's deadline (``time_limit`` seconds
  after the start); past it the child is sent SIGTERM and, a fraction of a
  second later, SIGKILL, and the call raises
  :class:`~.interface.IntegratorStopped`, an ``IntegratorError``;
* a child that dies (a segmentation fault in C, ``os._exit``, ``sys.exit``
  at import) gives an :class:`~.interface.IntegratorStopped` that says how it
  died, with the last line the code printed;
* an exception the code raises comes back as its type name and message
  (:class:`~.interface.IntegratorRaised`), and
  :func:`~.interface.step_increments` reports it as for code run in-process;
* what the code prints (on stdout or stderr) is kept apart, so that the
  parent's output (``--json``) stays one JSON object; its last line is quoted
  when the child fails;
* the child runs in its own session: Ctrl-C at the terminal reaches the
  parent only, which then stops the child.  On Linux the child is also
  killed when the parent dies.

The arrays go through :mod:`multiprocessing.connection` (pickles over two
pipes); the outputs are checked in the parent, as for any integrator.

Public API
----------
:data:`START_SECONDS`, :class:`Isolated`, :func:`serve`.
"""

from __future__ import annotations

import os
import pickle
import signal
import subprocess
import sys
import tempfile
import time
import weakref
from multiprocessing.connection import Connection

from ...core.validation import positive
from .interface import Integrator, IntegratorError, IntegratorRaised, IntegratorStopped

__all__ = ["START_SECONDS", "Isolated", "serve"]

#: Time a child takes to start and import numpy on the reference machine, rounded up [s] (for work estimates).
START_SECONDS = 1.0
#: Grace between SIGTERM and SIGKILL when a child is stopped [s].
_GRACE = 0.3


def _last_line(log) -> str:
    """The last non-empty line the child printed (at most 200 characters), or ""."""
    if log is None:
        return ""
    try:
        log.flush()
        log.seek(0, os.SEEK_END)
        size = log.tell()
        log.seek(max(0, size - 8192))
        text = log.read().decode("utf-8", "replace")
    except (OSError, ValueError):
        return ""
    lines = [" ".join(x.split()) for x in text.splitlines() if x.strip()]
    return lines[-1][:200] if lines else ""


def _signal_name(number: int) -> str:
    try:
        name = signal.Signals(number).name
    except ValueError:
        return f"signal {number}"
    meaning = {"SIGSEGV": "segmentation fault", "SIGABRT": "abort", "SIGFPE": "arithmetic fault", "SIGBUS": "bus error", "SIGILL": "illegal instruction", "SIGKILL": "killed"}
    return f"{name} ({meaning[name]})" if name in meaning else name


def _stop(proc: subprocess.Popen) -> None:
    """SIGTERM, then SIGKILL after a grace: the child may ignore the first (a C loop with handlers set)."""
    if proc.poll() is not None:
        return
    try:
        proc.terminate()
        try:
            proc.wait(_GRACE)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()
    except OSError:  # already gone
        pass


class Isolated:
    """The integrator ``FILE.py:NAME`` loaded and run in a child process (module docstring).

    Use as a context manager (the child is stopped on exit), or call :meth:`close`.

    Parameters
    ----------
    spec : str
        ``"path/to/file.py:NAME"`` (:func:`~.adapters.load_integrator`).
    time_limit : float, keyword-only
        Every call, and the loading, must end within this many seconds of the
        start [s]; past it the child is stopped.

    The child starts at once and loads the file while the caller goes on;
    the first use of :attr:`integrator` waits for it.

    Attributes
    ----------
    spec : str
        As given.

    Raises
    ------
    TypeError
        If ``spec`` is not a str.

    Examples
    --------
    >>> import pathlib, tempfile, numpy as np
    >>> folder = pathlib.Path(tempfile.mkdtemp())
    >>> _ = (folder / "mine.py").write_text("def total(gyro, n):\\n    return gyro.reshape(-1, n, 3).sum(axis=1)\\n")
    >>> with Isolated(f"{folder / 'mine.py'}:total", time_limit=60.0) as child:
    ...     child.integrator.function(np.ones((4, 3)), 2)
    array([[2., 2., 2.],
           [2., 2., 2.]])
    """

    def __init__(self, spec: str, *, time_limit: float):
        if not isinstance(spec, str):
            raise TypeError(f"Expected `spec` as a str \"FILE.py:NAME\", got {type(spec).__name__}")
        self.spec = spec
        self.time_limit = positive(time_limit, "time_limit")
        self._deadline = time.monotonic() + self.time_limit
        self._log = tempfile.TemporaryFile()
        to_child_r, to_child_w = os.pipe()
        from_child_r, from_child_w = os.pipe()
        code = "import sys; from strapdown.analysis.coning.integrators.isolation import serve; serve(int(sys.argv[1]), int(sys.argv[2]))"
        try:
            self._proc = subprocess.Popen(
                [sys.executable, "-c", code, str(to_child_r), str(from_child_w)],
                pass_fds=(to_child_r, from_child_w),
                stdin=subprocess.DEVNULL,
                stdout=self._log,
                stderr=self._log,
                start_new_session=True,
                close_fds=True,
            )
        finally:
            os.close(to_child_r)
            os.close(from_child_w)
        self._send_conn = Connection(to_child_w, readable=False)
        self._recv_conn = Connection(from_child_r, writable=False)
        self._finalizer = weakref.finalize(self, _close, self._proc, self._send_conn, self._recv_conn, self._log)
        self._send(("load", spec))
        self._integrator = None

    @property
    def integrator(self) -> Integrator:
        """The integrator as the parent sees it (its calls run in the child); the first access waits for the child to load the file.

        Raises
        ------
        ValueError, TypeError
            The loader refused the file (its message).
        IntegratorStopped
            The child did not load the file within the time limit, or died while loading it.
        """
        if self._integrator is None:
            reply = self._receive("loading it")
            if reply[0] == "refused":
                self.close()
                raise (TypeError if reply[1] == "TypeError" else ValueError)(reply[2])
            meta = reply[1]
            self._integrator = Integrator(
                self._call, output=meta["output"], velocity=meta["velocity"], name=meta["name"], input=meta["input"], sample_interval=meta["sample_interval"]
            )
        return self._integrator

    @property
    def remaining(self) -> float:
        """Seconds left before the deadline [s]."""
        return self._deadline - time.monotonic()

    def _failure(self, what: str, stopped: bool) -> IntegratorStopped:
        last = _last_line(self._log)
        tail = f"; its last output: {last!r}" if last else ""
        name = self._integrator.name if getattr(self, "_integrator", None) is not None else self.spec
        if stopped:
            return IntegratorStopped(
                f"integrator {name!r} did not return within the time limit of {self.time_limit:g} s (`time_limit`) while {what}: its process was stopped{tail}"
            )
        code = self._proc.returncode
        how = f"was killed by {_signal_name(-code)}" if code is not None and code < 0 else f"exited with status {code}"
        return IntegratorStopped(f"the process running integrator {name!r} {how} while {what}{tail}")

    def _send(self, message) -> None:
        try:
            self._send_conn.send(message)
        except (OSError, EOFError, ValueError):
            self._proc.wait()
            raise self._failure("receiving its input", stopped=False) from None

    def _receive(self, what: str):
        try:
            ready = self._recv_conn.poll(max(0.0, self.remaining))
        except (OSError, EOFError, ValueError):
            ready = True
        if not ready:
            _stop(self._proc)
            raise self._failure(what, stopped=True)
        try:
            return self._recv_conn.recv()
        except (OSError, EOFError):
            try:
                self._proc.wait(max(0.1, min(5.0, self.remaining)))
            except subprocess.TimeoutExpired:
                _stop(self._proc)
            raise self._failure(what, stopped=False) from None

    def _call(self, gyro, samples_per_step, accel=None):
        if self._proc.poll() is not None:
            raise self._failure("being called", stopped=False)
        self._send(("call", gyro, samples_per_step, accel))
        reply = self._receive(f"integrating {gyro.shape[0]} samples")
        if reply[0] == "raised":
            raise IntegratorRaised(reply[1], reply[2])
        if reply[0] == "unpicklable":
            raise IntegratorError(f"integrator {self._integrator.name!r} returned {reply[1]}, expected numeric arrays (it could not be passed back from its process)")
        return reply[1]

    def close(self) -> None:
        """Stop the child (it is asked to exit, then stopped if it does not)."""
        self._finalizer()

    def __enter__(self) -> Isolated:
        return self

    def __exit__(self, *exc) -> None:
        self.close()


def _close(proc, send_conn, recv_conn, log) -> None:
    try:
        send_conn.send(("exit",))
    except (OSError, EOFError, ValueError):
        pass
    try:
        proc.wait(_GRACE)
    except subprocess.TimeoutExpired:
        _stop(proc)
    for thing in (send_conn, recv_conn, log):
        try:
            thing.close()
        except OSError:
            pass


# --------------------------------------------------------------------------- the child
def _die_with_parent() -> None:
    """Linux: the kernel kills this process when its parent dies (PR_SET_PDEATHSIG)."""
    if not sys.platform.startswith("linux"):
        return
    try:
        import ctypes

        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)
    except (OSError, AttributeError):
        pass


def serve(read_fd: int, write_fd: int) -> None:
    """The child's loop: load the integrator, then answer calls until told to exit (or the pipe closes).

    Parameters
    ----------
    read_fd : int
        File descriptor of the pipe from the parent.
    write_fd : int
        File descriptor of the pipe to the parent.
    """
    _die_with_parent()
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    inbox, outbox = Connection(read_fd, writable=False), Connection(write_fd, readable=False)
    integrator = None
    while True:
        try:
            message = inbox.recv()
        except (EOFError, OSError):
            return
        if message[0] == "exit":
            return
        if message[0] == "load":
            from .adapters import load_integrator

            try:
                integrator = load_integrator(message[1])
            except (ValueError, TypeError) as exc:
                outbox.send(("refused", type(exc).__name__, " ".join(str(exc).split())))
                continue
            meta = {k: getattr(integrator, k) for k in ("name", "output", "velocity", "input", "sample_interval")}
            outbox.send(("ready", meta))
            continue
        _, gyro, n, accel = message
        try:
            out = integrator.function(gyro, n) if accel is None else integrator.function(gyro, n, accel)
        except BaseException as exc:  # the user's code, SystemExit included: reported, the child lives on
            detail = " ".join(str(exc).split()) or "no message"
            if isinstance(exc, SystemExit):
                detail = f"sys.exit({exc.code!r}) called"
            outbox.send(("raised", type(exc).__name__, detail))
            continue
        try:
            outbox.send(("ok", out))  # pickled whole before anything is written: a failure sends nothing
        except (pickle.PicklingError, TypeError, AttributeError):
            outbox.send(("unpicklable", type(out).__name__))
