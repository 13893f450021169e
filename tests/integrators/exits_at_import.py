"""A file that calls sys.exit(3) when it is imported."""

import sys

print("configuration not found")
sys.exit(3)


def integrate(gyro, samples_per_step):  # never reached
    return gyro
