"""Report section ``errata.md``: misprints in the source papers, with evidence.

Every entry is produced by a check that runs when the report is built; the
section gathers the ``errata(ctx)`` lists of all report sections, plus the
checks of the printed biquaternion formulas of Lebedev & Panov (1989)
(:func:`strapdown.analysis.coning.papers.biquaternion_checks.printed_formula_checks`).
Formatting only.
"""

from __future__ import annotations

from ..coning.papers.biquaternion_checks import printed_formula_checks
from . import Erratum, Section
from .rendering import at_round_off

SECTION = Section("errata", "Errata in the source papers", order=90, summary="Misprints found by independent checks, with evidence.", gathers=True)

#: Seed of the random points of the printed-formula checks.
CHECK_SEED = 0


def errata(ctx) -> list:
    """The errata this section's checks establish, with their evidence.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        The report context.

    Returns
    -------
    list of Erratum
    """
    c = printed_formula_checks(CHECK_SEED)
    return [
        Erratum(
            "Lebedev & Panov (1989), condition after eq. (1.12)",
            "λ0μ0 − λ1μ1 − λ2μ2 − λ3μ3 = 0",
            "λ0μ0 + λ1μ1 + λ2μ2 + λ3μ3 = 0 (the dual part of |Λ|² = 1)",
            f"On {c.points} random dual vectors the biquaternion obtained as the dual extension of the rotation-vector map gives "
            f"max |λ·μ| {at_round_off(c.unit_condition_plus)}, while the printed combination reaches {c.unit_condition_printed:.2f}.",
            "errata",
            kind="misprint",
        ),
        Erratum(
            "Lebedev & Panov (1989), eq. (1.12), μ_i",
            "μ_i = φ⁻¹ sin(φ/2) φ°_i − φ⁻²(½ cos(φ/2) − φ⁻¹ sin(φ/2)) (φ·φ°) φ_i",
            "μ_i = φ⁻¹ sin(φ/2) φ°_i + φ⁻²(½ cos(φ/2) − φ⁻¹ sin(φ/2)) (φ·φ°) φ_i",
            f"Against the dual extension of the real map (forward-mode derivative), the printed μ_i is off by up to "
            f"{c.mu_vec_error_printed:.2f}; with the sign of its second term flipped the difference is {at_round_off(c.mu_vec_error_fixed)} "
            f"(μ0 as printed: difference {at_round_off(c.mu0_error)}).",
            "errata",
            kind="misprint",
        ),
        Erratum(
            "Lebedev & Panov (1989), eq. (4.7), third component",
            "Λ° t (ε + cos ϑ)",
            "ν° t (ε + cos ϑ)",
            f"U_I = 2 R ∘ Q̄ computed from the biquaternion (4.4)–(4.5) matches (4.7) read with ν° to {c.u_inertial_error:.1e} m/s "
            f"over t ∈ [0, {c.time_span:g}] s (ν° = {c.motion.nu_dual:g} m/s², ϑ° = {c.motion.nutation_dual:g} m/s).",
            "errata",
            kind="misprint",
        ),
        Erratum(
            "Lebedev & Panov (1989), text before (4.6) and after (4.7)",
            "general solutions (1.10), (1.14)",
            "(1.10), (1.11): there is no eq. (1.14)",
            "Only (1.10) and (1.11) express W_E and W_I through U_E, U_I; the exact-state tests use them.",
            "errata",
            kind="misprint",
        ),
    ]


#: How each class is labelled in ``errata.md``.
KIND_LABELS = {
    "misprint": "misprint — a check decides it",
    "ambiguous": "ambiguous — the text admits readings; ours is stated with the alternatives",
    None: "not classified yet",
}


def _entry(i: int, e: Erratum) -> list:
    where = f" Details: [{e.section}]({e.section}.md)." if e.section and e.section != "errata" else ""
    lines = [
        f"## {i}. {e.source}",
        "",
        f"- **Class:** {KIND_LABELS[e.kind]}",
        f"- **Printed:** {e.printed}",
        f"- **{'Likely reading' if e.kind == 'ambiguous' else 'Correct'}:** {e.correct}",
    ]
    if e.alternatives:
        lines.append(f"- **Alternatives:** {e.alternatives}")
    return lines + [f"- **Evidence:** {e.evidence}{where}", ""]


def _summary(entries) -> list:
    counts = {kind: sum(e.kind == kind for e in entries) for kind in KIND_LABELS}
    plural = lambda n, word: f"{n} {word}" + ("" if n == 1 else "s")  # noqa: E731
    parts = [f"{plural(counts['misprint'], 'misprint')} (a check decides them)", f"{plural(counts['ambiguous'], 'ambiguous place')} (the text admits readings)"]
    if counts[None]:
        parts.append(f"{counts[None]} not classified yet")
    return [f"{len(entries)} entries: " + ", ".join(parts) + ".", ""]


def build(ctx) -> None:
    """Write ``errata.md``: the errata of every section, numbered, each with its class.

    Parameters
    ----------
    ctx : strapdown.analysis.report.Context
        Where to write, and whether to run the quick variant.
    """
    from . import discover

    entries = []
    for module in discover():
        if hasattr(module, "errata"):
            entries.extend(module.errata(ctx))
    lines = [
        "# Errata in the source papers",
        "",
        "Each entry comes from a check that the package runs when this report is built (a differential-equation",
        "residual, a symbolic derivation, a convergence study or a high-accuracy reference integration); the code",
        "follows the check, never the print. An entry is a **misprint** when the check decides it, and **ambiguous**",
        "when the text admits more than one reading: then ours is given as the likely reading, with the alternatives",
        "and their numbers, and it is not called correct.",
        "",
    ]
    lines += _summary(entries)
    for i, e in enumerate(entries, 1):
        lines += _entry(i, e)
    ctx.write_text("errata.md", "\n".join(lines))
