"""Peers' integrators as black boxes, fed like for like (``python-ins``, ``smsfusion``: dependencies of the package).

pyins (``python-ins`` on the package index)
    :func:`pyins_integrator` drives ``pyins.strapdown.Integrator``, the whole
    strapdown loop (numba compiled): ``compute_increments_from_imu`` forms
    ``θ_k`` from increment-type samples, and the loop multiplies the
    body-to-navigation direction-cosine matrices by the step rotations.  Its
    navigation frame is local-level on a rotating Earth; with the Earth rate
    ``pyins.earth.RATE`` set to zero before its loop is compiled, the body at
    rest at the equator (no specific force, ``with_altitude=False``), the
    transport rate is zero and its frame is inertial: its matrices are our Λ
    (E → I), multiplied on the right by each step, as ours.  Setting the rate
    changes pyins's module in this process only.  Its loop, compiled with that
    rate, is kept in numba's disk cache in the package's own cache directory
    (:func:`~strapdown.analysis.core.cache.cache_directory`, under
    ``numba-pyins-earth-rate-zero``): later processes load it instead of
    compiling again (about 3 s), and nothing is written into pyins's
    installation or numba's user-wide cache, so that other users of the
    installation see pyins unchanged.  Where that directory cannot be written
    the loop is compiled in memory, as before.  Its "before" sample is zero
    (the record starts from rest).  The attitude after
    every N-th sample is its output.
    :func:`pyins_increments` is its increment function alone
    (``compute_increments_from_imu``, one sample per step): rotation vector
    and velocity increment, coning and sculling.

smsfusion
    :func:`smsfusion_ins` drives ``smsfusion.StrapdownINS``, one sample per
    ``update`` call, built with ``g = 0`` so that its velocity is the apparent
    velocity W_I of the inertial frame (it has no Earth rate).  It takes rates
    and specific forces, not increments: it is given the mean rate and the
    mean specific force of each sample (``p/h``, ``b/h``), which over its
    sample period integrate back to the same increments.  Its attitude and
    velocity after every N-th sample are its output.  Its numba helpers are
    kept in numba's disk cache under ``numba-smsfusion`` in the package's
    cache directory, as pyins's loop is.

Every adapter gives its peer exactly the increments the package's own
algorithms get; the errors are measured against the same exact solution by
:mod:`.verification`.

Public API
----------
:func:`pyins_integrator`, :func:`pyins_increments`, :func:`smsfusion_ins`.
"""

from __future__ import annotations

import os
import sys
import warnings

import numpy as np

from ...core.validation import positive
from .interface import Integrator, IntegratorError, step_increments

__all__ = ["pyins_integrator", "pyins_increments", "smsfusion_ins"]

_GYRO = ["gyro_x", "gyro_y", "gyro_z"]
_ACCEL = ["accel_x", "accel_y", "accel_z"]


def _pyins(sample_interval: float):
    try:
        import pyins.earth
    except ImportError:
        raise ImportError("pyins is not installed: it is a dependency of strapdown-analysis (the package index name is python-ins)") from None
    # pyins's loop reads the Earth rate when numba compiles it, once per process: zero then gives an inertial
    # navigation frame.  The compiled loop keeps it for the rest of the process (the adapters say so); its disk cache
    # is the package's own (_disk_cache), so other processes and other users of the installation see pyins unchanged.
    pyins.earth.RATE = 0.0
    import pandas as pd
    from pyins import strapdown

    _disk_cache(strapdown.integrate, _PYINS_CACHE)  # its compiled loop, as pyins.strapdown imports it

    def imu(gyro, accel):
        rows = np.hstack([gyro, accel])
        rows = np.vstack([np.zeros((1, 6)), rows])  # pyins's "before" sample: the record starts from rest
        return pd.DataFrame(rows, index=np.arange(rows.shape[0]) * sample_interval, columns=_GYRO + _ACCEL)

    return pd, strapdown, imu


#: Subdirectory of the package's cache directory holding pyins's loop compiled with a zero Earth rate.
_PYINS_CACHE = "numba-pyins-earth-rate-zero"
#: Subdirectory of the package's cache directory holding smsfusion's compiled helpers.
_SMSFUSION_CACHE = "numba-smsfusion"


def _disk_cache(dispatcher, subdirectory: str) -> None:
    """Keep ``dispatcher``'s machine code in numba's disk cache, in the package's own cache directory.

    The peers compile their numba functions without ``cache=True``, so every
    process would compile them again (seconds).  numba's cache is keyed by
    the function's source (a hash of its file) and the argument types, not by
    the module globals it froze at compile time (pyins's Earth rate): so the
    entries go to a directory only this module uses, in which pyins's loop is
    always compiled with the rate at zero, and nothing is written into the
    peer's installation (which may be read-only) or numba's user-wide cache.
    :func:`pyins_integrator` still checks the compiled loop at rest.  A
    dispatcher already caching, or a directory that cannot be written, leaves
    the dispatcher as it was (compiled in memory).

    Parameters
    ----------
    dispatcher : numba.core.registry.CPUDispatcher
        A ``numba.njit`` function of a peer.
    subdirectory : str
        Its directory under :func:`~strapdown.analysis.core.cache.cache_directory`.
    """
    from numba.core import caching

    from ...core.cache import cache_directory

    # numba's cache classes (numba.core.caching; older numba releases spell the locator with a leading underscore): without them, compiled in memory
    UserProvidedCacheLocator = getattr(caching, "UserProvidedCacheLocator", None) or getattr(caching, "_UserProvidedCacheLocator", None)
    CompileResultCacheImpl, FunctionCache, NullCache = (getattr(caching, name, None) for name in ("CompileResultCacheImpl", "FunctionCache", "NullCache"))
    if None in (UserProvidedCacheLocator, CompileResultCacheImpl, FunctionCache, NullCache):
        return

    if not isinstance(getattr(dispatcher, "_cache", None), NullCache):
        return  # already caching (an earlier call in this process)
    root = str(cache_directory() / subdirectory)

    class _Locator(UserProvidedCacheLocator):
        def __init__(self, py_func, py_file):  # noqa: D107 - numba's locator, with our directory
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno
            self._cache_path = os.path.join(root, self.get_suitable_cache_subpath(py_file))

        @classmethod
        def from_function(cls, py_func, py_file):
            return super(UserProvidedCacheLocator, cls).from_function(py_func, py_file)

    class _Impl(CompileResultCacheImpl):
        _locator_classes = [_Locator]

    class _Cache(FunctionCache):
        _impl_class = _Impl

    try:
        dispatcher._cache = _Cache(dispatcher.py_func)
    except (RuntimeError, OSError):  # numba found no writable location: compile in memory
        pass


def pyins_integrator(*, sample_interval: float = 0.0025) -> Integrator:
    """pyins's ``Integrator`` (the whole strapdown loop) as a black box, attitude only.

    Parameters
    ----------
    sample_interval : float, keyword-only
        Time between samples [s] given to pyins (its increments do not depend on it).

    Returns
    -------
    Integrator
        Direction-cosine-matrix output.

    Raises
    ------
    ImportError
        If pyins is not installed.
    IntegratorError
        If pyins's Earth rate was compiled in before it could be set to zero
        (its loop compiles once per process, at its first use).
    """
    h = positive(sample_interval, "sample_interval")
    pd, strapdown, imu = _pyins(h)
    start = pd.Series({"lat": 0.0, "lon": 0.0, "alt": 0.0, "VN": 0.0, "VE": 0.0, "VD": 0.0, "roll": 0.0, "pitch": 0.0, "heading": 0.0})

    def run(gyro, samples_per_step):
        n = gyro.shape[0]
        inc = strapdown.compute_increments_from_imu(imu(gyro, np.zeros_like(gyro)), "increment")
        with warnings.catch_warnings():  # pyins 1.0 passes pandas a keyword that pandas 3 deprecates
            warnings.filterwarnings("ignore", message="The copy keyword is deprecated")
            integ = strapdown.Integrator(start, with_altitude=False)
        integ.integrate(inc)
        return np.array(integ.mat_nb[1 : n + 1][samples_per_step - 1 :: samples_per_step])

    integrator = Integrator(run, output="dcm", name="pyins Integrator")
    rest = step_increments(integrator, np.zeros((4, 3)), 1).rotation
    if np.abs(rest).max() > 0.0:
        raise IntegratorError(
            f"pyins's Integrator turns by {np.abs(rest).max():.3g} rad per sample at rest: its Earth rate was compiled in before it could be set "
            "to zero (create this adapter before any other use of pyins's Integrator in the process)"
        )
    return integrator


def pyins_increments(*, sample_interval: float = 0.0025) -> Integrator:
    """pyins's ``compute_increments_from_imu`` (coning and sculling, one sample per step) as a black box.

    Parameters
    ----------
    sample_interval : float, keyword-only
        Time between samples [s] given to pyins (its increments do not depend on it).

    Returns
    -------
    Integrator
        Rotation-vector output with velocity; ``samples_per_step`` must be 1.

    Raises
    ------
    ImportError
        If pyins is not installed.
    """
    h = positive(sample_interval, "sample_interval")
    _, strapdown, imu = _pyins(h)

    def run(gyro, samples_per_step, accel):
        if samples_per_step != 1:
            raise ValueError(f"pyins forms one increment per sample: samples_per_step must be 1, got {samples_per_step}")
        inc = strapdown.compute_increments_from_imu(imu(gyro, accel), "increment")
        return inc[["theta_x", "theta_y", "theta_z"]].to_numpy(), inc[["dv_x", "dv_y", "dv_z"]].to_numpy()

    return Integrator(run, velocity=True, name="pyins compute_increments_from_imu")


def smsfusion_ins(*, sample_interval: float = 0.0025) -> Integrator:
    """smsfusion's ``StrapdownINS`` as a black box (attitude and velocity, one ``update`` per sample).

    Parameters
    ----------
    sample_interval : float, keyword-only
        Sample period h [s]: smsfusion runs at ``fs = 1/h`` and is given the
        mean rate ``p/h`` [rad/s] and mean specific force ``b/h`` [m/s²].

    Returns
    -------
    Integrator
        Quaternion output with velocity.

    Raises
    ------
    ImportError
        If smsfusion is not installed.
    """
    h = positive(sample_interval, "sample_interval")
    try:
        from smsfusion import StrapdownINS
    except ImportError:
        raise ImportError("smsfusion is not installed: it is a dependency of strapdown-analysis") from None
    from numba.core.registry import CPUDispatcher

    for value in vars(sys.modules[StrapdownINS.__module__]).values():  # the compiled helpers its update calls
        if isinstance(value, CPUDispatcher):
            _disk_cache(value, _SMSFUSION_CACHE)
    x0 = np.r_[np.zeros(6), 1.0, 0.0, 0.0, 0.0, np.zeros(6)]

    def run(gyro, samples_per_step, accel):
        ins = StrapdownINS(1.0 / h, x0, g=0.0)
        q, v = [], []
        # the mean specific force and rate of every sample, divided once (the same floats as row by row)
        for k, (f, w) in enumerate(zip(accel / h, gyro / h), start=1):
            ins.update(f, w)
            if k % samples_per_step == 0:
                q.append(ins.quaternion())
                v.append(ins.velocity())
        return np.array(q), np.array(v)

    return Integrator(run, output="quaternion", velocity=True, name="smsfusion StrapdownINS")
