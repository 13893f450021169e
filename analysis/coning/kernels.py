"""Fused compiled simulator kernels, generated from an algorithm's terms (numba).

Almost every algorithm is purely pairwise, ``Δφ = P + Σ c_ij p_i × p_j``
(all but one of the registry): for these one kernel per run kind (attitude,
or biquaternion for the apparent velocity) takes the terms as data
(:func:`pairwise_data`, evaluated by the template's ``pairwise_increment``),
so that it is compiled once and serves every such algorithm, its number of
samples and of earlier samples included.  An algorithm with nested or
dot-weighted terms (Lebedev & Panov's sixth-order (2.2), user files) gets its
own kernel, whose increment ``Δφ`` (or ``ΔΦ = Δφ + s Δφ°``, Lebedev & Panov
1989, eq. (2.5)) is written as straight-line scalar code, term by term from
the :class:`~strapdown.derivations.coning.algorithms.Algorithm` data.  Both
follow the order of operations of
:func:`strapdown.analysis.coning.evaluation.increment`: the sum ``P``, the
pairwise terms folded by their left factor, then the nested and dot-weighted
terms; so a pairwise algorithm gives the same bits either way
(``benchmarks/bench_simulator.py`` measures what the specialised code would
gain).  Dual arithmetic is expanded into real and dual parts, so a sculling
run is a fused loop too.  Below the increment come the functions of
:mod:`strapdown.analysis.coning._kernel_template` (exact increments by
angle addition from anchors computed directly every few samples, the step
biquaternion (1.12), the product, the exact solution (1.5), (4.4)–(4.5), the
errors — exact minus algorithm, as in the numpy path — and their running
statistics), and the whole module is compiled with ``numba.njit(cache=True)``.

Generated modules are stored under ``<cache base>/kernels/``, named by the
SHA-256 of their own text, next to numba's cache of their machine code: the
first run of a kernel compiles it (a few seconds), later runs in any process
load it.  A stale kernel cannot be served, because a changed
generator or template gives a different text and so a different file.

numba is optional at run time: :func:`available` says whether it can be
imported, and without it :func:`strapdown.analysis.coning.simulator.simulate`
uses its numpy path (the reference the kernels are tested against).
"""

from __future__ import annotations

import functools
import hashlib
import importlib.util
import inspect
import os
import sys
import tempfile
import threading
from fractions import Fraction
from pathlib import Path
from typing import NamedTuple

import numpy as np

from ...derivations.coning.algorithms import Algorithm
from ..core import quaternion as quat
from ..core.dual import Dual
from ..core.progress import bar
from . import _kernel_template as template
from .streaming import N_SUMS, empty_sums

__all__ = [
    "ENGINES",
    "AUTO_MIN_WORK",
    "BLOCK",
    "available",
    "use_compiled",
    "increment_source",
    "kernel_source",
    "kernel",
    "compiled_module",
    "parameter_rows",
    "advance",
    "chunk_steps",
    "run_batch",
    "compiled_series",
    "Kernel",
    "is_pairwise",
    "pairwise_data",
    "SPECIALISE_MIN_WORK",
]

#: Steps between two flushes of the kernel's partial sums: a span that starts and ends at multiples
#: of it gives the same sums however a run is cut (:mod:`strapdown.analysis.coning._kernel_template`).
BLOCK = template.BLOCK

#: Values of the ``engine`` argument of the simulators.
ENGINES = ("auto", "numpy", "compiled")

#: Template functions copied into every generated module, in this order.
_TEMPLATE_FUNCTIONS = ("pairwise_increment", "qmul", "rotvec_quat", "error_rotvec", "fill_table", "phase", "anchor_of", "flush", "run", "window_peak")

_lock = threading.Lock()
_loaded: dict = {}


def available() -> bool:
    """True when numba can be imported (the compiled engine can run).

    Returns
    -------
    bool
    """
    try:
        import numba  # noqa: F401
    except ImportError:
        return False
    return True


#: A pairwise algorithm gets its own straight-line kernel only for a run of at least this many
#: point-steps: it runs about 150 ns per step faster than the data-driven kernel of every pairwise
#: algorithm, and its compilation (a few seconds, once per algorithm and install) pays after about
#: 2·10⁷ steps (``benchmarks/bench_simulator.py``).  Both give the same bits.
SPECIALISE_MIN_WORK = 1 << 25

#: ``engine="auto"`` compiles a kernel for an algorithm outside the registry only for a run of at
#: least this many point-steps, where the compile (seconds, once per algorithm and install) pays.
AUTO_MIN_WORK = 1 << 21


def use_compiled(engine: str, *, supported: bool = True, algorithm: Algorithm | None = None, work: int = 0) -> bool:
    """Whether a simulator call with ``engine`` runs the compiled kernel.

    ``"auto"`` takes the kernel when numba is available, the motion is
    supported, and either the algorithm is a registry entry (its kernel is
    compiled once per install and reused), or the numpy path cannot run it
    (cross-step terms), or the run is large enough (``work`` ≥
    :data:`AUTO_MIN_WORK` point-steps) that compiling a new kernel pays.  The
    choice depends only on the arguments, so a result never depends on what
    happens to be cached.

    Parameters
    ----------
    engine : {"auto", "numpy", "compiled"}
        ``"auto"`` as above; ``"numpy"``: the vectorised numpy reference;
        ``"compiled"``: the kernel, or an error.
    supported : bool, keyword-only
        Whether the kernels cover the motion (the regular precession (4.1)–(4.2)).
    algorithm : Algorithm, keyword-only, optional
        The algorithm to run (for ``"auto"``).
    work : int, keyword-only
        Points × steps of the call (for ``"auto"``).

    Returns
    -------
    bool

    Raises
    ------
    ValueError
        Unknown ``engine``, or ``"compiled"`` for a motion the kernels do not cover.
    ImportError
        ``"compiled"`` without numba.
    """
    if engine not in ENGINES:
        raise ValueError(f"Expected `engine` in {', '.join(repr(e) for e in ENGINES)}, got {engine!r}")
    if engine == "numpy":
        return False
    if engine == "compiled":
        if not supported:
            raise ValueError("Expected a RegularPrecession motion for engine='compiled' (the kernels cover the regular precession only), got another motion")
        if not available():
            raise ImportError("The compiled engine needs numba, which is not installed (pip install numba), or pass engine='numpy'")
        return True
    if not (supported and available()):
        return False
    if algorithm is None or algorithm.history > 0 or work >= AUTO_MIN_WORK:
        return True
    from ...derivations.coning.registry import REGISTRY

    return REGISTRY.get(algorithm.name) == algorithm


# --------------------------------------------------------------------------- code generation
class _Code:
    """Straight-line scalar code over (real, dual) parts; dual parts are dropped for a real run."""

    def __init__(self, dual: bool):
        self.dual = dual
        self.lines: list = []
        self._count = 0

    def let(self, value):
        """Bind a (re, du) pair of expressions to fresh names."""
        name = f"v{self._count}"
        self._count += 1
        self.lines.append(f"{name} = {value[0]}")
        if self.dual:
            self.lines.append(f"{name}d = {value[1]}")
            return (name, f"{name}d")
        return (name, None)

    def add(self, a, b):
        return self.let((f"{a[0]} + {b[0]}", f"{a[1]} + {b[1]}" if self.dual else None))

    def mul(self, a, b):
        return self.let((f"{a[0]} * {b[0]}", f"{a[0]} * {b[1]} + {a[1]} * {b[0]}" if self.dual else None))

    def scale(self, c: float, a):
        return self.let((f"{c!r} * {a[0]}", f"{c!r} * {a[1]}" if self.dual else None))

    def sub_products(self, a, b, c, d):
        """``a b − c d``."""
        re = f"{a[0]} * {b[0]} - {c[0]} * {d[0]}"
        du = f"{a[0]} * {b[1]} + {a[1]} * {b[0]} - ({c[0]} * {d[1]} + {c[1]} * {d[0]})" if self.dual else None
        return self.let((re, du))

    def cross(self, a, b):
        return (
            self.sub_products(a[1], b[2], a[2], b[1]),
            self.sub_products(a[2], b[0], a[0], b[2]),
            self.sub_products(a[0], b[1], a[1], b[0]),
        )

    def dot(self, a, b):
        total = self.mul(a[0], b[0])
        for k in (1, 2):
            total = self.add(total, self.mul(a[k], b[k]))
        return total


def is_pairwise(algorithm: Algorithm) -> bool:
    """Whether every term of ``algorithm`` is a plain cross product ``c p_i × p_j`` (no nesting, no dot factor).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.

    Returns
    -------
    bool
    """
    return all(not t.dots and isinstance(t.cross[0], int) and isinstance(t.cross[1], int) for t in algorithm.terms)


def pairwise_data(algorithm: Algorithm) -> np.ndarray:
    """The pairwise terms of ``algorithm`` as rows ``(row of p_i, row of p_j, c_ij)`` for the data-driven kernel.

    Rows are grouped by the left factor in the order of
    :attr:`Algorithm.pairwise`, as the generated code folds them; a sample
    index ``j`` is window row ``j − 1 + history``.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.

    Returns
    -------
    ndarray, shape (K, 3)
        Float rows (the indices are exact small integers).

    Examples
    --------
    >>> from strapdown.derivations.coning.registry import get
    >>> pairwise_data(get("two-sample"))
    array([[0.        , 1.        , 0.66666667]])
    """
    by_left: dict = {}
    for (i, j), c in algorithm.pairwise.items():
        by_left.setdefault(i, []).append((j, float(c)))
    h = algorithm.history
    rows = [(i - 1 + h, j - 1 + h, c) for i, row in by_left.items() for j, c in row]
    return np.array(rows, dtype=float).reshape(-1, 3)


def increment_source(algorithm: Algorithm, *, dual: bool) -> str:
    """Source of ``increment(w, wd)``: the algorithm's ``Δφ`` (and ``Δφ°``) as straight-line code.

    ``w[r, c]`` and ``wd[r, c]`` hold the real and dual parts of ``p_j``,
    ``j = 1 − history … N`` (row ``r = j − 1 + history``); the function
    returns ``(Δφ_x, Δφ_y, Δφ_z, Δφ°_x, Δφ°_y, Δφ°_z)`` (dual parts zero for a
    real run).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    dual : bool, keyword-only
        Generate the dual (velocity) extension, eq. (2.5) of Lebedev & Panov (1989).

    Returns
    -------
    str
        Python source of the function (numba-compatible).

    Raises
    ------
    TypeError
        If ``algorithm`` is not an :class:`Algorithm`.
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    code = _Code(dual)
    history = algorithm.history

    def sample(j):
        r = j - 1 + history
        return tuple((f"w[{r}, {c}]", f"wd[{r}, {c}]") for c in range(3))

    comps = {j: None for j in range(algorithm.first_index, algorithm.samples + 1)}
    for j in comps:
        comps[j] = tuple(code.let(part) for part in sample(j))

    def expr(e):
        if isinstance(e, int):
            return comps[e]
        a, b = e
        return code.cross(expr(a), expr(b))

    total = list(comps[1])
    for j in range(2, algorithm.samples + 1):
        total = [code.add(total[c], comps[j][c]) for c in range(3)]
    by_left: dict = {}
    for (i, j), c in algorithm.pairwise.items():
        by_left.setdefault(i, []).append((j, float(c)))
    for i, row in by_left.items():
        right = []
        for c in range(3):
            acc = None
            for j, coefficient in row:
                term = code.scale(coefficient, comps[j][c])
                acc = term if acc is None else code.add(acc, term)
            right.append(acc)
        term = code.cross(comps[i], right)
        total = [code.add(total[c], term[c]) for c in range(3)]
    for t in algorithm.terms:
        plain_pair = not t.dots and isinstance(t.cross[0], int) and isinstance(t.cross[1], int)
        if plain_pair:
            continue
        value = expr(t.cross)
        factor = None
        for i, j in t.dots:
            d = code.dot(comps[i], comps[j])
            factor = code.scale(float(t.coefficient), d) if factor is None else code.mul(factor, d)
        if factor is None:
            term = [code.scale(float(t.coefficient), value[c]) for c in range(3)]
        else:
            term = [code.mul(factor, value[c]) for c in range(3)]
        total = [code.add(total[c], term[c]) for c in range(3)]
    re = ", ".join(part[0] for part in total)
    du = ", ".join(part[1] for part in total) if dual else "0.0, 0.0, 0.0"
    body = "\n".join(f"    {line}" for line in code.lines)
    title = f"{algorithm.name}: " + " + ".join(str(t) for t in algorithm.terms) if algorithm.terms else algorithm.name
    return f'def increment(w, wd):\n    """Δφ{" + s Δφ°" if dual else ""} of {title}."""\n{body}\n    return ({re}, {du})\n'


def _algorithm_text(algorithm: Algorithm) -> str:
    terms = "; ".join(f"{Fraction(t.coefficient)} {t.cross} {t.dots}" for t in algorithm.terms)
    return f"N={algorithm.samples}; {terms}"


def kernel_source(algorithm: Algorithm, *, velocity: bool, specialised: bool = False) -> str:
    """Full source of the generated kernel module that runs ``algorithm``.

    A purely pairwise algorithm (:func:`is_pairwise`) gets the one
    data-driven module of its run kind, the same text for every such
    algorithm; any other, or any with ``specialised``, gets its own module with
    a straight-line increment.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    velocity : bool, keyword-only
        Biquaternion run (attitude and apparent velocity) instead of attitude only.
    specialised : bool, keyword-only
        Straight-line code even for a pairwise algorithm (for comparison: same
        results to the last bit, one compilation per algorithm).

    Returns
    -------
    str
        Module source: numba import, the run's constants, the increment (the
        data-driven one, or the generated :func:`increment_source`), and the
        template functions, each decorated with ``numba.njit(cache=True)``.
    """
    run = "biquaternion (attitude and apparent velocity)" if velocity else "attitude"
    if is_pairwise(algorithm) and not specialised:
        head = ["# algorithm: any purely pairwise algorithm, its terms as data (pairwise_increment)"]
        increment = "def step_increment(w, wd, pairs, samples, history):\n    return pairwise_increment(w, wd, pairs, samples, history)\n"
    else:
        head = [f"# algorithm: {algorithm.name}: {_algorithm_text(algorithm)}"]
        increment = increment_source(algorithm, dual=velocity) + "\n\n@numba.njit(cache=True, nogil=True)\ndef step_increment(w, wd, pairs, samples, history):\n    return increment(w, wd)\n"
    parts = [
        "# Generated by strapdown.analysis.coning.kernels; do not edit.",
        *head,
        f"# run: {run}",
        "import math",
        "",
        "import numba",
        "import numpy as np",
        "",
        f"DUAL = {bool(velocity)}",
        f"REANCHOR = {template.REANCHOR}",
        f"BLOCK = {template.BLOCK}",
        f"N_PARAMETERS = {template.N_PARAMETERS}",
        f"N_SUMS = {N_SUMS}",
        "",
        "",
        "@numba.njit(cache=True, nogil=True)",
        increment,
    ]
    return "\n".join(parts) + _template_text()


@functools.lru_cache(maxsize=1)
def _template_text() -> str:
    parts = []
    for name in _TEMPLATE_FUNCTIONS:
        parts += ["", "@numba.njit(cache=True, nogil=True)", inspect.getsource(getattr(template, name))]
    return "\n".join(parts)


# --------------------------------------------------------------------------- loading
def _kernel_directory() -> Path:
    from ..core.cache import cache_directory

    return cache_directory().parent / "kernels"


def _write_once(path: Path, text: str) -> Path:
    if path.is_file() and path.read_text(encoding="utf-8") == text:
        return path
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=".tmp-", suffix=".py")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path


def _module_path(text: str, name: str) -> Path:
    try:
        return _write_once(_kernel_directory() / name, text)
    except OSError:  # unwritable cache: compile from a private directory, without reuse across runs
        return _write_once(Path(tempfile.mkdtemp(prefix="strapdown-kernels-")) / name, text)


class Kernel(NamedTuple):
    """A compiled kernel and the data of the algorithm it runs (:func:`kernel`).

    Attributes
    ----------
    run : numba dispatcher
        ``run(par, n_steps, theta, k0, k1, sums, err, dwe, dwi, keep, origin, pairs, samples, history)``
        of :mod:`strapdown.analysis.coning._kernel_template`.
    pairs : ndarray, shape (K, 3)
        :func:`pairwise_data` of the algorithm (empty for a straight-line kernel, which does not read it).
    samples : int
        N, samples per step.
    history : int
        Samples of earlier steps read.
    window_peak : numba dispatcher, optional
        ``window_peak(err, i, count)`` of :mod:`strapdown.analysis.coning._kernel_template`:
        the peak distance of a window of a series from its least-squares line
        (compiled on its first call).
    """

    run: object
    pairs: np.ndarray
    samples: int
    history: int
    window_peak: object = None


def compiled_module(text: str):
    """Import the generated module ``text``, written once under the kernel directory by its digest.

    Its ``numba.njit(cache=True)`` functions compile on first use and are
    loaded from numba's cache afterwards, in any process.

    Parameters
    ----------
    text : str
        Source of the module.

    Returns
    -------
    module
    """
    digest = hashlib.sha256(text.encode()).hexdigest()[:24]
    with _lock:
        if digest in _loaded:
            return _loaded[digest]
        name = f"strapdown_kernel_{digest}"
        path = _module_path(text, f"{name}.py")
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        spec.loader.exec_module(module)
        _loaded[digest] = module
        return module


def kernel(algorithm: Algorithm, *, velocity: bool, specialised: bool | None = False, work: float = 0) -> Kernel:
    """The compiled kernel that runs ``algorithm`` (generated, written and compiled on first use).

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    velocity : bool, keyword-only
        Biquaternion run instead of attitude only.
    specialised : bool or None, keyword-only
        Straight-line code even for a pairwise algorithm (:func:`kernel_source`);
        None: when ``work`` reaches :data:`SPECIALISE_MIN_WORK`.
    work : float, keyword-only
        Point-steps of the run (for ``specialised=None``).

    Returns
    -------
    Kernel

    Raises
    ------
    ImportError
        If numba is not installed.
    TypeError
        If ``algorithm`` is not an :class:`Algorithm`.
    """
    if not isinstance(algorithm, Algorithm):
        raise TypeError(f"Expected `algorithm` to be an Algorithm, got {type(algorithm).__name__}")
    if not available():
        raise ImportError("The compiled engine needs numba, which is not installed (pip install numba), or pass engine='numpy'")
    if specialised is None:
        specialised = work >= SPECIALISE_MIN_WORK
    text = kernel_source(algorithm, velocity=velocity, specialised=specialised)
    module = compiled_module(text)
    run = module.run
    pairs = pairwise_data(algorithm) if is_pairwise(algorithm) and not specialised else np.zeros((0, 3))
    compiled = Kernel(run, np.ascontiguousarray(pairs), int(algorithm.samples), int(algorithm.history), module.window_peak)
    if not run.signatures:  # first use in this process: compile, or load what another process compiled
        from ..core.cache import building

        with building(_kernel_directory() / f"{hashlib.sha256(text.encode()).hexdigest()[:24]}.compile"):
            _first_call(compiled)
    return compiled


def _first_call(compiled: Kernel) -> None:
    """One step of one point through ``compiled``, with the argument types of every run: numba compiles (or loads) it."""
    one = (np.array([v]) for v in (0.5, 1.0, 0.5, 0.0, 0.0, 0.01))  # ε, ν, ϑ, ν°, ϑ°, h of a harmless motion
    par, theta = parameter_rows(*one, np.array([1.0, 0.0, 0.0, 0.0]), np.zeros(3), velocity=False)
    advance(compiled, par, theta, np.array([1], dtype=np.int64), empty_sums(1), 0, 1)


# --------------------------------------------------------------------------- running
def parameter_rows(eps, nu, nutation, nu_dual, nutation_dual, sample_interval, attitude0, w_inertial0, *, velocity: bool):
    """Parameter rows and initial (bi)quaternions of a batch of regular precessions.

    Parameters
    ----------
    eps, nu, nutation, nu_dual, nutation_dual, sample_interval : ndarray, shape (P,)
        ε [-], ν [rad/s], ϑ [rad], ν° [m/s²], ϑ° [m/s], h [s] of each point
        (Lebedev & Panov 1989, eqs. (4.1)–(4.2)).
    attitude0 : ndarray, shape (4,)
        Λ(0), unit quaternion.
    w_inertial0 : ndarray, shape (3,)
        W_I(0) [m/s].
    velocity : bool, keyword-only
        Biquaternion run: θ(0) = Λ(0) + s M(0) (:func:`~strapdown.analysis.coning.precession.initial_biquaternion`).

    Returns
    -------
    par : ndarray, shape (P, 14)
        ε, ν, ϑ, ν°, ϑ°, h, then the constant ``C = θ(0) ∘ P̄(0)`` of the exact
        solution (1.5) (real part, dual part).
    theta0 : ndarray, shape (P, 8)
        θ(0) (real part, dual part; the dual part zero for an attitude run).
    """
    from .precession import initial_biquaternion

    count = eps.shape[0]
    theta0 = initial_biquaternion(attitude0, w_inertial0) if velocity else Dual(np.asarray(attitude0, dtype=float), np.zeros(4))
    half_nut = Dual(nutation, nutation_dual if velocity else np.zeros(count)) * 0.5
    zero = np.zeros(count)
    # P(0) = (cos(ϑ/2), sin(ϑ/2), 0, 0), eq. (4.4) at t = 0 with dual ϑ for (4.5).
    p0 = Dual(np.stack([np.cos(half_nut.re), np.sin(half_nut.re), zero, zero], axis=-1), np.stack([-np.sin(half_nut.re) * half_nut.du, np.cos(half_nut.re) * half_nut.du, zero, zero], axis=-1))
    const = quat.multiply(Dual(np.broadcast_to(theta0.re, (count, 4)), np.broadcast_to(theta0.du, (count, 4))), quat.conjugate(p0))
    par = np.stack([eps, nu, nutation, nu_dual, nutation_dual, sample_interval], axis=-1)
    par = np.concatenate([par, const.re, const.du], axis=-1)
    theta = np.concatenate([np.broadcast_to(theta0.re, (count, 4)), np.broadcast_to(theta0.du, (count, 4))], axis=-1)
    return np.ascontiguousarray(par), np.ascontiguousarray(theta)


def chunk_steps(points: int, *, budget: int = 1 << 20) -> int:
    """Steps per call of the kernel for ``points`` runs: about ``budget`` point-steps, a multiple of the block.

    Parameters
    ----------
    points : int
        Number of parameter points advanced together.
    budget : int, keyword-only
        Point-steps per call (sets how often control returns to Python).

    Returns
    -------
    int
    """
    block = BLOCK
    return max(block, (budget // max(points, 1)) // block * block)


def advance(run: Kernel, par, theta, n_steps, sums, k0: int, k1: int, series=None, origin: int = 0) -> None:
    """Advance all points from step ``k0`` to ``k1`` with a compiled kernel, in place.

    Parameters
    ----------
    run : Kernel
        From :func:`kernel`.
    par : ndarray, shape (P, 14)
        From :func:`parameter_rows`.
    theta : ndarray, shape (P, 8)
        (Bi)quaternion after step ``k0``; updated to the one after ``k1``.
    n_steps : ndarray of int64, shape (P,)
        Steps of each run (a point stops at its own end).
    sums : ndarray, shape (P, 18)
        Accumulators (:mod:`strapdown.analysis.coning.streaming`), updated.
    k0, k1 : int
        First and last step index of the span.
    series : tuple of three ndarray, shape (P, rows, 3), optional
        Error series δφ_I, ΔW_E and ΔW_I (exact minus algorithm, as
        :class:`~strapdown.analysis.coning.simulator.SimulationResult`), step k
        of the span written at row ``k − origin``.
    origin : int
        Step index of row 0 of ``series``: 0 for whole series (rows n + 1), ``k0``
        for a window buffer that holds the span only (rows ``k1 − k0 + 1``).
    """
    data = (run.pairs, run.samples, run.history)
    if series is None:
        dummy = np.zeros((1, 1, 3))
        run.run(par, n_steps, theta, k0, k1, sums, dummy, dummy, dummy, False, 0, *data)
    else:
        run.run(par, n_steps, theta, k0, k1, sums, series[0], series[1], series[2], True, int(origin), *data)




def run_batch(algorithm: Algorithm, par, theta, n_steps, *, velocity: bool, series: bool, progress: bool = False):
    """Advance every point of a batch to its own end, in time chunks of :func:`chunk_steps`.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data (its kernel is compiled on first use, :func:`kernel`).
    par, theta : ndarray, shapes (P, 14) and (P, 8)
        From :func:`parameter_rows`; ``theta`` is advanced in place.
    n_steps : ndarray of int64, shape (P,)
        Steps of each run.
    velocity : bool, keyword-only
        Biquaternion run.
    series : bool, keyword-only
        Keep the error series (every point then runs ``max(n_steps)`` steps of storage).
    progress : bool, keyword-only
        Progress on stderr (:func:`strapdown.analysis.core.progress.bar`).

    Returns
    -------
    sums : ndarray, shape (P, 18)
        Accumulators of :mod:`strapdown.analysis.coning.streaming`.
    series : tuple of three ndarray, shape (P, max(n_steps) + 1, 3), or None
        δφ_I, ΔW_E, ΔW_I (exact minus algorithm) at every step end; the last two
        are placeholders of shape (1, 1, 3) in an attitude run (``series=True`` only).
    """
    last = int(n_steps.max())
    run = kernel(algorithm, velocity=velocity, specialised=None, work=float(n_steps.sum()))
    sums = empty_sums(par.shape[0])
    keep = None
    if series:
        # Unused series get one contiguous placeholder, so that the kernel's signature never changes.
        unused = np.zeros((1, 1, 3))
        keep = tuple(np.zeros((par.shape[0], last + 1, 3)) if velocity or i == 0 else unused for i in range(3))
    chunk = chunk_steps(par.shape[0])
    with bar(total=last * par.shape[0], desc="simulation", enabled=progress, unit="step") as shown:
        for k0 in range(0, last, chunk):
            k1 = min(last, k0 + chunk)
            advance(run, par, theta, n_steps, sums, k0, k1, keep)
            shown.update((k1 - k0) * par.shape[0])
    return sums, keep


def compiled_series(algorithm: Algorithm, motions, sample_interval: float, steps: int, attitude0, w_inertial0, *, velocity: bool):
    """Error series of a batch of regular precessions from the compiled kernel.

    The compiled engine of :func:`strapdown.analysis.coning.simulator.simulate`.

    Parameters
    ----------
    algorithm : Algorithm
        The algorithm as data.
    motions : sequence of RegularPrecession
        The parameter points.
    sample_interval : float
        Sample interval h [s].
    steps : int
        Steps n of every run.
    attitude0 : ndarray, shape (4,)
        Λ(0), unit quaternion.
    w_inertial0 : ndarray, shape (3,)
        W_I(0) [m/s].
    velocity : bool, keyword-only
        Biquaternion run.

    Returns
    -------
    error : ndarray, shape (len(motions), steps + 1, 3)
        Attitude error ``δφ_I = rotvec(Λ_exact ∘ Λ̄_alg)``, frame I [rad].
    dw_body, dw_inertial : ndarray, shape (len(motions), steps + 1, 3), or None
        ``ΔW_E = W_E* − W_E``, ``ΔW_I = W_I* − W_I`` [m/s] (velocity runs).
    """
    count = len(motions)
    columns = [np.array([getattr(m, k) for m in motions], dtype=float) for k in ("eps", "nu", "nutation", "nu_dual", "nutation_dual")]
    par, theta = parameter_rows(*columns, np.full(count, float(sample_interval)), attitude0, w_inertial0, velocity=velocity)
    _, keep = run_batch(algorithm, par, theta, np.full(count, steps, dtype=np.int64), velocity=velocity, series=True)
    return (keep[0], keep[1], keep[2]) if velocity else (keep[0], None, None)
