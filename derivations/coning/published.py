"""Published reference data of the coning papers, each with its source.

Everything here is typed from the papers as printed, misprints included: a
printed number that a check contradicts stays as printed, and the erratum
with its evidence is in ``reports/errata.md``.  These are reference data,
never inputs to a computation; the tests, the reports and ``strapdown
reproduce`` compare the package's results with them, and read them from here
only.  Experiment conditions (angles, frequencies, steps) are kept in the
units the paper prints; the numeric side converts them.

Page numbers are not given: neither stored copy of the papers carries them.

The module is organised in independent blocks, one per source:

* Budennyi, Kalinovsky, Panov et al. (Part 2): Table 1 column 2 as printed,
  Tables 2–5 and the conditions of Tables 3–5.
* Lebedev & Panov (1989): the table of section 6 and its conditions, and the
  printed formulas (1.12), (2.4), (4.7) and the structure functions of
  section 5.
* Published algorithms (Ignagni 1990, 1996; Savage 1998; the PSINS coefficient
  table): ``PUBLISHED_ALGORITHM_ERRORS`` and ``PUBLISHED_ALGORITHM_COEFFICIENTS``.

The coefficients of Table 1 define the registry algorithms and live in
:mod:`strapdown.derivations.coning.registry` (``PANOV_TABLE_1``, ``PANOV_BASIS``).
"""

from __future__ import annotations

from fractions import Fraction
from typing import NamedTuple

import sympy as sp

from .drift import COS as _COS
from .drift import EPS as _EPS
from .drift import NU as _NU
from .drift import SIN as _SIN
from .drift import THETA as _THETA
from .drift import THETA_DUAL as _THETA_DUAL

# ===========================================================================
# Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 1–5
# ===========================================================================
#: Budennyi, Kalinovsky, Panov et al. (Part 2), Table 1, column of algorithm 2 as printed:
#: (a1, a2, a3, a4).  Erratum: Tables 2 and 3 require a1 = a2 = 4/3, a3 = 0 (the registry's reading).
BUDENNYI_TABLE_1_COLUMN_2 = ("0", "0", "4/3", "0")


class BudennyiTable2Column(NamedTuple):
    """One column of Budennyi, Kalinovsky, Panov et al. (Part 2), Table 2.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5 (registry name ``panov-4s-<n>``).
    k : tuple of int
        k03, k12, k002, k110, k0001 of the local error (2), as printed.
    delta : Fraction
        δ4, as printed.
    additions : int
        s: additions of one step of the algorithm.
    multiplications : int
        u: multiplications of one step of the algorithm.
    """

    algorithm: int
    k: tuple
    delta: Fraction
    additions: int
    multiplications: int


#: Table 2: local-error coefficients and operation counts.  Algorithm 4's
#: k002 = 488, k0001 = −488 are a misprint of 448, −448 (errata).
BUDENNYI_TABLE_2 = (
    BudennyiTable2Column(1, (-1, 46, 16, 48, -16), Fraction(4, 45), 15, 9),
    BudennyiTable2Column(2, (16, 124, 64, 192, -64), Fraction(1, 45), 21, 15),
    BudennyiTable2Column(3, (0, 0, 64, 192, -64), Fraction(1, 45), 33, 24),
    BudennyiTable2Column(4, (52, 0, 488, 1344, -488), Fraction(1, 315), 45, 48),
    BudennyiTable2Column(5, (0, 0, 64, 192, -64), Fraction(1, 45), 45, 48),
)


class BudennyiConditions(NamedTuple):
    """Conditions of Tables 3–5 of Budennyi, Kalinovsky, Panov et al. (Part 2), as printed.

    Attributes
    ----------
    nutation_deg : float
        Nutation ϑ [deg].
    freq_hz : float
        Frequency f of the coning or precession [Hz] (ν = 2π f).
    step : float
        Algorithm step H = 4h [s] (Table 3).
    samples : int
        Samples per step N (four-sample algorithms).
    eps : tuple of float
        ε = μ/ν of the two motions: −1 (coning) and 0.5 (precession).
    required_drift_deg_per_h : tuple of float
        [u] of Table 4 and of Table 5 [deg/h].
    multiplication_cost : float
        m: a multiplication counts as m additions (eq. (6)).
    """

    nutation_deg: float
    freq_hz: float
    step: float
    samples: int
    eps: tuple
    required_drift_deg_per_h: tuple
    multiplication_cost: float


#: Headers of Tables 3, 4 and 5 and eq. (6): ϑ = 1°, f = 10 Hz, H = 0.01 s, [u] = 1e-3 and 1e-5 deg/h, m = 5.
BUDENNYI_CONDITIONS = BudennyiConditions(1.0, 10.0, 0.01, 4, (-1.0, 0.5), (1e-3, 1e-5), 5.0)


class BudennyiTable3Row(NamedTuple):
    """One row of Budennyi, Kalinovsky, Panov et al. (Part 2), Table 3.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    eps : float
        ε = μ/ν: −1 (coning) or 0.5 (precession).
    order : int
        ρ, the printed order of the drift.
    u_star_deg_per_h : float
        u*: constant drift rate by parallel computation [deg/h], as printed.
    u_a_deg_per_h : float or None
        u_a: the asymptotic estimate (3) [deg/h], as printed; None where not printed.
    """

    algorithm: int
    eps: float
    order: int
    u_star_deg_per_h: float
    u_a_deg_per_h: float | None


#: Table 3: constant drift rate [deg/h] at ϑ = 1°, f = 10 Hz, H = 0.01 s.
BUDENNYI_TABLE_3 = (
    BudennyiTable3Row(1, -1.0, 4, 2.47, 2.51),
    BudennyiTable3Row(2, -1.0, 4, 1.42, 1.44),
    BudennyiTable3Row(3, -1.0, 6, 3.95e-4, 3.76e-4),
    BudennyiTable3Row(4, -1.0, 4, 9.60e-2, 9.92e-2),
    BudennyiTable3Row(5, -1.0, 6, 5.98e-4, 6.45e-4),
    BudennyiTable3Row(1, 0.5, 4, 6.72e-2, 5.35e-2),
    BudennyiTable3Row(2, 0.5, 4, 1.31e-1, 1.20e-1),
    BudennyiTable3Row(3, 0.5, 4, 6.45e-1, 6.41e-1),
    BudennyiTable3Row(4, 0.5, 4, 5.95e-1, 5.91e-1),
    BudennyiTable3Row(5, 0.5, 4, 6.45e-1, None),
)


class BudennyiLoadRow(NamedTuple):
    """One row of Budennyi, Kalinovsky, Panov et al. (Part 2), Tables 4 and 5.

    Attributes
    ----------
    algorithm : int
        Algorithm number 1–5.
    eps : float
        ε = μ/ν: −1 (coning) or 0.5 (precession).
    order : int
        ρ, as printed.
    beta_star_4 : int
        β* of Table 4 ([u] = 1e-3 deg/h), by parallel computation [thousand operations/s].
    beta_a_4 : int or None
        β_a of Table 4, from the asymptotic estimate [thousand operations/s]; None where not printed.
    beta_star_5 : int
        β* of Table 5 ([u] = 1e-5 deg/h) [thousand operations/s].
    """

    algorithm: int
    eps: float
    order: int
    beta_star_4: int
    beta_a_4: int | None
    beta_star_5: int


#: Tables 4 and 5: the largest computational load [thousand operations/s] at ϑ = 1°, f = 10 Hz, m = 5.
BUDENNYI_TABLES_4_5 = (
    BudennyiLoadRow(1, -1.0, 4, 556, 556, 1760),
    BudennyiLoadRow(2, -1.0, 4, 572, 576, 1808),
    BudennyiLoadRow(3, -1.0, 6, 92, 98, 212),
    BudennyiLoadRow(4, -1.0, 4, 528, 532, 1672),
    BudennyiLoadRow(5, -1.0, 6, 148, 156, 336),
    BudennyiLoadRow(1, 0.5, 4, 284, 268, 836),
    BudennyiLoadRow(2, 0.5, 4, 361, 354, 1124),
    BudennyiLoadRow(3, 0.5, 4, 652, 684, 2064),
    BudennyiLoadRow(4, 0.5, 4, 900, 900, 2848),
    BudennyiLoadRow(5, 0.5, 4, 688, None, 3016),
)


# ===========================================================================
# Lebedev & Panov (1989), section 6: the table and its conditions
# ===========================================================================
class LebedevPanovVariant(NamedTuple):
    """One variant of the experiment of Lebedev & Panov (1989), section 6.

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
    tilted_start : bool
        Λ(0) = {cos(ϑ/2), sin(ϑ/2), 0, 0} if True, {1, 0, 0, 0} if False.
    """

    number: int
    nu_dual: float
    nutation_dual: float
    w_inertial0: tuple
    tilted_start: bool


class LebedevPanovConditions(NamedTuple):
    """Conditions of the experiment of Lebedev & Panov (1989), section 6, as printed.

    Attributes
    ----------
    duration : float
        Length of the run [s]; the table holds the errors at its end.
    spin_freq_hz : float
        ν / 2π [Hz] (the paper prints ν = 2π s⁻¹).
    nutation_deg : float
        ϑ [deg].
    sample_interval : float
        h [s]; the step is H = 4h.
    eps : tuple of float
        ε of the two motions: −1 (coning) and 0.5.
    orders : tuple of int
        ρ of the algorithms (2.2)/(2.5) compared: 4 and 6.
    variants : tuple of LebedevPanovVariant
        The three variants of ν°, ϑ°, W_I(0) and Λ(0).
    """

    duration: float
    spin_freq_hz: float
    nutation_deg: float
    sample_interval: float
    eps: tuple
    orders: tuple
    variants: tuple


#: Section 6: 100 s, ν = 2π s⁻¹, ϑ = 10°, h = 0.01 s, ε ∈ {−1, 0.5}, variants 1–3.
LEBEDEV_PANOV_CONDITIONS = LebedevPanovConditions(
    100.0,
    1.0,
    10.0,
    0.01,
    (-1.0, 0.5),
    (4, 6),
    (
        LebedevPanovVariant(1, 0.5, 10.0, (10.0, 0.0, 0.0), True),
        LebedevPanovVariant(2, 10.0, 100.0, (100.0, 0.0, 0.0), True),
        LebedevPanovVariant(3, 10.0, 100.0, (20.0, 35.0, 40.0), False),
    ),
)


class LebedevPanovCell(NamedTuple):
    """One printed cell of the table of Lebedev & Panov (1989), section 6.

    Attributes
    ----------
    quantity : str
        ``"drift"`` (constant drift rate δφ° [deg/h]), ``"dW_E"`` or ``"dW_I"`` (``|ΔW_E|``, ``|ΔW_I|`` at t = 100 s [m/s]).
    order : int
        ρ of the algorithm.
    eps : float
        ε of the motion.
    variants : tuple of int
        The variants the printed value stands for (the drift row covers 1–3, ``|ΔW_I|`` one cell for 2 and 3).
    value : float
        The printed value, in :attr:`unit` [deg/h or m/s].
    """

    quantity: str
    order: int
    eps: float
    variants: tuple
    value: float

    @property
    def unit(self) -> str:
        """Unit of :attr:`value` as printed: ``"deg/h"`` for the drift, ``"m/s"`` for ``|ΔW_E|``, ``|ΔW_I|``."""
        return "deg/h" if self.quantity == "drift" else "m/s"


#: The table of section 6 (the ρ = 6 rows of ``|ΔW_E|``, ``|ΔW_I|`` do not reproduce: errata).
LEBEDEV_PANOV_TABLE = (
    LebedevPanovCell("drift", 4, -1.0, (1, 2, 3), 1.590e-1),
    LebedevPanovCell("drift", 4, 0.5, (1, 2, 3), 8.216e-2),
    LebedevPanovCell("drift", 6, -1.0, (1, 2, 3), 3.476e-4),
    LebedevPanovCell("drift", 6, 0.5, (1, 2, 3), 8.372e-4),
    LebedevPanovCell("dW_E", 4, -1.0, (1,), 8.648e-3),
    LebedevPanovCell("dW_E", 4, -1.0, (2,), 8.619e-2),
    LebedevPanovCell("dW_E", 4, -1.0, (3,), 8.644e-2),
    LebedevPanovCell("dW_E", 4, 0.5, (1,), 4.597e-3),
    LebedevPanovCell("dW_E", 4, 0.5, (2,), 4.619e-2),
    LebedevPanovCell("dW_E", 4, 0.5, (3,), 4.644e-2),
    LebedevPanovCell("dW_E", 6, -1.0, (1,), 5.794e-6),
    LebedevPanovCell("dW_E", 6, -1.0, (2,), 5.851e-5),
    LebedevPanovCell("dW_E", 6, -1.0, (3,), 5.783e-5),
    LebedevPanovCell("dW_E", 6, 0.5, (1,), 4.017e-5),
    LebedevPanovCell("dW_E", 6, 0.5, (2,), 3.999e-4),
    LebedevPanovCell("dW_E", 6, 0.5, (3,), 6.406e-4),
    LebedevPanovCell("dW_I", 4, -1.0, (1,), 8.648e-3),
    LebedevPanovCell("dW_I", 4, -1.0, (2, 3), 8.755e-2),
    LebedevPanovCell("dW_I", 4, 0.5, (1,), 4.629e-3),
    LebedevPanovCell("dW_I", 4, 0.5, (2, 3), 4.688e-2),
    LebedevPanovCell("dW_I", 6, -1.0, (1,), 5.978e-6),
    LebedevPanovCell("dW_I", 6, -1.0, (2, 3), 6.207e-5),
    LebedevPanovCell("dW_I", 6, 0.5, (1,), 8.687e-5),
    LebedevPanovCell("dW_I", 6, 0.5, (2, 3), 1.232e-3),
)


# ===========================================================================
# Lebedev & Panov (1989): printed formulas
# ===========================================================================
#: Eq. (2.4): the local error of (2.2) is 8/945 h⁷ Σ c_w x_w (exact minus algorithm);
#: {word: c_w}, the word ``"1101"`` standing for x_1101 = ω' × (ω' × (ω × ω')).
EQ_2_4_FACTOR = Fraction(8, 945)
EQ_2_4 = {
    "23": 92, "05": 1, "14": 6, "004": 6, "013": 42, "103": 24, "112": -66, "202": -116, "301": -30,
    "0003": -34, "0012": -28, "0102": 128, "0201": -340, "1101": 246, "2001": 28, "00002": -64,
    "01001": -64, "10001": 256, "000001": 64, "1002": -176,
}  # fmt: skip

#: Section 5: the structure functions printed for ρ = 2 and 4 (algorithm (2.2) truncated to
#: that order), {ρ: {name: expression}} in ε, cos ϑ, sin ϑ and ϑ° (the symbols of
#: :mod:`strapdown.derivations.coning.drift`).
STRUCTURE_FUNCTIONS = {
    2: {"f": -_EPS, "g": 1 + _EPS * _COS, "f_dual": sp.Integer(0), "g_dual": -_EPS * _THETA_DUAL * _SIN},
    4: {
        "f": -_EPS * (4 * _EPS**2 + 24 * _EPS * _COS + 23),
        "g": 4 * _EPS**3 * _COS + 8 * _EPS**2 * (3 * _COS**2 - 1) + 19 * _EPS * _COS + 7,
        "f_dual": 24 * _EPS**2 * _THETA_DUAL * _SIN,
        "g_dual": -_EPS * _THETA_DUAL * _SIN * (4 * _EPS**2 + 48 * _EPS * _COS + 19),
    },
}

#: Symbols of the printed (1.12): the rotation vector φ and its dual part φ°.
PHI = sp.symbols("phi_1:4", real=True)
PHI_DUAL = sp.symbols("phi_dual_1:4", real=True)
_PHI_NORM = sp.sqrt(sum(c**2 for c in PHI))
_PHI_DOT = sum(a * b for a, b in zip(PHI, PHI_DUAL))


class BiquaternionFormula(NamedTuple):
    """The map of a dual vector Φ = φ + s φ° to the unit biquaternion Λ + s M, as printed in (1.12).

    Attributes
    ----------
    lam : tuple of sympy.Expr
        λ0 … λ3 in :data:`PHI`.
    mu : tuple of sympy.Expr
        μ0 … μ3 in :data:`PHI` and :data:`PHI_DUAL`.
    condition : sympy.Expr
        The printed second unit condition, λ0μ0 − λ1μ1 − λ2μ2 − λ3μ3 (= 0 as printed), in
        the symbols ``lambda_0:4`` and ``mu_0:4`` of :data:`CONDITION_SYMBOLS`.
    """

    lam: tuple
    mu: tuple
    condition: sp.Expr


#: Symbols λ0 … λ3, μ0 … μ3 of the printed unit condition after (1.12).
CONDITION_SYMBOLS = (sp.symbols("lambda_0:4", real=True), sp.symbols("mu_0:4", real=True))

#: Lebedev & Panov (1989), eq. (1.12) and the condition after it, as printed.  Errata: the sign
#: of the second term of μ_i and the signs of the condition (evidence in reports/errata.md).
EQ_1_12 = BiquaternionFormula(
    lam=(sp.cos(_PHI_NORM / 2),) + tuple(c / _PHI_NORM * sp.sin(_PHI_NORM / 2) for c in PHI),
    # μ0 keeps the printed order of its factors, −½ · φ⁻¹ · sin(φ/2) · (φ·φ°), so that a
    # numeric evaluation in that order rounds as the printed formula reads.
    mu=(sp.Mul(sp.Mul(sp.Rational(-1, 2), sp.Pow(_PHI_NORM, -1, evaluate=False), evaluate=False), sp.sin(_PHI_NORM / 2), _PHI_DOT, evaluate=False),)
    + tuple(
        sp.sin(_PHI_NORM / 2) / _PHI_NORM * d
        - _PHI_NORM**-2 * (sp.cos(_PHI_NORM / 2) / 2 - sp.sin(_PHI_NORM / 2) / _PHI_NORM) * _PHI_DOT * c
        for c, d in zip(PHI, PHI_DUAL)
    ),
    condition=CONDITION_SYMBOLS[0][0] * CONDITION_SYMBOLS[1][0] - sum(CONDITION_SYMBOLS[0][i] * CONDITION_SYMBOLS[1][i] for i in (1, 2, 3)),
)

#: Symbols of the printed (4.7): time t, ν° and the garbled symbol "Λ°" of its last row.
T, NU_DUAL, LAMBDA_DUAL = sp.symbols("t nu_dual Lambda_dual", real=True)

#: Lebedev & Panov (1989), eq. (4.7): U_I(t) = 2 R ∘ Q̄ of the dual regular precession, as printed,
#: in t, ε, ν, ϑ, ν°, ϑ° (symbols of :mod:`strapdown.derivations.coning.drift` and :data:`T`,
#: :data:`NU_DUAL`); the last row carries the garbled symbol :data:`LAMBDA_DUAL` (erratum: ν°).
EQ_4_7 = (
    sp.Integer(0),
    NU_DUAL * T * _SIN * sp.sin(_EPS * _NU * T) + _THETA_DUAL * sp.cos(_EPS * _NU * T),
    -NU_DUAL * T * _SIN * sp.cos(_EPS * _NU * T) + _THETA_DUAL * sp.sin(_EPS * _NU * T),
    LAMBDA_DUAL * T * (_EPS + _COS),
)
#: The symbols of (4.7) in the order (t, ε, ν, ϑ, ν°, ϑ°, Λ°).
EQ_4_7_SYMBOLS = (T, _EPS, _NU, _THETA, NU_DUAL, _THETA_DUAL, LAMBDA_DUAL)


# ---------------------------------------------------------------- published algorithms
class PublishedFigure(NamedTuple):
    """One published number about an algorithm.

    Attributes
    ----------
    key : str
        Short identifier, unique in its table.
    algorithm : str
        Registry name of the algorithm it is about.
    quantity : str
        What it is: ``"coning_coefficient"`` (ρ_N in the residual coning drift
        ``ρ_N α² Ω (ΩT)^{2N}``, T the algorithm step), ``"coefficient"`` (a
        printed algorithm coefficient).
    value : Fraction
        The printed number, exactly.
    source : str
        Author, year, table or equation.
    note : str
        How it is printed, where that matters.
    """

    key: str
    algorithm: str
    quantity: str
    value: Fraction
    source: str
    note: str = ""


# ===========================================================================
# PUBLISHED_ALGORITHM_ERRORS: published error figures of coning algorithms.
# (This block is self-contained: other tables of the domain go in blocks of
# their own.)
# ===========================================================================
_PSINS = "PSINS toolbox (Yan Gongmin), coning/sculling coefficient table glv.cs with the residual coefficient ρ_N"
#: Residual coning drift of the optimal N-sample compressed algorithm under classical coning
#: (half-cone angle α, coning rate Ω, step T = N h): drift ≈ ρ_N α² Ω (ΩT)^{2N}.  N = 1 is the
#: uncompensated one-sample update.  N = 2, 3 are also printed by Ignagni (1990).
PUBLISHED_ALGORITHM_ERRORS = (
    PublishedFigure("rho-1", "one-sample", "coning_coefficient", Fraction(1, 12), _PSINS, "row N = 1, no coning term"),
    PublishedFigure("rho-2", "compressed-2", "coning_coefficient", Fraction(1, 960), _PSINS),
    PublishedFigure("rho-3", "compressed-3", "coning_coefficient", Fraction(1, 204120), _PSINS),
    PublishedFigure("rho-4", "compressed-4", "coning_coefficient", Fraction(1, 82575360), _PSINS),
    PublishedFigure("rho-5", "compressed-5", "coning_coefficient", Fraction(1, 54140625000), _PSINS),
    PublishedFigure("rho-6", "compressed-6", "coning_coefficient", Fraction(1, 52295018840064), _PSINS),
)

#: Printed coefficients k_1 … k_{N−1} of the compressed optimal algorithms ``(Σ k_i p_i) × p_N``
#: (the registry holds the same numbers as its data; kept here as the quotation the tests
#: compare the derived optimal coefficients with).
PUBLISHED_ALGORITHM_COEFFICIENTS = {
    2: ((Fraction(2, 3),), _PSINS),
    3: ((Fraction(9, 20), Fraction(27, 20)), _PSINS + "; Ignagni (1996), Algorithm 3"),
    4: ((Fraction(54, 105), Fraction(92, 105), Fraction(214, 105)), _PSINS + "; Ignagni (1996), Algorithm 7"),
    5: ((Fraction(250, 504), Fraction(525, 504), Fraction(650, 504), Fraction(1375, 504)), _PSINS),
    6: ((Fraction(2315, 4620), Fraction(4558, 4620), Fraction(7296, 4620), Fraction(7834, 4620), Fraction(15797, 4620)), _PSINS),
}

#: The N = 6 row as the PSINS manual prints it in Tab. 10-1 ("Coning error compensation
#: coefficients"): k_1 = 2135/4620, where the glv.cs table has 2315/4620.
PSINS_TABLE_10_1_N6 = (
    (Fraction(2135, 4620), Fraction(4558, 4620), Fraction(7296, 4620), Fraction(7834, 4620), Fraction(15797, 4620)),
    "PSINS manual (Yan Gongmin), section 10.7, Tab. 10-1, row N = 6",
)
# ============================================================== end of block
