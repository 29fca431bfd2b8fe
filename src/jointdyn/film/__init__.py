"""Everything about a lubricant film: closed-form film models and their Jacobians, the finite
bearing (2-D Reynolds solver, cavitation conditions, force tables), shear, pressure fields and
dynamic coefficients. Force elements call this package, never the reverse."""
