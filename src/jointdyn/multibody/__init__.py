"""The multibody system: the user's :class:`Model`, the compiled frozen :class:`System`, the
equations of motion (accelerations, multipliers, projection) and the system Jacobian."""
