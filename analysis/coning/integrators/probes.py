"""Designed inputs for a black-box integrator: blocks of increments, fed in records, and what each block gave.

A *block* is ``B`` steps of ``N`` samples, zero except where a probe puts
increments, with ``B = ⌈reach/N⌉ + 1``: the last step's window ``1 − reach …
N`` lies inside the block, so that an integrator that reads at most ``reach``
samples back sees nothing of the block before it.  The output of each block's
last step is read.  Blocks go to the integrator one after another, in records
of at most :data:`RECORD_SAMPLES` samples (one call each): the cost of a call
(a round trip to a child process, :mod:`.isolation`) is paid per record, not
per probe.

The round-off of an output is modelled by :class:`NoiseFloor`: a relative
noise ν (measured on the code itself by :func:`~.assumptions.precision`, or
float64's round-off by default) times the size of the output and of the input.

Public API
----------
:data:`RECORD_SAMPLES`, :data:`FLOAT64_NOISE`, :class:`NoiseFloor`, :class:`Prober`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...core.validation import as_int
from .interface import Integrator, step_increments

__all__ = ["RECORD_SAMPLES", "FLOAT64_NOISE", "NoiseFloor", "Prober"]

#: Largest record handed to the integrator in one call [samples].
RECORD_SAMPLES = 1 << 18
#: Round-off of float64 arithmetic relative to the size of a result, times a safety factor of 8 [dimensionless].
FLOAT64_NOISE = 8 * float(np.finfo(float).eps)


@dataclass(frozen=True)
class NoiseFloor:
    """The round-off of an integrator's outputs: ``ν (|y| + |x| + c)``.

    Attributes
    ----------
    relative : float
        ν, the noise relative to the size of the outputs and inputs
        [dimensionless] (:data:`FLOAT64_NOISE` for float64 code).
    attitude : bool
        The outputs are attitudes (O(1) state): ``c = 1``; otherwise ``c = 0``.
    """

    relative: float = FLOAT64_NOISE
    attitude: bool = False

    def floor(self, values: np.ndarray, scale) -> np.ndarray:
        """Round-off of each output row.

        Parameters
        ----------
        values : ndarray, shape (n, 3)
            Outputs [rad or m/s].
        scale : float or ndarray, shape (n,)
            Largest input of each row [rad or m/s].

        Returns
        -------
        ndarray, shape (n,)
        """
        return self.relative * (np.abs(values).max(axis=-1) + np.abs(scale) + (1.0 if self.attitude else 0.0))


class Prober:
    """Blocks of probe increments fed to an integrator in records; the last step of each block read.

    Parameters
    ----------
    integrator : Integrator
        The black box.
    samples : int
        N, samples per step.
    reach : int
        Samples before the step that a block keeps free of the block before it.

    Attributes
    ----------
    blocks : int
        Steps per block, ``⌈reach/N⌉ + 1``.
    length : int
        Samples per block.
    fed : int
        Samples fed so far (every call).
    calls : int
        Calls made so far.
    """

    def __init__(self, integrator: Integrator, samples: int, reach: int):
        self.integrator = integrator
        self.n = as_int(samples, "samples", minimum=1)
        self.reach = as_int(reach, "reach", minimum=0)
        self.blocks = -(-self.reach // self.n) + 1
        self.length = self.blocks * self.n
        self.fed = 0
        self.calls = 0

    def row(self, index: int) -> int:
        """Row of window index ``index`` (``1 − reach … N``) in a block.

        Parameters
        ----------
        index : int
            Sample index, ``1 − reach … N`` (≤ 0: before the last step).

        Returns
        -------
        int
        """
        return (self.blocks - 1) * self.n + index - 1

    def zeros(self, count: int) -> np.ndarray:
        """``count`` empty blocks, shape (count, length, 3).

        Parameters
        ----------
        count : int
            Blocks.

        Returns
        -------
        ndarray
        """
        return np.zeros((count, self.length, 3))

    def record(self, gyro, accel=None):
        """One call on a whole record: every step's rotation (steps, 3) and velocity (or None).

        Parameters
        ----------
        gyro : ndarray, shape (n_samples, 3)
            Gyro increments [rad].
        accel : ndarray, shape (n_samples, 3), optional
            Accelerometer increments [m/s].

        Returns
        -------
        rotation : ndarray, shape (steps, 3)
        velocity : ndarray, shape (steps, 3) or None
        """
        out = step_increments(self.integrator, gyro, self.n, accel)
        self.fed += gyro.shape[0]
        self.calls += 1
        return out.rotation, out.velocity

    def last_steps(self, gyro, accel=None):
        """Outputs of the last step of every block: rotation (nb, 3) and velocity (nb, 3) or None.

        Parameters
        ----------
        gyro : ndarray, shape (nb, length, 3)
            Gyro increments of each block [rad].
        accel : ndarray, shape (nb, length, 3), optional
            Accelerometer increments [m/s] (integrators with velocity; zero when omitted).

        Returns
        -------
        rotation : ndarray, shape (nb, 3)
        velocity : ndarray, shape (nb, 3) or None
        """
        per_call = max(1, RECORD_SAMPLES // self.length)
        rots, vels = [], []
        for start in range(0, gyro.shape[0], per_call):
            g = gyro[start : start + per_call]
            a = None if accel is None else accel[start : start + per_call]
            rot, vel = self.record(g.reshape(-1, 3), None if a is None else a.reshape(-1, 3))
            rots.append(rot.reshape(g.shape[0], self.blocks, 3)[:, -1])
            if vel is not None:
                vels.append(vel.reshape(g.shape[0], self.blocks, 3)[:, -1])
        return np.concatenate(rots), (np.concatenate(vels) if vels else None)
