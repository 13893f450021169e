"""``strapdown azimuth`` and ``strapdown azimuth-design``: gyrocompass azimuth error under rocking (tilt channel).

Degrees at the edge, radians inside: options are converted with
:mod:`strapdown.analysis.core.units`.  Library imports are lazy, so that a
warm call imports neither SymPy nor the other domains.
"""

from __future__ import annotations

import math

from ..core import budget
from . import Result, UsageError
from ._executors import add_executor
from ._executors import executor as executor_from
from ._executors import workers as local_workers
from ._options import PROGRESS_HELP, add_limits, check_work, count, limits_from

__all__ = ["register", "check_rocking_domain"]


def check_rocking_domain(rocking_type, beta0_deg: float, gamma0_deg: float, sigmas_deg) -> None:
    """Raise :class:`UsageError` when the tilts or sigmas leave the range where the model is defined (in degrees).

    Parameters
    ----------
    rocking_type : type
        Rocking model class (supplies ``peak_factor``).
    beta0_deg, gamma0_deg : float
        Stable tilts [deg].
    sigmas_deg : dict
        ``{option: standard deviation [deg]}``.

    Raises
    ------
    ValueError
        A tilt outside (-90, 90) degrees.
    UsageError
        A standard deviation beyond the limit, stated in degrees.
    """
    from ..core.units import deg, rad
    from ..gyrocompass.rocking import tilt_domain_limit

    _tilts(beta0_deg, gamma0_deg)
    limit = deg(tilt_domain_limit(rocking_type, rad(beta0_deg), rad(gamma0_deg)))
    for name, value in sigmas_deg.items():
        if value > limit:
            raise UsageError(
                f"Expected --{name} <= {limit:.4g} deg (the tilts |tilt0| + {rocking_type.peak_factor:.3g}·sigma must stay within ±90 deg for {rocking_type.name} rocking), got {value:g}"
            )


def _tilts(beta0_deg, gamma0_deg) -> tuple:
    """The stable tilts typed in degrees, each in (-90, 90) (no tilt of a level platform reaches ±90°)."""
    from ..core.validation import in_open_interval

    return tuple(in_open_interval(v, name, -90.0, 90.0, text="(-90, 90) degrees") for name, v in (("--beta0-deg", beta0_deg), ("--gamma0-deg", gamma0_deg)))


def _latitude(value) -> float:
    from ..core.units import rad
    from ..core.validation import in_open_interval

    return rad(in_open_interval(value, "--lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))


def _azimuth(args) -> Result:
    from ..core.units import deg, rad
    from ..core.validation import as_int, nonnegative, positive
    from ..gyrocompass.azimuth import azimuth_monte_carlo
    from ..gyrocompass.rocking import MODELS, rocking_model

    lat = _latitude(args.lat_deg)
    sx_deg = nonnegative(args.sigma_xi_deg, "--sigma-xi-deg")
    se_deg = nonnegative(args.sigma_eta_deg, "--sigma-eta-deg")
    b0_deg, g0_deg = _tilts(args.beta0_deg, args.gamma0_deg)
    check_rocking_domain(MODELS[args.rocking], b0_deg, g0_deg, {"sigma-xi-deg": sx_deg, "sigma-eta-deg": se_deg})
    n = as_int(args.samples, "--samples", minimum=2)
    seed = as_int(args.seed, "--seed", minimum=0)
    period = positive(args.period, "--period")  # the library knows it per axis (period_xi, period_eta)
    model = rocking_model(args.rocking, rad(sx_deg), rad(se_deg), period=period, damping=args.damping)
    workers = local_workers(args)
    where = "--dask" if args.dask is not None else "--workers"
    check_work(args, budget.monte_carlo(n, workers=workers, what=f"{n:.3g} rocking samples (--samples) on {workers} worker(s) ({where})"))
    with executor_from(args) as executor:
        mc = azimuth_monte_carlo(lat, rad(b0_deg), rad(g0_deg), model, n, rng=seed, executor=executor, progress=args.progress, limits=limits_from(args))
    r, th = mc.result, mc.theory
    v14, v15 = (_in_samples(r.bound_holds(b, what=f"bound ({k})"), r) for k, b in ((14, mc.bound14), (15, mc.bound15)))
    data = {
        "rocking": args.rocking,
        "seed": seed,
        "rms_error_deg": deg(r.rms),
        "rms_ci_deg": [deg(r.rms_ci[0]), deg(r.rms_ci[1])],
        "mean_error_deg": deg(r.mean),
        "mean_ci_deg": [deg(r.mean_ci[0]), deg(r.mean_ci[1])],
        "bound14_deg": deg(mc.bound14),
        "bound15_deg": deg(mc.bound15),
        "theory_rms_first_order_deg": deg(th.rms_first_order),
        "theory_rms_second_order_deg": deg(th.rms),
        "theory_bias_deg": deg(th.bias),
        "quantiles_deg": {f"{level:g}": deg(v) for level, v in r.quantiles.items()},
        # the 95 % interval of each quantile (order statistics, trials as clusters); null where the samples do not reach
        "quantile_intervals_deg": {f"{level:g}": [deg(x) if math.isfinite(x) else None for x in ci] for level, ci in r.quantile_intervals.items()},
        "bound14_holds": r.covers(mc.bound14),
        "bound15_holds": r.covers(mc.bound15),
        # the same tests as verdicts: criterion, interval and, when not resolved, the trials a decision needs
        "bound14_verdict": v14.as_dict(scale=deg(1.0)),
        "bound15_verdict": v15.as_dict(scale=deg(1.0)),
        "samples": r.n_samples,
        "trials": r.n_trials,
    }
    text = (
        f"rms azimuth error {data['rms_error_deg']:.6g} deg (95 % CI {data['rms_ci_deg'][0]:.6g} .. {data['rms_ci_deg'][1]:.6g}), "
        f"mean {data['mean_error_deg']:.3g} deg; bound (14) {data['bound14_deg']:.6g} deg [holds: {v14}], "
        f"bound (15) {data['bound15_deg']:.6g} deg [holds: {v15}]; second-order theory {data['theory_rms_second_order_deg']:.6g} deg "
        f"({data['samples']} samples)"
    )
    return Result(data, text)


def _design(args) -> Result:
    import numpy as np

    from ..core.units import deg, rad
    from ..core.validation import as_int, in_open_interval, positive
    from ..gyrocompass.admissible_rocking import admissible_amplitude

    lat = _latitude(args.lat_deg)
    fmin, fmax = positive(args.freq_min_hz, "--freq-min-hz"), positive(args.freq_max_hz, "--freq-max-hz")
    fs = positive(args.sample_rate_hz, "--sample-rate-hz")
    if fmax <= fmin:
        raise ValueError(f"Expected `--freq-max-hz` > --freq-min-hz = {fmin:g} Hz, got {fmax:g}")
    if fmax >= fs / 2:
        raise ValueError(f"Expected `--freq-max-hz` < --sample-rate-hz/2 = {fs / 2:g} Hz, got {fmax:g}")
    T = positive(args.averaging_time, "--averaging-time")
    if T * fs < 1:
        raise ValueError(f"Expected `--averaging-time` >= 1/--sample-rate-hz = {1 / fs:g} s, got {T:g}")
    points = as_int(args.points, "--points", minimum=2)
    lags = T * fs
    check_work(args, budget.autocorrelation_sums(points, lags, what=f"{points} frequencies (--points) × {lags:.3g} samples (--averaging-time × --sample-rate-hz)"))
    allowed = rad(positive(args.budget_deg, "--budget-deg"))
    level = in_open_interval(args.level, "--level", 0.0, 1.0)
    b0_deg, g0_deg = _tilts(args.beta0_deg, args.gamma0_deg)
    d = admissible_amplitude(
        allowed,
        lat,
        T,
        np.geomspace(fmin, fmax, points),
        rocking=args.rocking,
        damping=args.damping,
        sample_rate=fs,
        beta0=rad(b0_deg),
        gamma0=rad(g0_deg),
        max_amplitude=rad(positive(args.max_amplitude_deg, "--max-amplitude-deg")),
        level=level,
        envelope=not args.exact_phase,
    )
    data = {
        "rocking": args.rocking,
        "budget_deg": args.budget_deg,
        "lat_deg": args.lat_deg,
        "averaging_time": T,
        "sample_rate_hz": fs,
        "envelope_over_phase": d.envelope,
        "level": d.level,
        "frequency_hz": d.frequency.tolist(),
        "amplitude_deg": deg(d.amplitude).tolist(),
        "amplitude_first_order_deg": deg(d.amplitude_first_order).tolist(),
        "amplitude_percentile_deg": deg(d.amplitude_percentile).tolist(),
        "variance_factor": d.variance_factor.tolist(),
    }
    rows = [f"{'f [Hz]':>10} {'a_max rms [deg]':>16} {'first order':>12} {f'{level:.0%} of |err|':>14}"]
    rows += [f"{f:10.4g} {a:16.5g} {a1:12.5g} {ap:14.5g}" for f, a, a1, ap in zip(data["frequency_hz"], data["amplitude_deg"], data["amplitude_first_order_deg"], data["amplitude_percentile_deg"])]
    return Result(data, "\n".join(rows))


def _in_samples(verdict, result):
    """A verdict counted in rocking samples (a trial of the Monte Carlo is a block of ``n_samples / n_trials`` of them)."""
    from dataclasses import replace

    per = result.n_samples // max(result.n_trials, 1)
    more = None if verdict.more_trials is None else verdict.more_trials * per
    return replace(verdict, n=result.n_samples, more_trials=more, trial="samples")


def register(commands) -> None:
    """Add ``azimuth`` and ``azimuth-design`` to the command line.

    Parameters
    ----------
    commands : Commands
        The registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add("azimuth", _azimuth, "Monte Carlo of the gyrocompass azimuth error under rocking against bounds (14), (15)", progress="own")
    p.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90 (required)")
    p.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 [deg], |β0| < 90 (default 0)")
    p.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 [deg], |γ0| < 90 (default 0)")
    p.add_argument("--sigma-xi-deg", type=float, required=True, help="standard deviation of ξ [deg] (required; sine amplitude = SX·√2)")
    p.add_argument("--sigma-eta-deg", type=float, required=True, help="standard deviation of η [deg] (required)")
    p.add_argument("--rocking", choices=["normal", "sine", "narrowband"], default="normal", help="rocking model: normal, sine or narrowband (default normal)")
    p.add_argument("--period", type=float, default=8.0, help="rocking period [s], sine and narrowband only (default 8)")
    p.add_argument("--damping", type=float, default=0.1, help="damping ratio of narrow-band rocking, in (0, 1) [dimensionless], narrowband only (default 0.1)")
    p.add_argument("--samples", type=count, default=1_000_000, help="rocking samples N [count] (default 1e6)")
    p.add_argument("--seed", type=count, default=0, help="root seed [count] (default 0)")
    add_executor(p)
    p.add_argument("--progress", action="store_true", help=PROGRESS_HELP)
    add_limits(p)
    commands.only_with(p, "--period", "--rocking", ("sine", "narrowband"))
    commands.only_with(p, "--damping", "--rocking", ("narrowband",))

    d = commands.add("azimuth-design", _design, "largest admissible rocking amplitude against rocking frequency for an azimuth budget (tilt channel)")
    d.add_argument("--budget-deg", type=float, required=True, help="azimuth error budget [deg] (required; on the rms and on the percentile)")
    d.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90 (required)")
    d.add_argument("--averaging-time", type=float, default=60.0, help="averaging time of the tilt estimates (16) [s] (default 60)")
    d.add_argument("--rocking", choices=["sine", "narrowband"], default="narrowband", help="rocking model: sine or narrowband (default narrowband)")
    d.add_argument("--damping", type=float, default=0.1, help="damping ratio of narrow-band rocking, in (0, 1) [dimensionless], narrowband only (default 0.1)")
    d.add_argument("--sample-rate-hz", type=float, default=10.0, help="accelerometer sample rate [Hz] (default 10)")
    d.add_argument("--freq-min-hz", type=float, default=0.02, help="lowest rocking frequency [Hz] (default 0.02)")
    d.add_argument("--freq-max-hz", type=float, default=1.0, help="highest rocking frequency [Hz], below half the sample rate (default 1)")
    d.add_argument("--points", type=count, default=12, help="frequencies, log-spaced [count] (default 12)")
    d.add_argument("--level", type=float, default=0.95, help="level of the percentile criterion, in (0, 1) [dimensionless] (default 0.95)")
    d.add_argument("--exact-phase", action="store_true", help="sine only: the exact Dirichlet factor instead of its envelope over phase (default off)")
    d.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 [deg], |β0| < 90 (default 0)")
    d.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 [deg], |γ0| < 90 (default 0)")
    d.add_argument("--max-amplitude-deg", type=float, default=20.0, help="cap of the reported amplitude [deg] (default 20)")
    add_limits(d)
    commands.only_with(d, "--damping", "--rocking", ("narrowband",))
    commands.only_with(d, "--exact-phase", "--rocking", ("sine",))
