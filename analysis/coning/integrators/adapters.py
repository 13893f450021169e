"""Adapters: stateful objects, compiled C functions, registry algorithms and Python files as integrators.

Each adapter returns an :class:`~.interface.Integrator` (the black-box
interface of :mod:`.interface`):

:func:`stateful`
    an object written the way flight code is written, one sample at a time:
    ``reset()`` clears every state (a new record), ``update(gyro)`` (or
    ``update(gyro, accel)``) takes one sample's increments, ``output()``
    returns the step's result and starts the next step (the way an
    autopilot reads and resets its delta-angle accumulator).
:func:`compiled`
    a C function through :mod:`ctypes`, with the signature

    .. code-block:: c

        int integrate(const double *gyro, const double *accel, size_t n_samples,
                      size_t samples_per_step, double *rotation, double *velocity);

    ``gyro`` and ``accel`` are ``n_samples × 3`` row-major [rad, m/s];
    ``rotation`` and ``velocity`` receive ``n_samples / samples_per_step``
    rows of three: the rotation vector of each step and its velocity
    increment in the body axes at the start of the step.  ``accel`` and
    ``velocity`` are NULL for a coning-only call.  The function starts every
    call from rest and returns 0 on success (``docs/integrator_example.c``).
:func:`per_sample_library`
    a per-sample C API (``reset`` / ``put`` / ``get``), or a C++ class
    behind an ``extern "C"`` shim (``docs/integrator_example.cpp``);
:func:`algorithm_integrator`
    an algorithm given as data, run from its own terms
    (:func:`strapdown.analysis.coning.evaluation.increment`; velocity by its dual
    extension, Lebedev & Panov 1989, eq. (2.5)).
:func:`as_integrator`, :func:`load_integrator`
    whatever a user hands over, or the ``FILE.py:NAME`` of the command line.

Public API
----------
:func:`stateful`, :func:`compiled`, :func:`per_sample_library`, :func:`algorithm_integrator`,
:func:`as_integrator`, :func:`load_integrator`.
"""

from __future__ import annotations

import ctypes
import hashlib
import importlib.util
import inspect
import os
import sys
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .interface import OUTPUTS, Integrator, IntegratorError

if TYPE_CHECKING:  # imported where used: the child process that runs user code stays light
    from ....derivations.coning.algorithms import Algorithm

__all__ = ["stateful", "compiled", "per_sample_library", "algorithm_integrator", "as_integrator", "load_integrator"]

_PROTOCOL = ("update", "output")


def _has_protocol(obj) -> bool:
    return all(callable(getattr(obj, m, None)) for m in _PROTOCOL)


def stateful(target, *, output: str = "rotation_vector", velocity: bool = False, name: str = "", input: str = "increment", sample_interval: float | None = None) -> Integrator:
    """An integrator object with ``reset`` / ``update`` / ``output`` as a black-box integrator.

    Every record: the object is reset (``reset()``; a class is instantiated
    anew instead), every sample is passed to ``update(gyro_row)`` (or
    ``update(gyro_row, accel_row)`` with ``velocity``), and after every
    ``samples_per_step`` samples ``output()`` gives the step: a rotation vector
    (``output="rotation_vector"``; with ``velocity`` a pair ``(rotation,
    velocity increment)``) or the attitude quaternion, see :mod:`.interface`.

    Parameters
    ----------
    target : object or class
        An object with ``update`` and ``output`` methods (and ``reset``), or a
        class whose instances have them (instantiated with no arguments).
    output : str, keyword-only
        One of :data:`~.interface.OUTPUTS`: what ``output()`` returns.
    velocity : bool, keyword-only
        ``update`` takes accelerometer increments too, and ``output`` returns a pair.
    name : str, keyword-only
        Name in messages (default: the class name).
    input : str, keyword-only
        ``"increment"`` or ``"rate"``: ``update`` takes the mean rates of the
        sample [rad/s, m/s²] (:mod:`.interface`).
    sample_interval : float, keyword-only, optional
        h [s] of a rate integrator.

    Returns
    -------
    Integrator

    Raises
    ------
    TypeError
        If ``target`` lacks ``update`` or ``output``, or an instance lacks ``reset``.

    Examples
    --------
    >>> class Sum:
    ...     def reset(self):
    ...         self.total = np.zeros(3)
    ...     def update(self, gyro):
    ...         self.total = self.total + gyro
    ...     def output(self):
    ...         out, self.total = self.total, np.zeros(3)
    ...         return out
    >>> from .interface import step_increments
    >>> step_increments(stateful(Sum), np.ones((4, 3)), 2).rotation
    array([[2., 2., 2.],
           [2., 2., 2.]])
    """
    is_class = inspect.isclass(target)
    if not _has_protocol(target):
        missing = ", ".join(m for m in _PROTOCOL if not callable(getattr(target, m, None)))
        raise TypeError(f"Expected `target` with methods update() and output() (and reset()), got {type(target).__name__} without {missing}")
    if not is_class and not callable(getattr(target, "reset", None)):
        raise TypeError(f"Expected `target` with a reset() method (or a class, instantiated for every record), got {type(target).__name__} without one")
    if output not in OUTPUTS or output == "dcm":
        raise ValueError(f"Expected `output` to be 'rotation_vector' or 'quaternion', got {output!r}")

    def run(gyro, samples_per_step, accel=None):
        obj = target() if is_class else target
        if callable(getattr(obj, "reset", None)):
            obj.reset()
        rows, vel_rows = [], []
        for k in range(gyro.shape[0]):
            if velocity:
                obj.update(gyro[k].copy(), accel[k].copy())
            else:
                obj.update(gyro[k].copy())
            if (k + 1) % samples_per_step == 0:
                out = obj.output()
                if velocity:
                    if not isinstance(out, (tuple, list)) or len(out) != 2:
                        raise IntegratorError(f"output() returned {type(out).__name__}, expected a pair (rotation, velocity increment)")
                    rows.append(np.asarray(out[0], dtype=float).copy())
                    vel_rows.append(np.asarray(out[1], dtype=float).copy())
                else:
                    rows.append(np.asarray(out, dtype=float).copy())
        return (np.array(rows), np.array(vel_rows)) if velocity else np.array(rows)

    label = name or (target.__name__ if is_class else type(target).__name__)
    return Integrator(run, output=output, velocity=velocity, name=label, input=input, sample_interval=sample_interval)


def compiled(library, function: str = "integrate", *, velocity: bool = False, name: str = "") -> Integrator:
    """A C function with the signature of the module docstring, through :mod:`ctypes`.

    Parameters
    ----------
    library : str or Path
        Shared library (``.so``, ``.dylib``, ``.dll``).
    function : str
        Name of the exported function.
    velocity : bool, keyword-only
        Pass accelerometer increments and read the velocity rows (the function
        must then accept non-NULL ``accel`` and ``velocity``).
    name : str, keyword-only
        Name in messages (default ``"<library>:<function>"``).

    Returns
    -------
    Integrator
        Rotation-vector output.

    Raises
    ------
    ValueError
        If the library cannot be loaded or does not export ``function``.
    """
    path = Path(library)
    try:
        lib = ctypes.CDLL(str(path))
    except OSError as exc:
        raise ValueError(f"Expected `library` to be a loadable shared library, got {str(path)!r} ({' '.join(str(exc).split())})") from None
    try:
        fn = getattr(lib, function)
    except AttributeError:
        raise ValueError(f"Expected `function` exported by {path.name}, got {function!r} (not found)") from None
    dbl = ctypes.POINTER(ctypes.c_double)
    fn.argtypes = [dbl, dbl, ctypes.c_size_t, ctypes.c_size_t, dbl, dbl]
    fn.restype = ctypes.c_int

    def pointer(a):
        return None if a is None else a.ctypes.data_as(dbl)

    def run(gyro, samples_per_step, accel=None):
        gyro = np.ascontiguousarray(gyro, dtype=np.float64)
        steps = gyro.shape[0] // samples_per_step
        rotation = np.zeros((steps, 3))
        vel = np.zeros((steps, 3)) if velocity else None
        acc = np.ascontiguousarray(accel, dtype=np.float64) if velocity else None
        status = fn(pointer(gyro), pointer(acc), gyro.shape[0], samples_per_step, pointer(rotation), pointer(vel))
        if status != 0:
            raise IntegratorError(f"returned status {status} (0 is success)")
        return (rotation, vel) if velocity else rotation

    return Integrator(run, velocity=velocity, name=name or f"{path.name}:{function}")


def per_sample_library(library, prefix: str = "integrator_", *, handle: bool = False, velocity: bool = False, name: str = "") -> Integrator:
    """A per-sample C API (reset / put / get), or a C++ class behind an ``extern "C"`` shim, through :mod:`ctypes`.

    Flight code written one sample at a time exports, with ``P`` the prefix:

    .. code-block:: c

        void P_reset(void);                          /* clear every state: a new record */
        void P_put(const double gyro[3]);            /* one sample: P_put(gyro, accel) with velocity */
        void P_get(double rotation[3]);              /* the step's result; starts the next step */
                                                     /* P_get(rotation, velocity) with velocity */

    and, with ``handle``, an object: ``void *P_create(void)``,
    ``void P_destroy(void *)``, and ``reset``, ``put`` and ``get`` taking
    that pointer first: the shape of an ``extern "C"`` shim around a C++
    class (``docs/integrator_example.cpp``).  Every record: one object is
    created (with ``handle``) and reset, every sample is put, and after every
    ``samples_per_step`` samples ``get`` gives the step's rotation vector
    [rad] (and velocity increment, body axes at the start of the step
    [m/s]), as :func:`stateful` does for a Python object.

    Parameters
    ----------
    library : str or Path
        Shared library (``.so``, ``.dylib``, ``.dll``).
    prefix : str
        The functions' common prefix (``"integrator_"`` gives ``integrator_reset`` …).
    handle : bool, keyword-only
        The functions take an object pointer first, made by ``P_create``.
    velocity : bool, keyword-only
        ``put`` takes accelerometer increments and ``get`` writes the velocity increment too.
    name : str, keyword-only
        Name in messages (default ``"<library>:<prefix>"``).

    Returns
    -------
    Integrator
        Rotation-vector output.

    Raises
    ------
    ValueError
        If the library cannot be loaded or lacks one of the functions.
    """
    path = Path(library)
    try:
        lib = ctypes.CDLL(str(path))
    except OSError as exc:
        raise ValueError(f"Expected `library` to be a loadable shared library, got {str(path)!r} ({' '.join(str(exc).split())})") from None
    wanted = ("reset", "put", "get") + (("create", "destroy") if handle else ())
    fns = {}
    for what in wanted:
        try:
            fns[what] = getattr(lib, prefix + what)
        except AttributeError:
            raise ValueError(f"Expected `library` {path.name} to export {prefix + what}() (`prefix` = {prefix!r}), got no such function") from None
    ptr = ctypes.c_void_p
    first = [ptr] if handle else []
    fns["reset"].argtypes, fns["reset"].restype = first, None
    fns["put"].argtypes, fns["put"].restype = first + [ptr] * (2 if velocity else 1), None
    fns["get"].argtypes, fns["get"].restype = first + [ptr] * (2 if velocity else 1), None
    if handle:
        fns["create"].argtypes, fns["create"].restype = [], ptr
        fns["destroy"].argtypes, fns["destroy"].restype = [ptr], None

    def run(gyro, samples_per_step, accel=None):
        gyro = np.ascontiguousarray(gyro, dtype=np.float64)
        acc = np.ascontiguousarray(accel, dtype=np.float64) if velocity else None
        steps = gyro.shape[0] // samples_per_step
        rotation = np.zeros((steps, 3))
        vel = np.zeros((steps, 3)) if velocity else None
        obj = fns["create"]() if handle else None
        if handle and not obj:
            raise IntegratorError(f"{prefix}create() returned NULL")
        lead = (obj,) if handle else ()
        g0, r0 = gyro.ctypes.data, rotation.ctypes.data
        a0, v0 = (acc.ctypes.data, vel.ctypes.data) if velocity else (0, 0)
        put, get = fns["put"], fns["get"]
        try:
            fns["reset"](*lead)
            for k in range(gyro.shape[0]):
                put(*lead, g0 + 24 * k, *((a0 + 24 * k,) if velocity else ()))
                if (k + 1) % samples_per_step == 0:
                    step = k // samples_per_step
                    get(*lead, r0 + 24 * step, *((v0 + 24 * step,) if velocity else ()))
        finally:
            if handle:
                fns["destroy"](obj)
        return (rotation, vel) if velocity else rotation

    return Integrator(run, velocity=velocity, name=name or f"{path.name}:{prefix}")


def algorithm_integrator(algorithm: Algorithm, *, velocity: bool = True) -> Integrator:
    """An algorithm given as data, as a black-box integrator (its own terms, no expansion).

    The samples before the record are zero (a record starts from rest); each
    step's window ``p_{1−history} … p_N`` is cut from the record
    (:func:`strapdown.analysis.coning.simulator.step_windows`) and evaluated by
    :func:`strapdown.analysis.coning.evaluation.increment`.  With ``velocity``
    the dual extension on ``q_j = p_j + s b_j`` gives ``ΔΦ = Δφ + s Δφ°``, the
    step biquaternion ``ϑ = λ + s m`` (Lebedev & Panov 1989, eq. (1.12)) and
    the velocity increment ``Δv = 2 vect(m ∘ λ̄)`` in the body axes at the
    start of the step.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    velocity : bool, keyword-only
        Take accelerometer increments too (sculling by the dual extension).

    Returns
    -------
    Integrator
        Rotation-vector output, named after the algorithm.

    Raises
    ------
    TypeError
        If ``algorithm`` is not an :class:`Algorithm`.

    References
    ----------
    Lebedev & Panov (1989), eqs. (1.12), (2.5).
    """
    from ....derivations.coning.algorithms import Algorithm
    from ...core import quaternion as quat
    from ...core.dual import Dual
    from ..evaluation import increment
    from ..simulator import step_windows

    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    history = algorithm.history

    def pad(x):
        return np.concatenate([np.zeros((history, 3)), x], axis=0)

    def run(gyro, samples_per_step, accel=None):
        if samples_per_step != algorithm.samples:
            raise ValueError(f"algorithm {algorithm.name!r} takes {algorithm.samples} samples per step, got {samples_per_step}")
        if accel is None:
            return increment(algorithm, step_windows(pad(gyro), algorithm.samples, history))
        phi = increment(algorithm, step_windows(Dual(pad(gyro), pad(accel)), algorithm.samples, history))
        step = quat.rotvec_to_quat(phi)
        dv = 2.0 * quat.vect(quat.multiply(step.du, quat.conjugate(step.re)))
        return phi.re, dv

    return Integrator(run, velocity=velocity, name=algorithm.name)


def as_integrator(obj, *, name: str = "") -> Integrator:
    """Whatever a user hands over, as an :class:`~.interface.Integrator`.

    Parameters
    ----------
    obj : Integrator, Algorithm, object or class with update/output, or callable
        An :class:`~.interface.Integrator` is returned as it is; an
        :class:`Algorithm` by :func:`algorithm_integrator`; an object or class
        with ``update`` and ``output`` by :func:`stateful`; any other callable
        is taken as ``function(gyro, samples_per_step)`` returning rotation
        vectors.
    name : str, keyword-only
        Name in messages (default: the object's own).

    Returns
    -------
    Integrator

    Raises
    ------
    TypeError
        If ``obj`` is none of these.
    """
    if isinstance(obj, Integrator):
        return obj
    algorithms = sys.modules.get(__name__.split(".analysis.")[0] + ".derivations.coning.algorithms")  # an Algorithm exists only once it is imported
    if algorithms is not None and isinstance(obj, algorithms.Algorithm):
        return algorithm_integrator(obj)
    if _has_protocol(obj):
        return stateful(obj, name=name)
    if callable(obj):
        return Integrator(obj, name=name)
    raise TypeError(f"Expected an Integrator, an Algorithm, an object with update() and output(), or a function, got {type(obj).__name__}")


def load_integrator(spec: str) -> Integrator:
    """The integrator ``NAME`` defined in the Python file ``FILE.py``, from ``"FILE.py:NAME"``.

    The file is executed as a module with its own directory first on
    ``sys.path`` (as ``python FILE.py`` would run it: a sibling module imports;
    the directory stays on the path, for imports made later by the
    integrator), so it may import what its directory holds, this package, and
    anything installed; ``NAME`` is then passed to :func:`as_integrator`.  A
    file that calls ``sys.exit`` while it is imported is refused with the exit
    status it gave.  :class:`~.isolation.Isolated` runs this loader in a child
    process, where a file that hangs or crashes cannot take the caller with it.

    Parameters
    ----------
    spec : str
        ``"path/to/file.py:NAME"``.

    Returns
    -------
    Integrator

    Raises
    ------
    ValueError
        A spec without ``:NAME``, a missing file, a file that cannot be
        imported (its error is quoted with the line) or that calls ``sys.exit``
        when imported, or no ``NAME`` in it (the message lists what the file
        defines).
    TypeError
        If ``NAME`` is not an integrator of any accepted kind.
    """
    if not isinstance(spec, str):
        raise TypeError(f"Expected `spec` as a str \"FILE.py:NAME\", got {type(spec).__name__}")
    file, sep, attr = spec.rpartition(":")
    if not sep or not file or not attr.isidentifier():
        raise ValueError(f"Expected `spec` as FILE.py:NAME (a Python file and the name of the integrator in it), got {spec!r}")
    path = Path(file)
    if not path.is_file():
        raise ValueError(f"Expected `spec` to name an existing Python file, got {file!r} ({'a directory' if path.is_dir() else 'not found'})")
    module_name = "strapdown_user_integrator_" + hashlib.sha1(os.fsencode(path.resolve())).hexdigest()[:12]
    loader_spec = importlib.util.spec_from_file_location(module_name, path)
    if loader_spec is None or loader_spec.loader is None:
        raise ValueError(f"Expected `spec` to name a Python file (.py), got {file!r}")
    module = importlib.util.module_from_spec(loader_spec)
    folder = str(path.resolve().parent)
    if folder not in sys.path:
        sys.path.insert(0, folder)  # its siblings import, as when the file is run as a script
    sys.modules[module_name] = module  # dataclasses and pickling look the module up by name
    try:
        loader_spec.loader.exec_module(module)
    except SyntaxError as exc:
        del sys.modules[module_name]
        raise ValueError(f"{file}: syntax error at line {exc.lineno}: {exc.msg}") from None
    except SystemExit as exc:
        del sys.modules[module_name]
        raise ValueError(f"{file}: importing it called sys.exit({exc.code!r}); expected a file that defines the integrator and returns") from None
    except Exception as exc:  # the user's file: its failure becomes one message
        del sys.modules[module_name]
        detail = " ".join(str(exc).split()) or "no message"
        raise ValueError(f"{file}: importing it raised {type(exc).__name__}: {detail}") from None
    if not hasattr(module, attr):
        found = sorted(k for k, v in vars(module).items() if not k.startswith("_") and (callable(v) or isinstance(v, Integrator)) and getattr(v, "__module__", module_name) == module_name)
        listed = ", ".join(found) if found else "nothing callable"
        raise ValueError(f"Expected `spec` to name an integrator defined in {file}, got {attr!r} (the file defines {listed})")
    return as_integrator(getattr(module, attr), name=attr)
