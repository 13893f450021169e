"""A six-degree-of-freedom IMU mount: a rigid block on isolators, its transfer matrix and its modes.

The model
---------
A rigid block (the IMU with its bracket) of mass m and inertia tensor J about
its centre of mass stands on N isolators.  Every position is in the block's
axes, which are the IMU's body axes (frame E), measured from a reference
point O of the designer's choice: the centre of mass at ``c``, the IMU's
measurement point (where the specific force is sensed) at ``p``, isolator i
attached at ``r_i``.  At rest the block's axes coincide with the base's.

Each isolator is a three-axis linear spring and viscous damper between a
point of the base and a point of the block, with stiffness ``K_i = diag(k_i)``
[N/m] and damping ``C_i = diag(c_i)`` [N·s/m] along the block's axes at rest;
it carries no moment of its own (its rotational stiffness is left out).  The
static load of gravity is carried by the isolators' preload; what the
preload adds to the stiffness under rotation (the pendulum term, of relative
order ``m g |c| / (k L²)``) is left out.

Coordinates ``q = (x, θ)``: the small displacement x of O and the small
rotation θ of the block, both relative to the inertial frame (the base's
frame at rest).  The base moves by ``q_b = (u, β)`` at O.  Isolator i
deflects by ``d_i = T_i (q − q_b)`` with ``T_i = [I, −[r_i×]]``
(``d_i = x − u + (θ − β) × r_i``) and pushes the block with
``F_i = −K_i d_i − C_i ḋ_i`` at ``r_i``, the generalised force ``T_iᵀ F_i``
(force and moment about O).  With the mass matrix about O,

    ``M = [[m I, −m[c×]], [m[c×], J − m[c×]²]]``,

``K = Σ T_iᵀ K_i T_i``, ``C = Σ T_iᵀ C_i T_i``, the block obeys
``M q̈ + C q̇ + K q = C q̇_b + K q_b``.

The transfer matrix
-------------------
Inputs are the base's six channels at O in the order of
:data:`~strapdown.analysis.vibration.environment.CHANNELS`: angular rate Ω
[rad/s] and acceleration A [m/s²] (``q_b = (−A/ω², Ω/(iω))`` for amplitudes
at ``e^{iωt}``).  Outputs are the IMU's: body rate ``ω = θ̇`` [rad/s] and the
first-order vibration of the specific force at p in the block's axes,
``f = ẍ − [p×]θ̈ + θ × g`` [m/s²]: the acceleration of p (gravity-free) plus
the tilt of the gravity reading, from ``f_E = Rᵀ(a − g)`` with ``R = I + [θ×]``
and g the gravity vector in the block's axes at rest (default
``(0, 0, g₀)``, the block's z axis down); the constant −g is not part of the
vibration.  Then

    ``H(ω) = O(ω) Z(ω)⁻¹ (K + iωC) P(ω)``,  ``Z = K + iωC − ω²M``,

with ``P`` the base input map above and ``O = [[0, iωI], [−ω²I, ω²[p×] − [g×]]]``.
In the convention ``S_ab ∝ Z_a conj(Z_b)`` the output is ``S_out = H S_in Hᴴ``;
in the package's convention (``G_ab = ½ conj(Z_a) Z_b``, Bendat & Piersol)
it reads ``G_out = conj(H) G_in Hᵀ`` (:mod:`strapdown.analysis.vibration.mount_response`).

Modes
-----
The eigenvalues λ of the first-order form ``[[0, I], [−M⁻¹K, −M⁻¹C]]``
(``scipy.linalg.eig``): natural frequency ``|λ|/2π``, damping ratio
``−Re λ/|λ|``, the mode shape from the eigenvector's displacement part
(:class:`Mode`).

Files
-----
:func:`load_mount` reads the TOML format of ``docs/mount-files.md``.

Public API
----------
.. autosummary::

   Isolator
   Mount
   Mode
   skew
   load_mount
   MOUNT_LIMITS
   MountLimits

References
----------
Harris & Piersol (2002), *Shock and Vibration Handbook*, 5th ed., ch. 3
(vibration of a resiliently supported rigid body); Bendat & Piersol (2010),
*Random Data*, 4th ed., eq. (6.11) (multiple-input/output spectral relations).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
from scipy import linalg

from ...derivations.toml_files import read_toml
from ..core.units import STANDARD_GRAVITY
from ..core.validation import as_array, positive
from ._file_tables import Table

__all__ = ["Isolator", "Mount", "Mode", "skew", "load_mount", "MountLimits", "MOUNT_LIMITS", "COORDINATES"]

#: Names of the six coordinates of a mode shape and of the energy shares.
COORDINATES = ("x", "y", "z", "rx", "ry", "rz")


def skew(v) -> np.ndarray:
    """``[v×]``, the matrix of the cross product by v: ``skew(v) @ w == np.cross(v, w)``.

    Parameters
    ----------
    v : array_like, shape (..., 3)
        Vectors.

    Returns
    -------
    ndarray, shape (..., 3, 3)

    Examples
    --------
    >>> bool(np.allclose(skew([1.0, 2.0, 3.0]) @ [4.0, 5.0, 6.0], np.cross([1, 2, 3], [4, 5, 6])))
    True
    """
    v = np.asarray(v, dtype=float)
    z = np.zeros(v.shape[:-1])
    return np.stack([np.stack([z, -v[..., 2], v[..., 1]], -1), np.stack([v[..., 2], z, -v[..., 0]], -1), np.stack([-v[..., 1], v[..., 0], z], -1)], -2)


def _vector(v, name: str, *, low=None) -> np.ndarray:
    arr = as_array(v, name)
    if arr.shape != (3,):
        raise ValueError(f"Expected `{name}` as three numbers, got shape {arr.shape}")
    if low is not None and np.any(arr < low):
        raise ValueError(f"Expected `{name}` with every component ≥ {low:g}, got {arr.tolist()}")
    arr = arr.copy()
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class Isolator:
    """One isolator: a three-axis spring and viscous damper between the base and the block.

    Attributes
    ----------
    position : ndarray (3,)
        Attachment point r_i from the reference point O, block axes [m].
    stiffness : ndarray (3,)
        Stiffness along the block's x, y, z axes [N/m], ≥ 0.
    damping : ndarray (3,)
        Viscous damping along x, y, z [N·s/m], ≥ 0.
    label : str
        Name for listings.
    """

    position: np.ndarray
    stiffness: np.ndarray
    damping: np.ndarray = field(default_factory=lambda: np.zeros(3))
    label: str = ""

    def __post_init__(self):
        object.__setattr__(self, "position", _vector(self.position, "position"))
        object.__setattr__(self, "stiffness", _vector(self.stiffness, "stiffness", low=0.0))
        object.__setattr__(self, "damping", _vector(self.damping, "damping", low=0.0))

    @property
    def transform(self) -> np.ndarray:
        """``T_i = [I, −[r_i×]]`` (3, 6): the deflection of the isolator per unit of ``q = (x, θ)``."""
        return np.hstack([np.eye(3), -skew(self.position)])


@dataclass(frozen=True)
class Mode:
    """A vibration mode of the mount.

    Attributes
    ----------
    frequency : float
        Natural frequency ``|λ|/2π`` [Hz].
    damping_ratio : float
        ``−Re λ/|λ|`` [dimensionless].  An overdamped mode has two real poles
        instead of a pair; each is listed as a mode of damping ratio 1 and
        frequency ``|λ|/2π``.
    damped_frequency : float
        ``Im λ/2π`` [Hz] (0 for a real pole).
    shape : tuple of complex
        The displacement part of the eigenvector in ``(x, y, z, rx, ry, rz)``
        (translation of O [m], rotation [rad]), scaled so that its largest
        kinetic-energy share has a real positive coordinate and the kinetic
        energy ``½ qᴴ M q`` is ½.
    energy : tuple of float
        Shares of the mode's kinetic energy: translation of the centre of mass
        along x, y, z and rotation about x, y, z (``Re(conj θ_k (Jθ)_k)``);
        they add to 1.
    """

    frequency: float
    damping_ratio: float
    damped_frequency: float
    shape: tuple
    energy: tuple

    @property
    def description(self) -> str:
        """The coordinates holding at least 20 % of the kinetic energy, largest first (e.g. ``"ry 71 %, x 28 %"``)."""
        order = np.argsort(self.energy)[::-1]
        parts = [f"{COORDINATES[k]} {100 * self.energy[k]:.0f} %" for k in order if self.energy[k] >= 0.2]
        return ", ".join(parts) or f"{COORDINATES[order[0]]} {100 * self.energy[order[0]]:.0f} %"


@dataclass(frozen=True, eq=False)
class Mount:
    """A rigid block on isolators (module docstring).

    Attributes
    ----------
    mass : float
        m [kg], > 0.
    inertia : ndarray (3, 3)
        Inertia tensor J about the centre of mass, block axes [kg·m²],
        symmetric positive definite.
    isolators : tuple of Isolator
        At least one; together they must hold the block in all six directions.
    cg : ndarray (3,)
        Centre of mass c from O [m].
    imu : ndarray (3,)
        IMU measurement point p from O [m].
    gravity : ndarray (3,)
        Gravity vector g in the block's axes at rest [m/s²] (default
        ``(0, 0, g₀)``: the block's z axis points down).
    name : str
    description : str

    Raises
    ------
    ValueError
        A mass or inertia that is not positive, no isolators, or isolators
        that leave a direction without stiffness (all on one line, say).
    """

    mass: float
    inertia: np.ndarray
    isolators: tuple
    cg: np.ndarray = field(default_factory=lambda: np.zeros(3))
    imu: np.ndarray = field(default_factory=lambda: np.zeros(3))
    gravity: np.ndarray = field(default_factory=lambda: np.array([0.0, 0.0, STANDARD_GRAVITY]))
    name: str = "mount"
    description: str = ""

    def __post_init__(self):
        object.__setattr__(self, "mass", positive(self.mass, "mass"))
        j = as_array(self.inertia, "inertia")
        if j.shape != (3, 3):
            raise ValueError(f"Expected `inertia` as a 3×3 matrix, got shape {j.shape}")
        if np.max(np.abs(j - j.T)) > 1e-12 * np.max(np.abs(j)):
            raise ValueError("Expected `inertia` symmetric")
        j = 0.5 * (j + j.T)
        low = np.linalg.eigvalsh(j)
        if low[0] <= 0:
            raise ValueError(f"Expected `inertia` positive definite, got principal moments {low.tolist()}")
        if low[0] + low[1] < low[2] * (1 - 1e-9):
            raise ValueError(f"Expected `inertia` of a rigid body (each principal moment at most the sum of the other two), got {low.tolist()}")
        j.setflags(write=False)
        object.__setattr__(self, "inertia", j)
        isolators = tuple(self.isolators)
        if not isolators or not all(isinstance(i, Isolator) for i in isolators):
            raise TypeError("Expected `isolators` as a nonempty sequence of Isolator")
        object.__setattr__(self, "isolators", isolators)
        for name in ("cg", "imu", "gravity"):
            object.__setattr__(self, name, _vector(getattr(self, name), name))
        k = self.stiffness_matrix
        mk = linalg.eigh(k, self.mass_matrix, eigvals_only=True) if np.max(np.abs(k)) > 0 else np.zeros(6)
        if not mk[-1] > 0 or mk[0] <= 1e-9 * mk[-1]:
            raise ValueError(
                "Expected isolators that hold the block in all six directions, got a stiffness matrix that is singular "
                "(isolators on one line, or no stiffness along an axis)"
            )

    @property
    def mass_matrix(self) -> np.ndarray:
        """M (6, 6) about O in ``q = (x, θ)`` [kg, kg·m, kg·m²]."""
        m, cx = self.mass, skew(self.cg)
        return np.block([[m * np.eye(3), -m * cx], [m * cx, self.inertia - m * cx @ cx]])

    def _assemble(self, attr: str) -> np.ndarray:
        out = np.zeros((6, 6))
        for iso in self.isolators:
            t = iso.transform
            out += t.T @ (getattr(iso, attr)[:, None] * t)
        return out

    @property
    def stiffness_matrix(self) -> np.ndarray:
        """``K = Σ T_iᵀ K_i T_i`` (6, 6) [N/m, N, N·m]."""
        return self._assemble("stiffness")

    @property
    def damping_matrix(self) -> np.ndarray:
        """``C = Σ T_iᵀ C_i T_i`` (6, 6) [N·s/m, N·s, N·m·s]."""
        return self._assemble("damping")

    def displacement_response(self, freq) -> np.ndarray:
        """``Z(ω)⁻¹ (K + iωC)``: block coordinates per unit of base coordinates, shape ``freq.shape + (6, 6)``.

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz], > 0.

        Returns
        -------
        ndarray of complex
        """
        f = np.asarray(freq, dtype=float)
        w = 2.0 * math.pi * f[..., None, None]
        k, c, m = self.stiffness_matrix, self.damping_matrix, self.mass_matrix
        base = k + 1j * w * c
        return np.linalg.solve(base - w**2 * m, base)

    def transfer(self, freq) -> np.ndarray:
        """``H(ω)``: IMU (ω, f) amplitudes per unit of base (Ω, A) amplitudes, shape ``freq.shape + (6, 6)`` (module docstring).

        Parameters
        ----------
        freq : array_like
            Frequencies [Hz], > 0.

        Returns
        -------
        ndarray of complex
            Rows: IMU body rate (x, y, z) [rad/s] and specific force (x, y, z)
            [m/s²]; columns: base angular rate (x, y, z) [rad/s] and
            acceleration (x, y, z) [m/s²].

        Examples
        --------
        Far below the modes the block follows the base: unit gain from base to
        IMU, up to the block's quasi-static tilt under acceleration, which tilts
        the gravity reading (0.1 % here):

        >>> from strapdown.analysis.vibration.examples import ISOLATED_MOUNT
        >>> h = load_mount(ISOLATED_MOUNT).transfer(0.01)
        >>> bool(np.allclose(h[:3, :3], np.eye(3), atol=1e-6)), bool(np.allclose(h[3:, 3:], np.eye(3), atol=2e-3))
        (True, True)
        """
        f = np.asarray(freq, dtype=float)
        if np.any(f <= 0):
            raise ValueError("Expected `freq` > 0")
        w = 2.0 * math.pi * f[..., None, None]
        g = self.displacement_response(f)
        eye = np.eye(3)
        zero = np.zeros(f.shape + (3, 3))
        inp = np.concatenate([np.concatenate([zero, -eye / w**2], -1), np.concatenate([eye / (1j * w) + zero, zero], -1)], -2)
        tilt = w**2 * skew(self.imu) - skew(self.gravity)
        out = np.concatenate([np.concatenate([zero, 1j * w * eye + zero], -1), np.concatenate([-(w**2) * eye + zero, tilt + zero], -1)], -2)
        return out @ g @ inp

    def modes(self) -> tuple:
        """The mount's modes, lowest natural frequency first (module docstring).

        Returns
        -------
        tuple of Mode
        """
        m, k, c = self.mass_matrix, self.stiffness_matrix, self.damping_matrix
        minv = np.linalg.inv(m)
        a = np.block([[np.zeros((6, 6)), np.eye(6)], [-minv @ k, -minv @ c]])
        lam, vec = linalg.eig(a)
        keep = [i for i in range(12) if lam[i].imag > 1e-9 * abs(lam[i]) or abs(lam[i].imag) <= 1e-9 * abs(lam[i])]
        modes = []
        cx = skew(self.cg)
        for i in keep:
            lv, q = lam[i], vec[:6, i]
            size = abs(lv)
            energy_q = np.real(np.conj(q) @ m @ q)
            q = q / math.sqrt(max(energy_q, 1e-300))
            x_cg, theta = q[:3] - cx @ q[3:], q[3:]
            shares = np.concatenate([self.mass * np.abs(x_cg) ** 2, np.real(np.conj(theta) * (self.inertia @ theta))])
            shares = shares / np.sum(shares)
            big = int(np.argmax(np.abs(q) * np.sqrt(np.diag(m))))
            q = q * np.exp(-1j * np.angle(q[big]))
            overdamped = abs(lv.imag) <= 1e-9 * size
            zeta, damped = (1.0, 0.0) if overdamped else (-lv.real / size, lv.imag / (2 * math.pi))
            modes.append(Mode(size / (2 * math.pi), zeta, damped, tuple(complex(z) for z in q), tuple(float(s) for s in shares)))
        modes.sort(key=lambda md: (md.frequency, md.damping_ratio))
        return tuple(modes)

    @property
    def total_stiffness(self) -> np.ndarray:
        """Sum of the isolators' stiffnesses per axis (3,) [N/m]."""
        return np.sum([i.stiffness for i in self.isolators], axis=0)


# --------------------------------------------------------------------------- files
@dataclass(frozen=True)
class MountLimits:
    """Limits of a mount file, checked before any arithmetic.

    Attributes
    ----------
    file_bytes : int
        Largest file size [bytes].
    isolators : int
        Most isolators [count].
    """

    file_bytes: int = 256 * 1024
    isolators: int = 64


#: The limits :func:`load_mount` applies by default.
MOUNT_LIMITS = MountLimits()
_TOP = {"name", "description", "mass_kg", "inertia_kg_m2", "cg_m", "imu_m", "gravity_m_s2", "isolator"}
_ISOLATOR = {"position_m", "stiffness_n_m", "damping_n_s_m", "label"}
_MAX_DEPTH = 4


def load_mount(path, *, limits: MountLimits = MOUNT_LIMITS) -> Mount:
    """Read a mount file (TOML; format in ``docs/mount-files.md``).

    Parameters
    ----------
    path : str or Path
        The file.
    limits : MountLimits, keyword-only
        Limits of the file (default :data:`MOUNT_LIMITS`).

    Returns
    -------
    Mount

    Raises
    ------
    ValueError
        A file that cannot be read or is not valid TOML, an unknown or missing
        key, a value of the wrong kind or out of range, an inertia that is not
        a rigid body's, isolators that do not hold the block; the message names
        the file, the table and the key.
    """
    path = Path(path)
    data = read_toml(path, max_bytes=limits.file_bytes, max_depth=_MAX_DEPTH, kind="mount file")
    top = Table(path, "top level", data, _TOP)
    mass = top.number("mass_kg", low=0.0, open_low=True, required=True)
    inertia_value = data.get("inertia_kg_m2")
    if isinstance(inertia_value, list) and len(inertia_value) == 3 and not any(isinstance(r, list) for r in inertia_value):
        inertia = np.diag(top.vector("inertia_kg_m2", low=0.0))
    else:
        inertia = top.matrix("inertia_kg_m2", required=True)
    isolators = []
    for i, t in enumerate(top.tables("isolator", limit=limits.isolators)):
        r = Table(path, f"[[isolator]] #{i + 1}", t, _ISOLATOR)
        isolators.append(
            Isolator(r.vector("position_m", required=True), r.vector("stiffness_n_m", required=True, low=0.0), r.vector("damping_n_s_m", [0.0] * 3, low=0.0), r.text("label", f"isolator {i + 1}"))
        )
    if not isolators:
        raise ValueError(f"{path}: no isolator (expected at least one [[isolator]] table)")
    try:
        return Mount(
            mass, inertia, tuple(isolators), top.vector("cg_m", [0.0] * 3), top.vector("imu_m", [0.0] * 3), top.vector("gravity_m_s2", [0.0, 0.0, STANDARD_GRAVITY]),
            top.text("name", path.stem), top.text("description", ""),
        )  # fmt: skip
    except ValueError as exc:
        raise ValueError(f"{path}: {exc}") from None
