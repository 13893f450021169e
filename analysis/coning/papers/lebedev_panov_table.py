"""The table of Lebedev & Panov (1989), section 6: attitude drift and apparent-velocity error.

The experiment of the paper: the dual regular precession (4.2)–(4.3) over
100 s at ν = 2π s⁻¹, ϑ = 10°, h = 0.01 s, for ε = −1 and 0.5 and three
variants of ν°, ϑ°, W_I(0), Λ(0); the nested algorithm (2.2) of order ρ = 4 or
6 and its dual extension (2.5) run beside the exact solution
(:func:`strapdown.analysis.coning.simulator.simulate`).  The table gives the
constant drift rate and ``|ΔW_E|``, ``|ΔW_I|`` at t = 100 s.

:func:`reproduce_table` sets every printed cell beside the simulation;
:func:`convergence_study` halves h for one cell (a method of order ρ shrinks
its error by 2^ρ); :func:`asymptotic_values` gives the same velocity errors
from the asymptotic error theory (5.1)–(5.6)
(:func:`strapdown.analysis.coning.drift_theory.asymptotic_velocity_error`),
which uses neither the simulator nor biquaternions.

References
----------
Lebedev & Panov (1989), eqs. (2.2), (2.5), (3.5), (4.2)–(4.7), (5.1)–(5.6), section 6.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cache
from typing import NamedTuple

import numpy as np

from ....derivations.coning import published as P
from ....derivations.coning.registry import get
from ...core.units import deg_per_h, rad
from ...core.validation import as_int, positive
from ..drift_theory import asymptotic_velocity_error
from ..precession import RegularPrecession, exact_state
from ..simulator import simulate

__all__ = [
    "QUANTITIES",
    "VariantState",
    "LebedevPanovSetup",
    "lebedev_panov_setup",
    "CellValues",
    "run_values",
    "CellComparison",
    "TableReproduction",
    "reproduce_table",
    "ConvergenceStudy",
    "convergence_study",
    "VelocityErrors",
    "asymptotic_values",
    "theory_agreement",
    "CellEvidence",
    "cell_evidence",
]

#: The quantities of the table: the drift rate [rad/s] and ``|ΔW_E|``, ``|ΔW_I|`` at the end of the run [m/s].
QUANTITIES = ("drift", "dW_E", "dW_I")


@dataclass(frozen=True)
class VariantState:
    """The translation and initial state of one variant.

    Attributes
    ----------
    number : int
        Variant 1–3.
    nu_dual : float
        ν° [m/s²].
    nutation_dual : float
        ϑ° [m/s].
    w_inertial0 : tuple of float
        W_I(0) [m/s].
    attitude0 : tuple of float
        Λ(0), unit quaternion (E → I).
    """

    number: int
    nu_dual: float
    nutation_dual: float
    w_inertial0: tuple
    attitude0: tuple


@dataclass(frozen=True)
class LebedevPanovSetup:
    """The experiment of section 6, in SI units.

    Attributes
    ----------
    nu : float
        ν [rad/s].
    nutation : float
        ϑ [rad].
    sample_interval : float
        h [s].
    duration : float
        Length of the run [s].
    variants : tuple of VariantState
        Variants 1–3.
    """

    nu: float
    nutation: float
    sample_interval: float
    duration: float
    variants: tuple

    def variant(self, number: int) -> VariantState:
        """Variant ``number``.

        Parameters
        ----------
        number : int
            1, 2 or 3.

        Returns
        -------
        VariantState

        Raises
        ------
        ValueError
            For an unknown variant.
        """
        for v in self.variants:
            if v.number == number:
                return v
        raise ValueError(f"Expected `variant` among {', '.join(str(v.number) for v in self.variants)}, got {number!r}")

    def motion(self, eps: float, number: int) -> RegularPrecession:
        """The dual regular precession (4.2) of variant ``number`` at ``eps``.

        Parameters
        ----------
        eps : float
            ε = μ/ν [-].
        number : int
            Variant 1–3.

        Returns
        -------
        RegularPrecession
        """
        v = self.variant(number)
        return RegularPrecession(eps, self.nu, self.nutation, v.nu_dual, v.nutation_dual)


def lebedev_panov_setup() -> LebedevPanovSetup:
    """The experiment as printed in section 6, converted to SI units.

    Returns
    -------
    LebedevPanovSetup

    Examples
    --------
    >>> s = lebedev_panov_setup()
    >>> s.duration, s.sample_interval, [v.number for v in s.variants]
    (100.0, 0.01, [1, 2, 3])
    """
    c = P.LEBEDEV_PANOV_CONDITIONS
    nutation = rad(c.nutation_deg)
    half = nutation / 2
    tilted = (math.cos(half), math.sin(half), 0.0, 0.0)
    variants = tuple(
        VariantState(v.number, v.nu_dual, v.nutation_dual, tuple(v.w_inertial0), tilted if v.tilted_start else (1.0, 0.0, 0.0, 0.0)) for v in c.variants
    )
    return LebedevPanovSetup(2 * math.pi * c.spin_freq_hz, nutation, c.sample_interval, c.duration, variants)


class CellValues(NamedTuple):
    """What the table reports for one run.

    Attributes
    ----------
    drift : float
        Constant drift rate of the attitude [rad/s].
    dW_E : float
        ``|ΔW_E|`` at the end of the run [m/s].
    dW_I : float
        ``|ΔW_I|`` at the end of the run [m/s].
    """

    drift: float
    dW_E: float
    dW_I: float


@cache
def _run_values(order: int, eps: float, variant: int, sample_interval: float) -> CellValues:
    setup = lebedev_panov_setup()
    v = setup.variant(variant)
    r = simulate(get(f"lebedev-panov-{order}"), setup.motion(eps, variant), sample_interval, setup.duration,
                 attitude0=v.attitude0, w_inertial0=v.w_inertial0, velocity=True)  # fmt: skip
    return CellValues(float(np.linalg.norm(r.drift, axis=-1)), float(r.final_dw_body), float(r.final_dw_inertial))


def run_values(order: int, eps: float, variant: int, *, sample_interval: float | None = None) -> CellValues:
    """Drift and velocity errors of the order-ρ algorithm (2.2)/(2.5) in one variant, by parallel computation.

    Parameters
    ----------
    order : int
        ρ: 2, 4 or 6 (registry ``lebedev-panov-<ρ>``).
    eps : float
        ε = μ/ν [-].
    variant : int
        Variant 1–3.
    sample_interval : float, keyword-only, optional
        h [s]; default the paper's 0.01 s.

    Returns
    -------
    CellValues

    Raises
    ------
    ValueError
        For an unknown order or variant, or a non-positive ``sample_interval``.
    """
    setup = lebedev_panov_setup()
    setup.variant(variant)
    order = as_int(order, "order")
    if order not in (2, 4, 6):
        raise ValueError(f"Expected `order` among 2, 4, 6, got {order}")
    h = setup.sample_interval if sample_interval is None else positive(sample_interval, "sample_interval")
    return _run_values(order, float(eps), variant, h)


def _printed_unit(quantity: str, value: float) -> float:
    return deg_per_h(value) if quantity == "drift" else value


class CellComparison(NamedTuple):
    """One printed cell beside the simulation of every variant it stands for.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.LebedevPanovCell
        The printed cell (deg/h or m/s).
    ours : tuple of float
        The simulated value for each of ``printed.variants`` [rad/s for the drift, m/s for ΔW].
    relative_differences : tuple of float
        ``ours / printed − 1`` per variant (in the printed unit).
    """

    printed: P.LebedevPanovCell
    ours: tuple
    relative_differences: tuple

    @property
    def worst(self) -> float:
        """The relative difference of largest magnitude."""
        return max(self.relative_differences, key=abs)


@dataclass(frozen=True)
class TableReproduction:
    """The whole table beside the simulation.

    Attributes
    ----------
    cells : tuple of CellComparison
        In the order of the printed table.
    tolerance : float
        Relative difference accepted as reproduced.
    """

    cells: tuple
    tolerance: float

    @property
    def reproduced(self) -> tuple:
        """Cells whose worst difference is within the tolerance."""
        return tuple(c for c in self.cells if abs(c.worst) <= self.tolerance)

    @property
    def not_reproduced(self) -> tuple:
        """Cells whose worst difference exceeds the tolerance."""
        return tuple(c for c in self.cells if abs(c.worst) > self.tolerance)

    @property
    def worst_reproduced(self) -> float:
        """Largest ``|difference|`` among the reproduced cells."""
        return max(abs(c.worst) for c in self.reproduced)


@cache
def _reproduce_table(tolerance: float) -> TableReproduction:
    cells = []
    for cell in P.LEBEDEV_PANOV_TABLE:
        ours = tuple(getattr(run_values(cell.order, cell.eps, v), cell.quantity) for v in cell.variants)
        rel = tuple(_printed_unit(cell.quantity, o) / cell.value - 1.0 for o in ours)
        cells.append(CellComparison(cell, ours, rel))
    return TableReproduction(tuple(cells), tolerance)


def reproduce_table(*, tolerance: float = 0.02) -> TableReproduction:
    """Every printed cell of the table of section 6 beside the parallel computation.

    Parameters
    ----------
    tolerance : float, keyword-only
        Relative difference accepted as reproduced.

    Returns
    -------
    TableReproduction

    References
    ----------
    Lebedev & Panov (1989), section 6, table.
    """
    return _reproduce_table(positive(tolerance, "tolerance"))


class ConvergenceStudy(NamedTuple):
    """One quantity of one run at successively halved sample intervals.

    Attributes
    ----------
    sample_intervals : tuple of float
        h [s].
    values : tuple of float
        The quantity at each h [rad/s or m/s].
    orders : tuple of float
        ``log2`` of successive ratios: the observed order (ρ for a method of order ρ).
    """

    sample_intervals: tuple
    values: tuple
    orders: tuple


@cache
def convergence_study(quantity: str, order: int, eps: float, variant: int, sample_intervals: tuple = (0.02, 0.01, 0.005)) -> ConvergenceStudy:
    """Halve h for one cell and read off the observed order.

    Parameters
    ----------
    quantity : str
        One of :data:`QUANTITIES`.
    order : int
        ρ of the algorithm.
    eps : float
        ε = μ/ν [-].
    variant : int
        Variant 1–3.
    sample_intervals : tuple of float
        h values [s], each half the one before.

    Returns
    -------
    ConvergenceStudy

    Raises
    ------
    ValueError
        For an unknown quantity, order or variant.
    """
    if quantity not in QUANTITIES:
        raise ValueError(f"Expected `quantity` among {', '.join(QUANTITIES)}, got {quantity!r}")
    values = [getattr(run_values(order, eps, variant, sample_interval=h), quantity) for h in sample_intervals]
    orders = tuple(float(np.log2(values[i] / values[i + 1])) for i in range(len(values) - 1))
    return ConvergenceStudy(tuple(sample_intervals), tuple(values), orders)


class VelocityErrors(NamedTuple):
    """``|ΔW_E|`` and ``|ΔW_I|`` at the end of the run.

    Attributes
    ----------
    dW_E : float
        [m/s].
    dW_I : float
        [m/s].
    """

    dW_E: float
    dW_I: float


@cache
def asymptotic_values(order: int, eps: float, variant: int) -> VelocityErrors:
    """``|ΔW_E|``, ``|ΔW_I|`` at the end of the run from the asymptotic error theory (5.1)–(5.6), no simulation.

    Parameters
    ----------
    order : int
        ρ of the algorithm (2.2)/(2.5).
    eps : float
        ε = μ/ν [-].
    variant : int
        Variant 1–3.

    Returns
    -------
    VelocityErrors

    References
    ----------
    Lebedev & Panov (1989), eqs. (3.5), (5.1)–(5.6).
    """
    setup = lebedev_panov_setup()
    v = setup.variant(variant)
    alg = get(f"lebedev-panov-{order}")
    err = asymptotic_velocity_error(alg, setup.duration, eps=eps, nu=setup.nu, nutation=setup.nutation, nu_dual=v.nu_dual,
                                    nutation_dual=v.nutation_dual, step=alg.samples * setup.sample_interval)  # fmt: skip
    w_body = exact_state(setup.motion(eps, variant), setup.duration, v.attitude0, v.w_inertial0).w_body
    return VelocityErrors(float(np.linalg.norm(err.dw_body(w_body))), float(err.dw_inertial))


def theory_agreement(order: int) -> float:
    """Largest ``|theory / simulation − 1|`` over the velocity cells of order ``order``, every variant.

    Parameters
    ----------
    order : int
        ρ of the algorithm.

    Returns
    -------
    float
    """
    return max(
        abs(getattr(asymptotic_values(order, c.eps, v), c.quantity) / getattr(run_values(order, c.eps, v), c.quantity) - 1.0)
        for c in P.LEBEDEV_PANOV_TABLE
        if c.order == order and c.quantity != "drift"
        for v in c.variants
    )


class CellEvidence(NamedTuple):
    """Everything that decides one variant of a printed cell that does not reproduce.

    Attributes
    ----------
    printed : strapdown.derivations.coning.published.LebedevPanovCell
        The printed cell (m/s).
    variant : int
        The variant.
    ours : float
        The simulated value at the paper's h [m/s].
    convergence : ConvergenceStudy
        The value at h = 0.02, 0.01, 0.005 s and the observed orders.
    theory : float
        The same quantity from the asymptotic error theory [m/s].
    """

    printed: P.LebedevPanovCell
    variant: int
    ours: float
    convergence: ConvergenceStudy
    theory: float

    @property
    def printed_over_ours(self) -> float:
        """printed / simulated."""
        return self.printed.value / self.ours

    @property
    def theory_over_ours(self) -> float:
        """theory / simulated."""
        return self.theory / self.ours

    @property
    def printed_over_theory(self) -> float:
        """printed / theory."""
        return self.printed.value / self.theory


def cell_evidence(reproduction: TableReproduction) -> tuple:
    """Convergence study and asymptotic theory for every variant of every cell that does not reproduce.

    Parameters
    ----------
    reproduction : TableReproduction
        From :func:`reproduce_table`.

    Returns
    -------
    tuple of CellEvidence
        In the order of the table, variant by variant.
    """
    out = []
    for c in reproduction.not_reproduced:
        p = c.printed
        for v, ours in zip(p.variants, c.ours):
            theory = getattr(asymptotic_values(p.order, p.eps, v), p.quantity)
            out.append(CellEvidence(p, v, ours, convergence_study(p.quantity, p.order, p.eps, v), theory))
    return tuple(out)
