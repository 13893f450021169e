"""Symbolic side of the navigation domain: the position (scrolling) algorithm and its errors, the Schuler responses.

position_algorithm
    The N-sample position algorithm as exact fractions, and its scrolling error under sculling in closed form.
schuler
    The free-inertial responses of the horizontal channel to constant sensor biases (Schuler, textbook form).
"""
