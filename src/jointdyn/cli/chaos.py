"""CLI commands for chaos and periodicity: poincare, bifurcation, lyapunov, spectrum, ensemble.

Registered on the application of :mod:`jointdyn.cli.common` when imported."""

from __future__ import annotations

import contextlib
import functools
import json
import math
from pathlib import Path

import typer
from rich.console import Console
from rich.table import Table

from jointdyn.cli.common import _one_line_errors, _progress, app
from jointdyn.io.derived import derived, output_file, status_of
from jointdyn.io.rundir import OutputDir

console = Console()


@contextlib.contextmanager
def _claimed(out: Path, kind: str, spec: dict, overwrite: bool):
    """``out`` claimed like a run directory (lock, atomic files, manifest last, ``--overwrite``
    by the manifest); the manifest says ``complete`` or why not."""
    od = OutputDir(out, kind, spec).claim(overwrite)
    try:
        yield od
    except BaseException as err:
        od.finish(status_of(err), str(err))
        raise
    od.finish("complete")


def _fail(err: Exception):
    typer.echo(f"error: {' '.join(str(err).split())}", err=True)
    raise typer.Exit(2) from None


def _guarded(command):
    """The command under the CLI's one-line errors and signal handling (Ctrl-C/SIGTERM: one
    line, exit 130/143) [T142], like every other jointdyn command."""

    @functools.wraps(command)
    def run(*args, **kwargs):

        with _one_line_errors():
            return command(*args, **kwargs)

    return run


def poincare(
    directory: Path = typer.Argument(..., help="a run directory with results.nc (from `jointdyn run`)"),
    element: str = typer.Option(None, help="journal element mapped (default: the first)"),
    driver: str = typer.Option(None, help="angle driver of the revolution (default: the first)"),
    period: float = typer.Option(None, help="period of the section [s] instead of the driver's 2π/ω"),
    angle: float = typer.Option(0.0, help="phase of the stroboscopic section in the revolution [deg]"),
    transient_revs: int = typer.Option(10, help="revolutions discarded at the start [rev]"),
    plane: str = typer.Option(
        None, help="plane-crossing section instead, VARIABLE=LEVEL (e.g. ey_bushing_over_c=0: upward)"
    ),
    out: Path = typer.Option(None, help="output directory (default: DIR)"),
):
    """Poincaré section (stroboscopic at a phase of the revolution, or a plane crossing) of a
    journal's relative position and velocity in the bushing frame: writes poincare.csv and poincare.png."""
    from jointdyn.studies.poincare import journal_section, phase, plot_sections
    from jointdyn.studies.saved_runs import load_run

    try:
        res = load_run(directory)
        _, w = phase(res, driver, period)
        pl = None
        if plane:
            key, sep, level = plane.partition("=")
            if not sep:
                raise ValueError(f"--plane {plane!r}: expected VARIABLE=LEVEL")
            pl = (key.strip(), float(level), 1)
        T = 2 * math.pi / abs(w)
        sec = journal_section(res, element, driver, math.radians(angle), transient_revs * T, period, plane=pl)
    except (ValueError, KeyError, TypeError) as err:
        _fail(err)
    out = Path(out or directory)
    where = f"plane {plane}" if plane else f"phase {angle:g}°"
    with derived(out, "poincare") as od:  # in a run directory: added to its manifest
        with od.write("poincare.csv") as tmp, open(tmp, "w") as f:
            names = list(sec.values)
            f.write(",".join(["t", *names]) + "\n")
            for i in range(sec.t.size):
                f.write(",".join(f"{v:.10g}" for v in [sec.t[i], *(sec.values[k][i] for k in names)]) + "\n")
        with od.write("poincare.png") as tmp:
            plot_sections({res.system.name: sec}, tmp, f"section at {where}")
    console.print(f"{sec.t.size} section points; wrote {out}/poincare.csv, poincare.png")


def bifurcation(
    spec: Path = typer.Argument(..., help="diagram file (TOML): [base], [bifurcation], optional [dask]"),
    out: Path = typer.Option(Path("out/bifurcation"), help="output directory"),
    workers: int = typer.Option(None, help="local worker processes (default: all cores)"),
    scheduler: str = typer.Option(None, help="Dask scheduler tcp://HOST:PORT (default: local processes)"),
    variable: str = typer.Option("ex_bushing_over_c", help="section variable drawn against the parameter"),
    resume: bool = typer.Option(False, help="keep the finished values of the same diagram in --out/sweep"),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files of a previous diagram in --out"),
):
    """Bifurcation diagram over one parameter, run as a sweep (DIR/sweep: one case file per
    value): writes bifurcation.nc and bifurcation.png."""
    from jointdyn.studies.bifurcation import VARIABLES, load_bifurcation, plot_bifurcation, run_bifurcation

    if variable not in VARIABLES:
        _fail(ValueError(f"--variable {variable!r}: valid: {list(VARIABLES)}"))
    try:
        if resume and overwrite:
            raise ValueError("--resume and --overwrite exclude each other")
        sp = load_bifurcation(spec)
        OutputDir(out, "bifurcation", {}).check(overwrite, resume)
        with _progress("bifurcation") as prog:
            task = prog.add_task(f"{len(sp.values)} values of {sp.parameter}", total=len(sp.values))
            ds = run_bifurcation(
                sp,
                out,
                workers=workers,
                scheduler=scheduler,
                progress=lambda d, n: prog.update(task, completed=d),
                resume=resume,
                overwrite=overwrite,
            )
        with output_file(Path(out) / "bifurcation.png") as tmp:  # added to the diagram's manifest
            plot_bifurcation(ds, tmp, variable)
    except ValueError as err:
        _fail(err)
    failed = int((ds["error"] != "").sum())
    console.print(f"wrote {out}/bifurcation.nc, bifurcation.png ({len(sp.values)} values, {failed} failed)")


def _value(text: str):
    """A --set value: a TOML value (number, bool, "string"), else the bare text."""
    import tomllib

    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text.strip()


def _model_system(model: str, set_: list[str], joint: str, shipped: dict):
    """The System of MODEL: a model file with ``--set`` keys, or a shipped model with variant
    ``joint``, its builder arguments ``shipped`` (None values = defaults) and ``--set`` keys."""
    from jointdyn.studies.runs import model_system

    keys = {}
    for item in set_:
        key, sep, value = item.partition("=")
        if not sep:
            raise ValueError(f"--set {item!r}: expected KEY=VALUE")
        keys[key.strip()] = _value(value)
    if model.endswith(".toml") or Path(model).is_file():
        return model_system(model, keys)[0]
    from jointdyn.models.catalog import shipped as catalog

    m = catalog(model)
    given = {k: v for k, v in shipped.items() if v is not None}
    return model_system(model, {m.variant_arg: joint, **given, **keys})[0]


def lyapunov(
    model: str = typer.Argument(..., help="slider-crank or a model file FILE.toml"),
    joint: str = typer.Option("dry", help="slider-crank piston-pin joint kind"),
    clearance: float = typer.Option(None, help="slider-crank radial clearance [m] (default 0.5e-3)"),
    speed: float = typer.Option(None, help="slider-crank crank speed [rpm] (default 5000)"),
    revs: float = typer.Option(30.0, help="averaging revolutions of the angle driver [rev]"),
    transient_revs: float = typer.Option(10.0, help="revolutions before averaging [rev]"),
    per_rev: int = typer.Option(16, help="renormalisations per revolution [-]"),
    period: float = typer.Option(None, help="revolution period [s] (default: 2π/ω of the first driver)"),
    tau: float = typer.Option(None, help="renormalisation interval [s] (default: period/per-rev)"),
    segments: int = typer.Option(None, help="renormalisation intervals [-] (default: revs·per-rev)"),
    transient: float = typer.Option(None, help="time before averaging [s] (default: transient-revs periods)"),
    time_scale: float = typer.Option(None, help="velocity weight of the norm [s] (default 1/ω, else 1)"),
    d0: float = typer.Option(1e-8, help="renormalised separation [norm units: m, rad]"),
    solver: str = typer.Option("auto", help="integrator"),
    rtol: float = typer.Option(1e-9, help="relative tolerance [-]"),
    atol: float = typer.Option(1e-12, help="absolute tolerance [SI]"),
    discard: int = typer.Option(10, help="first renormalisation intervals left out of the average [-]"),
    seed: int = typer.Option(1, help="seed of the initial deviation direction"),
    set_: list[str] = typer.Option([], "--set", help="model-file key a.b.c=VALUE (repeatable)"),
    out: Path = typer.Option(Path("out/lyapunov"), help="output directory"),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files of a previous result in --out"),
):
    """Largest Lyapunov exponent (Benettin two-trajectory renormalisation): writes summary.json
    (largest_lyapunov_exponent [1/s] and its standard error), lyapunov.csv and lyapunov.png.
    Intervals and averaging time count revolutions of the model's first angle driver (or of
    --period) unless --tau and --segments give them."""
    from jointdyn.errors import ModelError, SimulationError
    from jointdyn.studies import period as per
    from jointdyn.studies.lyapunov import plot_running, system_lyapunov

    try:
        from jointdyn.units import rpm

        shipped = {"clearance": 0.5e-3 if clearance is None and joint != "perfect" else clearance}
        shipped["speed"] = None if speed is None else rpm(speed)
        system = _model_system(model, set_, joint, shipped)
        T: float | None = None
        if period is not None:
            if not (math.isfinite(period) and period > 0):
                raise ValueError(f"--period = {period!r} [s]: must be finite and > 0")
            T, w = period, 2 * math.pi / period
        else:
            try:
                T, w = per.driver_period(system), abs(per.driver(system).omega)
            except ValueError as err:
                if tau is None or segments is None:
                    raise ValueError(f"{err}; or give --tau [s] and --segments [-]") from None
        ts = time_scale if time_scale is not None else (1.0 / w if T is not None else 1.0)
        kw = {
            "tau": tau if tau is not None else T / per_rev,
            "n_segments": segments if segments is not None else int(round(revs * per_rev)),
            "transient": transient if transient is not None else (transient_revs * T if T else 0.0),
        }
        OutputDir(out, "lyapunov", {}).check(overwrite)  # inputs first, then the output directory
        res = system_lyapunov(
            system,
            d0=d0,
            time_scale=ts,
            solver=solver,
            rtol=rtol,
            atol=atol,
            discard_segments=discard,
            seed=seed,
            **kw,
        )
    except (ModelError, ValueError, SimulationError, FloatingPointError) as err:
        _fail(err)
    summ = {"model": system.name, **res.summary()}
    with _claimed(out, "lyapunov", {"model": model, "set": list(set_)}, overwrite) as od:
        with od.write("summary.json") as tmp:
            tmp.write_text(json.dumps(summ, indent=2) + "\n", encoding="utf-8")
        with od.write("lyapunov.csv") as tmp, open(tmp, "w") as f:
            f.write("t,segment_rate,running_estimate\n")
            for row in zip(res.times, res.segment_rates, res.running):
                f.write(",".join(f"{v:.10g}" for v in row) + "\n")
        with od.write("lyapunov.png") as tmp:
            plot_running(res, tmp, f"{system.name}: largest Lyapunov exponent")
    console.print(
        f"{system.name}: λ₁ = {res.exponent:.6g} ± {res.stderr:.2g} 1/s (1 s.e., {res.batches} batches); "
        f"wrote {out}/summary.json, lyapunov.csv, lyapunov.png"
    )


def spectrum(
    directory: Path = typer.Argument(..., help="a run directory with results.nc (from `jointdyn run`)"),
    transient_revs: int = typer.Option(2, help="revolutions discarded at the start [rev]"),
    max_harmonic: float = typer.Option(40.0, help="highest harmonic drawn [-]"),
    driver: str = typer.Option(None, help="angle driver: its moment and revolution (default: the first)"),
    element: str = typer.Option(None, help="journal element whose force is analysed (default: the first)"),
    body: str = typer.Option(None, help="also the x acceleration of this body (e.g. slider)"),
    out: Path = typer.Option(None, help="output directory (default: DIR)"),
):
    """Amplitude spectra of an angle driver's moment, a journal element's force and optionally
    a body's x acceleration in harmonics of the driver's speed: writes spectrum.csv and
    spectrum.png."""
    from jointdyn.studies.saved_runs import load_run
    from jointdyn.studies.spectra import UNITS, plot_spectra, run_spectra

    try:
        if not (math.isfinite(max_harmonic) and max_harmonic > 0):  # before any work
            raise ValueError(f"--max-harmonic = {max_harmonic!r} [-]: must be finite and > 0")
        res = load_run(directory)
        sp = run_spectra(res, transient_revs, driver, body, "" if element is None else element)
    except (ValueError, KeyError) as err:
        _fail(err)
    out = Path(out or directory)
    names = [k for k in UNITS if k in sp]
    with derived(out, "spectrum") as od:  # in a run directory: added to its manifest
        with od.write("spectrum.csv") as tmp, open(tmp, "w") as f:
            f.write(",".join(["harmonic", *names]) + "\n")
            for i in range(sp["harmonic"].size):
                f.write(",".join(f"{v:.10g}" for v in [sp["harmonic"][i], *(sp[k][i] for k in names)]) + "\n")
        with od.write("spectrum.png") as tmp:
            plot_spectra(sp, tmp, max_harmonic, res.system.name)
    console.print(f"{sp['revs']} revolutions; wrote {out}/spectrum.csv, spectrum.png")


def ensemble(
    model: str = typer.Argument(
        "slider-crank", help="a shipped model (slider-crank) or a model file FILE.toml"
    ),
    joint: str = typer.Option("dry", help="shipped model's variant (slider-crank: piston-pin joint kind)"),
    set_: list[str] = typer.Option([], "--set", help="model-file key a.b.c=VALUE (repeatable)"),
    rtols: str = typer.Option("1e-7,1e-8,1e-9", help="comma-separated relative tolerances [-]"),
    replicas: int = typer.Option(1, help="runs per tolerance (replica r > 0: perturbed initial velocities)"),
    revs: int = typer.Option(60, help="revolutions of the first angle driver per run [rev]"),
    transient_revs: int = typer.Option(10, help="revolutions discarded [rev]"),
    samples_per_rev: int = typer.Option(720, help="output samples per revolution [-]"),
    workers: int = typer.Option(None, help="local worker processes (default: all cores)"),
    out: Path = typer.Option(Path("out/ensemble"), help="output directory"),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files of a previous ensemble in --out"),
):
    """Distributions of per-revolution quantities (median, 5–95 %) with a convergence check
    across tolerances: writes ensemble.json."""
    from jointdyn.studies.ensemble import ensemble as run_ensemble
    from jointdyn.studies.ensemble import ensemble_table

    try:
        OutputDir(out, "ensemble", {}).check(overwrite)
        kw: dict = {}
        for item in set_:
            key, sep, value = item.partition("=")
            if not sep:
                raise ValueError(f"--set {item!r}: expected KEY=VALUE")
            kw[key.strip()] = _value(value)
        if model.endswith(".toml"):
            name = model
        else:
            from jointdyn.models.catalog import shipped

            kw, name = {shipped(model).variant_arg: joint, **kw}, f"{model} ({joint})"
        r = run_ensemble(
            model,
            kw,
            tuple(float(v) for v in rtols.split(",")),
            replicas,
            revs,
            transient_revs,
            samples_per_rev,
            workers=workers,
        )
    except ValueError as err:  # SimulationError, Interrupted: the CLI wrapper (exit 1, 130/143)
        _fail(err)
    spec = {"model": model, "joint": joint, "set": list(set_), "rtols": rtols, "replicas": replicas}
    spec |= {"revs": revs, "transient": transient_revs, "samples_per_rev": samples_per_rev}
    with _claimed(out, "ensemble", spec, overwrite) as od, od.write("ensemble.json") as tmp:
        tmp.write_text(json.dumps(r, indent=2) + "\n", encoding="utf-8")
    tab = Table(title=f"{name}, revolutions {transient_revs}–{revs}, rtol {rtols}")
    for c in ("quantity", "unit", "median", "5 %", "95 %", "n", "shift", "converged"):
        tab.add_column(c)
    for row in ensemble_table(r):
        tab.add_row(
            row["quantity"],
            row["unit"],
            f"{row['median']:.4g}",
            f"{row['p5']:.4g}",
            f"{row['p95']:.4g}",
            str(row["n"]),
            f"{row['shift']:.3f}",
            str(row["converged"]),
        )
    console.print(tab)
    console.print(f"wrote {out}/ensemble.json")


for _command in (poincare, bifurcation, lyapunov, spectrum, ensemble):
    app.command()(_guarded(_command))
