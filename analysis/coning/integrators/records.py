"""Identification from a recorded input/output pair: a flight computer's or a rig's record, with no source code.

A record holds, for every sample, the input increments ``p_j`` [rad] (and
``b_j`` [m/s]), and for every step the integrator's output ``Δφ_k`` [rad]
(and ``Δv_k`` [m/s]) with the sample that ends it.  With no code to probe,
the coefficients of the isotropic model

    Δφ_k = Σ_j a_j p_(k,j) + Σ_{i<j} c_ij p_(k,i) × p_(k,j),          j = 1 − K … N,
    Δv_k = Σ_j a°_j b_(k,j) + Σ_{i,j} m_ij p_(k,i) × b_(k,j)

are the least-squares solution over the steps of the record (three equations
per step), each column scaled to unit norm, by the singular value
decomposition.  A column the record does not excite, or a combination of
columns it cannot tell apart, shows as a singular value below
:data:`RANK_TOLERANCE` times the largest: the coefficients with a component in
that null space are *unidentified*, and are named, with the combinations of
them that the record leaves free.  A pure cone about one axis, for instance,
gives every increment a constant component along the axis and a radial part
that turns at one rate: it determines three combinations of the coefficients
and no more.  The others are reconstructed as exact fractions
(:meth:`~.identification.Coefficient.measured`) from the least-squares
uncertainty, four standard deviations from the residual plus the float64
round-off of the outputs: a rich enough record of an exactly bilinear
integrator returns it exactly.  Terms of degree three and more (a composition
of exact rotations) are not in the model; they show in the residual, and bias
the coefficients by about the increments' size relative to them.

File formats (:func:`read_record`):

``.npz``
    arrays ``gyro`` (n, 3) [rad] and ``rotation`` (m, 3) [rad], optionally
    ``accel`` (n, 3) [m/s] and ``velocity`` (m, 3) [m/s], and ``step_end``
    (m,), the index of the last sample of each step (default: every N-th
    sample, ``N − 1, 2N − 1, …``).
``.csv``
    a header and one row per sample, columns ``gyro_x, gyro_y, gyro_z`` (and
    ``accel_x …``), and ``rotation_x, rotation_y, rotation_z`` (and
    ``velocity_x …``) filled on the row that ends a step and empty elsewhere.

Public API
----------
:data:`RANK_TOLERANCE`, :data:`MAX_RECORD_SAMPLES`, :class:`Record`, :class:`RecordIdentification`,
:func:`read_record`, :func:`identify_record`.
"""

from __future__ import annotations

import csv
import itertools
from dataclasses import dataclass
from fractions import Fraction
from pathlib import Path

import numpy as np

from ....derivations.coning.algorithms import MAX_HISTORY, Algorithm, Term, second_order_defect
from ...core import budget
from ...core.validation import as_int, as_vector
from .defaults import DEFAULT_MAX_PREVIOUS, TOLERANCE
from .identification import Coefficient, max_denominator
from .probes import FLOAT64_NOISE

__all__ = ["RANK_TOLERANCE", "MAX_RECORD_SAMPLES", "Record", "RecordIdentification", "read_record", "identify_record"]

#: A singular value below this times the largest is taken as zero: what it weighs is not identified.
RANK_TOLERANCE = 1e-9
#: A coefficient whose null-space component exceeds this is unidentified.
_NULL_WEIGHT = 1e-6
#: Largest record read [samples].
MAX_RECORD_SAMPLES = 10_000_000
#: Standard deviations of the least-squares uncertainty.
_SIGMAS = 4.0


@dataclass(frozen=True, eq=False)
class Record:
    """A recorded input/output pair.

    Attributes
    ----------
    gyro : ndarray, shape (n, 3)
        Input increments of each sample [rad].
    rotation : ndarray, shape (m, 3)
        The integrator's rotation vector of each step [rad].
    step_end : ndarray of int, shape (m,)
        Index of the last sample of each step.
    accel : ndarray, shape (n, 3), or None
        Accelerometer increments [m/s].
    velocity : ndarray, shape (m, 3), or None
        The integrator's velocity increment of each step [m/s].
    source : str
        Where it was read from.
    """

    gyro: np.ndarray
    rotation: np.ndarray
    step_end: np.ndarray
    accel: np.ndarray | None = None
    velocity: np.ndarray | None = None
    source: str = ""


def _columns(header, prefix) -> list | None:
    names = [f"{prefix}_{a}" for a in "xyz"]
    if not any(n in header for n in names):
        return None
    missing = [n for n in names if n not in header]
    if missing:
        raise ValueError(f"Expected `path` with columns {', '.join(names)}, got a header without {', '.join(missing)}")
    return [header.index(n) for n in names]


def _read_csv(path: Path) -> dict:
    with path.open(newline="", encoding="utf-8") as f:
        reader = csv.reader(f)
        try:
            header = [h.strip() for h in next(reader)]
        except StopIteration:
            raise ValueError(f"Expected `path` {str(path)!r} to hold a header and rows, got an empty file") from None
        cols = {k: _columns(header, k) for k in ("gyro", "accel", "rotation", "velocity")}
        for k in ("gyro", "rotation"):
            if cols[k] is None:
                raise ValueError(f"Expected `path` with columns {k}_x, {k}_y, {k}_z, got the header {', '.join(header)[:120]}")
        rows = {k: [] for k in cols if cols[k] is not None}
        ends = []
        for n, row in enumerate(itertools.islice(reader, MAX_RECORD_SAMPLES + 1)):
            if n >= MAX_RECORD_SAMPLES:
                raise ValueError(f"Expected `path` with at most {MAX_RECORD_SAMPLES:,} samples, got more")
            cells = {k: [row[i].strip() if i < len(row) else "" for i in idx] for k, idx in cols.items() if idx is not None}
            for k in ("gyro", "accel"):
                if k in cells:
                    try:
                        rows[k].append([float(c) for c in cells[k]])
                    except ValueError:
                        raise ValueError(f"Expected numbers in the {k} columns of `path`, got {cells[k]!r} at data row {n + 1}") from None
            filled = [any(c != "" for c in cells[k]) for k in ("rotation", "velocity") if k in cells]
            if any(filled):
                for k in ("rotation", "velocity"):
                    if k in cells:
                        try:
                            rows[k].append([float(c) for c in cells[k]])
                        except ValueError:
                            raise ValueError(f"Expected numbers in every {k} column of a step's row of `path`, got {cells[k]!r} at data row {n + 1}") from None
                ends.append(n)
    out = {k: np.array(v, dtype=float).reshape(-1, 3) for k, v in rows.items()}
    out["step_end"] = np.array(ends, dtype=int)
    return out


def read_record(path) -> Record:
    """Read a record (``.csv`` or ``.npz``, module docstring).

    Parameters
    ----------
    path : str or Path
        The file.

    Returns
    -------
    Record

    Raises
    ------
    ValueError
        A missing or unreadable file, an unknown suffix, missing columns or
        arrays, shapes that do not match, values that are not finite, or steps
        whose last sample is outside the record.
    """
    path = Path(path)
    if not path.is_file():
        raise ValueError(f"Expected `path` to name an existing file, got {str(path)!r} ({'a directory' if path.is_dir() else 'not found'})")
    if path.suffix == ".npz":
        try:
            with np.load(path, allow_pickle=False) as z:
                data = {k: np.asarray(z[k]) for k in z.files}
        except (OSError, ValueError) as exc:
            raise ValueError(f"Expected `path` to be a readable .npz file, got {str(path)!r} ({' '.join(str(exc).split())})") from None
        for k in ("gyro", "rotation"):
            if k not in data:
                raise ValueError(f"Expected `path` to hold the array {k!r}, got {', '.join(sorted(data)) or 'none'}")
    elif path.suffix == ".csv":
        data = _read_csv(path)
    else:
        raise ValueError(f"Expected `path` to be a .csv or .npz file, got {path.suffix or 'no suffix'!r}")
    gyro = as_vector(data["gyro"], "gyro")
    rotation = as_vector(data["rotation"], "rotation")
    accel = as_vector(data["accel"], "accel") if "accel" in data else None
    velocity = as_vector(data["velocity"], "velocity") if "velocity" in data else None
    if gyro.ndim != 2 or rotation.ndim != 2:
        raise ValueError(f"Expected `gyro` (n, 3) and `rotation` (m, 3), got shapes {gyro.shape} and {rotation.shape}")
    if accel is not None and accel.shape != gyro.shape:
        raise ValueError(f"Expected `accel` of the shape of `gyro`, {gyro.shape}, got {accel.shape}")
    if (accel is None) != (velocity is None):
        raise ValueError("Expected both `accel` and `velocity` or neither, got one of them")
    if velocity is not None and velocity.shape != rotation.shape:
        raise ValueError(f"Expected `velocity` of the shape of `rotation`, {rotation.shape}, got {velocity.shape}")
    step_end = np.asarray(data.get("step_end", np.full(0, -1)), dtype=int).ravel()
    return Record(gyro, rotation, step_end, accel, velocity, str(path))


def _text(f: Fraction) -> str:
    return f"{f.numerator}/{f.denominator}" if f.denominator != 1 else str(f.numerator)


@dataclass(frozen=True, eq=False)
class RecordIdentification:
    """What a record determines of the integrator that made it.

    Attributes
    ----------
    name : str
        Name of the integrator (the record's file by default).
    samples : int
        N.
    max_previous : int
        K.
    steps : int
        Steps of the record used (those whose window lies inside it).
    linear : dict
        ``{j: Coefficient or None}`` (None: not identified by this record).
    pairwise : dict
        ``{(i, j): Coefficient or None}``.
    unidentified : tuple of str
        The terms the record does not determine (``"p1"``, ``"p0×p1"``, ``"p1×b2"`` …).
    free : tuple of dict
        Combinations the record leaves free: each a null-space direction
        ``{term: weight}`` (largest weight 1, small weights dropped).
    rank : int
        Of the least-squares problem.
    unknowns : int
        Coefficients of the model.
    residual : float
        Root-mean-square residual of the outputs [rad].
    output_scale : float
        Root-mean-square output [rad].
    tolerance : float
        Reconstruction tolerance [dimensionless].
    sculling : dict or None
        ``{"linear": {j: Coefficient or None}, "bilinear": {(i, j): Coefficient or None}, "residual": float}``.
    """

    name: str
    samples: int
    max_previous: int
    steps: int
    linear: dict
    pairwise: dict
    unidentified: tuple
    free: tuple
    rank: int
    unknowns: int
    residual: float
    output_scale: float
    tolerance: float
    sculling: dict | None = None

    @property
    def identified(self) -> bool:
        """Every coefficient identified."""
        return not self.unidentified

    @property
    def exact(self) -> bool:
        """Every coefficient identified and reconstructed as an exact fraction."""
        coeffs = list(self.linear.values()) + list(self.pairwise.values())
        if self.sculling is not None:
            coeffs += list(self.sculling["linear"].values()) + list(self.sculling["bilinear"].values())
        return all(c is not None and c.exact is not None for c in coeffs)

    @property
    def terms(self) -> dict:
        """``{"i,j": "p/q"}``: the identified nonzero coefficients of ``p_i × p_j``."""
        return {f"{i},{j}": _text(c.fraction) for (i, j), c in self.pairwise.items() if c is not None and c.fraction}

    def algorithm(self, name: str | None = None) -> Algorithm:
        """The identified coning part as an :class:`Algorithm` (unidentified terms left out).

        Parameters
        ----------
        name : str, optional
            Name of the algorithm (default: the integrator's).

        Returns
        -------
        Algorithm
        """
        terms = tuple(Term(c.fraction, key) for key, c in self.pairwise.items() if c is not None and c.fraction)
        return Algorithm(
            name or self.name,
            self.samples,
            terms,
            description=f"identified from a record of {self.name!r} ({self.steps} steps)",
            reference="identified by strapdown identify --record (least squares, exact fractions)",
        )

    def toml(self, name: str | None = None) -> str:
        """The identified algorithm in the algorithm-file syntax, with what the record could not determine as comments.

        Parameters
        ----------
        name : str, optional
            ``name`` key (default: the integrator's).

        Returns
        -------
        str
        """
        alg = self.algorithm(name)
        lines = [f'name = "{alg.name}"', f"samples = {alg.samples}", f'description = "{alg.description}"', f'reference = "{alg.reference}"']
        if self.unidentified:
            lines.append(f"# not identified by the record (left out): {', '.join(self.unidentified)}")
        if not self.exact:
            lines.append("# some coefficients were not reconstructed within the tolerance: nearest fractions written")
        defect = second_order_defect(alg)
        if defect:
            lines.append(f"# second-order condition missed: sum c_ij (j - i) - N^3/12 = {_text(defect)} (load with allow_inconsistent)")
        lines.append("[cross]")
        lines += [f'"{i},{j}" = "{_text(c)}"' for (i, j), c in alg.pairwise.items()]
        return "\n".join(lines) + "\n"

    def as_dict(self) -> dict:
        """JSON-able summary (``strapdown identify --record --json``).

        Returns
        -------
        dict
        """

        def coef(c):
            if c is None:
                return None
            return {"value": c.value, "uncertainty": c.uncertainty, "exact": c.exact is not None, "fraction": _text(c.fraction)}

        out = {
            "integrator": self.name,
            "source": "record",
            "samples": self.samples,
            "max_previous": self.max_previous,
            "steps_used": self.steps,
            "identified": self.identified,
            "exact": self.exact,
            "rank": self.rank,
            "unknowns": self.unknowns,
            "unidentified": list(self.unidentified),
            "free_combinations": [dict(x) for x in self.free],
            "terms": self.terms,
            "linear": {str(j): (None if c is None else _text(c.fraction)) for j, c in self.linear.items()},
            "coefficients": {f"{i},{j}": coef(c) for (i, j), c in self.pairwise.items()},
            "residual_rms": self.residual,
            "output_rms": self.output_scale,
            "tolerance": self.tolerance,
            "max_denominator": max_denominator(self.tolerance),
            "sculling": None,
        }
        if self.sculling is not None:
            out["sculling"] = {
                "linear": {str(j): (None if c is None else _text(c.fraction)) for j, c in self.sculling["linear"].items()},
                "terms": {f"{i},{j}": (None if c is None else _text(c.fraction)) for (i, j), c in self.sculling["bilinear"].items() if c is None or c.fraction},
                "residual_rms": self.sculling["residual"],
            }
        return out

    def text(self) -> str:
        """What a person reads.

        Returns
        -------
        str
        """
        lines = [f"{self.name}: identified from a record, {self.samples} samples per step, {self.steps} steps used (K = {self.max_previous})"]
        lines.append(f"rank {self.rank} of {self.unknowns} coefficients; residual {self.residual:.3g} rad RMS against outputs of {self.output_scale:.3g} rad RMS")
        lin = [f"{_text(c.fraction)} p{j}" for j, c in self.linear.items() if c is not None and c.fraction]
        lines.append("linear part: " + (", ".join(lin) or "none"))
        lines.append("terms: " + (", ".join(f"{c} p{k.replace(',', '×p')}" for k, c in self.terms.items()) or "none") + (f" (exact fractions: {'yes' if self.exact else 'no'})"))
        if self.unidentified:
            lines.append(f"NOT identified by this record (it does not excite them apart): {', '.join(self.unidentified)}")
            for combo in self.free[:4]:
                lines.append("  free combination: " + " ".join(f"{w:+.3g} {t}" for t, w in combo.items()))
        else:
            lines.append("every term identified")
        if self.sculling is not None:
            terms = {k: c for k, c in self.sculling["bilinear"].items() if c is not None and c.fraction}
            lines.append("sculling: " + (", ".join(f"{_text(c.fraction)} p{i}×b{j}" for (i, j), c in terms.items()) or "none"))
        return "\n".join(lines)


def _solve(columns: list, labels: list, y: np.ndarray, tolerance: float) -> tuple:
    """Least squares of ``y`` on ``columns`` (each (rows,)): coefficients or None, unidentified labels, free combinations, rank, residual."""
    a = np.stack(columns, axis=1)
    norms = np.linalg.norm(a, axis=0)
    scale = np.where(norms > 0, norms, 1.0)
    u, s, vt = np.linalg.svd(a / scale, full_matrices=False)
    keep = s > RANK_TOLERANCE * (s[0] if len(s) and s[0] > 0 else 1.0)
    if not (norms > 0).any():
        keep[:] = False
    rank = int(keep.sum())
    theta_scaled = vt[keep].T @ ((u[:, keep].T @ y) / s[keep])
    resid = y - (a / scale) @ theta_scaled
    dof = max(1, len(y) - rank)
    sigma = float(np.sqrt(resid @ resid / dof))
    null = vt[~keep].T  # (unknowns, nullity)
    cov_diag = (vt[keep].T ** 2 / s[keep] ** 2).sum(axis=1) * sigma**2
    theta = theta_scaled / scale
    roundoff = FLOAT64_NOISE * float(np.abs(y).max() if len(y) else 0.0) / np.maximum(norms, 1e-300) * np.sqrt(len(y))
    unc = _SIGMAS * np.sqrt(cov_diag) / scale + roundoff
    weight = np.linalg.norm(null, axis=1) if null.size else np.zeros(len(labels))
    out, unidentified = [], []
    for k, label in enumerate(labels):
        if weight[k] > _NULL_WEIGHT or norms[k] == 0:
            out.append(None)
            unidentified.append(label)
        else:
            out.append(Coefficient.measured(float(theta[k]), float(unc[k]), tolerance))
    free = []
    for v in null.T:
        v = v / scale  # in the unscaled coefficients
        v = v / np.abs(v).max()
        free.append({labels[k]: float(v[k]) for k in np.argsort(-np.abs(v)) if abs(v[k]) > 1e-3})
    return out, tuple(unidentified), tuple(free), rank, float(np.sqrt(np.mean(resid**2)) * 1.0)


def _windows(x: np.ndarray, ends: np.ndarray, n: int, k: int) -> np.ndarray:
    """The windows ``1 − K … N`` of each step, shape (steps, W, 3)."""
    offsets = np.arange(-(n - 1) - k, 1)
    return x[ends[:, None] + offsets[None, :]]


def identify_record(
    record: Record, samples_per_step, *, max_previous=DEFAULT_MAX_PREVIOUS, tolerance: float = TOLERANCE, name: str | None = None, limits: budget.Limits | None = None
) -> RecordIdentification:
    """Identify the integrator that made ``record`` (module docstring).

    Parameters
    ----------
    record : Record
        Inputs and outputs.
    samples_per_step : int
        N, 1 … 64.
    max_previous : int, keyword-only
        K, 0 … 64: samples before the step in the model.
    tolerance : float, keyword-only
        Reconstruction tolerance [dimensionless].
    name : str, optional, keyword-only
        Name of the integrator (default: the record's file).
    limits : strapdown.analysis.core.budget.Limits, keyword-only, optional
        Largest estimated memory and run time (the design matrix).

    Returns
    -------
    RecordIdentification

    Raises
    ------
    TypeError
        If ``record`` is not a :class:`Record`.
    ValueError
        N or K out of range, steps that end outside the record, or no step
        whose window lies inside it; work beyond ``limits`` (naming ``max_previous``).

    Examples
    --------
    >>> rng = np.random.default_rng(1)
    >>> p = 0.01 * rng.standard_normal((400, 3))
    >>> steps = p.reshape(-1, 2, 3)
    >>> out = steps.sum(axis=1) + 2 / 3 * np.cross(steps[:, 0], steps[:, 1])
    >>> r = identify_record(Record(p, out, np.arange(1, 400, 2)), 2, max_previous=0)
    >>> r.terms, r.exact
    ({'1,2': '2/3'}, True)
    """
    if not isinstance(record, Record):
        raise TypeError(f"Expected `record` to be a Record, got {type(record).__name__}")
    n = as_int(samples_per_step, "samples_per_step", minimum=1)
    if n > 64:
        raise ValueError(f"Expected `samples_per_step` in 1..64, got {n}")
    k = as_int(max_previous, "max_previous", minimum=0)
    if k > MAX_HISTORY:
        raise ValueError(f"Expected `max_previous` in 0..{MAX_HISTORY}, got {k}")
    samples = record.gyro.shape[0]
    ends = record.step_end if record.step_end.size else np.arange(n - 1, n - 1 + n * record.rotation.shape[0], n)
    if ends.shape[0] != record.rotation.shape[0]:
        raise ValueError(f"Expected one `step_end` per row of `rotation` ({record.rotation.shape[0]}), got {ends.shape[0]}")
    if ends.size and (ends.max() >= samples or ends.min() < 0):
        raise ValueError(f"Expected every step to end inside the record of {samples} samples, got a step ending at sample {int(ends.max())}")
    use = ends - (n - 1) - k >= 0
    if not use.any():
        raise ValueError(f"Expected steps whose window of {n + k} samples (`samples_per_step` + `max_previous`) lies in the record, got none")
    w = n + k
    unknowns = w + w * (w - 1) // 2 + ((w + w * w) if record.velocity is not None else 0)
    budget.check(budget.ARRAY_ELEMENT.estimate(float(use.sum()) * 3 * unknowns * 3, what=f"`max_previous` = {k} ({int(use.sum())} steps × {unknowns} coefficients)"), limits)
    ends = ends[use]
    window = list(range(1 - k, n + 1))
    p = _windows(record.gyro, ends, n, k)
    pairs = [(a, b) for a in range(w) for b in range(a + 1, w)]
    cols = [p[:, a].ravel() for a in range(w)] + [np.cross(p[:, a], p[:, b]).ravel() for a, b in pairs]
    labels = [f"p{window[a]}" for a in range(w)] + [f"p{window[a]}×p{window[b]}" for a, b in pairs]
    y = record.rotation[use].ravel()
    coeffs, unident, free, rank, resid = _solve(cols, labels, y, tolerance)
    linear = {window[a]: coeffs[a] for a in range(w)}
    pairwise = {(window[a], window[b]): coeffs[w + q] for q, (a, b) in enumerate(pairs)}
    sculling = None
    if record.velocity is not None:
        b = _windows(record.accel, ends, n, k)
        sp = [(a, c) for a in range(w) for c in range(w)]
        scols = [b[:, a].ravel() for a in range(w)] + [np.cross(p[:, a], b[:, c]).ravel() for a, c in sp]
        slabels = [f"b{window[a]}" for a in range(w)] + [f"p{window[a]}×b{window[c]}" for a, c in sp]
        scoeffs, sunident, sfree, srank, sresid = _solve(scols, slabels, record.velocity[use].ravel(), tolerance)
        sculling = {
            "linear": {window[a]: scoeffs[a] for a in range(w)},
            "bilinear": {(window[a], window[c]): scoeffs[w + q] for q, (a, c) in enumerate(sp)},
            "residual": sresid,
        }
        unident, free, rank = unident + sunident, free + sfree, rank + srank
    label = name or (Path(record.source).name if record.source else "record")
    return RecordIdentification(label, n, k, int(use.sum()), linear, pairwise, unident, free, rank, unknowns, resid, float(np.sqrt(np.mean(y**2))), float(tolerance), sculling)
