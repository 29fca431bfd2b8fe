"""``jointdyn bearing-table``: the steady design table and, with ``--load``, the operating point
(registered on :mod:`jointdyn.cli.common`'s application) [T77]."""

from __future__ import annotations

import csv
import io
import math
import sys
from pathlib import Path

import typer

from jointdyn.cli.common import _one_line_errors, app

MAX_VALUES = 10_000  # eccentricity ratios in one table [-]


def _floats(text: str, name: str) -> list[float]:
    """Comma-separated numbers, or a range ``first:last:count`` (count values, ends included)."""
    try:
        if ":" in text:
            a, b, n = text.split(":")
            k = int(n)
            if k < 1:
                raise ValueError
            if k > MAX_VALUES:  # each value is a film solve: refuse before any work [T285]
                raise OverflowError
            return [float(a) + (float(b) - float(a)) * i / max(k - 1, 1) for i in range(k)]
        return [float(x) for x in text.split(",") if x.strip()]
    except OverflowError:
        raise ValueError(f"--{name} {text!r}: at most {MAX_VALUES} values (each is a film solve)") from None
    except ValueError:
        raise ValueError(
            f"--{name} {text!r}: give numbers separated by commas or a range first:last:count"
        ) from None


def _supply(grooves, groove_width, holes, hole_diameter, circumferential, arc, feed_pa, ld, extra):
    """The supply feature of the options, its feed pressure made dimensionless [T245], or None
    (the plain bearing) [T244, T366]."""
    from jointdyn.film.grooved import CircumferentialGroove, axial_grooves, feed_holes, partial_arc

    options = (
        ("--grooves", grooves),
        ("--feed-holes", holes),
        ("--circumferential-groove", circumferential),
        ("--partial-arc", arc),
    )
    given = [o for o, v in options if v is not None]
    if len(given) > 1:
        raise ValueError(
            f"{' and '.join(given)}: give one supply feature (axial grooves, feed holes, a "
            "circumferential groove or a partial arc)"
        )
    if holes is None and hole_diameter is not None:
        raise ValueError("--hole-diameter needs --feed-holes")
    if not given:
        if feed_pa != 0.0:
            raise ValueError(
                "--feed-pressure needs --grooves, --feed-holes, --circumferential-groove or --partial-arc"
            )
        return None
    if not (math.isfinite(feed_pa) and feed_pa >= 0.0):
        raise ValueError(f"--feed-pressure {feed_pa!r} [Pa]: must be finite and >= 0 (gauge)")
    feed = 0.0
    if feed_pa > 0.0:
        if any(v is None for v in extra):
            raise ValueError("--feed-pressure > 0 needs --speed, --radius, --clearance and --viscosity (SI)")
        speed, radius, clearance, viscosity = extra
        omega = 2.0 * math.pi * speed
        feed = feed_pa * clearance**2 / (6.0 * viscosity * omega * radius**2)  # P_f [T245]
    if grooves is not None:
        return axial_grooves(grooves, groove_width, feed)
    if arc is not None:
        return partial_arc(arc, feed)
    lr = 2.0 * ld  # L/R
    for name, v in (("--hole-diameter", hole_diameter), ("--circumferential-groove", circumferential)):
        if v is not None and not (math.isfinite(v) and 0.0 < v < 1.0):
            raise ValueError(f"{name} {v!r} [-, fraction of the bearing length L]: must be in (0, 1)")
    if holes is not None:
        if hole_diameter is None:
            raise ValueError("--feed-holes needs --hole-diameter (fraction of the bearing length L)")
        return feed_holes(holes, hole_diameter * lr, feed)
    return CircumferentialGroove(circumferential * lr, feed)


def bearing_table_cmd(
    model: str = typer.Option("finite", help="finite | long | short | alshaer2005 (film name: long, gumbel)"),
    cavitation: str = typer.Option(
        None, help="reynolds (Swift–Stieber, default) | gumbel (default of short and alshaer2005) | jfo"
    ),
    ld: float = typer.Option(..., help="length/diameter ratio L/D (> 0)"),
    eps: str = typer.Option(
        "0.1,0.2,0.4,0.6,0.8,0.9,0.97", help="eccentricity ratios: 0.1,0.5,... or a range first:last:count"
    ),
    out: Path = typer.Option(None, help="output CSV (default: stdout)"),
    load: float = typer.Option(None, help="with --speed etc.: solve the equilibrium for this load W in N"),
    speed: float = typer.Option(None, help="journal speed N in rev/s (bearing fixed)"),
    radius: float = typer.Option(None, help="journal radius R in m"),
    clearance: float = typer.Option(None, help="radial clearance c in m"),
    viscosity: float = typer.Option(None, help="dynamic viscosity μ in Pa·s (or --oil and --inlet-temp)"),
    grooves: int = typer.Option(
        None, help="axial supply grooves, evenly spaced from +90° off the load line (2: at ±90°)"
    ),
    groove_width: float = typer.Option(18.0, help="angular width of each groove in degrees"),
    feed_holes: int = typer.Option(
        None, help="round feed holes at mid-length, evenly spaced from +90° off the load line"
    ),
    hole_diameter: float = typer.Option(
        None, help="feed-hole diameter as a fraction of the bearing length L"
    ),
    circumferential_groove: float = typer.Option(
        None, help="a groove all around at mid-length: its width as a fraction of the bearing length L"
    ),
    partial_arc: float = typer.Option(
        None, help="partial bearing: its arc in degrees, centred on the load line (open elsewhere)"
    ),
    feed_pressure: float = typer.Option(
        0.0, help="supply pressure in Pa (gauge; > 0 needs --speed --radius --clearance --viscosity)"
    ),
    oil: str = typer.Option(
        None, help="oil grade (ISO_VG22…ISO_VG220, SAE_10…SAE_60): effective temperature"
    ),
    inlet_temp: float = typer.Option(None, help="oil inlet temperature T_in in °C (with --oil)"),
):
    """Steady bearing design table (Raimondi–Boyd variables) per ε; with --load/--speed/--radius/
    --clearance/--viscosity also the operating point (ε, attitude, h_min, power loss, peak pressure)."""
    from rich.console import Console
    from rich.markup import escape

    from jointdyn.bearing.design import bearing_table, equilibrium
    from jointdyn.core import interrupts

    console = Console(stderr=True)
    # Ctrl-C/SIGTERM as a flag, checked per ε: one line, exit 130/143, never a traceback [T332]
    with _one_line_errors():
        eps_list = _floats(eps, "eps")
        supply = _supply(
            grooves,
            groove_width,
            feed_holes,
            hole_diameter,
            circumferential_groove,
            partial_arc,
            feed_pressure,
            ld,
            (speed, radius, clearance, viscosity),
        )
        tab = bearing_table(model, cavitation, ld, eps_list, grooves=supply)
        op = None
        extra = (speed, radius, clearance)
        if (oil is None) != (inlet_temp is None):
            raise ValueError("--oil and --inlet-temp go together (grade and inlet temperature in °C)")
        if oil is not None and viscosity is not None:
            raise ValueError("give --viscosity or --oil with --inlet-temp, not both")
        if supply is None and (load is not None or any(v is not None for v in (*extra, viscosity, oil))):
            if load is None or any(v is None for v in extra) or (viscosity is None and oil is None):
                raise ValueError(
                    "--load needs --speed, --radius, --clearance and --viscosity or --oil/--inlet-temp (SI)"
                )
            length = ld * 2.0 * radius
            if oil is not None:
                from jointdyn.bearing.thermal import effective_temperature
                from jointdyn.film.viscosity import oil_by_name

                grade = oil_by_name(oil)
                op = effective_temperature(
                    load, speed, radius, length, clearance, grade, inlet_temp, model, cavitation
                )
            else:
                op = equilibrium(load, speed, radius, length, clearance, viscosity, model, cavitation)
        elif supply is not None and load is not None:  # the grooved operating point [T342]
            if any(v is None for v in (*extra, viscosity)) or oil is not None:
                raise ValueError(
                    "--load with a supply feature needs --speed, --radius, --clearance and --viscosity (SI)"
                )
            from jointdyn.bearing.design import _check_model
            from jointdyn.bearing.grooved_table import grooved_equilibrium

            _, cav = _check_model(model, cavitation)
            op = grooved_equilibrium(
                load,
                speed,
                radius,
                ld * 2.0 * radius,
                clearance,
                viscosity,
                cav,
                supply,
                feed_pressure,
            )
        interrupts.check()  # a signal during the operating point: nothing is written
    buf = io.StringIO()
    w = csv.writer(buf)
    w.writerow(list(tab))  # COLUMNS, then the dynamic coefficients where the film has them
    for i in range(len(tab["eps"])):
        w.writerow([f"{tab[c][i]:.6g}" for c in tab])
    if out:
        from jointdyn.io.derived import output_file

        try:  # into a run directory: under its lock, in its manifest; a device is written into [T338]
            with output_file(out, "bearing-table") as tmp:
                tmp.write_text(buf.getvalue(), encoding="utf-8")
        except (ValueError, OSError) as err:
            console.print(f"[red]error:[/red] {escape(str(err))}", soft_wrap=True)
            raise typer.Exit(2) from None
    else:
        sys.stdout.write(buf.getvalue())
    if op is not None:
        units = {
            "eps": "-",
            "attitude_deg": "deg",
            "h_min": "m",
            "friction_torque": "N·m",
            "power_loss": "W",
            "peak_pressure": "Pa",
            "theta_pmax_deg": "deg",
            "theta_end_deg": "deg",
            "flow": "m³/s",
            "side_flow": "m³/s",
            "sommerfeld": "-",
            "fill_min": "-",
            "t_eff": "°C",
            "delta_t": "K",
            "viscosity": "Pa·s",
        }
        from jointdyn.bearing.design import _check_model

        # a Gümbel film is cut where the gap is smallest (θ = π from the maximum film, [T21]): its
        # film end is 0 by construction, not a computed rupture — say so instead of a bare 0
        gumbel = _check_model(model, cavitation)[1] == "gumbel"
        console.print("operating point:")
        for k, v in op.items():
            if isinstance(v, float) and math.isfinite(v):
                unit = "m³/s" if "_flow_" in k else units[k]  # per supply feature
                if k == "theta_end_deg" and gumbel:
                    console.print(
                        f"  {k} = {v:.6g} " + escape(f"[{unit}]") + " (by construction: the gumbel film"
                        " is cut at the minimum film, θ = π; a computed rupture: --model long or finite"
                        " with --cavitation reynolds)",
                        soft_wrap=True,
                    )
                    continue
                console.print(f"  {k} = {v:.6g} " + escape(f"[{unit}]"))


app.command("bearing-table")(bearing_table_cmd)
