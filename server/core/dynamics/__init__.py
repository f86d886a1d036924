"""Machine dynamics on the one-mass model: reduction, loads, motors and the equation of motion."""
