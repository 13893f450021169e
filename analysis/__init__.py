"""Numerical error analysis of strapdown inertial navigation algorithms.

Installed as ``strapdown.analysis``, beside the symbolic side
``strapdown.derivations``.  Imports run one way: ``derivations`` (SymPy only)
← ``analysis`` (numerics, may lambdify derivations) ← ``analysis.cli`` and
``analysis.report``.  The subpackages of both sides mirror each other:

=================  ==========================================  ===================================
subpackage         analysis (numerics)                         derivations (SymPy)
=================  ==========================================  ===================================
``core``           quaternions, dual numbers, validation,      reproducible SymPy runs
                   units, Monte Carlo, verdicts, filterpy      (``derivations.reproducible``),
                   adapter, cache of generated code            user TOML files read defensively
                                                               (``derivations.toml_files``)
``coning``         algorithm evaluation (real and dual),       algorithms as data (cross-step
                   regular precession and classical sculling,  indices), the registry of published
                   simulator (numpy and compiled kernels,      algorithms, error series to any
                   batches, streaming), local error, drift     weight, drift, coning drift in
                   theory, error against frequency,            closed form, optimal coning,
                   computational load, observed orders         published data
``coning.papers``  the papers' tables and printed formulas     none: their printed numbers are
                   reproduced with the library above           reference data in ``coning.published``
                   (Budennyi et al. Tables 1–5, Lebedev &
                   Panov (1989) section 6, (1.12), (2.2),
                   (4.7), published coefficients)
``vibration``      the vibration environment: sensor filters   none (uses the coning derivations)
                   and decimation, lines and cross-spectra,
                   mean coning drift and sculling
                   rectification in closed form, DOP853 and
                   Monte Carlo checks, tuned algorithms,
                   sample rate for a drift budget, linear
                   vibration profiles through an IMU mount
``multistage``     corrected attitude stages (compiled),       Lyapunov function, Schuler
                   truth over the rotating Earth, decay rates  linearisation, composition, tilt
                   python-control loops, gain design, sensor   quaternion, published data
                   statistics, readings of section 5
``gyrocompass``    the tilt channel of Hrechka & Koroliov:     azimuth-error series, bounds
                   rocking models, azimuth Monte Carlo, bound  (14)–(15), published formulas
                   sweeps, finite-sample statistics of (16),
                   admissible rocking
``alignment``      self-alignment of the whole system:         gains of the linearised analytic
                   rocking base and IMU model, analytic,       alignment
                   inertial and Kalman alignment, theory of
                   every error term, admissible rocking per
                   method
``logs``           recorded IMU logs: reading, checks,         none
                   alignment and observability on a log,
                   the vibration environment of a log,
                   algorithms replayed on it, static noise
``cli``            the ``strapdown`` command line
``report``         report sections (formatting only)
=================  ==========================================  ===================================

Beside them, ``coning.integrators`` takes algorithms that exist only as code (a
function, an object updated one sample at a time, a compiled C function, a
peer's integrator) through one black-box interface, identifies them as exact
algorithms and runs the ``coning`` machinery on them (``strapdown identify``).

Conventions (stated once, used everywhere in :mod:`strapdown.analysis` and :mod:`strapdown.derivations`)
--------------------------------------------------------------------------------------------------------
Quaternions
    Scalar first, ``(q0, q1, q2, q3)``, stored as arrays of shape ``(..., 4)``.
    The product ``∘`` is Hamilton's (``i*j = k``).
Vectors
    Arrays of shape ``(..., 3)``; leading axes are batch or time.
Frames
    E is the body frame (the papers' E or x), I the reference (inertial) frame
    (the papers' I or ξ).  The attitude quaternion Λ maps E to I:
    ``v_I = Λ ∘ v_E ∘ Λ̄``, with kinematics ``2 Λ' = Λ ∘ ω`` where ω is the body
    rate resolved in E.
Rotation vector
    ``φ`` with ``Λ = (cos(|φ|/2), sin(|φ|/2) φ/|φ|)``.
Dual numbers
    ``x + s x°`` with ``s² = 0`` (:class:`strapdown.analysis.core.dual.Dual`).  A dual vector is
    ``Φ = φ + s φ°``, a biquaternion ``θ = Λ + s M``.  By the transfer principle
    (Kotelnikov–Study) the dual part of ``f(x + s x°)`` is the directional
    derivative ``f'(x) x°``: the dual extension of a real formula is forward-mode
    differentiation, and every real routine here that is written with the
    operations of :mod:`strapdown.analysis.core.dual` serves dual arguments unchanged.
Apparent velocity
    ``W_E = 2 vect(Λ̄ ∘ M)``, ``W_I = 2 vect(M ∘ Λ̄)``
    (Lebedev & Panov 1989, eq. (1.3)).
Errors
    Errors of an algorithm against the exact motion (the coning domain) have
    one sign, exact minus algorithm, on the symbolic side (series) and the
    numeric side (theory, simulator, compiled kernels, batches, streaming
    statistics, CLI and reports) alike:

    - the local error of a step is ``δφ = Δφ_exact − Δφ_algorithm``;
    - the accumulated attitude error is the rotation vector of the error
      rotation ``Λ_true ∘ Λ̄_computed``, ``δφ_I = rotvec(Λ_true ∘ Λ̄_computed)``
      with components in frame I (``Λ_true = exp(δφ_I) ∘ Λ_computed``); in the
      body axes it is ``δφ_E = Λ̄_computed ∘ δφ_I ∘ Λ_computed``
      (``Λ_true = Λ_computed ∘ exp(δφ_E)``);
    - apparent-velocity errors are ``ΔW_E = W_E,true − W_E,computed`` (frame E)
      and ``ΔW_I = W_I,true − W_I,computed`` (frame I), and a rectification
      (sculling) error is the rate of ``ΔW_I``: positive when the algorithm
      under-rectifies;
    - drift rates are slopes of these errors and carry their sign: a signed
      drift is the rate of ``Λ_true ∘ Λ̄_computed`` (a vector in frame I, or its
      component along a named axis: the precession axis n, or under coning the
      cone axis −n, where u > 0 means the computed attitude lags); a drift
      *rate* with no axis is a magnitude.

    Errors of an estimator against the truth (the stages of
    :mod:`strapdown.analysis.multistage`, the filter helpers of
    :mod:`strapdown.analysis.core.kalman`) are estimate minus truth, as their
    modules state.
Steps
    ``h`` is the sample interval, ``H = N h`` the step of an N-sample algorithm
    (public arguments ``sample_interval`` and ``step``); the multistage stages
    take one sample per step, so there ``h = H`` and the argument is ``step``.
Orders
    How an algorithm's error scales with the step has one name per meaning,
    used alike in the library, the command line (and its JSON keys), the docs
    and the reports:

    - the *weight* w of a series term is its power of h (local error) or of ν
      and H (drift ``d_w ν^w H^(w−1)``); ``--max-order K`` keeps the weights
      through K;
    - the *accuracy order* ρ (``accuracy_order``): the local error is
      O(h^(ρ+1)) in a general motion, so the error over a fixed time is
      O(h^ρ); the ρ of Budennyi, Kalinovsky, Panov et al., Table 2;
    - the *local-error order* ρ + 1 (``local_error_order``): the weight of the
      leading local error;
    - the *coning-drift order* m (``coning_drift_order``): under classical
      coning the drift is ``c α² ω (ωh)^m + O(α⁴)``; m ≥ ρ, and far above it
      for the algorithms tuned to coning (ignagni-1996-5: ρ = 3, m = 8);
    - the *drift order* at a motion (``drift_order``): the power of H of the
      leading term of the drift there (its weight minus one; the ρ of
      Budennyi et al., Table 3).  At a finite cone angle it can lie below m,
      through the α⁴ term (ignagni-1996-5 at 1°: 4);
    - an *observed* order is an exponent measured by halving h.
Units
    SI throughout; angles in radians inside the code.  Degrees and deg/h appear
    only at the edges (CLI and reports).

Sources are cited by author and year:
Lebedev & Panov (1989); Plotnikov (1999); Budennyi, Kalinovsky, Panov et al.
(Part 2, early 2000s); Hrechka & Koroliov.
"""

from importlib.metadata import PackageNotFoundError
from importlib.metadata import version as _version

try:
    __version__ = _version("strapdown-analysis")
except PackageNotFoundError:  # running from a source tree that is not installed
    __version__ = "0.1.0"

__all__ = ["__version__"]
