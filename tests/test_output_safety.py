"""Output safety against a hostile or careless user: nothing is written where it does not belong.

Symbolic links planted at the lock or at temporary names are never followed, links and special
files are never replaced (a character device named as an output file is written into), files
are created with the mode of any other file, ownership of a directory is its manifest's list
only (a user's files are kept and named), derived outputs join the manifest under the lock, and
a FIFO given as an input is refused instead of blocking. Runs are short (0.05–0.1 rev).
"""

from __future__ import annotations

import json
import os
import shutil
import signal
import stat
import subprocess
import sys
import warnings
from pathlib import Path

import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.core import atomic
from jointdyn.core.atomic import OutputError
from jointdyn.io import derived
from jointdyn.io.rundir import LOCK, MANIFEST, KeptFiles, OutputDir, read_manifest

runner = CliRunner()
EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
STATES = (
    "xi,xi_dot,gamma,gamma_dot,omega_journal,omega_bearing,viscosity,length,radius,clearance\n"
    "0.5,20,0.3,100,523.6,0,0.4,0.04,0.01,0.0005\n"
)
BEARING = ["bearing-table", "--model", "short", "--cavitation", "gumbel", "--ld", "1", "--eps", "0.5"]


@pytest.fixture
def no_block():
    """Fail (instead of hanging) if the test blocks for 60 s, e.g. on opening a FIFO."""

    def fail(signum, frame):
        raise AssertionError("blocked for 60 s")

    old = signal.signal(signal.SIGALRM, fail)
    signal.alarm(60)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


@pytest.fixture(scope="module")
def dry_run(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("runs") / "dry"
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "dry", "--revs", "0.1", "--out", str(out)])
    assert r.exit_code == 0, r.output
    return out


@pytest.fixture
def run_dir(dry_run, tmp_path) -> Path:
    d = tmp_path / "run"
    shutil.copytree(dry_run, d)
    return d


def dead_pid() -> int:
    p = subprocess.Popen([sys.executable, "-c", "pass"])
    p.wait()
    return p.pid


def one_line(output: str) -> None:
    assert "Traceback" not in output, output
    assert [ln for ln in output.splitlines() if ln.startswith("error:")], output


def temps(d: Path) -> list[Path]:
    return [p for p in d.rglob("*") if atomic.is_temp(p)]


# -- temporary names and targets ---------------------------------------------------------------
def test_temporary_names_are_unpredictable():
    a, b = atomic.temp_name(Path("d/summary.json")), atomic.temp_name(Path("d/summary.json"))
    assert a != b and atomic.is_temp(a) and atomic.is_temp(b)
    assert a.name.startswith(f".summary.json.{os.getpid()}.") and a.suffix == ".json"


def test_planted_symlinks_at_temporary_names_are_never_followed(tmp_path, monkeypatch):
    """Even when the random part is known (patched), a link planted at the temporary name makes
    the exclusive creation fail; another name is drawn; the link's target is untouched."""
    outside = tmp_path / "outside.txt"
    outside.write_text("secret")
    d = tmp_path / "d"
    d.mkdir()
    tokens = iter(["a" * 16, "b" * 16])
    monkeypatch.setattr(atomic.secrets, "token_hex", lambda n: next(tokens))
    planted = d / f".summary.json.{os.getpid()}.{'a' * 16}.tmp.json"
    planted.symlink_to(outside)
    atomic.write_text(d / "summary.json", "new")
    assert outside.read_text() == "secret"
    assert (d / "summary.json").read_text() == "new" and not (d / "summary.json").is_symlink()
    assert planted.is_symlink()  # someone else's link: neither followed nor removed


@pytest.mark.parametrize("kind", ["symlink", "dangling", "fifo", "directory"])
def test_links_and_special_files_are_never_replaced(tmp_path, kind, no_block):
    outside = tmp_path / "outside.txt"
    outside.write_text("secret")
    target = tmp_path / "summary.json"
    {
        "symlink": lambda: target.symlink_to(outside),
        "dangling": lambda: target.symlink_to(tmp_path / "nowhere"),
        "fifo": lambda: os.mkfifo(target),
        "directory": lambda: target.mkdir(),
    }[kind]()
    before = os.lstat(target).st_mode
    with pytest.raises(OutputError, match="summary.json: is a"):
        atomic.write_text(target, "new", devices=True)
    assert os.lstat(target).st_mode == before and outside.read_text() == "secret"
    assert not (tmp_path / "nowhere").exists() and not temps(tmp_path)


def test_a_character_device_is_written_into_never_replaced():
    atomic.write_text("/dev/null", "discarded", devices=True)
    assert stat.S_ISCHR(os.lstat("/dev/null").st_mode)
    with pytest.raises(OutputError, match="character device"):
        atomic.write_text("/dev/null", "x")  # inside a run directory a device is refused


@pytest.mark.parametrize("mask", [0o022, 0o077])
def test_files_get_the_mode_of_any_other_file(tmp_path, mask, dry_run):
    from jointdyn.simulation.results import Results

    old = os.umask(mask)
    try:
        (tmp_path / "plain.txt").write_text("x")
        atomic.write_text(tmp_path / "a.txt", "x")
        Results.load(dry_run / "results.nc").save(tmp_path / "r.nc")
    finally:
        os.umask(old)
    want = stat.S_IMODE((tmp_path / "plain.txt").stat().st_mode)
    assert want == 0o666 & ~mask
    for f in ("a.txt", "r.nc"):
        assert stat.S_IMODE((tmp_path / f).stat().st_mode) == want, f


def test_run_directory_files_share_one_mode(dry_run):
    modes = {f.name: stat.S_IMODE(f.stat().st_mode) for f in dry_run.iterdir()}
    assert set(modes.values()) == {atomic.file_mode()}, modes  # results.nc was 0600
    assert not (dry_run / LOCK).exists()  # the lock ends with the run


# -- the lock ------------------------------------------------------------------------------------
def test_a_symlink_at_the_lock_is_refused_and_never_written_through(tmp_path):
    outside = tmp_path / "outside.txt"
    outside.write_text("secret")
    out = tmp_path / "run"
    out.mkdir()
    (out / LOCK).symlink_to(outside)
    r = runner.invoke(app, ["run", "slider-crank", "--revs", "0.05", "--out", str(out)])
    assert r.exit_code == 2 and "not a jointdyn lock" in r.output, r.output
    one_line(r.output)
    assert outside.read_text() == "secret" and (out / LOCK).is_symlink()


def test_a_dead_writers_lock_is_taken_over_with_its_files_and_temporaries(tmp_path):
    """A killed writer leaves its lock with the names it wrote and its temporaries: the next
    ``--overwrite`` removes exactly those; a live process's temporary and the user's file stay."""
    d = tmp_path / "d"
    d.mkdir()
    pid = dead_pid()
    (d / LOCK).write_text(f"pid {pid} on host since then\nfile a.csv\n")
    (d / "a.csv").write_text("written by the killed run")
    stale = d / f".b.csv.{pid}.{'0' * 16}.tmp.csv"
    live = d / f".b.csv.{os.getpid()}.{'1' * 16}.tmp.csv"
    stale.write_text("half")
    live.write_text("in progress")
    (d / "user.txt").write_text("mine")
    with pytest.raises(OutputError, match="--overwrite"):
        OutputDir(d, "run", {}).claim()
    assert "file a.csv" in (d / LOCK).read_text()  # a refusal keeps the killed run's list
    with pytest.warns(KeptFiles, match="user.txt"):
        od = OutputDir(d, "run", {}).claim(overwrite=True)
    assert not (d / "a.csv").exists() and not stale.exists() and live.exists()
    assert (d / "user.txt").read_text() == "mine"
    with od.write("results.nc") as tmp:
        tmp.write_text("new")
    od.finish()
    assert not (d / LOCK).exists() and list(read_manifest(d)["files"]) == ["results.nc"]


def test_a_held_lock_refuses_a_second_writer(tmp_path):
    od = OutputDir(tmp_path / "d", "run", {}).claim()
    with pytest.raises(OutputError, match=f"another jointdyn process.*pid {os.getpid()}"):
        OutputDir(tmp_path / "d", "run", {}).claim(overwrite=True)
    od.finish()
    OutputDir(tmp_path / "d", "run", {}).claim(overwrite=True).finish()


# -- ownership: the manifest's list only -----------------------------------------------------------
def test_overwrite_removes_exactly_the_files_the_manifest_lists(tmp_path):
    d = tmp_path / "d"
    od = OutputDir(d, "sweep", {}).claim()
    (d / "cases").mkdir()
    for name in ("sweep.nc", "cases/case_00000.json"):
        with od.write(name) as tmp:
            tmp.write_text(name)
    od.finish()
    (d / "thesis_fig3.png").write_text("mine")
    (d / "cases" / "notes.txt").write_text("mine too")
    with pytest.warns(KeptFiles, match="kept 2 file.*cases, thesis_fig3.png"):
        OutputDir(d, "sweep", {}).claim(overwrite=True).finish()
    assert sorted(p.relative_to(d).as_posix() for p in d.rglob("*")) == [
        "cases",
        "cases/notes.txt",
        MANIFEST,
        "thesis_fig3.png",
    ]


def test_manifest_names_outside_the_directory_are_never_removed(tmp_path):
    d = tmp_path / "d"
    d.mkdir()
    victim = tmp_path / "victim.txt"
    victim.write_text("keep")
    files = {"../victim.txt": {}, str(victim): {}, "a/../../victim.txt": {}}
    (d / MANIFEST).write_text(json.dumps({"kind": "run", "files": files}))
    OutputDir(d, "run", {}).claim(overwrite=True).finish()
    assert victim.read_text() == "keep"


def test_a_file_jointdyn_did_not_write_is_never_replaced(tmp_path):
    d = tmp_path / "d"
    d.mkdir()
    (d / "results.nc").write_text("the user's")
    with pytest.raises(OutputError, match="results.nc, which jointdyn did not write"):
        OutputDir(d, "run", {}).claim(overwrite=True)  # refused before anything is touched
    (d / "results.nc").rename(d / "x.csv")
    with pytest.warns(KeptFiles):
        od = OutputDir(d, "run", {}).claim(overwrite=True)
    with pytest.raises(OutputError, match="x.csv is there and jointdyn did not write it"):
        with od.write("x.csv") as tmp:
            tmp.write_text("new")
    od.finish()
    assert (d / "x.csv").read_text() == "the user's" and not temps(d)


def test_run_overwrite_keeps_a_users_png_and_removes_its_own_files(run_dir):
    """``run --overwrite`` removed every ``*.png`` as its own; now only the manifest's files (the
    dry run's orbit.png, a derived poincare.csv) go, the user's figure stays and is named."""
    r = runner.invoke(app, ["poincare", str(run_dir), "--transient-revs", "0"])
    assert r.exit_code == 0, r.output
    (run_dir / "thesis_fig3.png").write_bytes(b"my figure")
    stale = run_dir / f".results.nc.{dead_pid()}.{'2' * 16}.tmp.nc"
    stale.write_bytes(b"half a file of a killed run")
    r = runner.invoke(app, ["run", "slider-crank", "--revs", "0.05", "--out", str(run_dir), "--overwrite"])
    assert r.exit_code == 0, r.output
    assert "warning:" in r.output and "thesis_fig3.png" in r.output
    assert (run_dir / "thesis_fig3.png").read_bytes() == b"my figure"
    for gone in ("orbit.png", "poincare.csv", "poincare.png", stale.name):
        assert not (run_dir / gone).exists(), gone
    m = read_manifest(run_dir)
    assert m["status"] == "complete" and "thesis_fig3.png" not in m["files"]
    assert not (run_dir / LOCK).exists() and not temps(run_dir)


def test_reproduce_keeps_a_users_files_and_a_killed_reproduction_reruns(tmp_path):
    from jointdyn.studies.reproduce import reproduce_alshaer2005

    out = tmp_path / "repro"
    out.mkdir()
    (out / "lab_measurements.csv").write_text("t,moment\n0,1\n")
    (out / "my_photo.png").write_bytes(b"photo")
    r = runner.invoke(app, ["reproduce", "alshaer2005", "--quick", "--out", str(out)])
    assert r.exit_code == 2 and "--overwrite" in r.output  # nothing removed without the flag
    # killed (os._exit: no cleanup) when the report is written, after the CSVs and figures
    code = (
        "import os; import jointdyn.studies.reproduce as r; r.report_html = lambda *a, **k: os._exit(9); "
        f"r.reproduce_alshaer2005({str(out)!r}, beyond=False, revs=0.05, ensemble=False)"
    )
    p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=600)
    assert p.returncode == 9, p.stderr
    assert (out / "summary.csv").exists() and not (out / MANIFEST).exists() and (out / LOCK).exists()
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        reproduce_alshaer2005(out, beyond=False, revs=0.05, ensemble=False, overwrite=True)
    kept = [str(w.message) for w in seen if w.category is KeptFiles]
    assert len(kept) == 1 and "lab_measurements.csv" in kept[0] and "my_photo.png" in kept[0]
    m = read_manifest(out)
    assert m["status"] == "complete" and "report.html" in m["files"]
    assert not {"lab_measurements.csv", "my_photo.png"} & set(m["files"])
    assert (out / "my_photo.png").read_bytes() == b"photo" and not (out / LOCK).exists() and not temps(out)


# -- derived outputs -------------------------------------------------------------------------------
def test_derived_outputs_join_the_manifest_under_the_lock(run_dir):
    for cmd in (["poincare", str(run_dir), "--transient-revs", "0"], ["plot", str(run_dir)]):
        r = runner.invoke(app, cmd)
        assert r.exit_code == 0, r.output
    m = read_manifest(run_dir)
    assert {"poincare.csv", "poincare.png", "plot_moment.png", "results.nc"} <= set(m["files"])
    assert m["status"] == "complete" and m["kind"] == "run" and not (run_dir / LOCK).exists()
    for name, meta in m["files"].items():
        assert atomic.sha256(run_dir / name) == meta["sha256"], name
    with derived.derived(run_dir, "poincare"):  # a writer holds the directory
        r = runner.invoke(app, ["poincare", str(run_dir), "--transient-revs", "0"])
        assert r.exit_code == 2 and "another jointdyn process" in r.output, r.output


def test_a_derived_output_never_replaces_an_unlisted_file(dry_run, tmp_path):
    d = tmp_path / "d"
    shutil.copytree(dry_run, d)
    (d / "poincare.csv").write_text("the user's")
    r = runner.invoke(app, ["poincare", str(d), "--transient-revs", "0"])
    assert r.exit_code == 2 and "poincare.csv is there and jointdyn did not write it" in r.output
    assert (d / "poincare.csv").read_text() == "the user's" and not temps(d)
    other = tmp_path / "other"
    other.mkdir()
    (other / "x.txt").write_text("x")
    r = runner.invoke(app, ["poincare", str(d), "--transient-revs", "0", "--out", str(other)])
    assert r.exit_code == 2 and "not empty" in r.output  # no manifest: not a jointdyn directory


def test_lyapunov_into_a_run_directory_is_refused_without_overwrite(dry_run, tmp_path):
    d = tmp_path / "d"
    shutil.copytree(dry_run, d)
    before = (d / "summary.json").read_bytes()
    args = ["lyapunov", str(EXAMPLES / "oscillator_damped.toml"), "--tau", "1", "--segments", "20"]
    r = runner.invoke(app, [*args, "--discard", "0", "--out", str(d)])
    assert r.exit_code == 2 and "--overwrite" in r.output, r.output
    assert (d / "summary.json").read_bytes() == before
    out = tmp_path / "lyap"
    r = runner.invoke(app, [*args, "--discard", "0", "--out", str(out)])
    assert r.exit_code == 0, r.output
    m = read_manifest(out)
    assert m["kind"] == "lyapunov" and set(m["files"]) == {"summary.json", "lyapunov.csv", "lyapunov.png"}
    assert not (out / LOCK).exists()


@pytest.mark.parametrize("command", ["ensemble", "bifurcation"])
def test_directory_commands_refuse_a_non_empty_directory(tmp_path, command):
    out = tmp_path / "o"
    out.mkdir()
    (out / "notes.txt").write_text("mine")
    spec = tmp_path / "b.toml"
    spec.write_text('[base]\njoint = "dry"\n[bifurcation]\nparameter = "clearance"\nvalues = [2e-4]\n')
    args = {"ensemble": ["ensemble"], "bifurcation": ["bifurcation", str(spec)]}[command]
    r = runner.invoke(app, [*args, "--out", str(out)])
    assert r.exit_code == 2 and "--overwrite" in r.output and "notes.txt" in r.output, r.output
    assert [p.name for p in out.iterdir()] == ["notes.txt"]


# -- single output files, per command ----------------------------------------------------------
def _single(command: str, target: Path, tmp_path: Path, dry_run: Path) -> list[str]:
    states = tmp_path / "states.csv"
    states.write_text(STATES)
    return {
        "bearing-table": [*BEARING, "--out", str(target)],
        "film-force": ["film-force", str(states), "--out", str(target)],
        "plot": ["plot", str(dry_run), "--out", str(target)],
    }[command]


@pytest.mark.parametrize("command", ["bearing-table", "film-force", "plot"])
def test_single_output_files_never_replace_links_or_special_files(command, tmp_path, dry_run, no_block):
    outside = tmp_path / "outside.txt"
    outside.write_text("secret")
    link, fifo = tmp_path / "link.out", tmp_path / "fifo.out"
    link.symlink_to(outside)
    os.mkfifo(fifo)
    for target, needle in (
        (link, "symbolic link"),
        (fifo, "FIFO"),
        (tmp_path / "no" / "x.out", "does not exist"),
    ):
        r = runner.invoke(app, _single(command, target, tmp_path, dry_run))
        assert r.exit_code == 2 and needle in r.output, r.output
        one_line(r.output)
    assert outside.read_text() == "secret" and link.is_symlink() and stat.S_ISFIFO(os.lstat(fifo).st_mode)
    r = runner.invoke(app, _single(command, Path("/dev/null"), tmp_path, dry_run))
    assert r.exit_code == 0, r.output
    assert stat.S_ISCHR(os.lstat("/dev/null").st_mode) and not temps(tmp_path)


def test_results_save_into_dev_null_and_refusing_a_link(dry_run, tmp_path):
    from jointdyn.simulation.results import Results

    res = Results.load(dry_run / "results.nc")
    res.save("/dev/null")
    assert stat.S_ISCHR(os.lstat("/dev/null").st_mode)
    (tmp_path / "r.nc").symlink_to(tmp_path / "elsewhere.nc")
    with pytest.raises(OutputError, match="symbolic link"):
        res.save(tmp_path / "r.nc")
    assert not (tmp_path / "elsewhere.nc").exists()


def test_bearing_table_to_stdout_by_name():
    p = subprocess.run(
        [sys.executable, "-m", "jointdyn", *BEARING, "--out", "/dev/stdout"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stderr
    assert p.stdout.splitlines()[0].startswith("eps,") and len(p.stdout.splitlines()) == 2


# -- inputs ---------------------------------------------------------------------------------------
@pytest.mark.parametrize("command", ["run", "sweep", "film-force", "bifurcation", "lyapunov"])
def test_a_fifo_as_input_is_refused_not_waited_on(tmp_path, command, no_block):
    fifo = tmp_path / "in.toml"
    os.mkfifo(fifo)
    args = {
        "run": ["run", str(fifo)],
        "sweep": ["sweep", str(fifo)],
        "film-force": ["film-force", str(fifo)],
        "bifurcation": ["bifurcation", str(fifo)],
        "lyapunov": ["lyapunov", str(fifo), "--tau", "1", "--segments", "2"],
    }[command]
    r = runner.invoke(app, [*args, "--out", str(tmp_path / "o")])
    assert r.exit_code == 2 and "is a FIFO, not a regular file" in r.output, r.output
    one_line(r.output)
    assert not (tmp_path / "o").exists()


def test_bifurcation_resume_and_overwrite_follow_its_manifest(tmp_path):
    """The diagram's directory lists its sweep's files and its figure; ``--resume`` keeps them
    listed, ``--overwrite`` removes exactly them (the user's file stays)."""
    spec, out = tmp_path / "b.toml", tmp_path / "bif"
    spec.write_text(
        '[base]\njoint = "dry"\nrtol = 1e-6\natol = 1e-9\n[bifurcation]\nparameter = "clearance"\n'
        "values = [2e-4]\ntransient_revs = 1\nrecord_revs = 1\n"
    )
    args = ["bifurcation", str(spec), "--out", str(out), "--workers", "1"]
    for extra in ([], ["--resume"]):
        r = runner.invoke(app, [*args, *extra])
        assert r.exit_code == 0, r.output
        m = read_manifest(out)
        assert m["kind"] == "bifurcation" and m["status"] == "complete"
        assert {
            "bifurcation.nc",
            "bifurcation.png",
            "sweep/manifest.json",
            "sweep/cases/case_00000.json",
        } <= set(m["files"])
    (out / "notes.txt").write_text("mine")
    r = runner.invoke(app, [*args, "--overwrite"])
    assert r.exit_code == 0 and "notes.txt" in r.output, r.output
    assert (out / "notes.txt").read_text() == "mine" and not (out / LOCK).exists()
    assert not [p for p in out.rglob("*") if p.name == LOCK or atomic.is_temp(p)]
