"""Chaos and periodicity of mechanisms: ensemble statistics, Poincaré sections, bifurcation
diagrams, Lyapunov exponents and spectra (see docs/user-guide/chaos.md)."""
