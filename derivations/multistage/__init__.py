"""Symbolic derivations for corrected attitude stages (Plotnikov 1999).

Modules
-------
published
    What the paper prints: the section-5 example, its results, formulas as printed.
lyapunov_function
    The Lyapunov function V, its derivative V′ = −lk|z|², and a strict Lyapunov function.
schuler
    The linearised stage and its Schuler tuning (acceleration → tilt transfer function).
composition
    The equation of the composite ν₁∘ν: every stage-1 correction cancels.
tilt_quaternion
    The tilt quaternion (1.9)–(1.10) derived from (1.7)–(1.8).
"""
