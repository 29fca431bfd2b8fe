"""A hostile-user campaign in seven families: each case runs as the console script would (or as a
Python snippet, for the API family) and is classified.

    PYTHONPATH=$PWD/src python -m benchmarks.hostile_campaign [--timeout 120] [--family NAME]

Outcomes (the issue's table): ``clear`` (refused: exit ≠ 0, one stderr line naming the expected
parameter), ``fine`` (success where success is right, every check passed), ``misleading``
(refused in several lines, without naming the parameter, or where success was right),
``traceback`` (a Python traceback, "internal error" or a numba ``SystemError``), ``hang`` (no end
within the timeout), ``silent wrong`` (exit 0 where a refusal is right, or a check failed: a
file written, changed or deleted outside what the case may write, a manifest whose files do not
match their recorded size and SHA-256, a lock or temporary left behind, a number that should be
finite and in range is not). Silent wrong *numbers* of a successful run cannot be told by a
script beyond these checks: the tests named in docs/validation.md check them.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import math
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from collections import Counter
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
EX = ROOT / "examples"
DRY = EX / "slider_crank_dry.toml"
SWEEP = '[base]\nfile = "{model}"\nrevs = 0.05\n[grid]\n{grid}\n'
FRICTION = '{{ law = "coulomb", coefficient = {mu}, regularization_velocity = 1e-4 }}'
FAMILIES = ("model files", "bearing physics", "long runs", "sweeps", "python api", "files", "chaos")
OUTCOMES = ("clear", "misleading", "traceback", "hang", "silent wrong", "fine")
STATE_COLS = "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance"
STATE = "0.5,0,0,0,500,0,0.01,0.04,0.01,5e-5"


@dataclass
class Case:
    """``argv`` of the CLI (or ``py``: a Python snippet); ``ok``: success is right; ``word``: the
    refusal names it; ``owns``: paths (relative to the campaign directory) the case may change;
    ``check``: a function of the campaign directory returning a complaint or ""; ``sig``:
    (CPU seconds, signal) sent to the running command once it has used that much CPU (then
    exit 128+signal and one line is clear)."""

    family: str
    name: str
    argv: list[str] = field(default_factory=list)
    ok: bool = False
    word: str = ""
    owns: tuple[str, ...] = ()
    check: object = None
    py: str = ""
    sig: tuple[float, int] | None = None


def _jd(*a) -> list[str]:
    return [str(x) for x in a]


def _finite_csv(rel: str, lo: float = -math.inf, hi: float = math.inf, skip: tuple[str, ...] = ()):
    """Every number of CSV ``rel`` finite and in [lo, hi], except columns ``skip`` (documented
    non-finite values, e.g. critical_mass = inf: stable for any mass)."""

    def check(d: Path) -> str:
        p = d / rel
        if not p.is_file():
            return f"{rel} missing"
        head, *rows = p.read_text().splitlines()
        cols = [k for k, h in enumerate(head.split(",")) if h not in skip]
        vals = [float(r.split(",")[k]) for r in rows for k in cols]
        if not vals:
            return f"{rel} has no rows"
        bad = [v for v in vals if not (math.isfinite(v) and lo <= v <= hi)]
        return f"{rel}: {len(bad)} values not finite in [{lo}, {hi}]" if bad else ""

    return check


def _finite_summary(rel: str):
    def check(d: Path) -> str:
        p = d / rel / "summary.json"
        if not p.is_file():
            return f"{rel}/summary.json missing"
        s = json.loads(p.read_text())
        bad = [k for k, v in s.get("metrics", {}).items() if isinstance(v, float) and not math.isfinite(v)]
        return f"non-finite metrics {bad}" if bad else ""

    return check


def _listed(rel: str, name: str):
    def check(d: Path) -> str:
        m = json.loads((d / rel / "manifest.json").read_text())
        return "" if name in m.get("files", {}) else f"{name} not in {rel}/manifest.json"

    return check


def _setup(d: Path, base: Path) -> list[Case]:
    """Write the inputs into ``d`` (``base``: a complete 2-revolution dry run) and list the cases."""
    (d / "sibling").mkdir()
    (d / "sibling" / "keep.txt").write_text("not jointdyn's\n")
    slash = d / "slash.toml"
    slash.write_text(DRY.read_text().replace("[elements.piston_pin]", '[elements."pin/x"]'))
    inline = '"elements.piston_pin.friction" = [' + ", ".join(FRICTION.format(mu=m) for m in (0.1, 0.2)) + "]"
    sweeps = {
        "inline": SWEEP.format(model=DRY, grid=inline),
        "slash": SWEEP.format(model=slash, grid='"simulation.rtol" = [1e-7, 1e-8]'),
        "nan": SWEEP.format(model=DRY, grid='"simulation.rtol" = [1e-7, nan]'),
        "repeat": SWEEP.format(model=DRY, grid='"simulation.rtol" = [1e-7, 1e-7]'),
        "unknown": SWEEP.format(model=DRY, grid='"bodies.crank.colour" = [1.0, 2.0]'),
        "negative": SWEEP.format(model=DRY, grid='"bodies.crank.mass" = [0.3, -1.0]'),
        "empty": SWEEP.format(model=DRY, grid='"simulation.rtol" = []'),
    }
    for k, text in sweeps.items():
        (d / f"sweep_{k}.toml").write_text(text)
    os.mkfifo(d / "fifo.toml")
    (d / "empty.toml").write_text("")
    (d / "binary.toml").write_bytes(b"\xff\xfe\x00garbage\x80" * 50)
    (d / "nanmass.toml").write_text(DRY.read_text().replace("mass = 0.3", "mass = nan", 1))
    (d / "link_zero.toml").symlink_to("/dev/zero")
    (d / "states.csv").write_text(f"{STATE_COLS}\n{STATE}\n")
    huge = "1e300,1e300,0,1e300,1e300,0,0.01,0.04,0.01,5e-5"
    (d / "states_huge.csv").write_text(f"{STATE_COLS}\n{STATE}\n{huge}\n")
    (d / "states_eps.csv").write_text(f"{STATE_COLS}\n1.5,0,0,0,500,0,0.01,0.04,0.01,5e-5\n")
    (d / "states_short.csv").write_text("xi,xi_dot\n0.5,0\n")
    (d / "notarun").mkdir()
    (d / "notarun" / "x.txt").write_text("x")
    for k in ("trunc", "plot", "poin", "spec", "trav", "lnk", "anim"):
        shutil.copytree(base, d / f"run_{k}")
    nc = d / "run_trunc" / "results.nc"
    nc.write_bytes(nc.read_bytes()[:4000])
    m = json.loads((d / "run_trav" / "manifest.json").read_text())
    m["files"]["../sibling/keep.txt"] = {"bytes": 15, "sha256": "0" * 64}
    (d / "run_trav" / "manifest.json").write_text(json.dumps(m))
    (d / "run_lnk" / "timeseries.csv").unlink()
    (d / "run_lnk" / "timeseries.csv").symlink_to(d / "sibling" / "keep.txt")
    (d / "lockdir").mkdir()
    (d / "lockdir" / ".jointdyn.lock").symlink_to(d / "sibling" / "keep.txt")
    (d / "outlink").symlink_to(d / "sibling")
    (d / "afile").write_text("a file, not a directory\n")

    def o(name: str) -> list[str]:
        return ["--out", str(d / name)]

    sc = ["run", "slider-crank", "--revs", "0.05"]
    bt = ["bearing-table", "--ld", "1"]
    pt = ["--speed", "10", "--radius", "0.01", "--viscosity", "0.01"]
    strib = ["stribeck", "--radius", "0.02", "--length", "0.02", "--clearance", "2e-5", "--viscosity", "0.05"]
    py_sc = "import jointdyn as j\n"
    cases = [
        # -- model files
        Case("model files", "FIFO as model file", ["run", d / "fifo.toml", *o("r1")], word="FIFO"),
        Case("model files", "first_step = -1", ["run", DRY, "--set", "simulation.first_step=-1", *o("r2")],
             word="first_step"),
        Case("model files", "rtol = 1e-300", ["run", DRY, "--set", "simulation.rtol=1e-300", *o("r3")],
             word="rtol"),
        Case("model files", "empty model file", ["run", d / "empty.toml", *o("r4")], word="empty.toml"),
        Case("model files", "binary model file", ["run", d / "binary.toml", *o("r5")], word="binary.toml"),
        Case("model files", "mass = nan", ["run", d / "nanmass.toml", *o("r6")], word="mass"),
        Case("model files", "--set mass=-1", ["run", DRY, "--set", "bodies.crank.mass=-1", *o("r7")],
             word="mass"),
        Case("model files", "--set unknown key", ["run", DRY, "--set", "bodies.crank.colour=1", *o("r8")],
             word="colour"),
        Case("model files", "model file links to /dev/zero", ["run", d / "link_zero.toml", *o("r9")],
             word="link_zero"),
        Case("model files", "directory as model file", ["run", d / "sibling", *o("r10")], word="sibling"),
        Case("model files", "example model file, 0.05 rev", ["run", DRY, "--set", "simulation.t_end=0.0006",
             *o("r11")],
             ok=True, owns=("r11",), check=_finite_summary("r11")),
        # -- bearing physics
        Case("bearing physics", "c > R", [*bt, "--load", "100", *pt[:2], "--radius", "0.01", "--clearance",
             "0.02", "--viscosity", "0.01"], word="clearance"),
        Case("bearing physics", "10⁶ eccentricities", [*bt, "--eps", "0.1:0.9:1000000"], word="eps"),
        Case("bearing physics", "asperity height 0.000499", [*sc, "--joint", "alshaer2005", "--contact",
             "--asperity-height", "0.000499", *o("b1")], word="asperity"),
        Case("bearing physics", "eps = 1", [*bt, "--eps", "1.0"], word="eps"),
        Case("bearing physics", "L/D = 0", ["bearing-table", "--ld", "0"], word="ld"),
        Case("bearing physics", "L/D = nan", ["bearing-table", "--ld", "nan"], word="ld"),
        Case("bearing physics", "film-force ξ̇ = ω = 1e300", ["film-force", d / "states_huge.csv"],
             word="row"),
        Case("bearing physics", "film-force ξ = 1.5", ["film-force", d / "states_eps.csv"], word="xi"),
        Case("bearing physics", "film-force missing columns", ["film-force", d / "states_short.csv"],
             word="column"),
        Case("bearing physics", "stribeck load -1", [*strib, "--load", "-1"], word="load"),
        Case("bearing physics", "run --viscosity -1", [*sc, "--joint", "alshaer2005", "--viscosity", "-1",
             *o("b2")], word="viscosity"),
        Case("bearing physics", "run --clearance 0", [*sc, "--joint", "dry", "--clearance", "0", *o("b3")],
             word="clearance"),
        Case("bearing physics", "bearing-table ε = 0.5 into a file", [*bt, "--eps", "0.5,0.8", *o("bt.csv")],
             ok=True, owns=("bt.csv",), check=_finite_csv("bt.csv", skip=("critical_mass", "whirl_ratio"))),
        Case("bearing physics", "film-force one state", ["film-force", d / "states.csv", *o("ff.csv")],
             ok=True, owns=("ff.csv",), check=_finite_csv("ff.csv")),
        # -- long runs, resources, signals
        Case("long runs", "animate --frames 1e8", ["animate", d / "run_anim", "--frames", "100000000"],
             word="frames"),
        Case("long runs", "samples-per-rev 5e6 × 100 rev", [*sc[:2], "--samples-per-rev", "5000000",
             "--revs", "100", *o("l1")], word="samples"),
        Case("long runs", "--revs -1", [*sc[:2], "--revs", "-1", *o("l2")], word="revs"),
        Case("long runs", "--revs nan", [*sc[:2], "--revs", "nan", *o("l3")], word="revs"),
        Case("long runs", "--revs inf", [*sc[:2], "--revs", "inf", *o("l4")], word="revs"),
        Case("long runs", "--samples-per-rev 0", [*sc, "--samples-per-rev", "0", *o("l5")], word="samples"),
        Case("long runs", "--revs 1e9 (time, not memory)", [*sc[:2], "--revs", "1e9", *o("l6")], word="revs"),
        Case("long runs", "SIGINT 8 CPU-s into a 200-rev run", [*sc[:2], "--joint", "dry", "--revs", "200",
             *o("l7")], sig=(8.0, signal.SIGINT), owns=("l7",)),
        Case("long runs", "SIGTERM 8 CPU-s into bearing-table 5000 ε", [*bt, "--eps", "0.1:0.95:5000",
             *o("l8.csv")], sig=(8.0, signal.SIGTERM), owns=("l8.csv",)),
        Case("long runs", "SIGINT 8 CPU-s into stribeck", [*strib, "--load", "100", "--speeds", "1:10000:400",
             *o("l9.csv")], sig=(8.0, signal.SIGINT), owns=("l9.csv", "l9.png")),
        # -- sweeps and Dask
        Case("sweeps", "inline-table grid value", ["sweep", d / "sweep_inline.toml", *o("s1")], ok=True,
             owns=("s1",)),
        Case("sweeps", "element named pin/x", ["sweep", d / "sweep_slash.toml", *o("s2")], word="pin/x"),
        Case("sweeps", "nan grid value", ["sweep", d / "sweep_nan.toml", *o("s3")], word="rtol"),
        Case("sweeps", "repeated grid value", ["sweep", d / "sweep_repeat.toml", *o("s4")], word="rtol"),
        Case("sweeps", "unknown parameter", ["sweep", d / "sweep_unknown.toml", *o("s5")], word="colour"),
        Case("sweeps", "negative mass in the grid", ["sweep", d / "sweep_negative.toml", *o("s6")],
             word="mass"),
        Case("sweeps", "empty grid list", ["sweep", d / "sweep_empty.toml", *o("s7")], word="rtol"),
        Case("sweeps", "missing spec file", ["sweep", d / "nope.toml", *o("s8")], word="nope.toml"),
        Case("sweeps", "--workers 0", ["sweep", d / "sweep_inline.toml", "--workers", "0", *o("s9")],
             word="workers"),
        Case("sweeps", "scheduler nobody listens on", ["sweep", d / "sweep_inline.toml", "--scheduler",
             "tcp://127.0.0.1:9", *o("s10")], word="127.0.0.1", owns=("s10",)),
        Case("sweeps", "scheduler not an address", ["sweep", d / "sweep_inline.toml", "--scheduler",
             "banana", *o("s11")], word="scheduler"),
        # -- Python API
        Case("python api", "SimConfig(t_end=-1)", py=py_sc + "j.SimConfig(t_end=-1.0)", word="t_end"),
        Case("python api", "SimConfig(rtol=nan)", py=py_sc + "j.SimConfig(t_end=1.0, rtol=float('nan'))",
             word="rtol"),
        Case("python api", "SimConfig(n_out=1)", py=py_sc + "j.SimConfig(t_end=1.0, n_out=1)", word="n_out"),
        Case("python api", "slider_crank('bogus')", py=py_sc + "j.slider_crank('bogus')", word="bogus"),
        Case("python api", "Model.add_body(mass=-1)", py=py_sc + "m = j.Model('m')\n"
             "m.add_body('b', mass=-1.0, inertia=1.0)", word="mass"),
        Case("python api", "load a truncated results.nc", py=py_sc + f"j.load({str(nc)!r})",
             word="results.nc"),
        Case("python api", "load a missing file", py=py_sc + f"j.load({str(d / 'none.nc')!r})",
             word="none.nc"),
        Case("python api", "element of an unknown name", word="nope",
             py=py_sc + f"r = j.load({str(base / 'results.nc')!r})\nr.element('nope', 'x')"),
        Case("python api", "simulate an uncompiled model", py=py_sc + "j.simulate(j.slider_crank('dry'), "
             "j.SimConfig(t_end=1e-3))", word="compile"),
        Case("python api", "simulate t_end = 1 ms", ok=True, py=py_sc + "import math\n"
             "r = j.simulate(j.slider_crank('dry').compile(), j.SimConfig(t_end=1e-3, n_out=11))\n"
             "assert all(map(math.isfinite, r.q.ravel())), 'non-finite q'"),
        # -- security and files
        Case("files", "bearing-table --out missing dir", [*bt, "--eps", "0.5", *o("no/t.csv")], word="no"),
        Case("files", "bearing-table --out /dev/null", [*bt, "--eps", "0.5", "--out", "/dev/null"], ok=True),
        Case("files", "--out a link to another directory", [*sc, *o("outlink")], word="outlink"),
        Case("files", "--out a non-empty foreign directory", [*sc, *o("sibling")], word="sibling"),
        Case("files", "--out a regular file", [*sc, *o("afile")], word="afile"),
        Case("files", "lock file links outside", [*sc, *o("lockdir")], word="lock"),
        Case("files", "--overwrite, listed file is a link outside", [*sc, "--joint", "dry", *o("run_lnk"),
             "--overwrite"], word="link", owns=("run_lnk",)),
        Case("files", "--overwrite, manifest lists ../sibling/keep.txt", [*sc, "--joint", "dry",
             *o("run_trav"), "--overwrite"], ok=True, owns=("run_trav",)),
        Case("files", "plot --out into its run directory", ["plot", d / "run_plot", "--out",
             d / "run_plot" / "mine.png"], ok=True, owns=("run_plot",),
             check=_listed("run_plot", "mine.png")),
        Case("files", "bearing-table --out into a run directory", [*bt, "--eps", "0.5", "--out",
             d / "run_plot" / "bt.csv"], ok=True, owns=("run_plot",), check=_listed("run_plot", "bt.csv")),
        Case("files", "stribeck --out into a run directory", [*strib, "--load", "100", "--speeds", "10,100",
             "--out", d / "run_plot" / "st.csv"], ok=True, owns=("run_plot",),
             check=_listed("run_plot", "st.png")),
        Case("files", "film-force --out into a run directory", ["film-force", d / "states.csv", "--out",
             d / "run_plot" / "ff.csv"], ok=True, owns=("run_plot",), check=_listed("run_plot", "ff.csv")),
        Case("files", "plot --out a FIFO", ["plot", d / "run_plot", "--out", d / "fifo.toml"], word="FIFO"),
        # -- chaos commands
        Case("chaos", "ensemble --rtols 1e-7,1e-7", ["ensemble", "slider-crank", "--rtols", "1e-7,1e-7",
             *o("c1")], word="rtols"),
        Case("chaos", "Lyapunov of the zero-DOF slider-crank", ["lyapunov", "slider-crank", "--joint",
             "perfect", *o("c2")], word="degree"),
        Case("chaos", "lyapunov --d0 0", ["lyapunov", "slider-crank", "--d0", "0", *o("c3")], word="d0"),
        Case("chaos", "poincare into the run", ["poincare", d / "run_poin", "--transient-revs", "0"], ok=True,
             owns=("run_poin",), check=_listed("run_poin", "poincare.csv")),
        Case("chaos", "poincare --transient-revs 1000", ["poincare", d / "run_poin", "--transient-revs",
             "1000", *o("c4")], word="transient"),
        Case("chaos", "poincare --plane garbage", ["poincare", d / "run_poin", "--plane", "garbage",
             *o("c5")], word="plane"),
        Case("chaos", "poincare of a foreign directory", ["poincare", d / "notarun", *o("c6")],
             word="notarun"),
        Case("chaos", "poincare of a truncated results.nc", ["poincare", d / "run_trunc", *o("c7")],
             word="results.nc"),
        Case("chaos", "spectrum into the run", ["spectrum", d / "run_spec", "--transient-revs", "0"], ok=True,
             owns=("run_spec",)),
        Case("chaos", "spectrum --max-harmonic -1", ["spectrum", d / "run_spec", "--transient-revs", "0",
             "--max-harmonic", "-1", *o("c8")], word="harmonic"),
        Case("chaos", "spectrum --transient-revs -1", ["spectrum", d / "run_spec", "--transient-revs", "-1",
             *o("c10")], word="transient"),
        Case("chaos", "poincare --transient-revs -1", ["poincare", d / "run_poin", "--transient-revs", "-1",
             *o("c11")], word="transient"),
        Case("chaos", "bifurcation of a missing spec", ["bifurcation", d / "nope.toml", *o("c9")],
             word="nope.toml"),
    ]  # fmt: skip
    for c in cases:
        c.argv = _jd(*c.argv)
        if not c.owns and "--out" in c.argv:
            c.owns = (os.path.relpath(c.argv[c.argv.index("--out") + 1], d),)
    return cases


def _snapshot(d: Path) -> dict[str, tuple]:
    """Every entry under ``d`` (links not followed): kind, size, mtime, content hash of files."""
    out = {}
    for root, dirs, files in os.walk(d):
        for n in dirs + files:
            p = Path(root) / n
            st = p.lstat()
            digest = ""
            if p.is_file() and not p.is_symlink():
                digest = hashlib.sha256(p.read_bytes()).hexdigest()
            elif p.is_symlink():
                digest = os.readlink(p)
            out[os.path.relpath(p, d)] = (st.st_mode >> 12, st.st_size, digest)
    return out


def _outside(before: dict, after: dict, owns: tuple[str, ...]) -> str:
    def mine(rel: str) -> bool:
        return any(rel == o or rel.startswith(o.rstrip("/") + "/") for o in owns)

    changed = sorted(k for k in set(before) | set(after) if before.get(k) != after.get(k) and not mine(k))
    return f"changed outside --out: {', '.join(changed[:4])}" if changed else ""


def _damaged(d: Path, owns: tuple[str, ...], before: dict, after: dict) -> str:
    """A manifest the case wrote whose files differ from it, or a lock or temporary it left."""
    for o in owns:
        p = d / o
        if not p.is_dir() or p.is_symlink():
            continue
        for q in p.rglob("*"):
            new = os.path.relpath(q, d) not in before
            if new and (q.name == ".jointdyn.lock" or (q.name.startswith(".") and ".tmp" in q.name)):
                return f"left behind: {os.path.relpath(q, d)}"
        mf = p / "manifest.json"
        rel = os.path.relpath(mf, d)
        if not mf.is_file() or before.get(rel) == after.get(rel):
            continue
        m = json.loads(mf.read_text())
        for name, rec in m.get("files", {}).items():
            f = p / name
            if m.get("status") == "complete" and (not f.is_file() or f.is_symlink()):
                return f"manifest lists missing {o}/{name}"
            digest = hashlib.sha256(f.read_bytes()).hexdigest() if f.is_file() else ""
            if digest and "sha256" in rec and digest != rec["sha256"]:
                return f"{o}/{name} differs from its manifest"
    return ""


def _wait_cpu(p: subprocess.Popen, seconds: float, wall: float = 120.0) -> None:
    """Wait until process ``p`` has used ``seconds`` of CPU (past its imports, into the work,
    however loaded the machine is), at most ``wall`` seconds."""
    tick = os.sysconf("SC_CLK_TCK")
    t0 = time.monotonic()
    while p.poll() is None and time.monotonic() - t0 < wall:
        try:
            fields = Path(f"/proc/{p.pid}/stat").read_text().rsplit(")", 1)[1].split()
        except OSError:
            return
        if (int(fields[11]) + int(fields[12])) / tick >= seconds:
            return
        time.sleep(0.1)


def _default_sigint() -> None:
    """A command started from a background job inherits SIGINT ignored: restore the default."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def run_case(c: Case, d: Path, timeout: float) -> tuple[str, str]:
    if c.py:
        code = c.py.replace("\n", "\n    ")
        cmd = [
            sys.executable,
            "-c",
            f"try:\n    {code}\nexcept Exception as e:\n"
            "    import sys; print(type(e).__name__ + ': ' + str(e), file=sys.stderr); sys.exit(2)",
        ]
    else:
        cmd = [sys.executable, "-c", "import jointdyn_entry as e; e.main()", *c.argv]
    before = _snapshot(d)
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         stdin=subprocess.DEVNULL, cwd=d, preexec_fn=_default_sigint)  # fmt: skip
    try:
        if c.sig:
            _wait_cpu(p, c.sig[0])
            if p.poll() is None:
                p.send_signal(c.sig[1])
        _, err = p.communicate(timeout=timeout)
    except subprocess.TimeoutExpired:
        p.kill()
        p.communicate()
        return "hang", f"no end within {timeout:g} s"
    lines = [ln for ln in err.splitlines() if ln.strip() and not ln.startswith("warning:")]
    first = (lines or [""])[0][:140]
    if any(k in err for k in ("Traceback", "internal error", "SystemError")):
        return "traceback", (lines or [""])[-1][:140]
    after = _snapshot(d)
    bad = _outside(before, after, c.owns) or _damaged(d, c.owns, before, after)
    if not bad and c.check and p.returncode == 0:
        bad = c.check(d)
    if bad:
        return "silent wrong", bad
    if c.sig:
        want = 128 + c.sig[1]
        ok = p.returncode == want and len(lines) == 1
        return ("clear" if ok else "misleading"), f"exit {p.returncode}: {first}"
    if p.returncode == 0:
        return ("fine" if c.ok else "silent wrong"), "exit 0"
    if c.ok:
        return "misleading", first
    named = c.word.lower() in " ".join(lines).lower()
    return ("clear" if len(lines) == 1 and named else "misleading"), first


def _base(d: Path) -> Path:
    base = d / "base"
    cmd = [sys.executable, "-c", "import jointdyn_entry as e; e.main()", "run", "slider-crank",
           "--joint", "dry", "--revs", "2", "--out", str(base)]  # fmt: skip
    subprocess.run(cmd, check=True, capture_output=True)
    return base


def main(argv=None) -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--timeout", type=float, default=120.0)
    ap.add_argument("--family", choices=FAMILIES, action="append")
    args = ap.parse_args(argv)
    table: dict[str, Counter] = {f: Counter() for f in FAMILIES}
    with tempfile.TemporaryDirectory() as tmp:
        base = _base(Path(tmp))
        d = Path(tmp) / "c"
        d.mkdir()
        for c in _setup(d, base):
            if args.family and c.family not in args.family:
                continue
            outcome, detail = run_case(c, d, args.timeout)
            table[c.family][outcome] += 1
            print(f"{outcome:12s} {c.family}: {c.name}: {detail}", flush=True)
    print("\n| family | cases | " + " | ".join(OUTCOMES) + " |")
    print("|---|" + "---|" * (len(OUTCOMES) + 1))
    total: Counter = Counter()
    for f, cnt in table.items():
        if cnt:
            total.update(cnt)
            print(f"| {f} | {sum(cnt.values())} | " + " | ".join(str(cnt[o]) for o in OUTCOMES) + " |")
    print(f"| all | {sum(total.values())} | " + " | ".join(str(total[o]) for o in OUTCOMES) + " |")
    return 0 if set(total) <= {"clear", "fine"} else 1


if __name__ == "__main__":
    raise SystemExit(main())
