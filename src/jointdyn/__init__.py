"""jointdyn: planar multibody dynamics with ideal, clearance and lubricated joints."""
