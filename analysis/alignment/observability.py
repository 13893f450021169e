"""Observability of the alignment error states: the rank, the unobservable directions in words, the degree.

A *problem* is a linear error model (:mod:`~strapdown.analysis.alignment.error_model`) that may change at
given instants (a block turned on a table into several positions), with the
prior, the measurement noise and the epoch of the filter that would estimate
it.  :func:`observability` answers three questions about it:

rank
    The dimension of the observable subspace.  For one segment it is found by
    the orthogonal staircase reduction of the pair ``(Aᵀ, Hᵀ)`` (Van Dooren
    1981): each step takes the directions the measurements (or the coupling
    from the directions found so far) reach, by an SVD with a rank decision at
    :data:`RTOL` of the (unit) norm, and turns the rest by an orthogonal
    similarity, so rounding stays at the size of the model's own (no powers
    of A, no division by small couplings); the directions never reached are
    the unobservable subspace.  The states are first put in units of their
    prior standard deviations, where the couplings that decide the rank are of
    comparable size.  For a piecewise-constant model (a block turned into
    several positions) a state is unobservable when it is unobservable in the
    first segment and its transition into every later segment is unobservable
    there: the null space of the stacked conditions ``(I − N_j N_jᵀ) Φ_{0→j}``
    (the total observability matrix of Goshen-Meskin & Bar-Itzhack 1992).
unobservable directions
    A basis of the unobservable subspace in reduced row-echelon form, pivots
    taken in the order attitude, velocity, position, sensor biases, rocking
    states: each direction says which combination of errors the
    measurements cannot tell from one radian of the pivot state (for the
    stationary model, the classical pairs: north tilt ↔ east accelerometer
    bias, east tilt ↔ north accelerometer bias, azimuth ↔ east gyro bias;
    Bar-Itzhack & Berman 1988).  The partners are ranked by their size in
    equivalent angles.
degree of observability
    the standard deviation of each state after the horizon relative to its
    prior (the Kalman covariance of the problem, computed by filterpy), and the
    eigenvalues of the Gramian (the information per direction).

References
----------
Van Dooren, P., "The generalized eigenstructure problem in linear system
theory", *IEEE Trans. Autom. Control* 26(1), 1981, 111–129 (the staircase form).
Bar-Itzhack, I. Y., Berman, N., "Control theoretic approach to inertial
navigation systems", *J. Guid. Control Dyn.* 11(3), 1988, 237–245.
Goshen-Meskin, D., Bar-Itzhack, I. Y., "Observability analysis of piece-wise
constant systems", *IEEE Trans. Aerosp. Electron. Syst.* 28(4), 1992, 1056–1075.

Public API
----------
BodyRotation, ObservabilityProblem, UnobservableDirection, ObservabilityResult,
stationary_problem, rocking_problem, multi_position_problem, observability,
observability_gramian, unobservable_subspace
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.linalg import expm

from ..core import budget, kalman
from ..core.validation import as_array, as_float, positive
from .error_model import ErrorModel, alignment_error_model, navigation_error_model, state_labels
from .fine import FilterTuning, assumed_disturbance
from .imu import Scenario
from .tilt_attitude import attitude_matrix

__all__ = [
    "BodyRotation",
    "ObservabilityProblem",
    "UnobservableDirection",
    "ObservabilityResult",
    "stationary_problem",
    "rocking_problem",
    "multi_position_problem",
    "observability",
    "observability_gramian",
    "unobservable_subspace",
    "PIVOT_ORDER",
    "RTOL",
    "GRAMIAN_STEP",
]

#: Rank decisions of the staircase: singular values below RTOL of the (unit) norm count as zero.
RTOL = 1e-10
#: Longest sub-interval of the Gramian's sum [s] (Van Loan's formula over a long interval loses damped modes to cancellation).
GRAMIAN_STEP = 5.0
#: Pivot order of the unobservable directions: attitude first, then velocity, position, biases, the rest.
PIVOT_ORDER = ("phi", "dv", "dp", "eps", "acc")
_AXES = {"x": 0, "y": 1, "z": 2}


@dataclass(frozen=True)
class BodyRotation:
    """The block turned about one of its own axes at an instant (a turntable step).

    Parameters
    ----------
    time : float
        When [s], after the start.
    axis : str
        Body axis, ``"x"``, ``"y"`` or ``"z"``.
    angle : float
        Rotation angle [rad], right-handed about the axis.
    """

    time: float
    axis: str
    angle: float

    def __post_init__(self):
        object.__setattr__(self, "time", positive(self.time, "time"))
        if self.axis not in _AXES:
            raise ValueError(f"Expected `axis` in ('x', 'y', 'z'), got {self.axis!r}")
        object.__setattr__(self, "angle", as_float(self.angle, "angle"))

    def matrix(self) -> np.ndarray:
        """The rotation of the body, ``R_axis(angle)`` (3, 3)."""
        c, s = math.cos(self.angle), math.sin(self.angle)
        i = _AXES[self.axis]
        j, k = (i + 1) % 3, (i + 2) % 3
        R = np.eye(3)
        R[j, j], R[j, k], R[k, j], R[k, k] = c, -s, s, c
        return R


@dataclass(frozen=True)
class ObservabilityProblem:
    """A piecewise-constant error model with the prior and noise of the filter that would estimate it.

    Attributes
    ----------
    kind : str
        What it models (``"stationary"``, ``"rocking"``, ``"multi-position"``, ``"recorded"``).
    models : tuple of ErrorModel
        The model of each segment (same states and measurements).
    durations : tuple of float
        Duration of each segment [s].
    P0 : ndarray
        ``(n, n)`` prior covariance.
    R : ndarray
        ``(m, m)`` measurement noise covariance per epoch.
    epoch : float
        Measurement interval [s].
    latitude : float
        Latitude [rad].
    """

    kind: str
    models: tuple
    durations: tuple
    P0: np.ndarray
    R: np.ndarray
    epoch: float
    latitude: float

    def __post_init__(self):
        if not self.models or len(self.models) != len(self.durations):
            raise ValueError(f"Expected one duration per model, got {len(self.models)} models and {len(self.durations)} durations")
        first = self.models[0]
        for m in self.models:
            if not isinstance(m, ErrorModel):
                raise TypeError(f"Expected `models` of ErrorModel, got {type(m).__name__}")
            if m.names != first.names or m.H.shape != first.H.shape:
                raise ValueError("Expected every segment with the same states and measurements")
        object.__setattr__(self, "durations", tuple(positive(d, "durations") for d in self.durations))
        object.__setattr__(self, "epoch", positive(self.epoch, "epoch"))

    @property
    def names(self) -> tuple:
        """State names."""
        return self.models[0].names

    @property
    def duration(self) -> float:
        """The whole horizon [s]."""
        return float(sum(self.durations))


@dataclass(frozen=True)
class UnobservableDirection:
    """One basis direction of the unobservable subspace, normalised on its pivot state.

    Attributes
    ----------
    state : str
        The pivot state (component 1).
    components : dict
        State name → component, in the state's SI unit per unit of the pivot
        (zero components left out).
    partners : tuple of str
        The other states of the direction, largest in equivalent angles first.
    text : str
        The direction in words, ``"azimuth ↔ east gyro bias"``.
    """

    state: str
    components: dict
    partners: tuple
    text: str


@dataclass(frozen=True)
class ObservabilityResult:
    """What the measurements can tell about the states of a problem.

    Attributes
    ----------
    kind : str
        The problem's kind.
    names : tuple of str
        State names.
    labels : tuple of str
        The states in words.
    rank : int
        Dimension of the observable subspace.
    unobservable : tuple of UnobservableDirection
        A basis of the unobservable subspace.
    posterior_ratio : ndarray
        ``(n,)`` standard deviation of each state after the horizon over its prior [1].
    gramian_eigenvalues : ndarray
        ``(n,)`` eigenvalues of the observability Gramian over the horizon
        (:func:`observability_gramian`, states in units of their prior
        standard deviations): the information the measurements add along each
        eigenvector, in units of the prior's information [1], largest first.
        The Gramian is symmetric positive semi-definite, so they are its
        singular values too in exact arithmetic; those of unobservable
        directions are zero to rounding and may come out slightly negative.
        With no process noise, the posterior covariance in the same units is
        ``(I + W)⁻¹``.
    duration : float
        Horizon [s].
    latitude : float
        Latitude [rad].
    """

    kind: str
    names: tuple
    labels: tuple
    rank: int
    unobservable: tuple
    posterior_ratio: np.ndarray
    gramian_eigenvalues: np.ndarray
    duration: float
    latitude: float

    @property
    def dim(self) -> int:
        """State dimension."""
        return len(self.names)

    def little_learned(self, threshold: float = 0.9) -> tuple:
        """The states (names) of which the filter has learned little within the horizon: ``posterior_ratio ≥ threshold``.

        Rank and degree differ: a state outside every unobservable direction
        is observable *given time*, and may still be almost unlearned after
        the horizon.

        Parameters
        ----------
        threshold : float
            Standard deviation over the prior at or above which a state counts as little learned [1].

        Returns
        -------
        tuple of str
        """
        t = as_float(threshold, "threshold")
        return tuple(n for n, x in zip(self.names, self.posterior_ratio) if np.isfinite(x) and x >= t)

    @property
    def pairs(self) -> tuple:
        """``(pivot, leading partner)`` of each unobservable direction, in words."""
        labels = dict(zip(self.names, self.labels))
        return tuple((labels[d.state], labels[d.partners[0]] if d.partners else "") for d in self.unobservable)


def _prior(names, tuning: FilterTuning) -> np.ndarray:
    per = {
        "phi_N": tuning.prior_tilt,
        "phi_E": tuning.prior_tilt,
        "phi_D": tuning.prior_heading,
        "dv": tuning.prior_velocity,
        "dp": 1.0,
        "eps": tuning.gyro_bias,
        "acc": tuning.accel_bias,
    }
    sig = [per.get(n, per.get(n.partition("_")[0], 0.0)) for n in names]
    return np.diag(np.square(sig))


def stationary_problem(latitude, *, attitude=(0.0, 0.0, 0.0), tuning: FilterTuning | None = None, duration: float = 300.0) -> ObservabilityProblem:
    """The twelve-state model of a block at rest, with zero-velocity measurements.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    attitude : array_like, keyword-only
        Stable (ψ0, β0, γ0) [rad] (the NED-resolved biases make the result independent of it).
    tuning : FilterTuning, optional, keyword-only
        Prior, noise and epoch (default :class:`strapdown.analysis.alignment.fine.FilterTuning`).
    duration : float, keyword-only
        Horizon of the degree of observability [s].

    Returns
    -------
    ObservabilityProblem
    """
    tuning = FilterTuning() if tuning is None else tuning
    a = as_array(attitude, "attitude", last=3).reshape(3)
    sc = Scenario(latitude, a[0], a[1], a[2], duration=duration)
    model = alignment_error_model(sc, tuning)
    P0 = _prior(model.names, tuning)
    return ObservabilityProblem("stationary", (model,), (sc.duration,), P0, tuning.measurement_noise**2 * np.eye(3), tuning.epoch, sc.latitude)


def rocking_problem(scenario: Scenario, tuning: FilterTuning | None = None) -> ObservabilityProblem:
    """The model of the fine-alignment filter on a rocking base: the rocking states seen through the lever arm.

    Parameters
    ----------
    scenario : Scenario
        Place, stable attitude, rocking, lever arm and horizon (its duration).
    tuning : FilterTuning, optional
        Prior, noise and epoch; its disturbance model is replaced by the
        shaping filter of the scenario's rocking
        (:func:`strapdown.analysis.alignment.fine.assumed_disturbance`).

    Returns
    -------
    ObservabilityProblem
    """
    from dataclasses import replace

    tuning = FilterTuning() if tuning is None else tuning
    tuning = replace(tuning, disturbance=assumed_disturbance(scenario.motion, scenario, kind="shaping"))
    model = alignment_error_model(scenario, tuning)
    P0 = _prior(model.names, tuning)
    axes = model.names[12::2]
    dist = tuning.disturbance
    w = 2.0 * math.pi / dist.period
    for k, name in enumerate(axes):
        s = dist.sigma[("psi_r", "beta_r", "gamma_r").index(name)]
        P0[12 + 2 * k, 12 + 2 * k], P0[13 + 2 * k, 13 + 2 * k] = s * s, (w * s) ** 2
    return ObservabilityProblem("rocking", (model,), (scenario.duration,), P0, tuning.measurement_noise**2 * np.eye(3), tuning.epoch, scenario.latitude)


def multi_position_problem(latitude, rotations, duration: float, *, attitude=(0.0, 0.0, 0.0), tuning: FilterTuning | None = None) -> ObservabilityProblem:
    """A block at rest turned into several positions: biases in body axes, the attitude changing at each rotation.

    Parameters
    ----------
    latitude : float
        Latitude φ [rad].
    rotations : sequence of BodyRotation
        The turns, in time order, inside the horizon.
    duration : float
        Horizon [s].
    attitude : array_like, keyword-only
        Initial (ψ0, β0, γ0) [rad].
    tuning : FilterTuning, optional, keyword-only
        Prior, noise and epoch.

    Returns
    -------
    ObservabilityProblem

    Raises
    ------
    ValueError
        For rotations out of order or outside the horizon.
    """
    tuning = FilterTuning() if tuning is None else tuning
    T = positive(duration, "duration")
    rots = tuple(rotations)
    for r in rots:
        if not isinstance(r, BodyRotation):
            raise TypeError(f"Expected `rotations` of BodyRotation, got {type(r).__name__}")
    times = [r.time for r in rots]
    if times != sorted(times) or (times and (times[-1] >= T or len(set(times)) < len(times))):
        raise ValueError(f"Expected `rotations` at distinct increasing times inside (0, {T:g}) s, got {times}")
    C = attitude_matrix(as_array(attitude, "attitude", last=3).reshape(3))
    edges = [0.0, *times, T]
    models = []
    for j in range(len(edges) - 1):
        models.append(navigation_error_model(latitude, attitude=C, biases="body", gyro_noise=tuning.gyro_noise, accel_noise=tuning.accel_noise))
        if j < len(rots):
            C = C @ rots[j].matrix()
    P0 = _prior(models[0].names, tuning)
    return ObservabilityProblem("multi-position", tuple(models), tuple(np.diff(edges)), P0, tuning.measurement_noise**2 * np.eye(3), tuning.epoch, as_float(latitude, "latitude"))


def _check_work(problem: ObservabilityProblem, limits, *, covariance: bool) -> None:
    """Refuse a horizon whose covariance run or Gramian exceeds ``limits``, and an epoch longer than the horizon."""
    T, epoch = problem.duration, problem.epoch
    if epoch > T:
        raise ValueError(f"Expected the filter's `epoch` at most the horizon `duration` = {T:g} s, got {epoch:g} s (no measurement would fall inside)")
    steps = [max(1.0, round(d / epoch)) for d in problem.durations]
    gram = sum(max(1.0, math.ceil(d / GRAMIAN_STEP)) for d in problem.durations)
    n, m = problem.P0.shape[0], problem.R.shape[0]
    what = f"`duration` = {T:.3g} s of {problem.kind} observability ({sum(steps):.3g} epochs of {epoch:g} s (`epoch`), {n} states)"
    est = budget.observability(sum(steps) if covariance else 0.0, max(steps) if covariance else 0.0, gram, states=n, measurements=m, what=what)
    budget.check(est, limits)


def observability_gramian(problem: ObservabilityProblem, *, limits: budget.Limits | None = None) -> np.ndarray:
    """``W = ∫ Φᵀ Hᵀ N⁻¹ H Φ dt`` over the horizon, states in units of their prior standard deviations.

    Parameters
    ----------
    problem : ObservabilityProblem
        The model, prior and measurement noise.
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (default 2 GB, 300 s); a horizon
        beyond them raises :class:`~strapdown.analysis.core.budget.BudgetExceeded`.

    Returns
    -------
    ndarray
        ``(n, n)`` symmetric; its eigenvalues are the information the
        measurements add along their eigenvectors, in units of the prior's.

    Raises
    ------
    ValueError
        For an epoch longer than the horizon, or a horizon beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).

    References
    ----------
    Goshen-Meskin & Bar-Itzhack (1992) (piecewise-constant systems); Van Loan (1978)
    (each sub-interval, :func:`strapdown.analysis.core.kalman.discretise`).
    """
    _check_work(problem, limits, covariance=False)
    return _gramian(problem)


def _gramian(problem: ObservabilityProblem) -> np.ndarray:
    S = _prior_scales(problem)
    Ninv = np.linalg.inv(problem.R * problem.epoch)  # measurement noise density [unit² s]
    n = len(S)
    W = np.zeros((n, n))
    Phi0 = np.eye(n)
    for m, d in zip(problem.models, problem.durations):
        A = m.A * S[None, :] / S[:, None]
        Hs = m.H * S[None, :]
        k = max(1, int(math.ceil(d / GRAMIAN_STEP)))
        h = d / k
        _, Wh = kalman.discretise(A.T, Hs.T @ Ninv @ Hs, h)  # ∫_0^h e^{Aᵀs} Hᵀ N⁻¹ H e^{As} ds
        Fh = expm(A * h)
        for _ in range(k):
            W += Phi0.T @ Wh @ Phi0
            Phi0 = Fh @ Phi0
    return 0.5 * (W + W.T)


def _null(X: np.ndarray, tol: float) -> np.ndarray:
    """Orthonormal basis of the null space of ``X`` (columns); singular values at most ``tol`` count as zero."""
    k = X.shape[1]
    if X.shape[0] == 0 or k == 0:
        return np.eye(k)
    _, s, vh = np.linalg.svd(X, full_matrices=True)
    return vh[int(np.sum(s > tol)) :].T


def _staircase(A: np.ndarray, H: np.ndarray, tol: float) -> np.ndarray:
    """Unobservable subspace of one block by the orthogonal staircase of ``(Aᵀ, Hᵀ)``."""
    norms = np.linalg.norm(H, axis=1)
    H = H[norms > 0] / norms[norms > 0, None]
    scale = float(np.linalg.norm(A, 2)) or 1.0
    Ar = A.T / scale  # the staircase of the controllable part of (Aᵀ, Hᵀ): the observable directions of (A, H)
    Br = H.T
    V = np.eye(A.shape[0])
    while V.shape[1]:
        u, s, _ = np.linalg.svd(Br, full_matrices=True)
        rho = int(np.sum(s > tol))
        if rho == 0:
            break
        Ar = u.T @ Ar @ u
        V = V @ u
        Br = Ar[rho:, :rho]  # how the directions just reached drive the rest
        Ar = Ar[rho:, rho:]
        V = V[:, rho:]
    return V


def _blocks(A: np.ndarray) -> list:
    """Groups of states A does not couple (connected components), merged where their spectra meet."""
    from scipy.sparse.csgraph import connected_components

    n, labels = connected_components((A != 0) | (A.T != 0), directed=False)
    groups = [np.flatnonzero(labels == k) for k in range(n)]
    spectra = [np.linalg.eigvals(A[np.ix_(g, g)]) for g in groups]
    merged = True
    while merged:
        merged = False
        for i in range(len(groups)):
            for j in range(i + 1, len(groups)):
                d = np.abs(spectra[i][:, None] - spectra[j][None, :])
                size = np.maximum(np.abs(spectra[i])[:, None], np.abs(spectra[j])[None, :])
                if np.any(d <= 1e-9 * np.maximum(size, 1e-300)):
                    groups[i] = np.concatenate([groups[i], groups.pop(j)])
                    spectra[i] = np.concatenate([spectra[i], spectra.pop(j)])
                    merged = True
                    break
            if merged:
                break
    return groups


def unobservable_subspace(A, H, *, tol: float = RTOL) -> np.ndarray:
    """Orthonormal basis of the unobservable subspace of ``(A, H)``, block by block, by the orthogonal staircase.

    The states are split into groups that A does not couple; groups whose
    spectra meet are kept together (identical oscillators sharing the output
    can cancel in it).  Groups with disjoint spectra are observable together
    exactly when each is observable alone (the parallel connection of systems
    with disjoint spectra), so each group is reduced on its own, at the scale
    of its own dynamics: a stiff block (a rocking oscillator) then does not
    swamp the slow couplings of another (the Earth rate).

    Parameters
    ----------
    A : array_like
        ``(n, n)`` dynamics (scale the states first so that the couplings inside a block are comparable).
    H : array_like
        ``(m, n)`` measurement matrix.
    tol : float, keyword-only
        Rank decisions at ``tol`` times the block's norm (A and the rows of H are scaled to unit norm).

    Returns
    -------
    ndarray
        ``(n, k)``, k = n − rank.

    References
    ----------
    Van Dooren (1981) (the staircase form, here of the dual pair ``(Aᵀ, Hᵀ)``);
    Chen, C.-T., *Linear System Theory and Design*, 3rd ed., Oxford, 1999,
    sec. 6.3 (observability of a parallel connection: the PBH test mode by mode).

    Examples
    --------
    A double integrator seen through its position is observable, through its velocity not:

    >>> A = np.array([[0.0, 1.0], [0.0, 0.0]])
    >>> unobservable_subspace(A, [[1.0, 0.0]]).shape[1], unobservable_subspace(A, [[0.0, 1.0]]).shape[1]
    (0, 1)
    """
    A = np.atleast_2d(np.asarray(A, dtype=float))
    H = np.atleast_2d(np.asarray(H, dtype=float))
    n = A.shape[0]
    parts = []
    for g in _blocks(A):
        V = _staircase(A[np.ix_(g, g)], H[:, g], tol)
        if V.shape[1]:
            Z = np.zeros((n, V.shape[1]))
            Z[g] = V
            parts.append(Z)
    return np.concatenate(parts, axis=1) if parts else np.zeros((n, 0))


def _unobservable(problem: ObservabilityProblem, S: np.ndarray) -> np.ndarray:
    """Basis (prior-scaled states) of the states unobservable over every segment of ``problem``."""
    n = len(S)
    rows, Phi = [], np.eye(n)
    for m, d in zip(problem.models, problem.durations):
        A = m.A * S[None, :] / S[:, None]
        N = unobservable_subspace(A, m.H * S[None, :])
        if len(problem.models) == 1:
            return N
        C = Phi - N @ (N.T @ Phi)  # x must land in this segment's unobservable subspace
        norm = float(np.linalg.norm(Phi, 2))
        rows.append(C / norm)
        Phi = expm(A * d) @ Phi
    return _null(np.concatenate(rows), RTOL)


def _prior_scales(problem: ObservabilityProblem) -> np.ndarray:
    S = np.sqrt(np.diag(problem.P0))
    return np.where(S > 0.0, S, problem.models[0].scales)


def _rref_directions(Z: np.ndarray, names) -> list:
    """Basis of span(Z) (scaled) in reduced row-echelon form, pivots in :data:`PIVOT_ORDER`; rows normalised on their pivot."""
    rank = {p: i for i, p in enumerate(PIVOT_ORDER)}
    order = sorted(range(len(names)), key=lambda i: (rank.get(names[i].partition("_")[0], len(PIVOT_ORDER)), i))
    B = Z.T.copy()  # k × n
    k = B.shape[0]
    pivots = []
    row = 0
    for col in order:
        if row == k:
            break
        i = row + int(np.argmax(np.abs(B[row:, col])))
        if abs(B[i, col]) < 1e-8:
            continue
        B[[row, i]] = B[[i, row]]
        B[row] /= B[row, col]
        for r in range(k):
            if r != row:
                B[r] -= B[r, col] * B[row]
        pivots.append(col)
        row += 1
    B[np.abs(B) < 1e-9] = 0.0
    return list(zip(pivots, B[: len(pivots)]))


def observability(problem: ObservabilityProblem, *, limits: budget.Limits | None = None) -> ObservabilityResult:
    """Rank, unobservable directions and degree of observability of a problem.

    The rank (and the unobservable directions) says which states the
    measurements can tell apart *at all*, given any time; the degree of
    observability (:attr:`ObservabilityResult.posterior_ratio`) says how much
    the filter has learned about each *within the horizon*.  A state can be
    observable in rank and still unlearned after the horizon (ratio near 1).

    Parameters
    ----------
    problem : ObservabilityProblem
        From :func:`stationary_problem`, :func:`rocking_problem`,
        :func:`multi_position_problem` or a recorded log
        (:func:`strapdown.analysis.logs.alignment.recorded_problem`).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time of the covariance run over the
        horizon (default 2 GB, 300 s); a horizon beyond them raises
        :class:`~strapdown.analysis.core.budget.BudgetExceeded` before anything is allocated.

    Returns
    -------
    ObservabilityResult

    Raises
    ------
    TypeError
        If ``problem`` is not an ObservabilityProblem.
    ValueError
        For an ``epoch`` longer than the horizon, or a horizon beyond ``limits``
        (:class:`~strapdown.analysis.core.budget.BudgetExceeded`, naming ``duration``).

    References
    ----------
    Bar-Itzhack & Berman (1988) (the stationary model's unobservable pairs);
    Goshen-Meskin & Bar-Itzhack (1992) (piecewise-constant systems).

    Examples
    --------
    >>> r = observability(stationary_problem(math.radians(45.0)))
    >>> r.rank, r.dim
    (9, 12)
    >>> [d.text for d in r.unobservable]
    ['north tilt ↔ east accelerometer bias', 'east tilt ↔ north accelerometer bias', 'azimuth ↔ east gyro bias']
    """
    if not isinstance(problem, ObservabilityProblem):
        raise TypeError(f"Expected `problem` to be an ObservabilityProblem, got {type(problem).__name__}")
    _check_work(problem, limits, covariance=True)
    names = problem.names
    labels = state_labels(names)
    n = len(names)
    S = problem.models[0].scales  # equivalent angles: the couplings inside a block are of order one
    M = _unobservable(problem, S)
    directions = []
    E = problem.models[0].scales  # equivalent angles: the partners are ranked in these
    for col, row in _rref_directions(M, names):
        comp = row * S / S[col]  # SI per unit of the pivot
        row = comp * E[col] / E  # the same direction in equivalent angles, pivot 1
        others = sorted((i for i in range(n) if i != col and row[i] != 0.0), key=lambda i: -abs(row[i]))
        partners = tuple(names[i] for i in others)
        lead = [labels[i] for i in others if abs(row[i]) >= (1.0 - 1e-6) * abs(row[others[0]])]  # ties named together
        text = f"{labels[col]} ↔ {' and '.join(lead)}" if others else f"{labels[col]} (alone)"
        directions.append(UnobservableDirection(names[col], {names[i]: float(comp[i]) for i in range(n) if row[i] != 0.0}, partners, text))
    return ObservabilityResult(
        problem.kind, names, labels, n - M.shape[1], tuple(directions), _posterior_ratio(problem), np.linalg.eigvalsh(_gramian(problem))[::-1].copy(),
        problem.duration, problem.latitude,
    )


def _posterior_ratio(problem: ObservabilityProblem) -> np.ndarray:
    """``√(P_T,ii / P_0,ii)`` of the filter over the horizon (filterpy, segment after segment)."""
    P = problem.P0
    for m, d in zip(problem.models, problem.durations):
        steps = max(1, int(round(d / problem.epoch)))
        F, Q = m.discretise(d / steps)
        P = kalman.filter_sequence(F, Q, m.H, problem.R, P, steps).posterior[-1]
    p0 = np.diag(problem.P0)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.where(p0 > 0, np.sqrt(np.maximum(np.diag(P), 0.0) / np.where(p0 > 0, p0, 1.0)), np.nan)
