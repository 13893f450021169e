"""What Plotnikov (1999) prints: the section-5 example, its results, and formulas as printed.

Reference data, kept once, each with its place in the paper.  The package never
computes *with* the printed results; the printed formulas are here so that the
checks can evaluate them against the derivations (several are misprinted:
see the errata of the stability report).  Scale factors printed in percent are
given as fractions.

Printed formulas are SymPy expressions in the symbols :data:`SYMBOLS`; they (and
SymPy) are loaded on first access, so that the numbers import without SymPy.

Examples
--------
>>> PRINTED_GAINS.stage2_before
(0.015, 0.000125)
>>> PAPER.yaw_stage1.value
-0.03
"""

from __future__ import annotations

from typing import NamedTuple

__all__ = [
    "SOURCE",
    "Reported",
    "Section5Results",
    "PAPER",
    "PrintedGains",
    "PRINTED_GAINS",
    "Section5Setup",
    "SECTION5",
    "PublishedSymbols",
    "PRINTED_C_SECOND_VARIANT",
]
#: Printed formulas and their symbols, built with SymPy on first access (module ``__getattr__``).
_LAZY = ("SYMBOLS", "PRINTED_COS_GAMMA_1_9", "PRINTED_TILT_QUATERNION_1_10", "PRINTED_W3_3_7", "PRINTED_M11_3_7", "PRINTED_M13_3_7", "PRINTED_LINEARISED_3_8")
__all__ += list(_LAZY)

SOURCE = "Plotnikov (1999)"


class Reported(NamedTuple):
    """One number reported by the paper.

    Attributes
    ----------
    value : float
        As printed (signs kept).
    unit : str
    place : str
        Where it is printed.
    """

    value: float
    unit: str
    place: str


class Section5Results(NamedTuple):
    """Results of the section-5 simulation as printed (fig. 6 and its discussion).

    Attributes
    ----------
    stage1_pitch_peak : Reported
        Largest pitch error after stage 1.
    stage2_estimate : Reported
        The second stage's own estimate over the same interval.
    two_stage_pitch_bound : Reported
        Bound of the pitch error after two stages.
    pitch_reduction : Reported
        "eight times smaller".
    roll_reduction : Reported
        "reduced twofold".
    yaw_stage1 : Reported
        Yaw error after stage 1.
    yaw_two_stage : Reported
        Yaw error after two stages.
    """

    stage1_pitch_peak: Reported
    stage2_estimate: Reported
    two_stage_pitch_bound: Reported
    pitch_reduction: Reported
    roll_reduction: Reported
    yaw_stage1: Reported
    yaw_two_stage: Reported


#: Results of section 5.
PAPER = Section5Results(
    stage1_pitch_peak=Reported(3.4e-2, "rad", "section 5, fig. 6a"),
    stage2_estimate=Reported(3.3e-2, "rad", "section 5, fig. 6b"),
    two_stage_pitch_bound=Reported(4.5e-3, "rad", "section 5, fig. 6c"),
    pitch_reduction=Reported(8.0, "-", "section 5, after fig. 6c"),
    roll_reduction=Reported(2.0, "-", "section 5, last paragraph"),
    yaw_stage1=Reported(-3e-2, "rad", "section 5, last paragraph"),
    yaw_two_stage=Reported(-3.5e-3, "rad", "section 5, last paragraph"),
)


class PrintedGains(NamedTuple):
    """Gains of section 5 as printed.

    Attributes
    ----------
    stage1 : tuple
        (k [1/s], l [1/s²]) of stage 1, kept for the whole run.
    stage2_before : tuple
        (k⁽¹⁾, l⁽¹⁾) of stage 2 until the switch.
    switch_time : float
        Switch of stage 2 [s].
    stage2_after : tuple
        (k⁽¹⁾, l⁽¹⁾) after the switch as printed: "k⁽¹⁾ = 0; l⁽¹⁾ = (1.24·10⁻³) s⁻²",
        "with the Schuler conditions fulfilled".
    """

    stage1: tuple
    stage2_before: tuple
    switch_time: float
    stage2_after: tuple


#: Section 5, second paragraph.
PRINTED_GAINS = PrintedGains(stage1=(0.01, 0.5e-4), stage2_before=(1.5e-2, 1.25e-4), switch_time=600.0, stage2_after=(0.0, 1.24e-3))


class Section5Setup(NamedTuple):
    """The example of section 5 as printed.

    Attributes
    ----------
    latitude_deg : float
        φ = 45° [deg].
    rest_end : float
        At rest for t = 0…1000 s [s].
    duration : float
        Rocking until 5000 s [s].
    rocking_amplitude : tuple
        (ψ, θ, γ) amplitudes 0.2, 0.1, 0.1 [rad].
    rocking_frequency : float
        ``sin πt``: π [rad/s].
    rocking_phase : tuple
        ``sin(πt + 0.5π)`` for ψ, ``sin πt`` for θ, γ [rad].
    envelope_decay : float
        ``E = exp(−0.1(t − 600))``: 0.1 [1/s].
    envelope_origin : float
        The 600 of the same formula [s].
    accel_start : float
        ``t = 1200…1220 s`` [s].
    accel_duration : float
        20 [s].
    accel : float
        ``V̇ζ₁ = 20 m/s²`` [m/s²] (to the north).
    scale_factor_error : float
        "10⁻³ %" for gyros and accelerometers [-].
    gyro_drift : float
        "0.5·10⁻⁷ s⁻¹", "with different signs by component" [rad/s].
    accel_bias : float
        "10⁻³ m/s²", "with different signs by component" [m/s²].
    initial : tuple
        ``ν(t₀) = ν₁(t₀) = 1``.
    """

    latitude_deg: float = 45.0
    rest_end: float = 1000.0
    duration: float = 5000.0
    rocking_amplitude: tuple = (0.2, 0.1, 0.1)
    rocking_frequency: float = 3.141592653589793
    rocking_phase: tuple = (1.5707963267948966, 0.0, 0.0)
    envelope_decay: float = 0.1
    envelope_origin: float = 600.0
    accel_start: float = 1200.0
    accel_duration: float = 20.0
    accel: float = 20.0
    scale_factor_error: float = 1e-5
    gyro_drift: float = 0.5e-7
    accel_bias: float = 1e-3
    initial: tuple = (1.0, 0.0, 0.0, 0.0)


#: Section 5, first paragraph.
SECTION5 = Section5Setup()

#: Section 1, after (1.6): "c = 2 and the difference μ⁺ − 2ν is taken" in the second variant.
PRINTED_C_SECOND_VARIANT = 2.0


class PublishedSymbols(NamedTuple):
    """Symbols of the printed formulas (:data:`SYMBOLS`).

    Attributes
    ----------
    n1, n2, n3 : sympy.Symbol
        Load factors ``n_xi = W_xi/g`` in body axes.
    h, n : sympy.Symbol
        ``√(n₂² + n₃²)`` and ``√(n₁² + n₂² + n₃²)`` of (1.9).
    g : sympy.Symbol
        Gravity.
    W1, W3 : sympy.Symbol
        Horizontal specific force in η.
    alpha, beta, chi : sympy.Symbol
        Small error angles of stage 1 about the axes 1, 2, 3 of η (fig. 5).
    """

    n1: object
    n2: object
    n3: object
    h: object
    n: object
    g: object
    W1: object
    W3: object
    alpha: object
    beta: object
    chi: object


def _formulas() -> dict:
    import sympy as sp

    s = PublishedSymbols(
        *sp.symbols("n1 n2 n3", real=True),
        *sp.symbols("h n", positive=True),
        sp.Symbol("g", positive=True),
        *sp.symbols("W1 W3", real=True),
        *sp.symbols("alpha beta chi", real=True),
    )
    mu0 = sp.Rational(1, 2) * sp.sqrt(s.h / s.n + s.n2 / s.n + s.n3 / s.h + 1)
    return {
        "SYMBOLS": s,
        # (1.9) as printed: cos γ = −n_x2/h.
        "PRINTED_COS_GAMMA_1_9": -s.n2 / s.h,
        # (1.10) as printed: (μ0, μ1, μ2, μ3) in the load factors.
        "PRINTED_TILT_QUATERNION_1_10": (
            mu0,
            -(s.n3 / s.n + s.n3 / s.h) / (4 * mu0),
            -s.n1 * s.n3 / (4 * mu0 * s.n * s.h),
            (s.n1 * s.n2 + s.n1) / (4 * mu0 * s.n * s.h),
        ),
        # (3.7) as printed: W3(1) = W3 − gα − W1β.
        "PRINTED_W3_3_7": s.W3 - s.g * s.alpha - s.W1 * s.beta,
        # (3.7) as printed: M11 = n_η3(1) = −W3(1)/g = α − n3 − n1β (n = W/g in η).
        "PRINTED_M11_3_7": s.alpha - s.W3 / s.g - s.W1 / s.g * s.beta,
        # (3.7) as printed: M13 = n_η1(1) = W1(1)/g = n1 + χ − n3β.
        "PRINTED_M13_3_7": s.W1 / s.g + s.chi - s.W3 / s.g * s.beta,
        "PRINTED_LINEARISED_3_8": _linearised_3_8(sp),
    }


def _linearised_3_8(sp) -> dict:
    """(3.8) as printed, with the integrals as states y₁, y₃ (y' = l(…)), in functions of t.

    The names are those of :data:`strapdown.derivations.multistage.schuler.SYMBOLS`
    (SymPy functions with equal names and assumptions are equal).
    """
    t = sp.Symbol("t", real=True)
    k, l = sp.symbols("k l", positive=True)
    f = {n: sp.Function(n, real=True)(t) for n in ("alpha", "beta", "chi", "theta1", "gamma1", "omega1", "omega3", "y1", "y3", "n1", "n3")}
    theta_in = f["chi"] + f["n1"] - f["theta1"] - f["n3"] * f["beta"]
    gamma_in = f["alpha"] - f["n3"] - f["gamma1"] - f["n1"] * f["beta"]
    return {
        "psi1": sp.diff(f["beta"], t),
        "theta1": sp.diff(f["chi"], t) + f["omega3"] + k * theta_in + f["y3"],
        "gamma1": sp.diff(f["alpha"], t) + f["omega1"] + k * gamma_in + f["y1"],
        "y3": l * theta_in,
        "y1": l * gamma_in,
    }


def __getattr__(name):
    """The printed formulas and :data:`SYMBOLS`, built (with SymPy) on first access."""
    if name in _LAZY:
        values = _formulas()
        globals().update(values)
        return values[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
