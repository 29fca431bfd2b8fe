"""Studies over any model: single runs, sweeps, ensembles, Poincaré sections, bifurcation
diagrams, Lyapunov exponents, spectra and the paper's reproduction."""
