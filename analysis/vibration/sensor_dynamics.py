"""Sensor dynamics of an inertial measurement unit: analog filters, digital filters, decimation.

A sensor channel (one axis of the gyro triad or of the accelerometer triad)
is, in this order:

1. an **analog filter** ``H_a(s)`` acting on the continuous rate (or specific
   force) before it is integrated: a first-order low-pass, a Butterworth or
   Bessel low-pass of any order, or any rational transfer function in
   ``scipy.signal`` form (numerator and denominator in powers of s, s in
   rad/s, highest power first);
2. **integration** over the sensor interval ``h_s``: the channel delivers
   increments ``∫ y dt`` (an integrating gyro, a velocity-increment
   accelerometer);
3. a **digital filter** ``D(z)`` on that stream of increments, at the sensor
   rate (a MEMS digital low-pass), in ``scipy.signal.lfilter`` form;
4. **decimation** by an integer M: M consecutive filtered increments are
   summed into one increment of the algorithm's sample interval ``h = M h_s``
   (the increment over ``h`` is the sum of the increments over its parts).

Every stage is linear and time-invariant, so a sinusoid of angular frequency
ω comes out of the chain as the increments of the sinusoid multiplied by the
*equivalent response*

    H(ω) = H_a(iω) · D(e^{iω h_s}),

(:meth:`Sensor.response`): the increments over ``h`` of the sensed channel
are those of a continuous signal ``Re(H(ω) A e^{iωt})`` — the stage 2
integration and the stage 4 sum are exact and add no response of their own.
Filters must pass a constant unchanged (unit gain at zero frequency): a scale
factor is a different error and is not modelled here, and a constant body rate
of second order in the vibration amplitude (the axial rate of a cone) then
passes the sensor as it is.

Public API
----------
.. autosummary::

   AnalogFilter
   DigitalFilter
   ChannelFilter
   Sensor
   IDEAL_SENSOR
   analog_filter
   digital_filter

References
----------
Savage (1998), "Strapdown inertial navigation integration algorithm design,
part 1", on sensor filtering and pseudo-coning; Mark & Tazartes (1996),
"Tuning of coning algorithms to gyro data frequency response characteristics".
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..core.validation import as_array, as_int, positive

__all__ = ["AnalogFilter", "DigitalFilter", "ChannelFilter", "Sensor", "IDEAL_SENSOR", "analog_filter", "digital_filter", "ANALOG_KINDS", "DIGITAL_KINDS"]

#: Kinds of analog filter (the ``filter`` key of an environment file).
ANALOG_KINDS = ("none", "lowpass1", "butterworth", "bessel", "transfer_function")
#: Kinds of digital filter (the ``digital`` key of an environment file).
DIGITAL_KINDS = ("none", "coefficients", "butterworth", "moving_average")

#: Largest order of a designed filter and length of a coefficient list [count].
MAX_ORDER = 16
#: Tolerance on the unit gain at zero frequency [-].
DC_GAIN_TOLERANCE = 1e-9


def _coefficients(values, name: str) -> tuple:
    arr = as_array(values, name)
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"Expected `{name}` to be a non-empty list of numbers, got shape {arr.shape}")
    if arr.size > MAX_ORDER + 1:
        raise ValueError(f"Expected `{name}` to have at most {MAX_ORDER + 1} coefficients, got {arr.size}")
    return tuple(float(v) for v in arr)


@dataclass(frozen=True)
class AnalogFilter:
    """A rational analog transfer function ``H_a(s) = num(s) / den(s)``, s in rad/s.

    Attributes
    ----------
    num, den : tuple of float
        Coefficients in descending powers of s (``scipy.signal`` form).
    description : str
        What it is, for listings ("first-order low-pass, 100 Hz").

    Raises
    ------
    ValueError
        An improper transfer function, an unstable one (a pole with real part
        ≥ 0), or a gain at zero frequency other than 1.
    """

    num: tuple = (1.0,)
    den: tuple = (1.0,)
    description: str = "none"

    def __post_init__(self):
        num = _coefficients(self.num, "num")
        den = _coefficients(self.den, "den")
        num = tuple(np.trim_zeros(np.asarray(num), "f")) or (0.0,)
        den = tuple(np.trim_zeros(np.asarray(den), "f"))
        if not den:
            raise ValueError("Expected `den` with a nonzero coefficient, got all zeros")
        if len(num) > len(den):
            raise ValueError(f"Expected a proper transfer function (degree of `num` ≤ degree of `den`), got degrees {len(num) - 1} and {len(den) - 1}")
        poles = np.roots(den)
        if np.any(poles.real >= 0.0):
            bad = poles[poles.real >= 0.0][0]
            raise ValueError(f"Expected a stable analog filter (every pole with negative real part), got a pole at {bad:.6g} rad/s")
        if abs(den[-1]) == 0.0 or abs(num[-1] / den[-1] - 1.0) > DC_GAIN_TOLERANCE:
            gain = num[-1] / den[-1] if den[-1] else math.inf
            raise ValueError(f"Expected an analog filter with unit gain at zero frequency (a gyro passes a constant rate unchanged), got {gain:.6g}")
        object.__setattr__(self, "num", tuple(float(v) for v in num))
        object.__setattr__(self, "den", tuple(float(v) for v in den))

    @property
    def order(self) -> int:
        """Number of states (degree of the denominator)."""
        return len(self.den) - 1

    def response(self, omega) -> np.ndarray:
        """``H_a(iω)`` (``scipy.signal.freqs``).

        Parameters
        ----------
        omega : array_like
            Angular frequencies ω [rad/s].

        Returns
        -------
        ndarray of complex
        """
        w = np.asarray(omega, dtype=float)
        if self.order == 0:
            return np.full(w.shape, self.num[-1] / self.den[-1], dtype=complex)
        from scipy import signal

        _, h = signal.freqs(self.num, self.den, worN=w.ravel())
        return h.reshape(w.shape)

    def state_space(self):
        """``(A, B, C, D)`` of the filter (``scipy.signal.tf2ss``, controller canonical form).

        Returns
        -------
        tuple of ndarray
            Shapes (n, n), (n, 1), (1, n), (1, 1) with n = :attr:`order`.
        """
        from scipy import signal

        return signal.tf2ss(self.num, self.den)

    @property
    def slowest_rate(self) -> float:
        """Smallest ``|Re p|`` over the poles p [rad/s] (inf without poles): the transient's decay rate."""
        if self.order == 0:
            return math.inf
        return float(np.min(-np.roots(self.den).real))


@lru_cache(maxsize=256)
def _butterworth(order: int, cutoff_hz: float, sensor_interval: float) -> tuple:
    """``scipy.signal.butter`` at the sensor rate, designed once per (order, cut-off, interval)."""
    from scipy import signal

    b, a = signal.butter(order, cutoff_hz, fs=1.0 / sensor_interval)
    b, a = b / a[0], a / a[0]
    b.setflags(write=False)
    a.setflags(write=False)
    return b, a


@dataclass(frozen=True)
class DigitalFilter:
    """A digital filter on the stream of increments at the sensor rate.

    Either fixed coefficients ``b, a`` (``scipy.signal.lfilter`` form), or a
    design rule whose coefficients depend on the sensor rate (a Butterworth
    low-pass with its cut-off in Hz, a moving average of ``taps`` samples).

    Attributes
    ----------
    kind : str
        One of :data:`DIGITAL_KINDS`.
    b, a : tuple of float
        Coefficients (``kind == "coefficients"``).
    cutoff_hz : float
        −3 dB frequency of a Butterworth design [Hz].
    order : int
        Order of a Butterworth design [count].
    taps : int
        Length of a moving average [count].
    """

    kind: str = "none"
    b: tuple = (1.0,)
    a: tuple = (1.0,)
    cutoff_hz: float = 0.0
    order: int = 0
    taps: int = 1

    def __post_init__(self):
        if self.kind not in DIGITAL_KINDS:
            raise ValueError(f"Expected `kind` among {', '.join(DIGITAL_KINDS)}, got {self.kind!r}")
        if self.kind == "coefficients":
            b = _coefficients(self.b, "b")
            a = _coefficients(self.a, "a")
            if a[0] == 0.0:
                raise ValueError("Expected `a` with a nonzero first coefficient, got 0")
            b = tuple(v / a[0] for v in b)
            a = tuple(v / a[0] for v in a)
            poles = np.roots(a) if len(a) > 1 else np.zeros(0)
            if np.any(np.abs(poles) >= 1.0):
                raise ValueError(f"Expected a stable digital filter (every pole inside the unit circle), got a pole of modulus {np.max(np.abs(poles)):.6g}")
            gain = sum(b) / sum(a) if sum(a) != 0.0 else math.inf
            if abs(gain - 1.0) > DC_GAIN_TOLERANCE:
                raise ValueError(f"Expected a digital filter with unit gain at zero frequency (sum(b) = sum(a)), got {gain:.6g}")
            object.__setattr__(self, "b", b)
            object.__setattr__(self, "a", a)
        elif self.kind == "butterworth":
            positive(self.cutoff_hz, "cutoff_hz")
            order = as_int(self.order, "order", minimum=1)
            if order > MAX_ORDER:
                raise ValueError(f"Expected `order` ≤ {MAX_ORDER}, got {order}")
        elif self.kind == "moving_average":
            taps = as_int(self.taps, "taps", minimum=1)
            if taps > 1024:
                raise ValueError(f"Expected `taps` ≤ 1024, got {taps}")

    def coefficients(self, sensor_interval: float) -> tuple:
        """``(b, a)`` at the sensor interval ``h_s`` [s].

        Parameters
        ----------
        sensor_interval : float
            Sensor sample interval h_s [s], > 0.

        Returns
        -------
        tuple of ndarray
            ``b``, ``a`` with ``a[0] = 1``.

        Raises
        ------
        ValueError
            A Butterworth cut-off at or above the Nyquist frequency ``1/(2 h_s)``.
        """
        hs = positive(sensor_interval, "sensor_interval")
        if self.kind == "none":
            return np.ones(1), np.ones(1)
        if self.kind == "coefficients":
            return np.asarray(self.b), np.asarray(self.a)
        if self.kind == "moving_average":
            return np.full(self.taps, 1.0 / self.taps), np.ones(1)
        nyquist = 0.5 / hs
        if self.cutoff_hz >= nyquist:
            raise ValueError(f"Expected the digital filter's `cutoff_hz` below the sensor Nyquist frequency {nyquist:g} Hz, got {self.cutoff_hz:g}")
        return _butterworth(self.order, self.cutoff_hz, hs)

    def response(self, omega, sensor_interval: float) -> np.ndarray:
        """``D(e^{iω h_s})`` (``scipy.signal.freqz``).

        Parameters
        ----------
        omega : array_like
            Angular frequencies ω [rad/s].
        sensor_interval : float
            Sensor sample interval h_s [s].

        Returns
        -------
        ndarray of complex
        """
        w = np.asarray(omega, dtype=float)
        if self.kind == "none":
            return np.ones(w.shape, dtype=complex)
        b, a = self.coefficients(sensor_interval)
        from scipy import signal

        _, h = signal.freqz(b, a, worN=(w * sensor_interval).ravel())
        return h.reshape(w.shape)

    @property
    def description(self) -> str:
        """What it is, for listings."""
        if self.kind == "none":
            return "none"
        if self.kind == "butterworth":
            return f"digital Butterworth order {self.order}, {self.cutoff_hz:g} Hz"
        if self.kind == "moving_average":
            return f"moving average of {self.taps}"
        return f"digital b = {list(self.b)}, a = {list(self.a)}"


@dataclass(frozen=True)
class ChannelFilter:
    """The filters of one sensor axis: analog, then (after integration) digital.

    Attributes
    ----------
    analog : AnalogFilter
    digital : DigitalFilter
    """

    analog: AnalogFilter = AnalogFilter()
    digital: DigitalFilter = DigitalFilter()

    def response(self, omega, sensor_interval: float) -> np.ndarray:
        """Equivalent response ``H_a(iω) · D(e^{iω h_s})`` (module docstring).

        Parameters
        ----------
        omega : array_like
            Angular frequencies ω [rad/s].
        sensor_interval : float
            Sensor sample interval h_s [s].

        Returns
        -------
        ndarray of complex
        """
        return self.analog.response(omega) * self.digital.response(omega, sensor_interval)

    @property
    def description(self) -> str:
        """Analog and digital parts, for listings."""
        parts = [p for p in (self.analog.description, self.digital.description) if p != "none"]
        return " + ".join(parts) or "ideal"


def _triad_response(sensor, omega, sensor_interval: float) -> np.ndarray:
    """:meth:`Sensor.response` at the sensor interval [s]; identical axes are evaluated once."""
    seen: dict = {}
    for a in sensor.axes:
        if a not in seen:
            seen[a] = a.response(omega, sensor_interval)
    return np.stack([seen[a] for a in sensor.axes], axis=-1)


@lru_cache(maxsize=128)
def _kept_response(sensor, sensor_interval: float, shape: tuple, omega_bytes: bytes) -> np.ndarray:
    """:func:`_triad_response` at float64 frequencies given by their bytes, kept read-only."""
    out = _triad_response(sensor, np.frombuffer(omega_bytes).reshape(shape), sensor_interval)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class Sensor:
    """A sensor triad: the filters of its x, y and z axes, and the decimation.

    Attributes
    ----------
    axes : tuple of three ChannelFilter
        Filters of the x, y, z channels (body axes).
    decimation : int
        Sensor samples summed into one algorithm sample, M ≥ 1 [count].
    """

    axes: tuple = (ChannelFilter(), ChannelFilter(), ChannelFilter())
    decimation: int = 1

    def __post_init__(self):
        if len(self.axes) != 3 or not all(isinstance(a, ChannelFilter) for a in self.axes):
            raise TypeError("Expected `axes` to be three ChannelFilter")
        object.__setattr__(self, "decimation", as_int(self.decimation, "decimation", minimum=1))

    def sensor_interval(self, sample_interval: float) -> float:
        """The sensor interval ``h_s = h / M`` [s].

        Parameters
        ----------
        sample_interval : float
            Algorithm sample interval h [s].

        Returns
        -------
        float
        """
        return positive(sample_interval, "sample_interval") / self.decimation

    def response(self, omega, sample_interval: float) -> np.ndarray:
        """Equivalent responses of the three channels, shape ``omega.shape + (3,)``.

        Parameters
        ----------
        omega : array_like
            Angular frequencies ω [rad/s].
        sample_interval : float
            Algorithm sample interval h [s] (the sensor runs at ``h / decimation``).

        Returns
        -------
        ndarray of complex
        """
        hs = self.sensor_interval(sample_interval)
        w = np.asarray(omega)
        if w.dtype == np.float64:  # real frequencies: kept for the run (several algorithms, tunings and rate searches ask again)
            return _kept_response(self, hs, w.shape, w.tobytes())
        return _triad_response(self, omega, hs)

    @property
    def is_ideal(self) -> bool:
        """No filter on any axis (decimation does not count: it is exact)."""
        return all(a.analog.order == 0 and a.digital.kind == "none" for a in self.axes)

    @property
    def identical_axes(self) -> bool:
        """The three axes have the same filters."""
        return self.axes[0] == self.axes[1] == self.axes[2]

    @property
    def description(self) -> str:
        """The filters, once if the axes agree, per axis otherwise."""
        if self.identical_axes:
            return self.axes[0].description
        return "; ".join(f"{n}: {a.description}" for n, a in zip("xyz", self.axes))


#: A sensor with no dynamics (ideal increments, no decimation).
IDEAL_SENSOR = Sensor()


def analog_filter(kind: str = "none", *, cutoff_hz: float | None = None, order: int | None = None, num=None, den=None) -> AnalogFilter:
    """Build an analog filter by kind.

    Parameters
    ----------
    kind : str
        ``"none"``; ``"lowpass1"`` (``1/(1 + s/ω_c)``); ``"butterworth"`` or
        ``"bessel"`` (low-pass of ``order``, −3 dB at the cut-off;
        ``scipy.signal.butter`` / ``bessel(norm="mag")`` with ``analog=True``);
        ``"transfer_function"`` (``num``, ``den`` in powers of s, s in rad/s).
    cutoff_hz : float, keyword-only
        −3 dB frequency f_c [Hz], ω_c = 2π f_c (low-pass kinds).
    order : int, keyword-only
        Filter order [count] (Butterworth, Bessel; default 2).
    num, den : sequence of float, keyword-only
        Transfer function (``"transfer_function"``).

    Returns
    -------
    AnalogFilter

    Raises
    ------
    ValueError
        An unknown kind, a missing or bad parameter, an unstable filter or one
        whose gain at zero frequency is not 1.

    Examples
    --------
    >>> f = analog_filter("lowpass1", cutoff_hz=100.0)
    >>> round(abs(complex(f.response(2 * math.pi * 100.0))) ** 2, 6)
    0.5
    """
    if kind not in ANALOG_KINDS:
        raise ValueError(f"Expected `kind` among {', '.join(ANALOG_KINDS)}, got {kind!r}")
    if kind == "none":
        return AnalogFilter()
    if kind == "transfer_function":
        if num is None or den is None:
            raise ValueError("Expected `num` and `den` for a transfer_function filter, got " + ("neither" if num is None and den is None else "only one"))
        return AnalogFilter(tuple(as_array(num, "num").ravel()), tuple(as_array(den, "den").ravel()), "transfer function")
    if cutoff_hz is None:
        raise ValueError(f"Expected `cutoff_hz` for a {kind} filter, got none")
    fc = positive(cutoff_hz, "cutoff_hz")
    wc = 2.0 * math.pi * fc
    if kind == "lowpass1":
        return AnalogFilter((1.0,), (1.0 / wc, 1.0), f"first-order low-pass, {fc:g} Hz")
    n = 2 if order is None else as_int(order, "order", minimum=1)
    if n > MAX_ORDER:
        raise ValueError(f"Expected `order` ≤ {MAX_ORDER}, got {n}")
    from scipy import signal  # imported where it is used: it takes longer to import than a command's checks

    if kind == "butterworth":
        b, a = signal.butter(n, wc, analog=True)
        text = f"Butterworth order {n}, {fc:g} Hz"
    else:
        b, a = signal.bessel(n, wc, analog=True, norm="mag")
        text = f"Bessel order {n}, {fc:g} Hz"
    b, a = np.asarray(b, float), np.asarray(a, float)
    b = b * (a[-1] / b[-1])  # unit gain at zero frequency to the last bit
    return AnalogFilter(tuple(b), tuple(a), text)


def digital_filter(kind: str = "none", *, b=None, a=None, cutoff_hz: float | None = None, order: int | None = None, taps: int | None = None) -> DigitalFilter:
    """Build a digital filter by kind.

    Parameters
    ----------
    kind : str
        ``"none"``, ``"coefficients"`` (``b``, ``a``), ``"butterworth"``
        (``cutoff_hz``, ``order``; designed at the sensor rate when used) or
        ``"moving_average"`` (``taps``).
    b, a : sequence of float, keyword-only
        ``scipy.signal.lfilter`` coefficients (``a`` default ``[1]``).
    cutoff_hz : float, keyword-only
        −3 dB frequency [Hz] of a Butterworth design.
    order : int, keyword-only
        Order of a Butterworth design [count] (default 2).
    taps : int, keyword-only
        Length of a moving average [count].

    Returns
    -------
    DigitalFilter

    Raises
    ------
    ValueError
        An unknown kind, a missing or bad parameter, an unstable filter, or a
        gain at zero frequency other than 1.
    """
    if kind not in DIGITAL_KINDS:
        raise ValueError(f"Expected `kind` among {', '.join(DIGITAL_KINDS)}, got {kind!r}")
    if kind == "none":
        return DigitalFilter()
    if kind == "coefficients":
        if b is None:
            raise ValueError("Expected `b` for a digital filter given by coefficients, got none")
        return DigitalFilter("coefficients", tuple(as_array(b, "b").ravel()), tuple(as_array([1.0] if a is None else a, "a").ravel()))
    if kind == "butterworth":
        if cutoff_hz is None:
            raise ValueError("Expected `cutoff_hz` for a digital Butterworth filter, got none")
        return DigitalFilter("butterworth", cutoff_hz=positive(cutoff_hz, "cutoff_hz"), order=2 if order is None else order)
    if taps is None:
        raise ValueError("Expected `taps` for a moving average, got none")
    return DigitalFilter("moving_average", taps=taps)
