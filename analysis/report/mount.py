"""Report section ``mount.md``: a linear vibration profile through an IMU mount, its modes and the coning they cause.

Formatting only: the numbers come from
:mod:`strapdown.analysis.vibration.profile`,
:mod:`~strapdown.analysis.vibration.mount` and
:mod:`~strapdown.analysis.vibration.mount_response`, on the package's examples
:data:`strapdown.analysis.vibration.examples.AIRFRAME_PROFILE` and
:data:`~strapdown.analysis.vibration.examples.ISOLATED_MOUNT`.
"""

from __future__ import annotations

import numpy as np

from ...derivations.coning.registry import get
from ..core.units import DEG, RAD_PER_S_TO_DEG_PER_H, STANDARD_GRAVITY
from ..vibration.environment import load_environment
from ..vibration.examples import AIRFRAME_PROFILE, ISOLATED_MOUNT, QUALIFICATION
from ..vibration.mount import COORDINATES, load_mount
from ..vibration.mount_response import mount_drift, mount_environment, output_density
from ..vibration.profile import load_profile
from . import Section
from .rendering import fixed_layout

SECTION = Section(
    "mount",
    "Linear vibration through an IMU mount",
    order=38,
    summary=(
        "A linear random-vibration profile (breakpoints, dB/octave slopes) through a six-degree-of-freedom IMU mount: "
        "the mount's modes, the IMU's cross-spectra, and the coning and sculling each mode band causes."
    ),
)

#: Algorithm sample interval of the drift tables [s].
H = 1e-3
#: Algorithms of the drift tables.
ALGORITHMS = ("one-sample", "two-sample", "optimal-3", "ignagni-1996-5")
K = RAD_PER_S_TO_DEG_PER_H
G = STANDARD_GRAVITY


def _vector(v, scale: float = K, digits: int = 3) -> str:
    return "(" + ", ".join(f"{x * scale:+.{digits}e}" for x in v) + ")"


def build(ctx) -> None:
    """Write ``mount.md`` and its figures.

    Parameters
    ----------
    ctx : Context
        Where to write, and the run mode.
    """
    import matplotlib.pyplot as plt

    quick = ctx.quick
    excitation = load_profile(AIRFRAME_PROFILE)
    mount = load_mount(ISOLATED_MOUNT)
    response = mount_environment(mount, excitation)
    lin = excitation.linear[0]
    ang = excitation.angular[0]
    lines = [
        "# Linear vibration through an IMU mount",
        "",
        "A designer's vibration specification is a linear random-vibration profile of the structure (MIL-STD-810 Method 514,",
        "RTCA DO-160 Section 8: breakpoints in g²/Hz and slopes in dB/octave), and between that structure and the IMU there is a",
        "mount. The mount's rocking modes turn linear vibration into angular vibration, and angular vibration with a quadrature",
        "part between two axes is coning. The package reads the profile and the mount (`docs/mount-files.md`), computes the",
        "mount's transfer matrix H from the base's six channels to the IMU's body rate and specific force",
        "(`strapdown.analysis.vibration.mount`), and the IMU's cross-spectral density",
        "",
        "$$G_{out}(f) = \\overline{H}\\,G_{in}\\,H^T$$",
        "",
        "(the convention $G_{ab} = \\frac{1}{2}\\,\\bar Z_a Z_b$ of the environment files; $S_{out} = H S_{in} H^H$ for $S_{ab} \\propto Z_a \\bar Z_b$),",
        "tabulated as an environment that every environment command takes (`strapdown.analysis.vibration.mount_response`;",
        "`strapdown mount-environment --profile P --mount M --out ENV`).",
        "",
        "## The example: an isolated IMU on a vibrating airframe",
        "",
        f"*{excitation.description}* (`airframe-profile.toml`, an illustration of the format, not a standard's numbers). The linear",
        "profile, on the three axes, uncorrelated:",
        "",
        "| breakpoint [Hz] | level [g²/Hz] | slope to the next [dB/octave] |",
        "|---|---|---|",
    ]
    slopes = list(lin.slope_db_per_octave) + [None]
    for f, level, s in zip(lin.frequency, lin.level, slopes):
        lines.append(f"| {f:g} | {level / G**2:.4g} | {'' if s is None else f'{s:+.3g}'} |")
    base_rms = excitation.rms()
    lines += [
        "",
        f"Its rms is {lin.rms / G:.4g} g per axis (the exact integral of the power laws); the angular profile adds"
        f" {np.degrees(ang.rms):.3g} deg/s rms per axis.",
        "",
        f"*{mount.description}* (`isolated-imu-mount.toml`): mass {mount.mass:g} kg, {len(mount.isolators)} isolators, centre of mass at",
        f"{np.round(mount.cg * 1e3, 1).tolist()} mm and the IMU at {np.round(mount.imu * 1e3, 1).tolist()} mm from the centre of the isolator plane",
        "(body axes, z down).",
        "",
        "### Modes",
        "",
        "| mode | natural frequency [Hz] | damping ratio | motion (share of kinetic energy) |",
        "|---|---|---|---|",
    ]
    for i, md in enumerate(response.modes):
        lines.append(f"| {i + 1} | {md.frequency:.2f} | {md.damping_ratio:.3f} | {md.description} |")
    imu_rms = response.output_rms()
    lines += [
        "",
        "Shares of kinetic energy: translation of the centre of mass along x, y, z and rotation about x, y, z ("
        + ", ".join(COORDINATES)
        + "). The centre of mass above the isolator plane couples translation and rocking.",
        "",
        "| channel | base rms | IMU rms |",
        "|---|---|---|",
    ]
    for i, axis in enumerate("xyz"):
        lines.append(f"| angular rate {axis} [deg/s] | {np.degrees(base_rms[i]):.3g} | {np.degrees(imu_rms[i]):.3g} |")
    for i, axis in enumerate("xyz"):
        lines.append(f"| acceleration / specific force {axis} [g] | {base_rms[3 + i] / G:.3g} | {imu_rms[3 + i] / G:.3g} |")
    lines += [
        "",
        f"The table of the environment has {response.points} frequencies (interpolation error {response.table_error:.2g}, an error of coherence, within",
        f"the tolerance {response.tolerance:g}).",
        "",
    ]

    # ------------------------------------------------------------ figure: spectra and modes
    f = np.geomspace(*excitation.band, 300 if quick else 800)
    g = output_density(mount, excitation, f)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7.2, 6.6), sharex=True)
    top.loglog(f, lin.at(f) / G**2, "k--", label="base acceleration, each axis")
    for i, axis in enumerate("xyz"):
        top.loglog(f, np.real(g[:, 3 + i, 3 + i]) / G**2, label=f"IMU specific force {axis}")
    top.set_ylabel("density [g²/Hz]")
    top.set_ylim(1e-7, 1e0)
    top.legend(loc="lower left", fontsize=7)
    for i, axis in enumerate("xyz"):
        bottom.loglog(f, np.real(g[:, i, i]) / DEG**2, label=f"IMU angular rate {axis}")
    for (a, b), style in zip(((0, 1), (1, 2), (2, 0)), ("k-", "k--", "k:")):
        bottom.loglog(f, np.abs(np.imag(g[:, a, b])) / DEG**2, style, lw=0.9, label=f"|quadrature| ω{'xyz'[a]}–ω{'xyz'[b]} (coning about {'xyz'[3 - a - b]})")
    bottom.set_ylabel("density [(deg/s)²/Hz]")
    bottom.set_xlabel("frequency [Hz]")
    bottom.set_ylim(1e-6, 1e3)
    bottom.legend(loc="lower left", fontsize=6.5)
    for ax in (top, bottom):
        for md in response.modes:
            ax.axvline(md.frequency, color="0.75", lw=0.6, zorder=0)
    fixed_layout(fig, left=0.8, right=0.15, bottom=0.5, top=0.2, hgap=0.25)
    ctx.savefig(fig, "figures/mount-spectra.png")
    lines += [
        "![the IMU's spectra through the mount](figures/mount-spectra.png)",
        "",
        "Above: the base acceleration profile and the IMU's specific force (the mount amplifies near its translational modes and",
        "isolates above them). Below: the IMU's angular rates and the magnitude of the quadrature spectra between two rate axes,",
        "the part that cones (grey lines: the natural frequencies).",
        "",
    ]

    # ------------------------------------------------------------ drift per mode band
    algorithms = [get(n) for n in ALGORITHMS]
    d = mount_drift(algorithms, response, H)
    lines += [
        "## Coning and sculling per mode band",
        "",
        f"At h = {H * 1e3:g} ms with ideal sensors, the mean coning drift (exact minus algorithm) of each algorithm, split into the bands",
        "around the modes (between the geometric means of adjacent natural frequencies; the modes overlap, so this attributes",
        "the drift, it does not separate the physics). Vectors are in the body axes; |u| is the magnitude.",
        "",
        "| band [Hz] | modes | true coning rate [deg/h] | " + " | ".join(f"{a.name}: vector [deg/h], \\|u\\|" for a in algorithms) + " |",
        "|---|---|---|" + "---|" * len(algorithms),
    ]
    for j, band in enumerate(d.bands):
        cells = [f"{_vector(d.coning[i, j], digits=2)}, {np.linalg.norm(d.coning[i, j]) * K:.3g}" for i in range(len(algorithms))]
        lines.append(f"| {band.low:.4g}–{band.high:.4g} | {', '.join(str(m + 1) for m in band.modes)} | {_vector(d.true_coning[j], digits=2)} | " + " | ".join(cells) + " |")
    totals = [f"{_vector(t, digits=3)}, {np.linalg.norm(t) * K:.4g}" for t in d.total_coning]
    lines.append(f"| all | | {_vector(d.true_coning.sum(axis=0), digits=3)} | " + " | ".join(totals) + " |")
    lines += [
        "",
        "| algorithm | rectification error, all bands [m/s²] | \\|·\\| [m/s²] |",
        "|---|---|---|",
    ]
    for a, s in zip(algorithms, d.total_sculling):
        lines.append(f"| {a.name} | {_vector(s, scale=1.0)} | {np.linalg.norm(s):.3g} |")
    # the same vibration through the sensors of the qualification example
    qualification = load_environment(QUALIFICATION)
    through = mount_environment(mount, excitation, gyro=qualification.gyro, accelerometer=qualification.accelerometer)
    ds = mount_drift(algorithms, through, H)
    sensor = ds.sensor.sum(axis=0)
    lines += [
        "",
        f"Through the sensors of `qualification.toml` (gyro: {qualification.gyro.description}; decimation {qualification.decimation}), the same",
        f"vibration adds a pseudo-coning part {_vector(sensor)} deg/h (|·| = {np.linalg.norm(sensor) * K:.3g} deg/h) to every algorithm, and",
        "the totals become:",
        "",
        "| algorithm | coning drift [deg/h] | \\|u\\| [deg/h] |",
        "|---|---|---|",
    ]
    for a, t in zip(algorithms, ds.total_coning):
        lines.append(f"| {a.name} | {_vector(t)} | {np.linalg.norm(t) * K:.4g} |")

    # ------------------------------------------------------------ figure: drift per band
    fig, ax = plt.subplots(figsize=(7.2, 4.0))
    x = np.arange(len(d.bands))
    width = 0.8 / (len(algorithms) + 1)
    ax.bar(x - 0.4 + width / 2, np.linalg.norm(d.true_coning, axis=1) * K, width, color="0.6", label="true coning rate")
    for i, a in enumerate(algorithms):
        ax.bar(x - 0.4 + width * (i + 1.5), np.linalg.norm(d.coning[i], axis=1) * K, width, label=a.name)
    ax.set_yscale("log")
    ax.set_ylim(top=np.max(np.linalg.norm(d.true_coning, axis=1)) * K * 1e3)  # room for the legend above the bars
    ax.set_xticks(x, [f"{b.low:.0f}–{b.high:.0f} Hz\nmode {', '.join(str(m + 1) for m in b.modes)}" for b in d.bands], fontsize=7)
    ax.set_ylabel(f"|coning drift| per band [deg/h], h = {H * 1e3:g} ms")
    ax.legend(loc="upper right", fontsize=7, ncol=2)
    fixed_layout(fig, left=0.8, right=0.15, bottom=0.6, top=0.2)
    ctx.savefig(fig, "figures/mount-coning-by-mode.png")
    lines += [
        "",
        "![coning per mode band](figures/mount-coning-by-mode.png)",
        "",
        "## Checks",
        "",
        "The test suite (`tests/test_mount.py`) checks the closed forms against a time-domain simulation that shares no linear",
        "algebra with them (`strapdown.analysis.vibration.mount_simulation`): DOP853 on the nonlinear rigid block, each isolator's",
        "force from the motion of its two attachment points, random base motion (random-phase multisines with Gaussian amplitudes).",
        "Welch's estimates of the six channels' cross-spectra, with intervals from independent realisations, hold the closed form",
        "at three frequencies and reject a conjugated convention, a 10 % heavier block and an IMU placed at the centre of mass; the",
        "coning drift of the one-sample and two-sample algorithms run on the simulated gyro increments holds the closed-form drift",
        "of the mount's spectra and rejects 0.7 times it, and the drift at half the interval. The modes and transmissibility of a",
        "decoupled mount are the textbook closed forms.",
        "",
        f"Mode: {'quick' if quick else 'full'}.",
    ]
    ctx.write_text("mount.md", "\n".join(lines))
