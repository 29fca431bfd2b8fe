"""Foundations below every layer: the declared slot layout of the flat tables, planar kinematics,
argument checks, borrowed arrays for the compiled loops, and the ideal joints (kinematic
constraints)."""
