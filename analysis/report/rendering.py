"""Deterministic figures: the same pixels on every machine with the same matplotlib.

numpy picks its implementation of ``sin``, ``exp``, ``geomspace`` and friends by
the instruction set of the processor (AVX-512, AVX2, ...), and OpenBLAS its
kernels likewise, so the same computation can differ in the last bit from one
machine to the next.  Agg's anti-aliasing turns such a difference in a vertex
into a different grey level of a pixel, so without care a PNG differs across
machines even though every printed number agrees.

:func:`quantise` therefore rounds every coordinate a figure will draw (line
data, collection vertices and offsets, image values, text positions, the view
limits) to :data:`MANTISSA_BITS` significant bits, far below a pixel (2⁻²⁴ of a
value is 1/16 000 of a pixel on a 1000-pixel axis) yet far above the last bit,
before the figure is rendered.  Two machines then draw identical coordinates,
unless a value lies within a few units in the last place of a rounding
boundary (probability about 2⁻²⁸ per value).  Fonts, the rasteriser and the
PNG encoder come with matplotlib, so byte equality of figures needs the same
matplotlib version (recorded in the report manifest).
"""

from __future__ import annotations

import functools

import numpy as np

__all__ = [
    "MANTISSA_BITS",
    "configure_matplotlib",
    "round_bits",
    "quantise",
    "at_round_off",
    "fixed_layout",
    "layout_overflow",
    "layout_overlaps",
    "agg_canvas",
    "drawn_ticks_only",
    "unplaced_empty_labels",
]

#: Significant bits kept of every drawn coordinate.
MANTISSA_BITS = 24


def round_bits(values, bits: int = MANTISSA_BITS):
    """Round ``values`` to ``bits`` significant bits (exactly, in binary; inf and NaN pass through).

    Parameters
    ----------
    values : array_like
        Numbers to round (a masked array keeps its mask).
    bits : int
        Significant bits to keep [count], 1 … 52.

    Returns
    -------
    ndarray
        Float array of the same shape.

    Examples
    --------
    >>> float(round_bits(1.0 + 2.0**-40)) == 1.0, float(round_bits(3.0)) == 3.0
    (True, True)
    """
    if not 1 <= int(bits) <= 52:
        raise ValueError(f"Expected `bits` in 1 … 52, got {bits}")
    if np.ma.isMaskedArray(values):
        return np.ma.array(round_bits(np.ma.getdata(values), bits), mask=np.ma.getmask(values))
    x = np.asarray(values, dtype=float)
    mantissa, exponent = np.frexp(x)
    scale = float(2**bits)
    out = np.ldexp(np.round(mantissa * scale) / scale, exponent)
    return np.where(np.isfinite(x), out, x)


def at_round_off(value: float, floor: float = 1e-13) -> str:
    """Text for a difference that should be round-off: a bound below ``floor``, else the number.

    The last bits of a round-off-level difference depend on the instruction set
    (see the module docstring), so printing its digits would make a report differ
    from one machine to the next; a bound does not.

    Parameters
    ----------
    value : float
        A non-negative difference [any unit].
    floor : float
        Bound printed when ``value`` is below it [same unit as ``value``].

    Returns
    -------
    str
        ``"< 1e-13"`` or, above the floor, the value to two digits.

    Examples
    --------
    >>> at_round_off(7.2e-16), at_round_off(3.1e-9)
    ('< 1e-13', '3.1e-09')
    """
    return f"< {floor:.0e}" if abs(value) < floor else f"{value:.1e}"


def _numeric(values) -> bool:
    try:
        arr = np.asarray(values)
    except Exception:  # ragged or exotic data: leave it alone
        return False
    return arr.dtype.kind in "fiu" and arr.size > 0


def _lines(ax) -> None:
    for line in ax.get_lines():
        x, y = line.get_data(orig=True)
        if _numeric(x) and _numeric(y):
            line.set_data(round_bits(x), round_bits(y))


def _collections(ax) -> None:
    for coll in ax.collections:
        offsets = coll.get_offsets()
        if _numeric(offsets):
            coll.set_offsets(round_bits(offsets))
        if hasattr(coll, "get_coordinates"):  # QuadMesh: its vertices are the coordinates
            coords = coll.get_coordinates()
            coords[...] = round_bits(coords)
        else:
            for path in coll.get_paths():
                vertices = path.vertices
                if vertices.flags.writeable:  # read-only paths are matplotlib's constant marker shapes
                    vertices[...] = round_bits(vertices)
        array = coll.get_array()
        if array is not None and _numeric(array):
            coll.set_array(round_bits(array))
        _norm(coll)


def _norm(mappable) -> None:
    norm = getattr(mappable, "norm", None)
    if norm is not None and norm.vmin is not None and norm.vmax is not None:
        vmin, vmax = float(round_bits(norm.vmin)), float(round_bits(norm.vmax))
        if vmin < vmax:
            norm.vmin, norm.vmax = vmin, vmax


def _images(ax) -> None:
    for image in ax.get_images():
        data = image.get_array()
        if data is not None and _numeric(data) and np.asarray(data).dtype.kind == "f":
            image.set_data(round_bits(data))
        _norm(image)


def _patches(ax) -> None:
    for patch in ax.patches:
        if hasattr(patch, "get_xy") and hasattr(patch, "set_xy") and not hasattr(patch, "get_width"):
            xy = patch.get_xy()
            if _numeric(xy):
                patch.set_xy(round_bits(xy))
        elif hasattr(patch, "get_width") and hasattr(patch, "set_bounds"):  # Rectangle (bars)
            x, y = patch.get_xy()
            patch.set_bounds(*(float(v) for v in round_bits([x, y, patch.get_width(), patch.get_height()])))


def _texts(ax) -> None:
    for text in ax.texts:
        x, y = text.get_position()
        if isinstance(x, (int, float)) and isinstance(y, (int, float)):
            text.set_position(tuple(float(v) for v in round_bits([x, y])))


def _limits(ax) -> None:
    for get, set_ in ((ax.get_xlim, ax.set_xlim), (ax.get_ylim, ax.set_ylim)):
        low, high = get()  # autoscaled from the data if not set
        rl, rh = (float(v) for v in round_bits([low, high]))
        if rl != rh:
            set_(rl, rh, auto=None)


def quantise(fig) -> None:
    """Round every coordinate ``fig`` will draw to :data:`MANTISSA_BITS` bits, in place.

    Call it once the figure is complete, just before saving it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    """
    axes = fig.get_axes()
    for ax in axes:
        _lines(ax)
        _collections(ax)
        _images(ax)
        _patches(ax)
        _texts(ax)
    for ax in axes:
        _limits(ax)


def fixed_layout(fig, *, left: float = 0.7, right: float = 0.15, bottom: float = 0.5, top: float = 0.3, wgap: float = 0.6, hgap: float = 0.5, grid=None) -> None:
    """Place the subplot grid of ``fig`` with margins and gaps fixed in inches.

    The figure is then drawn once when saved: a layout engine or
    ``bbox_inches="tight"`` measures every tick label and text in one or two
    extra passes, which cost more than the drawing.  Margins are chosen for the
    figure's own labels; ``tools/check_figures.py`` draws every report figure
    and reports any text that reaches past an edge.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure (its axes on one grid, as ``plt.subplots`` makes them).
    left, right, bottom, top : float, keyword-only
        Margins between the grid and the figure's edges [in].
    wgap, hgap : float, keyword-only
        Gaps between columns and between rows of the grid [in].
    grid : tuple of int, optional, keyword-only
        ``(rows, columns)`` of the grid (default: that of the figure's first axes).

    Raises
    ------
    ValueError
        If the margins and gaps leave no room for the axes.
    """
    width, height = fig.get_size_inches()
    if grid is None:
        spec = next((ax.get_subplotspec() for ax in fig.axes if ax.get_subplotspec() is not None), None)
        grid = (1, 1) if spec is None else spec.get_gridspec().get_geometry()
    rows, cols = grid
    axes_w = (width - left - right - (cols - 1) * wgap) / cols
    axes_h = (height - bottom - top - (rows - 1) * hgap) / rows
    if axes_w <= 0 or axes_h <= 0:
        raise ValueError(f"Expected margins and gaps that leave room for the axes in a {width:g} x {height:g} in figure, got axes of {axes_w:.3g} x {axes_h:.3g} in")
    fig.subplots_adjust(left=left / width, right=1.0 - right / width, bottom=bottom / height, top=1.0 - top / height, wspace=wgap / axes_w, hspace=hgap / axes_h)


def layout_overflow(fig) -> tuple:
    """How far the drawn content of ``fig`` reaches past each edge [in]; negative: the spare margin.

    Draws the figure's layout (the cost that :func:`fixed_layout` saves the
    report); for checks, not for the report itself.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A complete figure.

    Returns
    -------
    tuple of float
        ``(left, bottom, right, top)`` [in].
    """
    renderer = fig.canvas.get_renderer()
    box = fig.get_tightbbox(renderer)
    width, height = fig.get_size_inches()
    return (-box.x0, -box.y0, box.x1 - width, box.y1 - height)


def layout_overlaps(fig, tolerance: float = 0.01) -> list:
    """Pairs of axes where the labels or ticks of one reach into the frame of the other.

    Like :func:`layout_overflow`, for checks (it draws the figure's layout).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        A complete figure.
    tolerance : float
        Overlap that is ignored, in each direction [in].

    Returns
    -------
    list of tuple
        ``(i, j, width, height)``: the decorations of ``fig.axes[i]`` overlap the
        frame of ``fig.axes[j]`` by ``width`` x ``height`` [in].
    """
    renderer = fig.canvas.get_renderer()
    dpi = fig.dpi
    axes = [ax for ax in fig.axes if ax.get_visible()]
    boxes = [ax.get_tightbbox(renderer) for ax in axes]
    frames = [ax.get_window_extent(renderer) for ax in axes]
    out = []
    for i, box in enumerate(boxes):
        for j, frame in enumerate(frames):
            if i == j or box is None:
                continue
            w = (min(box.x1, frame.x1) - max(box.x0, frame.x0)) / dpi
            h = (min(box.y1, frame.y1) - max(box.y0, frame.y0)) / dpi
            if w > tolerance and h > tolerance:
                out.append((fig.axes.index(axes[i]), fig.axes.index(axes[j]), w, h))
    return out


def configure_matplotlib() -> None:
    """Headless, deterministic matplotlib settings used by every figure."""
    import matplotlib

    matplotlib.use("Agg")
    matplotlib.rcParams.update(
        {
            "svg.hashsalt": "strapdown-analysis",
            "svg.fonttype": "path",
            "figure.dpi": 110,
            "axes.grid": True,
            "grid.alpha": 0.3,
            "font.size": 9,
            "axes.titlesize": 10,
            "legend.fontsize": 8,
            # Titles sit at the top of their axes.  Left to matplotlib (None), every draw
            # measures the tick labels of each axes to see whether a title must move up: about
            # a fifth of the report's drawing time.  No figure of the report has ticks on top,
            # and every one is byte-identical with either setting.
            "axes.titley": 1.0,
        }
    )


def agg_canvas(fig):
    """Give ``fig`` an Agg canvas whose renderers share one mathtext parser with every other figure's.

    matplotlib gives each renderer a parser of its own, and its cache of parsed
    expressions is keyed by the parser: every figure parses its mathtext again,
    although most of it is the same few tick labels of log axes
    (``$\\mathdefault{10^{-3}}$``), about a tenth of the drawing time.  A parse
    depends only on the expression, the dpi and the font, so one parser gives
    the same pixels.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; its canvas is replaced.

    Returns
    -------
    matplotlib.backends.backend_agg.FigureCanvasAgg
        The new canvas of ``fig``.
    """
    return _canvas_class()(fig)


@functools.cache
def _canvas_class():
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.mathtext import MathTextParser

    parser = MathTextParser("path")  # the output type RendererAgg parses to

    class SharedParserCanvas(FigureCanvasAgg):
        """Agg canvas whose renderers parse mathtext with one parser shared by every figure."""

        def get_renderer(self):
            renderer = super().get_renderer()
            renderer.mathtext_parser = parser
            return renderer

    return SharedParserCanvas


#: Margin, as a fraction of the view interval (in the axis's scale), within which
#: :func:`drawn_ticks_only` keeps tick locations outside the view: far wider than
#: matplotlib's own test of whether a tick is in view (10⁻¹⁰) and its test of whether a
#: minor tick duplicates a major one (10⁻⁵), so no tick that is drawn goes missing.
IN_VIEW_MARGIN = 1e-3


def drawn_ticks_only(fig) -> None:
    """Let matplotlib make tick objects only for the ticks of ``fig`` it will draw.

    matplotlib makes a tick (three lines and two texts) for every location its
    locator gives, then draws those in view.  A log axis's locator gives the
    decades around the view and every minor tick in them: about a quarter of the
    report's ticks were made and never drawn, a tenth of the drawing time.  Each
    locator whose labels do not depend on the other locations (a
    :class:`~matplotlib.ticker.LogFormatter` reads only the view limits, a
    :class:`~matplotlib.ticker.NullFormatter` nothing) is wrapped so that it
    gives only the locations in view (within :data:`IN_VIEW_MARGIN`); the
    ticks drawn and their labels are the same.  A linear axis keeps its locator:
    :class:`~matplotlib.ticker.ScalarFormatter` chooses its digits from every
    location.  Call it once the view limits are final, just before saving.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; the locators of its axes are replaced.
    """
    from matplotlib import ticker

    in_view = _in_view_class()
    for ax in fig.get_axes():
        for axis in (ax.xaxis, ax.yaxis):
            for locator, formatter, set_locator in (
                (axis.get_major_locator(), axis.get_major_formatter(), axis.set_major_locator),
                (axis.get_minor_locator(), axis.get_minor_formatter(), axis.set_minor_locator),
            ):
                if isinstance(formatter, (ticker.LogFormatter, ticker.NullFormatter)) and not isinstance(locator, (ticker.NullLocator, in_view)):
                    set_locator(in_view(locator))


def unplaced_empty_labels(fig) -> None:
    """Keep matplotlib from placing the axis labels of ``fig`` that have no text.

    An axis label goes below (or beside) the tick labels of its axis: at every
    draw matplotlib measures them and the spine again to place it, even when the
    label is empty and draws nothing (the inner panels of a grid).  Such a label
    is pinned to the middle of its axes instead (``set_label_coords``); nothing
    drawn changes.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure; its empty axis labels are pinned.
    """
    for ax in fig.get_axes():
        for axis in (ax.xaxis, ax.yaxis):
            if not axis.label.get_text():
                axis.set_label_coords(0.5, 0.5)


@functools.cache
def _in_view_class():
    from matplotlib import ticker

    class InView(ticker.Locator):
        """The locations of another locator that lie in the view interval of its axis."""

        def __init__(self, locator):
            self.locator = locator
            self.axis = locator.axis

        def set_axis(self, axis):
            self.axis = axis
            self.locator.set_axis(axis)

        def __call__(self):
            locs = np.asarray(self.locator())
            if locs.size == 0:
                return locs
            transform = self.axis.get_transform()
            low, high = sorted(transform.transform(np.asarray(self.axis.get_view_interval(), dtype=float)))
            margin = IN_VIEW_MARGIN * (high - low)
            if not np.isfinite(margin):
                return locs
            t = transform.transform(locs.astype(float))
            return locs[((t >= low - margin) & (t <= high + margin)) | ~np.isfinite(t)]

        def tick_values(self, vmin, vmax):
            return self.locator.tick_values(vmin, vmax)

        def nonsingular(self, v0, v1):
            return self.locator.nonsingular(v0, v1)

        def view_limits(self, vmin, vmax):
            return self.locator.view_limits(vmin, vmax)

    return InView
