"""Amplitude spectra of periodic-in-the-mean signals in harmonics of a driver's speed [T130].

Over an integer number N of revolutions sampled at equal time steps, the discrete Fourier
transform has its bins exactly at the harmonics k/N of the driver's frequency (no leakage for a
periodic signal, rectangular window); the one-sided amplitude of bin m is 2|X_m|/n_samples
(|X_0|/n for the mean). Harmonic order h = m/N [-].
"""

from __future__ import annotations

import math

import numpy as np

from jointdyn import post
from jointdyn.core import atomic
from jointdyn.studies.poincare import stroboscopic_indices


def amplitude_spectrum(x: np.ndarray, revs: int) -> tuple[np.ndarray, np.ndarray]:
    """(harmonic order h [-], amplitude [unit of x]) of ``x`` sampled uniformly over exactly
    ``revs`` revolutions (the last sample, equal to the first of the next revolution, excluded
    by the caller) [T130]."""
    x = np.asarray(x, float)
    if revs < 1:
        raise ValueError(f"revs = {revs!r} [rev]: must be ≥ 1")
    n = x.size
    X = np.fft.rfft(x)
    amp = 2.0 * np.abs(X) / n
    amp[0] /= 2.0
    if n % 2 == 0:
        amp[-1] /= 2.0
    return np.arange(X.size) / revs, amp


def run_spectra(
    res,
    transient_revs: int = 0,
    driver: str | None = None,
    body: str | None = None,
    element: str | None = "",
) -> dict:
    """Spectra over the complete revolutions of angle driver ``driver`` (default: the model's
    first) after ``transient_revs``: its moment (``drive_moment`` [N·m]), the x acceleration
    of ``body`` (``body_x_acceleration`` [m/s²]) if given, and the force magnitude of journal ``element`` [N]
    (``""``: the model's first, if it has one; None: none). Returns {"harmonic": h, name:
    amplitude, "revs": N}."""
    from jointdyn.studies import period as per

    driver = per.driver_name(res.system, driver)
    if element == "":
        journals = per.journal_elements(res.system)
        element = journals[0] if journals else None
    elif element is not None:
        element = per.journal(res.system, element)
    if transient_revs < 0:  # b[-1] would be taken as the start: silently the last revolution
        raise ValueError(f"transient_revs = {transient_revs} [rev]: must be >= 0")
    angle = per.driver_angle(res, driver)
    b = stroboscopic_indices(angle, float(angle[0]))
    if b.size < transient_revs + 2:
        raise ValueError(
            f"transient_revs = {transient_revs} [rev]: the run has {max(b.size - 1, 0)} complete revolutions"
        )
    a, z = b[transient_revs], b[-1]
    revs = b.size - 1 - transient_revs
    sl = slice(a, z)  # [a, z): whole revolutions, endpoint excluded
    dt = np.diff(res.t[sl])
    if dt.size and np.ptp(dt) > 1e-9 * dt.mean():
        raise ValueError("the output samples are not equally spaced in time; a spectrum needs a uniform grid")
    series = {"drive_moment": post.driving_moment(res, driver)[sl]}
    if body is not None:
        if body not in res.system.body_names:
            raise ValueError(f"--body {body!r}: no such body; valid: {list(res.system.body_names)}")
        series["body_x_acceleration"] = res.qdd[sl, 3 * res.system.body_index(body)]
    if element is not None:
        series["joint_force"] = np.hypot(res.element(element, "Fx"), res.element(element, "Fy"))[sl]
    out: dict = {"revs": revs}
    for k, v in series.items():
        h, amp = amplitude_spectrum(v, revs)
        out["harmonic"] = h
        out[k] = amp
    return out


UNITS = {"drive_moment": "N·m", "body_x_acceleration": "m/s²", "joint_force": "N"}


def plot_spectra(spec: dict, path, max_harmonic: float = 40.0, title: str = "") -> None:
    """Amplitude against harmonic order (log scale) for each series of :func:`run_spectra`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    names = [k for k in UNITS if k in spec]
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.6 * len(names)), sharex=True, squeeze=False)
    h = spec["harmonic"]
    if not (math.isfinite(max_harmonic) and max_harmonic > 0):
        raise ValueError(f"max_harmonic = {max_harmonic!r} [-]: must be finite and > 0")
    keep = (h > 0) & (h <= max_harmonic)
    for ax, k in zip(axes[:, 0], names):
        ax.semilogy(h[keep], np.maximum(spec[k][keep], 1e-300), lw=0.8)
        ax.set_ylabel(f"{k}\n[{UNITS[k]}]")
        ax.grid(alpha=0.3)
    axes[-1, 0].set_xlabel(f"harmonic of the driver's speed [-] ({spec['revs']} revolutions)")
    if title:
        axes[0, 0].set_title(title)
    fig.tight_layout()
    with atomic.replacing(path) as tmp:
        fig.savefig(tmp, dpi=120, format="png")
    plt.close(fig)
