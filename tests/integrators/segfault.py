"""An integrator that dereferences a null pointer: its process dies of SIGSEGV."""

import ctypes


def integrate(gyro, samples_per_step):
    return ctypes.string_at(0)
