"""Integrators as code: take a user's coning and sculling routine as it is, and say what it computes.

A designer's algorithm is rarely a row of the registry
(:mod:`strapdown.derivations.coning.registry`): it is code, an autopilot's
per-sample recursion, a DCM integrator, a vendor's compiled routine.  This
subpackage treats such code as a black box, identifies its bilinear part as
an exact algorithm, and runs the package's machinery on it.

=======================  ===================================================================
module                   holds
=======================  ===================================================================
``interface``            the black-box interface (:class:`~.interface.Integrator`), its
                         checked call (:func:`~.interface.step_increments`) and the loading
                         of ``FILE.py:NAME``
``adapters``             stateful objects (reset / update / output), compiled C functions
                         (ctypes), and a registry algorithm run from its own terms
``peers``                pyins's integrator and smsfusion's ``StrapdownINS``, like for like
``recursions``           per-sample recursions as autopilots write them, and the
                         quaternion composition of the samples
``identification``       designed probes, the exact bilinear coefficients, the remainder
``sculling_terms``       the identified sculling part as data, its rectification error
``verification``         the integrator itself against the exact solution
``assessment``           everything above for one integrator, ready to print
``studies``              the integrators of the report: flight-code recursions, a composition
                         without coning term, the peers like for like
=======================  ===================================================================

Conventions are the package's (``strapdown.analysis``): increments ``p_j``
[rad] and ``b_j`` [m/s] per sample, sample indices ``1 … N`` in the current
step and ``≤ 0`` before it, errors exact minus algorithm.
"""

__all__: list = []
