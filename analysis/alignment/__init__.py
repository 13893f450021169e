"""Self-alignment of the whole system on a rocking base.

Every sensor sees the rocking (the gyros its rates, the accelerometers its tilts
and the lever-arm accelerations), with the sensor errors of a real IMU; three
methods estimate the attitude, each against its theory.  Builds on the tilt
channel of Hrechka & Koroliov in :mod:`strapdown.analysis.gyrocompass`.

earth
    Earth rate and normal gravity (WGS-84), NED.
tilt_attitude
    The attitude in the paper's angles (ψ, β, γ) and its kinematics.
base_motion
    Rocking in three axes as smooth random functions (sine, sum of sines, narrow-band, white).
imu
    Kinematically consistent gyro and accelerometer increments with lever arm and sensor errors.
preintegration
    Epoch increments (coning and sculling compensated).
kernels
    Compiled loops of the self-alignment Monte Carlo (sensor increments, preintegration, the filter's epochs).
estimate
    What an alignment method returns.
analytic
    Formula (2) with the averaged outputs and the estimates (16), or levelled.
inertial
    Inertial-frame (coarse) alignment: Wahba's problem on integrated specific force.
fine
    Kalman fine alignment with NEES and NIS, and the rocking model it assumes.
theory
    First-order theory of every error term; the Kalman filter's own prediction.
monte_carlo
    Monte Carlo of each method against its theory.
design
    The admissible rocking amplitude against frequency for each method.
studies
    The whole-system studies of the report.
error_model
    The linear error model of a navigator in continuous time (at rest, rocking, in motion).
observability
    Rank, unobservable directions in words and degree of observability; stationary, rocking, multi-position.
coarse_to_fine
    The fine filter started from the inertial-frame coarse result and its covariance.
compass_loop
    Compass-loop (gyrocompass) alignment with tunable bandwidth and damping, and its linear theory.
comparison
    The methods side by side on the same trials, each against its trials' bias floor.
sensor_models
    Sensor errors as a data sheet specifies them; Allan deviation (allantools) and its read-back.
trajectory
    A manoeuvring vehicle over the rotating Earth: exact kinematics and ideal increments.
aided
    GNSS-aided in-motion alignment: navigator, filter, aided floor, Monte Carlo.
design_studies
    The studies of the alignment-design report.
"""
