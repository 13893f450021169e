"""Figures of a recorded log (``strapdown log inspect --figure``): rates and specific force against time, with the gaps.

Public API
----------
.. autosummary::

   draw_overview
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from ..core.units import DEG_PER_RAD

__all__ = ["draw_overview"]


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
    tmp = p.with_name(f".{p.name}.partial")
    try:
        fig.savefig(tmp, format="png")
        os.replace(tmp, p)
    finally:
        if tmp.exists():
            tmp.unlink()
    return p
