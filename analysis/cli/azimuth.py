"""``strapdown azimuth`` and ``strapdown azimuth-design``: gyrocompass azimuth error under rocking."""

from __future__ import annotations

import math

import numpy as np

from ..core import budget
from . import Result
from ._options import add_limits, check_work, count


def _rad(value, name):
    """A stable tilt typed in degrees, in radians; a tilt of ±90° or more is no tilt of a level platform."""
    from ..core.validation import in_open_interval

    return math.radians(in_open_interval(value, name, -90.0, 90.0, text="(-90, 90) degrees"))


def _sigma(value, name):
    """A rocking standard deviation typed in degrees, in radians, in [0, 90) degrees."""
    from ..core.validation import nonnegative

    sigma = nonnegative(value, name)
    if sigma >= 90.0:
        raise ValueError(f"Expected `{name}` below 90 degrees, got {sigma:g} degrees")
    return math.radians(sigma)


def _latitude(value) -> float:
    from ..core.validation import in_open_interval

    return math.radians(in_open_interval(value, "lat-deg", -90.0, 90.0, text="(-90, 90) degrees"))


def _azimuth(args) -> Result:
    from ..core.validation import as_int
    from ..gyrocompass.azimuth import azimuth_monte_carlo
    from ..gyrocompass.rocking import rocking_model

    lat = _latitude(args.lat_deg)
    sx = _sigma(args.sigma_xi_deg, "sigma-xi-deg")
    se = _sigma(args.sigma_eta_deg, "sigma-eta-deg")
    n = as_int(args.samples, "samples", minimum=2)
    seed = as_int(args.seed, "seed", minimum=0)
    model = rocking_model(args.rocking, sx, se, period=args.period_s, damping=args.damping)
    executor = None
    workers = as_int(args.workers, "workers", minimum=1)
    check_work(args, budget.monte_carlo(n, workers=workers, what=f"{n:.3g} rocking samples (--samples) on {workers} worker(s) (--workers)"))
    if workers > 1:
        from ..core.montecarlo import process_pool

        executor = process_pool(workers)
    try:
        mc = azimuth_monte_carlo(lat, _rad(args.beta0_deg, "beta0-deg"), _rad(args.gamma0_deg, "gamma0-deg"), model, n, rng=seed, executor=executor, progress=args.progress)
    finally:
        if executor is not None:
            executor.shutdown()
    data = {"rocking": args.rocking, "seed": seed, **mc.as_dict(degrees=True)}
    # a quantile outside the histogram is unknown: null in JSON, never NaN
    data["quantiles_deg"] = {k: (v if math.isfinite(v) else None) for k, v in data["quantiles_deg"].items()}
    text = (
        f"rms azimuth error {data['rms_error_deg']:.6g} deg (95 % CI {data['rms_ci_deg'][0]:.6g} .. {data['rms_ci_deg'][1]:.6g}), "
        f"mean {data['mean_error_deg']:.3g} deg; bound (14) {data['bound14_deg']:.6g} deg [{data['bound14_holds']}], "
        f"bound (15) {data['bound15_deg']:.6g} deg [{data['bound15_holds']}]; second-order theory {data['theory_rms_second_order_deg']:.6g} deg "
        f"({data['samples']} samples)"
    )
    return Result(data, text)


def _design(args) -> Result:
    from ..core.validation import as_int, positive
    from ..gyrocompass.admissible_rocking import admissible_amplitude

    lat = _latitude(args.lat_deg)
    fmin, fmax = positive(args.freq_min_hz, "freq-min-hz"), positive(args.freq_max_hz, "freq-max-hz")
    if fmax <= fmin:
        raise ValueError(f"Expected `freq-max-hz` > freq-min-hz = {fmin:g}, got {fmax:g}")
    points = as_int(args.points, "points", minimum=2)
    allowed = math.radians(positive(args.budget_deg, "budget-deg"))
    averaging, rate = positive(args.averaging_time_s, "averaging-time-s"), positive(args.sample_rate_hz, "sample-rate-hz")
    if averaging * rate < 1.0:
        raise ValueError(f"Expected `--averaging-time-s` at least one sample interval 1/--sample-rate-hz = {1.0 / rate:.3g} s, got {averaging:g} s")
    lags = averaging * rate
    check_work(args, budget.autocorrelation_sums(points, lags, what=f"{points} frequencies (--points) × {lags:.3g} samples (--averaging-time-s × --sample-rate-hz)"))
    freqs = np.geomspace(fmin, fmax, points)
    d = admissible_amplitude(
        allowed,
        lat,
        args.averaging_time_s,
        freqs,
        rocking=args.rocking,
        damping=args.damping,
        sample_rate=args.sample_rate_hz,
        beta0=_rad(args.beta0_deg, "beta0-deg"),
        gamma0=_rad(args.gamma0_deg, "gamma0-deg"),
        max_amplitude=math.radians(positive(args.max_amplitude_deg, "max-amplitude-deg")),
    )
    data = {
        "rocking": args.rocking,
        "budget_deg": args.budget_deg,
        "lat_deg": args.lat_deg,
        "averaging_time_s": args.averaging_time_s,
        "frequency_hz": d["frequency"].tolist(),
        "amplitude_deg": np.degrees(d["amplitude"]).tolist(),
        "amplitude_first_order_deg": np.degrees(d["amplitude_first_order"]).tolist(),
        "variance_factor": d["variance_factor"].tolist(),
    }
    rows = [f"{'f [Hz]':>10} {'a_max [deg]':>12} {'first order':>12}"]
    rows += [f"{f:10.4g} {a:12.5g} {a1:12.5g}" for f, a, a1 in zip(data["frequency_hz"], data["amplitude_deg"], data["amplitude_first_order_deg"])]
    return Result(data, "\n".join(rows))


def register(commands) -> None:
    p = commands.add("azimuth", _azimuth, "Monte Carlo of the gyrocompass azimuth error under rocking against bounds (14), (15)", progress="own")
    p.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90")
    p.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 [deg] (default 0)")
    p.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 [deg] (default 0)")
    p.add_argument("--sigma-xi-deg", type=float, required=True, help="standard deviation of ξ [deg] (sine amplitude = SX·√2)")
    p.add_argument("--sigma-eta-deg", type=float, required=True, help="standard deviation of η [deg]")
    p.add_argument("--rocking", choices=["normal", "sine", "narrowband"], default="normal", help="rocking model (default normal)")
    p.add_argument("--period-s", type=float, default=8.0, help="rocking period [s] (sine, narrowband)")
    p.add_argument("--damping", type=float, default=0.1, help="damping ratio of narrow-band rocking")
    p.add_argument("--samples", type=count, default=1_000_000, help="rocking samples N (default 1e6)")
    p.add_argument("--seed", type=count, default=0, help="root seed (default 0)")
    p.add_argument("--workers", type=count, default=1, help="worker processes (the result does not depend on it)")
    p.add_argument("--progress", action="store_true", help="progress bar on stderr")
    add_limits(p)
    commands.only_with(p, "--period-s", "--rocking", ("sine", "narrowband"))
    commands.only_with(p, "--damping", "--rocking", ("narrowband",))

    d = commands.add("azimuth-design", _design, "largest admissible rocking amplitude against rocking frequency for an azimuth budget")
    d.add_argument("--budget-deg", type=float, required=True, help="rms azimuth error budget [deg]")
    d.add_argument("--lat-deg", type=float, required=True, help="latitude φ [deg], |φ| < 90")
    d.add_argument("--averaging-time-s", type=float, default=60.0, help="averaging time of the tilt estimates (16) [s]")
    d.add_argument("--rocking", choices=["sine", "narrowband"], default="narrowband", help="rocking model (default narrowband)")
    d.add_argument("--damping", type=float, default=0.1, help="damping ratio of narrow-band rocking")
    d.add_argument("--sample-rate-hz", type=float, default=10.0, help="accelerometer sample rate [Hz]")
    d.add_argument("--freq-min-hz", type=float, default=0.02, help="lowest rocking frequency [Hz]")
    d.add_argument("--freq-max-hz", type=float, default=1.0, help="highest rocking frequency [Hz]")
    d.add_argument("--points", type=count, default=12, help="frequencies (log-spaced)")
    d.add_argument("--beta0-deg", type=float, default=0.0, help="stable tilt β0 [deg]")
    d.add_argument("--gamma0-deg", type=float, default=0.0, help="stable tilt γ0 [deg]")
    d.add_argument("--max-amplitude-deg", type=float, default=20.0, help="cap of the reported amplitude [deg]")
    add_limits(d)
    commands.only_with(d, "--damping", "--rocking", ("narrowband",))
