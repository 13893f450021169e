"""Navigation over the rotating Earth and its error budget.

integration
    Strapdown integration in a non-rotating frame: attitude (coning), velocity (sculling), position (scrolling).
convergence
    The integration against exact motions: errors and observed orders as h halves.
scrolling
    The scrolling error of the position algorithm in closed form, in a vibration environment, and by simulation.
earth_model
    The navigator's Earth: spherical, WGS-84 rotation rate, radial gravity; frames I, E, NED.
mechanization
    The navigator over the rotating Earth (inertial-frame mechanization, vertical channel held), compiled.
imu_file
    An IMU's data sheet: its errors, read from a TOML file.
error_model
    The linear navigation error model with the states of one sensor-error source.
covariance
    Covariance (and mean) propagation of the error model over a mission, exact discretisation.
alignment
    Initial conditions: the attitude error of an alignment method, correlated with the sensor states.
error_budget
    The error budget: one run per source by superposition, the total, the dominant source.
monte_carlo
    The nonlinear navigator with sensor errors drawn from the data sheet, against the budget.
"""
