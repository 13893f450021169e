"""An integrator that never returns: the child process is stopped at the time limit."""


def integrate(gyro, samples_per_step):
    while True:
        pass
