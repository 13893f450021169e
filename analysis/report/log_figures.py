"""Figures of a recorded log: rates and specific force against time with the gaps (``strapdown log inspect --figure``),
and an alignment filter's histories (``strapdown align --log FILE --figure PNG``).

Public API
----------
.. autosummary::

   draw_overview
   draw_alignment_history
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ..core.atomic import replaced_atomically
from ..core.units import DEG_PER_RAD

__all__ = ["draw_overview", "draw_alignment_history"]


def draw_overview(overview, path, *, title: str = "") -> Path:
    """Draw a :class:`~strapdown.analysis.logs.overview.LogOverview` as a PNG (written atomically).

    Parameters
    ----------
    overview : LogOverview
        The binned log.
    path : str or Path
        The PNG.
    title : str, keyword-only
        Above the figure.

    Returns
    -------
    Path
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    from .rendering import fixed_layout

    p = Path(path)
    fig = Figure(figsize=(8.0, 5.6), dpi=100)
    axes = fig.subplots(2, 1, sharex=True)
    fixed_layout(fig, left=0.85, right=0.2, bottom=0.55, top=0.45, hgap=0.25, grid=(2, 1))
    colours = ("tab:blue", "tab:orange", "tab:green")
    panels = (
        (overview.rate_mean, overview.rate_min, overview.rate_max, DEG_PER_RAD, "angular rate [deg/s]"),
        (overview.force_mean, overview.force_min, overview.force_max, 1.0, "specific force [m/s²]"),
    )
    for ax, (mean, lo, hi, scale, label) in zip(axes, panels):
        for i, (axis, colour) in enumerate(zip("xyz", colours)):
            ax.fill_between(overview.time, lo[:, i] * scale, hi[:, i] * scale, color=colour, alpha=0.2, linewidth=0)
            ax.plot(overview.time, mean[:, i] * scale, color=colour, linewidth=0.8, label=axis)
        for g in overview.gaps:
            ax.axvspan(g.start, g.start + g.duration, color="tab:red", alpha=0.25, linewidth=0)
        ax.set_ylabel(label)
        ax.grid(True, alpha=0.3)
    axes[0].legend(loc="upper right", ncols=3, fontsize=8)
    axes[1].set_xlabel("time from the log's start [s]" + (f"   (red: {len(overview.gaps)} gap(s))" if overview.gaps else ""))
    if title:
        axes[0].set_title(title, fontsize=9)
    if overview.time.size:
        axes[1].set_xlim(float(np.min(overview.time)), float(np.max(overview.time)))
    with replaced_atomically(p) as tmp:
        fig.savefig(tmp, format="png")
    return p


def draw_alignment_history(history, path, *, title: str = "") -> Path:
    """Draw a :class:`~strapdown.analysis.logs.filter_history.FilterHistory` as a PNG (written atomically).

    Three panels against time: the standard deviations of the tilts and the azimuth (log scale),
    the bias estimates, and the NIS of each update with the block means and their χ² band.

    Parameters
    ----------
    history : FilterHistory
        The filter's histories.
    path : str or Path
        The PNG.
    title : str, keyword-only
        Above the figure.

    Returns
    -------
    Path
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    from ..core.units import RAD_PER_S_TO_DEG_PER_H
    from .rendering import fixed_layout

    h = history
    p = Path(path)
    fig = Figure(figsize=(8.0, 8.0), dpi=100)
    axes = fig.subplots(4, 1, sharex=True)
    fixed_layout(fig, left=0.95, right=0.2, bottom=0.55, top=0.45, hgap=0.25, grid=(4, 1))
    t = h.times
    for i, (label, colour) in enumerate((("north tilt", "tab:blue"), ("east tilt", "tab:orange"), ("azimuth", "tab:green"))):
        axes[0].semilogy(t, h.sigma[:, i] * DEG_PER_RAD, color=colour, linewidth=1.0, label=label)
    axes[0].set_ylabel("σ [deg]")
    axes[0].legend(loc="upper right", ncols=3, fontsize=8)
    axes_names = ("N", "E", "D") if h.bias_frame == "NED" else ("x", "y", "z")
    colours = ("tab:blue", "tab:orange", "tab:green")
    for i in range(3):
        axes[1].plot(t, h.gyro_bias[:, i] * RAD_PER_S_TO_DEG_PER_H, color=colours[i], linewidth=1.0, label=axes_names[i])
        axes[2].plot(t, h.accel_bias[:, i], color=colours[i], linewidth=1.0, label=axes_names[i])
    axes[1].set_ylabel("gyro bias [deg/h]")
    axes[2].set_ylabel("accel. bias [m/s²]")
    axes[1].legend(loc="upper right", ncols=3, fontsize=8, title=f"{h.bias_frame} axes", title_fontsize=8)
    axes[3].semilogy(t, np.maximum(h.nis, 1e-6), ".", color="0.6", markersize=2, label="NIS")
    axes[3].step(h.block_times, h.block_nis, where="post", color="tab:red", linewidth=1.2, label=f"mean of {h.block}")
    axes[3].axhspan(h.band[0], h.band[1], color="tab:green", alpha=0.15, linewidth=0, label="band")
    axes[3].axhline(h.dof, color="tab:green", linewidth=0.8)
    axes[3].set_ylabel(f"NIS (χ²({h.dof}))")
    axes[3].legend(loc="upper right", ncols=3, fontsize=8)
    axes[3].set_xlabel("time from the segment's start [s]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
    if title:
        axes[0].set_title(title, fontsize=9)
    if t.size > 1:
        axes[3].set_xlim(float(t[0]), float(t[-1]))
    with replaced_atomically(p) as tmp:
        fig.savefig(tmp, format="png")
    return p
