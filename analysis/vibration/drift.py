"""Mean coning drift and sculling rectification of an algorithm in a vibration environment, in closed form.

Derivation (second order in the vibration amplitude, exact in ωh)
------------------------------------------------------------------
Let the body rate and specific force of one line be ``Re(Z e^{iωt})``,
``Z = (A, B)``, A the rate and B the specific-force amplitude, and let the
sensor chain of :mod:`strapdown.analysis.vibration.sensor_dynamics` have the
equivalent responses ``H_c(ω)`` per channel: the algorithm receives exactly
the increments of ``Re(H A e^{iωt})`` (and of ``Re(H B e^{iωt})``).

*Truth.*  To second order the attitude's rotation vector grows at the mean
non-commutativity rate ``⟨½ θ × ω⟩`` (θ = ∫ω), plus the constant second-order
body rate; with ``⟨Re(a e^{iωt}) × Re(b e^{iωt})⟩ = ½ Re(a × b̄)`` this is
``q/(2ω)`` with the *coning vector*

    q = ½ Im(A × Ā) = −Im w(P_ωω),     P_ab = ½ conj(Z_a) Z_b,

``w(M) = (M_yz − M_zy, M_zx − M_xz, M_xy − M_yx)``.

*Algorithm.*  The computed attitude grows at the mean rate of its step
composition (``½ Θ_n × P_n``, a geometric series in the step phase) plus its
terms ``c_ij p_i × p_j``; both are means of products of sinusoids sampled at
the steps, hence exact.  Written with the sensed amplitudes ``Ã = H A`` the
algorithm's mean rate differs from the truth *of the sensed motion*
``q̃/(2ω)`` (``q̃ = ½ Im(Ã × conj Ã)``) by exactly the classical coning drift
of the algorithm,

    u_algorithm = q̃ · D(ωh) / ω,      D(x) = [E(Nx) − Σ_l k_l R_l(x)] / (N x),

the closed form of :func:`strapdown.derivations.coning.drift.coning_drift`
(derived from the exact one-step formula; for classical coning q = α²ω²
gives u = α² ω D).  Only the pairwise terms act, through their lag sums
``k_l`` (cross-step pairs included); nested and dot terms are of higher order.
The constant second-order body rate passes the sensors (unit gain at zero
frequency) and cancels between truth and algorithm.

*Drift* (exact minus algorithm, package convention) is then the sum of

* the **sensor part** (pseudo-coning) ``u_sensor = (q − q̃)/(2ω)``: what even
  an exact integration of the sensed motion would miss.  Identical filters on
  the three axes give ``q̃ = |H|² q``; filters that differ between axes mix the
  in-phase part of A into q̃, so in-phase vibration on two axes then cones
  too;
* the **algorithm part** ``u_algorithm`` above, the algorithm's own residual
  on the motion it is given.

*Sculling.*  By the transfer principle (ω → ω + s a, Lebedev & Panov 1989,
eq. (2.5)) the velocity algorithm is the algorithm's dual extension and the
rectification error is the dual part of the same formulas, with the
*sculling vector* ``q_s = Im(A × B̄) = −2 Im w(P_ωa)`` in place of q and the
gyro and accelerometer responses on A and B: sensor part
``(q_s − q̃_s)/(2ω)`` (pseudo-sculling, including a phase mismatch between
gyro and accelerometer filters) and algorithm part ``q̃_s D(ωh)/ω``, both the
rate of ``ΔW_I = W_I,true − W_I,computed`` [m/s²] (positive: the algorithm
under-rectifies).

*Lines of one frequency* are coherent (one rotor): their amplitudes add
before the bilinear forms are taken, and they make one part
(:func:`coherent_groups`).

*Spectra.*  Each band of a spectrum adds incoherent lines, ``P = G(f) df``:
the drift is ``∫ u(f) df`` with the same integrand, taken by composite
Gauss–Legendre quadrature in log f, every table frequency a break point
(:func:`strapdown.analysis.core.quadrature.integrate`, to
:data:`QUADRATURE_RTOL` of the integral of the integrand's magnitude).

*Lines of different frequencies* add their drifts only where no pair of them
aliases: the cross terms of two lines oscillate at ``f₁ ± f₂``, and where the
sum or the difference is a multiple of the step rate 1/H the algorithm samples
them at one phase and they leave a phase-locked mean.  Such a pair adds a part
of kind ``"alias"`` (:mod:`strapdown.analysis.vibration.aliasing`, with its
derivation); a pair near an alias is listed in
:attr:`EnvironmentDrift.near_aliases` with its beat period (its mean over many
beats is zero, so it is not in the total).  Components of a stationary spectrum
at different frequencies are uncorrelated and add no such mean.

The quoted quantity: the drift is a vector in the body axes (frame I to this
order), :attr:`EnvironmentDrift.total_vector`, and its magnitude
:attr:`EnvironmentDrift.magnitude`.  A signed value is a *projection*, on an
axis that is named with it: :attr:`EnvironmentDrift.total` is the component
along the environment's *coning axis*, the direction of the true coning rate
Σ q/(2ω) (for a coning line, its axis), so that ``u > 0`` means the computed
attitude lags about that axis; drift about other axes (a tail rotor coning
about y when the main rotor cones about z) is in the vector and the magnitude,
not in that projection.

Public API
----------
.. autosummary::

   DriftPart
   EnvironmentDrift
   environment_drift
   response_integrals
   coherent_groups
   line_response
   segment_count
   quadrature_evaluations
   theory_warnings
   SMALL_ANGLE
   QUADRATURE_RTOL

References
----------
Lebedev & Panov (1989), eq. (2.5) (transfer principle); Ignagni (1990, 1998);
Savage (1998), parts 1–2 (pseudo-coning, pseudo-sculling); Mark & Tazartes
(1996) (algorithms and gyro frequency response).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..coning.drift_theory import coning_drift_function
from ..core.validation import positive
from .aliasing import NEAR_ALIAS_BEAT, alias_pairs
from .environment import Environment, Spectrum, VibrationLine

__all__ = [
    "DriftPart", "EnvironmentDrift", "environment_drift", "response_integrals", "coherent_groups", "line_response",
    "coning_vector", "sculling_vector", "QUADRATURE_RTOL", "ResponseIntegrals", "segment_count", "quadrature_evaluations",
    "theory_warnings", "SMALL_ANGLE",
]  # fmt: skip

#: Relative tolerance of the spectrum quadrature (against the integral of the magnitude).
QUADRATURE_RTOL = 1e-10


def _w(m: np.ndarray) -> np.ndarray:
    """``(M_yz − M_zy, M_zx − M_xz, M_xy − M_yx)`` of the 3×3 blocks ``m[..., 3, 3]``."""
    return np.stack([m[..., 1, 2] - m[..., 2, 1], m[..., 2, 0] - m[..., 0, 2], m[..., 0, 1] - m[..., 1, 0]], axis=-1)


def coning_vector(power: np.ndarray) -> np.ndarray:
    """Coning vector ``q = −Im w(P_ωω)`` of cross-power matrices ``P`` (..., 6, 6) [(rad/s)²].

    Parameters
    ----------
    power : ndarray, shape (..., 6, 6)
        ``P_ab = ½ conj(Z_a) Z_b`` of a line, or ``G(f) df`` of a band.

    Returns
    -------
    ndarray, shape (..., 3)
    """
    return -np.imag(_w(power[..., :3, :3]))


def sculling_vector(power: np.ndarray) -> np.ndarray:
    """Sculling vector ``q_s = −2 Im w(P_ωa)`` of cross-power matrices (..., 6, 6) [(rad/s)(m/s²)].

    Parameters
    ----------
    power : ndarray, shape (..., 6, 6)
        Cross-power matrices.

    Returns
    -------
    ndarray, shape (..., 3)
    """
    return -2.0 * np.imag(_w(power[..., :3, 3:]))


class ResponseIntegrals:
    """Integrals of the drift integrand against a set of algorithm response functions.

    For response functions ``φ_j(x)`` of x = ωh, the totals over the lines and
    spectra of an environment of

    * ``true``: ``q/(2ω)`` and ``q_s/(2ω)``,
    * ``sensed``: ``q̃/(2ω)`` and ``q̃_s/(2ω)``,
    * ``algorithm[j]``: ``q̃ φ_j(ωh)/ω`` and ``q̃_s φ_j(ωh)/ω``,

    each as a pair of vectors (coning [rad/s], sculling [m/s²]), per part
    (line or spectrum).  With ``φ = D`` of an algorithm this is its drift; with
    the lag responses it is the linear model of the tuning
    (:mod:`strapdown.analysis.vibration.tuning`).

    Attributes
    ----------
    parts : list of (kind, label, band)
        One entry per line or spectrum.
    true, sensed : ndarray, shape (parts, 2, 3)
    algorithm : ndarray, shape (functions, parts, 2, 3)
    """

    def __init__(self, parts, true, sensed, algorithm):
        self.parts, self.true, self.sensed, self.algorithm = parts, true, sensed, algorithm


#: Channel pairs (a, b) of the cross-power entries the drift reads: the coning vector from the rate block,
#: ``q = −2 Im(P_yz, P_zx, P_xy)`` (Hermitian), and the sculling vector from the rate–specific-force block,
#: ``q_s = −2 Im(P_{ωy az} − P_{ωz ay}, P_{ωz ax} − P_{ωx az}, P_{ωx ay} − P_{ωy ax})``.
_ROWS = np.array([1, 2, 0, 1, 2, 2, 0, 0, 1])
_COLS = np.array([2, 0, 1, 5, 4, 3, 5, 4, 3])


def _vectors(e: np.ndarray) -> tuple:
    """Coning and sculling vectors of the entries ``e`` (..., 9) (:data:`_ROWS`, :data:`_COLS`)."""
    q = -2.0 * np.imag(e[..., 0:3])
    d = e[..., 3::2] - e[..., 4::2]
    return q, -2.0 * np.imag(d)


def _integrand(environment: Environment, sample_interval: float, functions, freq: np.ndarray, entries: np.ndarray) -> np.ndarray:
    """Columns (true c, true s, sensed c, sensed s, alg_j c, alg_j s …), shape (n, 2 + 2 + 2J, 3), of the entries (n, 9)."""
    omega = 2.0 * math.pi * freq
    response = environment.response(omega, sample_interval)
    sensed = np.conj(response[:, _ROWS]) * response[:, _COLS] * entries
    q, qs = _vectors(entries)
    qt, qts = _vectors(sensed)
    inv = (1.0 / omega)[:, None]
    cols = [0.5 * q * inv, 0.5 * qs * inv, 0.5 * qt * inv, 0.5 * qts * inv]
    x = omega * sample_interval
    for phi in functions:
        v = np.asarray(phi(x), dtype=float).reshape(-1)[:, None] * inv
        cols += [qt * v, qts * v]
    return np.stack(cols, axis=1)


#: Gauss–Legendre order of the direct adaptive quadrature (a panel against its two halves) [count].
PANEL_ORDER = 4
#: Halvings of a panel before the direct quadrature gives up [count].
MAX_HALVINGS = 40
#: Most integrand evaluations of the direct quadrature of one spectrum [count].
MAX_EVALUATIONS = 2**21
#: Largest array of integrand values evaluated at once [bytes].
CHUNK_BYTES = 2**22
_GL_NODES, _GL_WEIGHTS = np.polynomial.legendre.leggauss(PANEL_ORDER)

#: Width of a product-integration panel in ln f [-] (1 % in frequency).
PRODUCT_WIDTH = 0.01
#: Nodes of the product rule per panel (exact for responses of degree 7 in ln f) and of its check [count].
PRODUCT_NODES, CHECK_NODES = 8, 4
#: Largest change of ln G over one segment of the moments' quadrature [-].
SEGMENT_LOG_RANGE = 2.0


class _Unresolved(ValueError):
    """The spectrum quadrature did not converge (its message says where)."""


def _panel_values(g, a: np.ndarray, b: np.ndarray, size: int) -> tuple:
    """Gauss–Legendre integrals of g over [a, b] (coarse), [a, m] and [m, b] (halves), and ∫|g| over the halves; in chunks."""
    per_node = max(size * 8, 8)
    chunk = max(1, CHUNK_BYTES // (per_node * 3 * PANEL_ORDER))
    coarse, left, right, absolute = (np.empty((a.size, size)) for _ in range(4))
    for k in range(0, a.size, chunk):
        aa, bb = a[k : k + chunk], b[k : k + chunk]
        mm = 0.5 * (aa + bb)
        spans = [(aa, bb), (aa, mm), (mm, bb)]
        u = np.concatenate([(0.5 * (lo + hi))[:, None] + (0.5 * (hi - lo))[:, None] * _GL_NODES[None, :] for lo, hi in spans], axis=0).ravel()
        vals = g(u).reshape(3, aa.size, PANEL_ORDER, size)
        half = np.array([0.5 * (hi - lo) for lo, hi in spans])[:, :, None]
        ints = np.einsum("pkn,n,pkns->pks", np.broadcast_to(half, (3, aa.size, PANEL_ORDER)), _GL_WEIGHTS, vals)
        coarse[k : k + chunk], left[k : k + chunk], right[k : k + chunk] = ints
        absolute[k : k + chunk] = np.einsum("pkn,n,pkns->ks", np.broadcast_to(half[1:], (2, aa.size, PANEL_ORDER)), _GL_WEIGHTS, np.abs(vals[1:]))
    return coarse, left, right, absolute


def _adaptive(g, a: np.ndarray, b: np.ndarray, size: int, rtol: float, atol: float) -> np.ndarray:
    """∫ g du over the panels [a, b] (values of ``size`` elements), each halved where it and its halves disagree.

    A panel is accepted when ``|halves − panel| ≤ max(atol · width/Σwidth, rtol · |halves|)``
    elementwise; its halves' sum is kept, and the halves of a rejected panel
    start from the values already computed.
    """
    coarse, left, right, _ = _panel_values(g, a, b, size)
    width = float(np.sum(b - a))
    total = np.zeros(size)
    evaluations = 3 * PANEL_ORDER * a.size
    for _ in range(MAX_HALVINGS):
        fine = left + right
        if not np.all(np.isfinite(fine)):
            bad = int(np.nonzero(~np.all(np.isfinite(fine), axis=1))[0][0])
            raise _Unresolved(f"the integrand is not finite near {math.exp(0.5 * (a[bad] + b[bad])):.6g} Hz")
        ok = np.all(np.abs(fine - coarse) <= np.maximum(atol * ((b - a) / width)[:, None], rtol * np.abs(fine)), axis=1)
        total += fine[ok].sum(axis=0)
        if ok.all():
            return total
        a, b, m = a[~ok], b[~ok], 0.5 * (a[~ok] + b[~ok])
        coarse = np.concatenate([left[~ok], right[~ok]])
        a, b = np.concatenate([a, m]), np.concatenate([m, b])
        evaluations += 3 * PANEL_ORDER * a.size
        if evaluations > MAX_EVALUATIONS:
            raise _Unresolved(f"the integrand is not resolved by {MAX_EVALUATIONS} evaluations, near {math.exp(0.5 * (a[0] + b[0])):.6g} Hz")
        _, left, right, _ = _panel_values(g, a, b, size)
    worst = int(np.argmax(np.max(np.abs(left + right - coarse), axis=1)))
    raise _Unresolved(f"the integrand is not resolved near {math.exp(0.5 * (a[worst] + b[worst])):.6g} Hz after {MAX_HALVINGS} halvings")


class _ProductRule(NamedTuple):
    """Product-integration weights of one spectrum (:func:`_product_rule`)."""

    panels: np.ndarray  # (P + 1,) panel edges in u = ln f
    segments: np.ndarray  # (S + 1,) segment edges (every table frequency among them)
    first: np.ndarray  # (P + 1,) index of each panel's first segment
    nodes: np.ndarray  # (P, PRODUCT_NODES) nodes in u
    weights: np.ndarray  # (P, PRODUCT_NODES, 9) complex: ∫ G_e f L-interpolant du
    check_nodes: np.ndarray  # (P, CHECK_NODES)
    check_weights: np.ndarray  # (P, CHECK_NODES, 9)


def _segments(spectrum: Spectrum) -> np.ndarray:
    """Edges in u of the segments: each table interval split so that a segment spans at most
    :data:`PRODUCT_WIDTH` in ln f and :data:`SEGMENT_LOG_RANGE` in ln G."""
    u = np.log(spectrum.frequency)
    auto = np.real(np.diagonal(spectrum.density, axis1=1, axis2=2))
    with np.errstate(divide="ignore"):
        logs = np.log(np.where(auto > 0, auto, np.nan))
    jump = np.nan_to_num(np.nanmax(np.abs(np.diff(logs, axis=0)), axis=1, initial=0.0), nan=0.0) if auto.size else np.zeros(u.size - 1)
    split = np.maximum(1, np.maximum(np.ceil(np.diff(u) / PRODUCT_WIDTH), np.ceil(jump / SEGMENT_LOG_RANGE))).astype(int)
    starts = np.repeat(u[:-1], split) + np.repeat(np.diff(u) / split, split) * (np.arange(split.sum()) - np.repeat(np.cumsum(split) - split, split))
    return np.append(starts, u[-1])


@lru_cache(maxsize=16)
def _product_rule(spectrum: Spectrum) -> _ProductRule:
    """Weights that integrate ``G_e(f)`` against any response smooth on a panel (module docstring of the quadrature).

    The segments (:func:`_segments`) are grouped into panels of at least
    :data:`PRODUCT_WIDTH` in ln f.  On each panel a response r(u) is replaced
    by its polynomial interpolant at the Gauss–Legendre nodes ``u_j``, so that
    ``∫ G_e f r du ≈ Σ_j W_je r(u_j)`` with ``W_je = ∫ G_e f ℓ_j du`` (ℓ_j the
    Lagrange basis), computed once from the Legendre moments of ``G_e f`` by
    Gauss–Legendre of order 8 on every segment.
    """
    seg = _segments(spectrum)
    widths = np.diff(seg)
    # panels: consecutive segments until the width reaches PRODUCT_WIDTH
    cum = np.concatenate([[0.0], np.cumsum(widths)])
    first = [0]
    while first[-1] < widths.size:
        nxt = int(np.searchsorted(cum, cum[first[-1]] + PRODUCT_WIDTH * (1 - 1e-9), side="left"))
        first.append(min(max(nxt, first[-1] + 1), widths.size))
    first = np.array(first)
    if first.size > 2 and cum[-1] - cum[first[-2]] < 0.5 * PRODUCT_WIDTH:  # a short last panel joins the one before
        first = np.delete(first, -2)
    panels = seg[first]
    P = panels.size - 1
    owner = np.repeat(np.arange(P), np.diff(first))  # panel of each segment
    x8, w8 = np.polynomial.legendre.leggauss(8)
    K = max(PRODUCT_NODES, CHECK_NODES)
    moments = np.zeros((P, 9, K), dtype=complex)
    lo_p, hi_p = panels[:-1], panels[1:]
    chunk = 4096
    for s0 in range(0, widths.size, chunk):
        a, b = seg[:-1][s0 : s0 + chunk], seg[1:][s0 : s0 + chunk]
        u = (0.5 * (a + b))[:, None] + (0.5 * (b - a))[:, None] * x8[None, :]
        f = np.exp(u)
        e = spectrum.entries(f.ravel(), _ROWS, _COLS).reshape(u.shape + (9,)) * f[..., None] * (0.5 * (b - a))[:, None, None] * w8[None, :, None]
        own = owner[s0 : s0 + chunk]
        xi = (2.0 * u - (lo_p[own] + hi_p[own])[:, None]) / (hi_p[own] - lo_p[own])[:, None]
        leg = np.polynomial.legendre.legvander(xi, K - 1)  # (seg, 8, K)
        contrib = np.einsum("sne,snk->sek", e, leg)
        starts = np.concatenate([[0], np.nonzero(np.diff(own))[0] + 1])  # segments are in panel order
        moments[own[starts]] += np.add.reduceat(contrib, starts, axis=0)

    def weights(n):
        x, w = np.polynomial.legendre.leggauss(n)
        leg = np.polynomial.legendre.legvander(x, n - 1)  # (n, n): L_k(x_j)
        # r ≈ Σ_k c_k L_k with c_k = (2k+1)/2 Σ_j w_j r_j L_k(x_j); ∫ G f r = Σ_k c_k m_k
        factor = (2 * np.arange(n) + 1) / 2.0
        wts = np.einsum("j,jk,k,pek->pje", w, leg, factor, moments[:, :, :n])
        nodes = (0.5 * (lo_p + hi_p))[:, None] + (0.5 * (hi_p - lo_p))[:, None] * x[None, :]
        return nodes, wts

    nodes, wts = weights(PRODUCT_NODES)
    cnodes, cwts = weights(CHECK_NODES)
    return _ProductRule(panels, seg, first, nodes, wts, cnodes, cwts)


def segment_count(spectrum: Spectrum) -> int:
    """Segments of the product-integration weights of ``spectrum`` (their cost is per segment) [count].

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum.

    Returns
    -------
    int
    """
    return int(_segments(spectrum).size - 1)


def quadrature_evaluations(spectrum: Spectrum) -> float:
    """Integrand evaluations of one :func:`response_integrals` over ``spectrum``, once its weights are known [count].

    Parameters
    ----------
    spectrum : Spectrum
        The spectrum.

    Returns
    -------
    float
        ``(PRODUCT_NODES + CHECK_NODES)`` per panel; panels where the response
        is not smooth are integrated directly, which adds to this.
    """
    width = math.log(spectrum.frequency[-1] / spectrum.frequency[0])
    return (PRODUCT_NODES + CHECK_NODES) * max(1.0, width / PRODUCT_WIDTH)


def _spectrum_integral(environment, sample_interval, functions, spectrum: Spectrum, rtol: float) -> np.ndarray:
    """∫ integrand df over the spectrum's table by product integration (:func:`_product_rule`).

    The integrand is linear in the entries of G: on each panel the responses
    (sensor filters, ``φ_j(ωh)/ω``) are integrated against the weights of the
    product rule, and against those of a rule of order :data:`CHECK_NODES`;
    where the two differ by more than the tolerance (a response that is not
    smooth on the panel: a sharp resonance, ωh far above π), the panel is
    integrated directly on its segments (:func:`_adaptive`), with the
    interpolated spectrum at every node.
    """
    rule = _product_rule(spectrum)
    columns = 4 + 2 * len(functions)
    size = columns * 3

    def by_panel(nodes, wts):
        f = np.exp(nodes.ravel())
        vals = _integrand(environment, sample_interval, functions, f, wts.reshape(-1, 9))
        return vals.reshape(nodes.shape + (size,)).sum(axis=1)

    main = by_panel(rule.nodes, rule.weights)
    check = by_panel(rule.check_nodes, rule.check_weights)
    if not np.all(np.isfinite(main)):
        raise _Unresolved("the integrand is not finite")
    atol = rtol * float(np.max(np.abs(main).sum(axis=0)))
    widths = np.diff(rule.panels)
    ok = np.all(np.abs(main - check) <= np.maximum(atol * (widths / widths.sum())[:, None], rtol * np.abs(main)), axis=1)
    total = main[ok].sum(axis=0)
    if not ok.all():
        bad = np.nonzero(~ok)[0]
        seg_index = np.concatenate([np.arange(rule.first[p], rule.first[p + 1]) for p in bad])
        a, b = rule.segments[seg_index], rule.segments[seg_index + 1]

        def g(u):
            f = np.exp(u)
            return (_integrand(environment, sample_interval, functions, f, spectrum.entries(f, _ROWS, _COLS)) * f[:, None, None]).reshape(f.size, size)

        total = total + _adaptive(g, a, b, size, rtol, atol)
    return total.reshape(columns, 3)


def coherent_groups(lines) -> list:
    """Lines grouped by frequency, in order of first appearance: lines of one frequency are coherent.

    Two lines of the same frequency (a coning and a sculling line of one rotor)
    have a fixed relative phase, so their cross terms do not average out: the
    closed form takes their sum as one line.

    Parameters
    ----------
    lines : sequence of VibrationLine
        The lines.

    Returns
    -------
    list of list of VibrationLine
    """
    groups: dict = {}
    for ln in lines:
        groups.setdefault(ln.frequency, []).append(ln)
    return list(groups.values())


def response_integrals(environment: Environment, sample_interval: float, functions, *, rtol: float = QUADRATURE_RTOL) -> ResponseIntegrals:
    """Truth, sensed truth and algorithm responses of every line and spectrum (:class:`ResponseIntegrals`).

    Parameters
    ----------
    environment : Environment
        Lines, spectra and sensors.
    sample_interval : float
        Algorithm sample interval h [s], > 0.
    functions : sequence of callable
        Response functions ``φ_j(x)`` of x = ωh (vectorised).
    rtol : float, keyword-only
        Relative tolerance of the spectrum quadrature.

    Returns
    -------
    ResponseIntegrals

    Raises
    ------
    TypeError
        If ``environment`` is not an :class:`Environment`.
    ValueError
        For a non-positive sample interval, a digital filter whose cut-off
        lies above the sensor's Nyquist frequency at this interval, or an
        interval at which a spectrum's integral does not converge (naming
        ``sample_interval``).
    """
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    h = positive(sample_interval, "sample_interval")
    functions = tuple(functions)
    parts, values = [], []
    if environment.lines:
        groups = coherent_groups(environment.lines)
        freq = np.array([g[0].frequency for g in groups])
        power = np.stack([VibrationLine(g[0].frequency, sum(ln.amplitude for ln in g)).power for g in groups])
        values.extend(_integrand(environment, h, functions, freq, power[:, _ROWS, _COLS]))
        parts.extend(("line", " + ".join(ln.label for ln in g), (g[0].frequency, g[0].frequency)) for g in groups)
    for s in environment.spectra:
        try:
            values.append(_spectrum_integral(environment, h, functions, s, rtol))
        except _Unresolved as exc:
            raise ValueError(
                f"Expected `sample_interval` = {h:g} s to give a response integral over spectrum {s.label!r} that converges; "
                f"it does not ({exc}): the sensors' and the algorithm's responses are not resolved at this interval"
            ) from None
        parts.append(("spectrum", s.label, s.band))
    n = len(parts)
    arr = np.zeros((n, 4 + 2 * len(functions), 3)) if not values else np.stack(values)
    true = arr[:, 0:2]
    sensed = arr[:, 2:4]
    alg = np.stack([arr[:, 4 + 2 * j : 6 + 2 * j] for j in range(len(functions))]) if functions else np.zeros((0, n, 2, 3))
    return ResponseIntegrals(parts, true, sensed, alg)


@dataclass(frozen=True, eq=False)
class DriftPart:
    """Drift and rectification of one line or one spectrum.

    Attributes
    ----------
    kind : str
        ``"line"``, ``"spectrum"`` or ``"alias"`` (the cross terms of two lines
        whose sum or difference frequency is a multiple of the step rate: an
        algorithm part only, :mod:`strapdown.analysis.vibration.aliasing`).
    label : str
        Its name.
    band : tuple of float
        Its frequency (twice for a line), band, or the two lines' frequencies (alias) [Hz].
    true_coning : ndarray (3,)
        Mean non-commutativity rate of the true motion ``q/(2ω)`` [rad/s].
    sensor : ndarray (3,)
        Pseudo-coning drift ``(q − q̃)/(2ω)`` [rad/s].
    algorithm : ndarray (3,)
        The algorithm's residual on the sensed motion ``q̃ D(ωh)/ω`` [rad/s].
    true_rectification : ndarray (3,)
        Rectified specific force of the true motion ``q_s/(2ω)`` [m/s²].
    sensor_sculling : ndarray (3,)
        Pseudo-sculling rectification error [m/s²].
    algorithm_sculling : ndarray (3,)
        The velocity algorithm's residual [m/s²].
    """

    kind: str
    label: str
    band: tuple
    true_coning: np.ndarray
    sensor: np.ndarray
    algorithm: np.ndarray
    true_rectification: np.ndarray
    sensor_sculling: np.ndarray
    algorithm_sculling: np.ndarray

    @property
    def total(self) -> np.ndarray:
        """Coning drift vector, sensor plus algorithm [rad/s]."""
        return self.sensor + self.algorithm

    @property
    def total_sculling(self) -> np.ndarray:
        """Rectification error vector, sensor plus algorithm [m/s²]."""
        return self.sensor_sculling + self.algorithm_sculling


def _axis(primary: np.ndarray, fallback: np.ndarray) -> np.ndarray:
    for v in (primary, fallback):
        n = float(np.linalg.norm(v))
        if n > 0.0:
            return v / n
    return np.array([0.0, 0.0, 1.0])


@dataclass(frozen=True, eq=False)
class EnvironmentDrift:
    """Mean coning drift and sculling rectification of an algorithm in an environment.

    Attributes
    ----------
    algorithm : Algorithm
        The algorithm (its dual extension is the velocity algorithm).
    sample_interval : float
        h [s].
    parts : tuple of DriftPart
        One per line frequency (coherent lines together) and spectrum, in the environment's order.
    coning_axis : ndarray (3,)
        Unit direction of the true coning rate (module docstring); signed drifts are along it.
    sculling_axis : ndarray (3,)
        Unit direction of the true rectified specific force.
    near_aliases : tuple of AliasPair
        Pairs of lines near an alias with the step rate, with their beat
        period (not in the mean: it averages out over many beats).
    warnings : tuple of str
        Where the environment lies outside the closed form's range (:func:`theory_warnings`).
    """

    algorithm: Algorithm
    sample_interval: float
    parts: tuple
    coning_axis: np.ndarray
    sculling_axis: np.ndarray
    near_aliases: tuple = ()
    warnings: tuple = ()

    def _sum(self, name):
        return sum((getattr(p, name) for p in self.parts), np.zeros(3))

    @property
    def total_vector(self) -> np.ndarray:
        """Coning drift vector [rad/s] (exact minus algorithm)."""
        return self._sum("total")

    @property
    def sensor_vector(self) -> np.ndarray:
        """Pseudo-coning part [rad/s]."""
        return self._sum("sensor")

    @property
    def algorithm_vector(self) -> np.ndarray:
        """Algorithm residual [rad/s]."""
        return self._sum("algorithm")

    @property
    def magnitude(self) -> float:
        """``|total_vector|``, the drift rate [rad/s]: the one number to quote."""
        return float(np.linalg.norm(self.total_vector))

    @property
    def sculling_magnitude(self) -> float:
        """``|sculling_vector|``, the rectification-error rate [m/s²]."""
        return float(np.linalg.norm(self.sculling_vector))

    @property
    def total(self) -> float:
        """Projection of the drift on the coning axis [rad/s] (a component, not the drift rate: see :attr:`magnitude`)."""
        return float(self.total_vector @ self.coning_axis)

    @property
    def sensor(self) -> float:
        """Projection of the pseudo-coning on the coning axis [rad/s]."""
        return float(self.sensor_vector @ self.coning_axis)

    @property
    def algorithm_part(self) -> float:
        """Projection of the algorithm residual on the coning axis [rad/s]."""
        return float(self.algorithm_vector @ self.coning_axis)

    @property
    def sculling_vector(self) -> np.ndarray:
        """Rectification error vector [m/s²]."""
        return self._sum("total_sculling")

    @property
    def sculling(self) -> float:
        """Projection of the rectification error on the sculling axis [m/s²]."""
        return float(self.sculling_vector @ self.sculling_axis)

    @property
    def sensor_sculling(self) -> float:
        """Signed pseudo-sculling along the sculling axis [m/s²]."""
        return float(self._sum("sensor_sculling") @ self.sculling_axis)

    @property
    def algorithm_sculling(self) -> float:
        """Signed velocity-algorithm residual along the sculling axis [m/s²]."""
        return float(self._sum("algorithm_sculling") @ self.sculling_axis)


#: Rotation-vector amplitude above which the second-order closed form is flagged [rad]: the terms left out are
#: of relative order θ², 1 % here.
SMALL_ANGLE = 0.1


def theory_warnings(environment: Environment, sample_interval: float) -> tuple:
    """Where the environment lies outside the range of the closed form (empty when inside).

    The closed form is second order in the vibration amplitude and exact in
    ωh.  Its expansion parameters are the rotation-vector amplitude θ of the
    vibration (:meth:`~strapdown.analysis.vibration.environment.Environment.rotation_amplitude`)
    and the largest rotation over one sample ``Ω h`` (Ω: the rate amplitude,
    :meth:`~strapdown.analysis.vibration.environment.Environment.rate_amplitude`);
    the terms left out are of relative order θ² (and the algorithm's own
    higher-order terms of order ``(Ω h)²``).  Either above
    :data:`SMALL_ANGLE` is flagged.

    Parameters
    ----------
    environment : Environment
        The environment.
    sample_interval : float
        h [s], > 0.

    Returns
    -------
    tuple of str
    """
    h = positive(sample_interval, "sample_interval")
    out = []
    theta = environment.rotation_amplitude()
    if theta > SMALL_ANGLE:
        out.append(f"outside the small-angle range of the closed form: the vibration's rotation-vector amplitude reaches {theta:.3g} rad "
                   f"(lines plus 3σ of the spectra), and the terms it leaves out are of relative order θ² = {theta**2:.3g}")  # fmt: skip
    step_angle = environment.rate_amplitude() * h
    if step_angle > SMALL_ANGLE:
        out.append(f"outside the small-angle range of the closed form: the rotation over one sample reaches Ω h = {step_angle:.3g} rad "
                   f"(Ω: lines plus 3σ of the spectra's rate), and terms of relative order (Ω h)² = {step_angle**2:.3g} are left out")  # fmt: skip
    return tuple(out)


def environment_drift(algorithm: Algorithm, environment: Environment, sample_interval: float, *, rtol: float = QUADRATURE_RTOL,
                      min_beat_period: float = NEAR_ALIAS_BEAT) -> EnvironmentDrift:  # fmt: skip
    """Mean coning drift and sculling rectification of ``algorithm`` in ``environment`` (module docstring).

    Parameters
    ----------
    algorithm : Algorithm
        Registry or file algorithm (cross-step indices allowed); its dual
        extension is the velocity algorithm.
    environment : Environment
        Lines, spectra and sensors.
    sample_interval : float
        Algorithm sample interval h [s], > 0 (step H = N h).
    rtol : float, keyword-only
        Relative tolerance of the spectrum quadrature.
    min_beat_period : float, keyword-only
        Pairs of lines whose beat with the step rate is longer than this are
        listed as near an alias [s] (:func:`strapdown.analysis.vibration.aliasing.alias_pairs`).

    Returns
    -------
    EnvironmentDrift

    Raises
    ------
    TypeError
        If ``algorithm`` is not an Algorithm or ``environment`` not an Environment.
    ValueError
        For a non-positive sample interval or a digital filter above the
        sensor's Nyquist frequency.

    References
    ----------
    Lebedev & Panov (1989), eq. (2.5); Ignagni (1990); Savage (1998).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> from strapdown.analysis.vibration.environment import coning_line
    >>> from strapdown.analysis.vibration.sensor_dynamics import Sensor, ChannelFilter, analog_filter
    >>> lp = ChannelFilter(analog_filter("lowpass1", cutoff_hz=100.0))
    >>> env = Environment((coning_line(10.0, math.radians(1.0)),), gyro=Sensor((lp, lp, lp)))
    >>> d = environment_drift(get("two-sample"), env, 1e-3)
    >>> round(d.sensor * 180 / math.pi * 3600, 2)    # pseudo-coning [deg/h]
    19.54
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not isinstance(environment, Environment):
        raise TypeError(f"Expected `environment` to be an Environment, got {type(environment).__name__}")
    if not environment.has_motion:
        raise ValueError(
            "Expected an `environment` with motion (a line or spectrum with a nonzero amplitude), got no motion: no line or spectrum, "
            "or every amplitude and density zero (a file of sensors only); its drift would be zero by construction"
        )
    D = coning_drift_function(algorithm)
    r = response_integrals(environment, sample_interval, (D,), rtol=rtol)
    parts = []
    for i, (kind, label, band) in enumerate(r.parts):
        true, sensed, alg = r.true[i], r.sensed[i], r.algorithm[0, i]
        parts.append(DriftPart(kind, label, tuple(band), true[0], true[0] - sensed[0], alg[0], true[1], true[1] - sensed[1], alg[1]))
    pairs = alias_pairs(algorithm, environment, sample_interval, min_beat_period=min_beat_period)
    zero = np.zeros(3)
    for p in pairs:
        if p.exact:
            label = f"{p.labels[0]} × {p.labels[1]} ({p.kind} {p.multiple}/H)"
            parts.append(DriftPart("alias", label, p.frequencies, zero, zero, p.drift, zero, zero, p.sculling))
    total = sum((p.total for p in parts), np.zeros(3))
    scull = sum((p.total_sculling for p in parts), np.zeros(3))
    c_axis = _axis(r.true[:, 0].sum(axis=0) if r.parts else np.zeros(3), total)
    s_axis = _axis(r.true[:, 1].sum(axis=0) if r.parts else np.zeros(3), scull)
    return EnvironmentDrift(algorithm, float(sample_interval), tuple(parts), c_axis, s_axis, tuple(p for p in pairs if not p.exact),
                            theory_warnings(environment, sample_interval))  # fmt: skip


def line_response(algorithm: Algorithm, line: VibrationLine, environment: Environment, sample_interval: float) -> DriftPart:
    """The drift of one line seen through the sensors of ``environment`` (its own lines and spectra ignored).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm.
    line : VibrationLine
        The line.
    environment : Environment
        Supplies the sensors.
    sample_interval : float
        h [s].

    Returns
    -------
    DriftPart
    """
    env = Environment((line,), (), environment.gyro, environment.accelerometer)
    return environment_drift(algorithm, env, sample_interval).parts[0]
