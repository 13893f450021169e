"""Integrators in the wild, assessed: flight-code recursions, a composition without coning term, peers like for like.

What the report section "Integrators in the wild" shows, computed here:

:func:`recursion_study`
    Savage's per-sample recursion (:mod:`.recursions`) in each form flight code
    has written it (:data:`RECURSIONS`), identified and verified for N = 1 … 8.
:func:`composition_study`
    the exact rotation of every sample composed, with no coning term.
:func:`peer_study`
    every integrator, the peers' included, fed the same increments of the
    same two motions (:data:`CONING`, :data:`SCULLING`, sampled at
    :data:`SAMPLE_INTERVAL`) and measured against the same exact solution
    (:func:`~.verification.coning_drift_rate`, :func:`~.verification.sculling_rate`),
    beside the closed forms of what each was identified to be.

Public API
----------
:data:`RECURSIONS`, :data:`RECURSION_SAMPLES`, :data:`CONING`, :data:`SCULLING`,
:data:`SAMPLE_INTERVAL`, :data:`MEMORY_PROBED`, :class:`PeerRun`, :func:`recursion_study`,
:func:`composition_study`, :func:`peer_study`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ....derivations.coning.registry import get
from ..drift_theory import coning_drift_function
from ..precession import RegularPrecession
from ..sculling_motion import ScullingMotion
from .adapters import algorithm_integrator
from .assessment import Assessment, assess
from .peers import pyins_increments, pyins_integrator, smsfusion_ins
from .recursions import quaternion_composition, recursion
from .verification import coning_drift_rate, sculling_rate

__all__ = ["RECURSIONS", "RECURSION_SAMPLES", "CONING", "SCULLING", "SAMPLE_INTERVAL", "MEMORY_PROBED", "PeerRun", "recursion_study", "composition_study", "peer_study"]

#: The forms of Savage's recursion: key → (label, keyword arguments of :func:`~.recursions.recursion`).
RECURSIONS = {
    "savage": ("Savage's recursion (previous α = α_(m−1))", {}),
    "one-accumulator": ("α and β in one accumulator (ArduPilot's form)", {"one_accumulator": True}),
    "previous-alpha-older": ("previous α one sample older, α_(m−2) (PX4's IntegratorConing)", {"alpha_lag": 2}),
    "previous-increment-overwritten": ("previous Δα overwritten before it is read (the 2014–2015 EKF slip)", {"previous_lag": 0}),
}
#: Samples per step of the recursion tables.
RECURSION_SAMPLES = tuple(range(1, 9))
#: Sample interval of the like-for-like runs [s] (400 Hz).
SAMPLE_INTERVAL = 1.0 / 400.0
#: Classical coning of the like-for-like runs: 10 Hz, half-cone angle 1° (Budennyi, Kalinovsky, Panov et al., Table 3).
CONING = RegularPrecession(-1.0, 2 * math.pi * 10.0, math.radians(1.0))
#: Longest memory the assumption tests probe here [samples]: these integrators read at most one sample
#: back, and a test that said otherwise would still see it (the scan reaches twice as far).
MEMORY_PROBED = 8
#: Classical sculling of the like-for-like runs: 10 Hz, θ₀ = 1 mrad, A = 1 m/s², in phase (40 samples per period).
SCULLING = ScullingMotion(1e-3, 1.0, 2 * math.pi * 10.0)


def _verify(verify, n) -> bool:
    return bool(verify) if isinstance(verify, bool) else n in verify


def recursion_study(variant: str, samples=RECURSION_SAMPLES, *, velocity: bool = True, verify=True) -> tuple:
    """Savage's recursion in one of its written forms, assessed for each N.

    Parameters
    ----------
    variant : str
        A key of :data:`RECURSIONS`.
    samples : sequence of int
        The N to assess.
    velocity : bool, keyword-only
        With the sculling recursion (not for the one-accumulator form).
    verify : bool or collection of int, keyword-only
        Run the integrator against the exact solution: for every N, none, or the N listed.

    Returns
    -------
    tuple of Assessment

    Raises
    ------
    ValueError
        For an unknown variant.
    """
    if variant not in RECURSIONS:
        raise ValueError(f"Expected `variant` among {', '.join(RECURSIONS)}, got {variant!r}")
    kwargs = dict(RECURSIONS[variant][1])
    kwargs["velocity"] = velocity and not kwargs.get("one_accumulator", False)
    integrator = recursion(**kwargs)
    return tuple(assess(integrator, n, verify=_verify(verify, n), name=f"{variant}-{n}", max_previous_limit=MEMORY_PROBED) for n in samples)


def composition_study(samples=RECURSION_SAMPLES, *, verify=True) -> tuple:
    """The quaternion composition of the samples (no coning term), assessed for each N.

    Parameters
    ----------
    samples : sequence of int
        The N to assess.
    verify : bool or collection of int, keyword-only
        Run the integrator against the exact solution: for every N, none, or the N listed.

    Returns
    -------
    tuple of Assessment
    """
    integrator = quaternion_composition(velocity=True)
    return tuple(assess(integrator, n, verify=_verify(verify, n), name=f"composition-{n}", max_previous_limit=MEMORY_PROBED) for n in samples)


@dataclass(frozen=True)
class PeerRun:
    """One integrator on the common data, beside the closed forms of what it was identified to be.

    Attributes
    ----------
    label : str
        What it is.
    source : str
        Where it comes from (a peer, flight code, this package).
    samples : int
        N.
    assessment : Assessment
        Its identification (and verification).
    drift : float
        Simulated coning drift on :data:`CONING` [rad/s], exact minus integrator, along the cone axis.
    drift_closed_form : float or None
        ``α² ω D(ωh)`` of the identified algorithm [rad/s] (None without a closed form).
    sculling : float or None
        Simulated rectification error rate on :data:`SCULLING` [m/s²] (None: no velocity output).
    sculling_closed_form : float or None
        The identified sculling part's rate, first order in θ₀ A [m/s²].
    """

    label: str
    source: str
    samples: int
    assessment: Assessment
    drift: float
    drift_closed_form: float | None
    sculling: float | None
    sculling_closed_form: float | None


def _peers():
    """(label, source, integrator, N, verify) of every row of the like-for-like table."""
    rows = [
        ("pyins Integrator (whole strapdown loop)", "pyins (python-ins 1.0)", pyins_integrator(sample_interval=SAMPLE_INTERVAL), 1, True),
        ("pyins compute_increments_from_imu", "pyins (python-ins 1.0)", pyins_increments(sample_interval=SAMPLE_INTERVAL), 1, True),
        ("smsfusion StrapdownINS", "smsfusion 1.9", smsfusion_ins(sample_interval=SAMPLE_INTERVAL), 1, True),
        ("Savage's recursion, N = 4", "flight-code form (ArduPilot's bilinear part)", recursion(velocity=True), 4, False),
        ("previous α one sample older, N = 4", "flight-code form (PX4's IntegratorConing)", recursion(alpha_lag=2, velocity=True), 4, False),
        ("quaternion composition, N = 4", "no coning term", quaternion_composition(velocity=True), 4, False),
    ]
    for name in ("savage-1+1", "two-sample", "compressed-4"):
        alg = get(name)
        rows.append((f"{name} (registry, from its terms)", "this package", algorithm_integrator(alg), alg.samples, False))
    return rows


def peer_study() -> tuple:
    """Every row of the like-for-like comparison (module docstring).

    The peers are assessed with verification (the round trip of pyins's
    integrator is checked against the exact solution); every row then runs
    on the same coning and sculling data.

    Returns
    -------
    tuple of PeerRun

    Raises
    ------
    ImportError
        If pyins or smsfusion is not installed (both are dependencies of the package).
    """
    out = []
    for label, source, integrator, n, verify in _peers():
        a = assess(integrator, n, verify=verify, max_previous_limit=MEMORY_PROBED)
        history = max(a.identification.history, a.identification.max_previous)
        u = coning_drift_rate(integrator, n, CONING, SAMPLE_INTERVAL, steps=400 // n, history=history)
        u_cf = None
        if a.coning is not None:
            u_cf = CONING.nutation**2 * CONING.nu * float(coning_drift_function(a.algorithm)(CONING.nu * SAMPLE_INTERVAL))
        s = s_cf = None
        if integrator.velocity:
            s = sculling_rate(integrator, n, SCULLING, SAMPLE_INTERVAL, history=history)
            s_cf = a.identification.sculling.terms(n).rectification_error(SCULLING, SAMPLE_INTERVAL).rate
        out.append(PeerRun(label, source, n, a, u, u_cf, s, s_cf))
    return tuple(out)
