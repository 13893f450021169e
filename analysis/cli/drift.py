"""``strapdown drift``: constant drift rate of an algorithm under regular precession.

Any registry algorithm or TOML file runs, cross-step ones too (indices ≤ 0:
the samples before the first step come from the exact motion).  The asymptotic
rate u_a of the symbolic drift theory (Lebedev & Panov 1989, section 5) is
printed for algorithms within one step; for cross-step algorithms it is not
available and the JSON value is null.

Signs follow the package convention, exact minus algorithm: the drift vector
(``drift_vector_deg_per_h``, components in frame I, the run starting at
Λ(0) = 1) is the rate of the error rotation ``Λ_exact ∘ Λ̄_computed``, and
``asymptotic_drift_vector_deg_per_h`` is the theory's vector along the
precession axis, with the same sign.
"""

from __future__ import annotations

import numpy as np

from ..coning.drift_theory import asymptotic_drift, asymptotic_drift_vector
from ..coning.precession import RegularPrecession
from ..coning.simulator import simulate
from ..core.units import deg_per_h
from . import Result
from ._options import add_algorithm, add_motion, algorithm_from, motion_parameters, run_summary


def _run(args) -> Result:
    alg = algorithm_from(args)
    params = motion_parameters(args, alg)
    motion = RegularPrecession(params["eps"], params["nu"], params["nutation"])
    r = simulate(alg, motion, args.sample_interval, args.duration)
    data, header = run_summary(alg, r, params)
    asymptotic = asymptotic_vector = None
    if alg.history == 0:
        u_a = asymptotic_drift(alg, eps=params["eps"], nu=params["nu"], nutation=params["nutation"], step=r.step)
        asymptotic = float(deg_per_h(float(u_a))) if np.isfinite(u_a) else None  # NaN: no drift through the series' weight
        vector = deg_per_h(asymptotic_drift_vector(alg, eps=params["eps"], nu=params["nu"], nutation=params["nutation"], step=r.step))
        asymptotic_vector = vector.tolist() if np.all(np.isfinite(vector)) else None
    data |= {
        "eps": params["eps"],
        "nutation_deg": args.nutation_deg,
        "freq_hz": args.freq_hz,
        "simulated_drift_deg_per_h": float(deg_per_h(r.drift_rate)),
        "drift_vector_deg_per_h": deg_per_h(r.drift).tolist(),
        "asymptotic_drift_deg_per_h": asymptotic,
        "asymptotic_drift_vector_deg_per_h": asymptotic_vector,
        "final_error_rad": float((r.attitude_error[-1] ** 2).sum() ** 0.5),
    }
    if asymptotic is not None:
        u_a_text = f"{asymptotic:.6g} deg/h"
    else:
        u_a_text = "not available for cross-step algorithms" if alg.history else "zero through the weights of the series"
    text = (
        f"{header}\n"
        f"constant drift rate: {data['simulated_drift_deg_per_h']:.6g} deg/h, "
        f"vector (frame I, exact minus algorithm) {', '.join(f'{x:.6g}' for x in data['drift_vector_deg_per_h'])} deg/h\n"
        f"asymptotic drift rate u_a: {u_a_text}"
    )
    return Result(data, text)


def register(commands) -> None:
    """Add the ``drift`` command.

    Parameters
    ----------
    commands : Commands
        The command registry of :mod:`strapdown.analysis.cli`.
    """
    p = commands.add(
        "drift",
        _run,
        "constant drift rate of an algorithm under regular precession (parallel computation)",
    )
    add_algorithm(p)
    add_motion(p)
