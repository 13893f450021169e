"""The vibration environment: algorithms and sensors in the designer's vibration, as a domain of its own.

Built on :mod:`strapdown.analysis.coning` (the algorithms, their drift
functions and the simulator); the coning domain never imports this one.

Modules
-------
sensor_dynamics
    Sensor filters: analog transfer functions, digital filters, decimation.
environment
    Vibration environments (lines, cross-spectra, sensors) and their TOML files.
examples
    The example environment files shipped with the package.
drift
    Mean coning drift and sculling rectification in an environment, closed form,
    sensor part (pseudo-coning, pseudo-sculling) apart from the algorithm's; the
    drift vector and its magnitude; the closed form's range.
aliasing
    Pairs of lines whose sum or difference frequency is a multiple of the step
    rate: their phase-locked mean drift; near aliases and their beat periods.
noise
    Gyro white noise and quantization through the correction terms: mean and
    random walk, against the coning residual.
simulation
    DOP853 references: pseudo-coning (continuous filters, exact kinematics) and
    any deterministic lines, aliasing pairs included.
monte_carlo
    Monte Carlo of the mean drift with an exact truth (compiled kernel).
tuning
    Algorithms tuned to an environment (coning and sculling).
rate_design
    Lowest sample rate and load for a drift budget in an environment.
profile
    Linear random-vibration profiles: breakpoints, dB/octave slopes, grms; the base excitation.
mount
    The six-degree-of-freedom IMU mount: rigid block on isolators, transfer matrix, modes.
mount_response
    The IMU's cross-spectra through the mount as an environment; drift per mode band.
mount_simulation
    DOP853 simulation of the mount under random base motion: Welch and drift checks.
"""
