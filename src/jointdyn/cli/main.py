"""The run commands: ``run``, ``reproduce`` and ``sweep``."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.markup import escape
from rich.table import Table

from jointdyn.cli.common import _one_line_errors, _progress, app, console
from jointdyn.models.catalog import DEFAULT, SHIPPED
from jointdyn.studies.memory import check_disk, check_memory

#: the short options of ``run`` are those of the default shipped model
_M = SHIPPED[DEFAULT]
_RA = _M.run_args()


def _arg_help(name: str, text: str) -> str:
    """Help of a shipped model's builder argument: its unit and default from the builder."""
    default, unit = _M.numeric_args()[name]
    return f"{text} [{unit}] (default {default:.6g})"


_JOINT_HELP = "piston-pin joint kind: " + ", ".join(_M.variants())


def _solver_help() -> str:
    from jointdyn.integrators import SOLVERS

    return "integrator: auto (radau5 for a lubricated joint, else dopri5), " + ", ".join(SOLVERS)


#: CLI spelling of the shipped model's builder arguments and run settings
OPTION_NAMES = {k: "--" + k.replace("_", "-") for k in (*_M.arguments(), "shear", "bushing")}
OPTION_NAMES |= {k: "--" + k.replace("_", "-") for k in ("revs", "samples_per_rev", "rtol", "atol")}


@app.command()
def run(
    model: str = typer.Argument(..., help=f"shipped model ({', '.join(SHIPPED)}) or a model file FILE.toml"),
    joint: str = typer.Option(None, help=_JOINT_HELP + " (default perfect)"),
    revs: float = typer.Option(None, help=f"crank revolutions to simulate [rev] (default {_RA['revs']:g})"),
    samples_per_rev: int = typer.Option(
        None, help=f"output samples per crank revolution [-] (default {_RA['samples_per_rev']})"
    ),
    out: Path = typer.Option(Path("out/run"), help="output directory (must be empty or a previous run's)"),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files from a previous run in --out"),
    solver: str = typer.Option(None, help=_solver_help()),
    rtol: float = typer.Option(None, help=f"relative tolerance [-] (default {_RA['rtol']:g})"),
    atol: float = typer.Option(None, help=f"absolute tolerance [SI of each state] (default {_RA['atol']:g})"),
    clearance: float = typer.Option(
        None, help=_arg_help("clearance", "radial clearance c of an imperfect joint")
    ),
    viscosity: float = typer.Option(None, help=_arg_help("viscosity", "lubricant dynamic viscosity")),
    speed: float = typer.Option(None, help="crank speed, CCW [rpm] (default 5000; the drive's omega)"),
    length: float = typer.Option(None, help=_arg_help("length", "bearing length")),
    friction: float = typer.Option(None, help="Ambrósio friction coefficient in contact [-] (default 0)"),
    contact: bool = typer.Option(False, help="lubricated joint: add Lankarani–Nikravesh asperity contact"),
    shear: bool = typer.Option(
        None,
        "--shear/--no-shear",
        help="lubricated joint: apply the film's shear torques (default: off, as the paper)",
    ),
    bushing: str = typer.Option(
        None, help="body carrying the bearing hole: rod (default, as the paper) or slider"
    ),
    asperity_height: float = typer.Option(None, help="with --contact: contact starts at h_min < this [m]"),
    restitution: float = typer.Option(
        None, help=_arg_help("restitution", "dry joint: coefficient of restitution")
    ),
    set_: list[str] = typer.Option(
        [], "--set", help="model-file key a.b.c=VALUE, for a model file or a shipped model (repeatable)"
    ),
):
    """Simulate a shipped mechanism or a model file; write results.nc, timeseries.csv,
    summary.json, figures and manifest.json."""
    from jointdyn.io.rundir import OutputDir

    sc_opts = {
        "joint": joint,
        "revs": revs,
        "samples_per_rev": samples_per_rev,
        "solver": solver,
        "rtol": rtol,
        "atol": atol,
        "clearance": clearance,
        "viscosity": viscosity,
        "speed": speed,
        "length": length,
        "friction": friction,
        "asperity_height": asperity_height,
        "restitution": restitution,
        "shear": shear,
        "bushing": bushing,
    }
    given = {k: v for k, v in sc_opts.items() if v is not None} | ({"contact": True} if contact else {})
    is_file = model.endswith(".toml") or Path(model).is_file()
    od = None
    with _one_line_errors(out):
        if is_file:
            if given:
                names = ", ".join(OPTION_NAMES.get(k, "--" + k) for k in given)
                raise ValueError(f"{names}: apply to a shipped model; for a model file use --set a.b=VALUE")
            from jointdyn.studies.runs import prepare_model_file, run_model_file

            prepared = prepare_model_file(model, set_)
            check_memory(prepared[1], prepared[2].n_out, "simulation.n_out")
            _large_write(check_disk(prepared[1], prepared[2].n_out, out, "simulation.n_out"))
            od = OutputDir(out, "run", prepared[3]).claim(overwrite)
            with _progress("run") as prog:
                task = prog.add_task(prepared[0].name, total=1.0)
                res = run_model_file(
                    model, od, set_, prepared=prepared, progress=lambda f: prog.update(task, completed=f)
                )
            files = ", ".join([*od.files, "manifest.json"])
            console.print(
                f"{escape(res.system.name)}: {len(res.t)} samples, {res.stats['rhs_evaluations']} RHS "
                f"evaluations, {res.wall_time:.3f} s; wrote {escape(str(out))}/: {files}"
            )
            return
        from jointdyn.models.catalog import shipped

        shipped(model)  # one line for an unknown name
        if "speed" in given:  # rpm only at this edge, rad/s inside
            from jointdyn.core.checks import check
            from jointdyn.units import rpm

            check("--speed", given["speed"], "rpm", "!= 0")
            given["speed"] = rpm(given["speed"])
        _run_shipped(model, given, set_, out, overwrite)


def _run_shipped(name: str, given: dict, set_: list[str], out: Path, overwrite: bool) -> None:
    from jointdyn.integrators import SOLVERS
    from jointdyn.io.rundir import OutputDir
    from jointdyn.models.catalog import shipped
    from jointdyn.studies.runs import run_shipped

    m = shipped(name)
    variant = given.pop(m.variant_arg, m.default_variant)
    ra = m.run_args()
    run_kw = {k: given.pop(k) for k in ("solver", "rtol", "atol", "samples_per_rev") if k in given}
    revs = given.pop("revs", ra["revs"])
    model_kw = m.model_kw(variant, given, OPTION_NAMES)
    m.check_run(
        revs, run_kw.get("samples_per_rev", ra["samples_per_rev"]), **_tols(run_kw), names=OPTION_NAMES
    )
    if run_kw.get("solver", "auto") not in ("auto", *SOLVERS):
        raise ValueError(f"--solver {run_kw['solver']!r}: unknown; valid: auto, {', '.join(SOLVERS)}")
    model, cfg = m.setup(variant, revs, model_kw, **run_kw)
    if set_:  # the keys checked before the directory is claimed
        from jointdyn.io.modelfile import with_keys

        with_keys(model, cfg, list(set_), f"{name} ({variant})", assemble=False)
    check_memory(model, cfg.n_out, "--revs × --samples-per-rev")
    _large_write(check_disk(model, cfg.n_out, out, "--revs × --samples-per-rev"))
    spec = {"model": name, m.variant_arg: variant, "revs": revs, **run_kw} | {
        k: given[k] for k in given if k not in run_kw
    }
    spec |= {"set": list(set_)} if set_ else {}
    od = OutputDir(out, "run", spec).claim(overwrite)
    with _progress("run") as prog:
        task = prog.add_task(f"{name} ({variant})", total=1.0)
        _, _, summary = run_shipped(
            name,
            variant,
            revs,
            out=od,
            progress=lambda f: prog.update(task, completed=f),
            model_kw=model_kw,
            keys=set_,
            **run_kw,
        )
    tab = Table(title=f"{m.title(variant)} ({revs:g} rev)")
    tab.add_column("quantity")
    tab.add_column("value", justify="right")
    for k, v in summary.items():
        if not isinstance(v, dict):
            tab.add_row(k, f"{v:.6g}" if isinstance(v, float) else escape(str(v)))
    console.print(tab)
    console.print(f"wrote {escape(str(out))}/: {', '.join(od.files)}, manifest.json")


def _large_write(need: float) -> None:
    """Say before a run that its files will be large (≥ 1 GiB): their writing takes a while."""
    if need >= 2**30:
        typer.echo(f"the results will take up to ≈ {need / 2**30:.3g} GiB on disk", err=True)


def _tols(run_kw: dict) -> dict:
    return {k: run_kw[k] for k in ("rtol", "atol") if k in run_kw}


@app.command()
def reproduce(
    paper: str = typer.Argument(..., help="which paper: alshaer2005"),
    out: Path = typer.Option(Path("out/alshaer2005"), help="output directory"),
    quick: bool = typer.Option(False, help="1 revolution instead of 4 (CI smoke run)"),
    beyond: bool = typer.Option(True, help="also run the beyond-the-paper cases"),
    overwrite: bool = typer.Option(False, help="replace the files of a previous reproduction in --out"),
):
    """Run the paper's comparison (perfect, dry, Ott, π-film) and write figures + report.html;
    the full run also reports the dry case as a distribution (ensemble_dry.md)."""
    from jointdyn.io.rundir import OutputDir
    from jointdyn.studies.reproduce import BEYOND_CASES, PAPER_CASES, reproduce_alshaer2005, summary_markdown

    with _one_line_errors():
        if paper != "alshaer2005":
            raise ValueError(f"PAPER {paper!r}: unknown; valid: alshaer2005")
        OutputDir(out, "reproduce", {}).check(overwrite)
        cases = PAPER_CASES + (BEYOND_CASES if beyond else ())
        with _progress("reproduce") as prog:
            names = [c.name for c in cases] + ([] if quick else ["dry ensemble"])
            tasks = {n: prog.add_task(n, total=1.0) for n in names}
            runs = reproduce_alshaer2005(
                out,
                quick=quick,
                beyond=beyond,
                progress=lambda name, f: prog.update(tasks[name], completed=f),
                overwrite=overwrite,
            )
    console.print(escape(summary_markdown(runs)))
    if (Path(out) / "ensemble_dry.md").exists():  # the dry case as a distribution (full runs)
        console.print(escape((Path(out) / "ensemble_dry.md").read_text(encoding="utf-8")))
    console.print(f"wrote {escape(str(out))}/report.html, summary.csv, <case>.csv and the figures")


@app.command()
def sweep(
    spec: Path = typer.Argument(
        ..., help="sweep file (TOML): [base], [grid]/[zip]/[sample], [output], [dask]"
    ),
    out: Path = typer.Option(
        Path("out/sweep"), help="output directory (empty, or this sweep's with --resume)"
    ),
    resume: bool = typer.Option(
        False, help="keep finished cases of the same sweep, run only the missing ones"
    ),
    overwrite: bool = typer.Option(False, help="replace jointdyn's files from a previous sweep in --out"),
    scheduler: str = typer.Option(
        None, help="Dask scheduler address tcp://HOST:PORT (default: local processes)"
    ),
    workers: int = typer.Option(None, help="local worker processes [-] (default: all cores)"),
    case_timeout: float = typer.Option(
        None, help="a case whose integration runs longer is recorded as failed [s] (default: no limit)"
    ),
    worker_timeout: float = typer.Option(
        60.0, help="Dask: wait this long for a worker, or for a silent scheduler, then stop [s]"
    ),
):
    """Run a parameter study; writes DIR/cases/*.json per case, DIR/sweep.nc and DIR/manifest.json."""
    from jointdyn.studies.sweep import load_sweep, run_sweep

    with _one_line_errors(out):
        if resume and overwrite:
            raise ValueError("--resume and --overwrite exclude each other")
        if workers is not None and workers < 1:
            raise ValueError(f"--workers = {workers} [-]: must be an integer >= 1")
        sp = load_sweep(spec)
        n = len(sp.cases())
        with _progress("sweep") as prog:
            task = prog.add_task(f"{n} cases", total=n)
            ds = run_sweep(
                sp,
                out,
                resume=resume,
                scheduler=scheduler,
                workers=workers,
                overwrite=overwrite,
                progress=lambda done, total: prog.update(task, completed=done),
                case_timeout=case_timeout,
                worker_timeout=worker_timeout,
                notice=lambda line: typer.echo(line, err=True),
            )
    failed = int((ds["error"] != "").sum())
    console.print(f"wrote {escape(str(out))}/sweep.nc ({n} cases, {failed} failed)")
