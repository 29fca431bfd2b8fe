"""``jointdyn stribeck``: the steady Stribeck curve of a journal bearing in mixed lubrication at a
constant load (registered on :mod:`jointdyn.cli.common`'s application) [T270–T272]."""

from __future__ import annotations

import csv
import io
from pathlib import Path

import typer

from jointdyn.cli.common import _one_line_errors, app


def _pair(text: str, name: str) -> tuple[float, float]:
    try:
        a, b = (float(x) for x in text.split(","))
    except ValueError:
        raise ValueError(f"--{name} {text!r}: give two numbers SIGMA1,SIGMA2 in m") from None
    return a, b


def _speeds(text: str) -> list[float]:
    """Comma-separated speeds, or a geometric range ``first:last:count`` [rev/min]."""
    try:
        if ":" in text:
            a, b, n = text.split(":")
            k = int(n)
            if k < 2 or float(a) <= 0.0 or float(b) <= 0.0:
                raise ValueError
            return [float(a) * (float(b) / float(a)) ** (i / (k - 1)) for i in range(k)]
        return [float(x) for x in text.split(",") if x.strip()]
    except ValueError:
        raise ValueError(
            f"--speeds {text!r}: give speeds in rev/min separated by commas or a range first:last:count (> 0)"
        ) from None


def _mesh(text: str) -> tuple[int, int]:
    try:
        a, b = (int(x) for x in text.split(","))
        if a < 8 or b < 2:
            raise ValueError
    except ValueError:
        raise ValueError(
            f"--mesh {text!r}: give NT,NZ (cells around >= 8, on the half length >= 2)"
        ) from None
    return a, b


def stribeck_cmd(
    radius: float = typer.Option(..., help="journal radius R in m"),
    length: float = typer.Option(..., help="bearing length L in m"),
    clearance: float = typer.Option(..., help="radial clearance c in m"),
    load: float = typer.Option(..., help="constant load W in N"),
    speeds: str = typer.Option(
        "1,3,10,30,100,300,1000,3000",
        help="journal speeds in rev/min: 1,10,... or a geometric range first:last:count",
    ),
    viscosity: float = typer.Option(None, help="dynamic viscosity μ in Pa·s (or --oil)"),
    oil: str = typer.Option(None, help="oil grade, e.g. ISO_VG46 (with --temperature)"),
    temperature: float = typer.Option(40.0, help="oil temperature in °C (with --oil)"),
    roughness: str = typer.Option(
        "0.4e-6,0.3e-6", help="RMS roughness SIGMA1,SIGMA2 of journal, bushing in m"
    ),
    eta_beta_sigma: float = typer.Option(0.04, help="Greenwood–Tripp roughness parameter ηβσ (-)"),
    sigma_over_beta: float = typer.Option(1e-3, help="Greenwood–Tripp σ/β (-)"),
    modulus: float = typer.Option(1.1e11, help="composite modulus E' in Pa"),
    boundary_friction: float = typer.Option(0.1, help="boundary friction coefficient f_b (-)"),
    pressure_viscosity: float = typer.Option(0.0, help="Barus pressure–viscosity α in 1/Pa (0: isoviscous)"),
    gamma: float = typer.Option(1.0, help="Peklenik surface orientation γ: 1/9,1/6,1/3,1,3,6,9"),
    flow_factors: bool = typer.Option(True, help="Patir–Cheng average film (--no-flow-factors: smooth film)"),
    mesh: str = typer.Option("144,16", help="finite-volume mesh NT,NZ"),
    out: Path = typer.Option(
        Path("stribeck.csv"), help="output CSV; the figure is written next to it (.png)"
    ),
):
    """Stribeck curve at constant load: for each speed the mixed-lubrication equilibrium (film +
    Greenwood–Tripp asperity load = W), friction torque (film shear with Patir–Cheng factors +
    boundary friction), friction coefficient, h_min, ε, asperity share of the load, Hersey number."""
    from rich.console import Console
    from rich.markup import escape

    from jointdyn.bearing.mixed import STRIBECK_COLUMNS, Bearing, stribeck
    from jointdyn.film.asperity import GreenwoodTripp, composite_sigma
    from jointdyn.film.flow_factors import AverageFlow

    console = Console(stderr=True)
    with _one_line_errors():  # Ctrl-C: one line, exit 130 (checked per speed) [T332]
        if (viscosity is None) == (oil is None):
            raise ValueError(
                "give exactly one of --viscosity (Pa·s) and --oil (a grade, with --temperature in °C)"
            )
        if oil is not None:
            from jointdyn.film.viscosity import oil_by_name

            viscosity = oil_by_name(oil).viscosity(temperature)
        s1, s2 = _pair(roughness, "roughness")
        gt = GreenwoodTripp(composite_sigma(s1, s2), eta_beta_sigma, sigma_over_beta, modulus)
        flow = AverageFlow.of(s1, s2, clearance, gamma) if flow_factors else None
        fb = boundary_friction
        b = Bearing(radius, length, clearance, viscosity, gt, flow, fb, pressure_viscosity=pressure_viscosity)
        tab = stribeck(b, load, _speeds(speeds), _mesh(mesh))
        buf = io.StringIO()
        w = csv.writer(buf)
        w.writerow(STRIBECK_COLUMNS)
        for i in range(len(tab["speed_rpm"])):
            w.writerow([f"{tab[c][i]:.6g}" for c in STRIBECK_COLUMNS])
        from jointdyn.io.derived import output_file

        with output_file(out, "stribeck") as tmp:  # a run directory's lock and manifest [T338]
            tmp.write_text(buf.getvalue(), encoding="utf-8")
        import matplotlib

        matplotlib.use("Agg")
        from jointdyn.viz.stribeck import stribeck_figure

        fig = stribeck_figure(tab, f"W = {load:g} N, R = {radius:g} m, L = {length:g} m, c = {clearance:g} m")
        png = out.with_suffix(".png")
        with output_file(png, "stribeck") as tmp:  # atomic, never replacing a link or a special file
            fig.savefig(tmp, dpi=120, format="png")
    k = min(range(len(tab["speed_rpm"])), key=lambda i: tab["friction_coefficient"][i])
    console.print(
        f"wrote {escape(str(out))} and {escape(str(png))}: minimum friction coefficient "
        f"{tab['friction_coefficient'][k]:.4g} at {tab['speed_rpm'][k]:.4g} rpm"
    )


app.command("stribeck")(stribeck_cmd)
