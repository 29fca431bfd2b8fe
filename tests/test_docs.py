"""Documentation: the site builds with ``mkdocs build --strict`` (which executes every
``examples/NN_*.py``), each tutorial page shows its figure, and the getting-started page's
commands work literally in a fresh virtual environment (slow)."""

from __future__ import annotations

import importlib.util
import os
import re
import shutil
import subprocess
import sys
import venv
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = sorted((ROOT / "examples").glob("[0-9][0-9]_*.py"))
PNG = b"\x89PNG\r\n\x1a\n"


def _need_docs_tools():
    for mod in ("mkdocs", "mkdocstrings", "mkdocstrings_handlers.python", "material"):
        if importlib.util.find_spec(mod) is None:
            pytest.skip(f"{mod} not installed (pip install -e '.[docs]')")


def _load_hook():
    spec = importlib.util.spec_from_file_location("run_examples", ROOT / "docs" / "hooks" / "run_examples.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def test_site_builds_strict_and_tutorials_show_their_figures(tmp_path):
    _need_docs_tools()
    assert len(EXAMPLES) >= 3
    site = tmp_path / "site"
    env = dict(os.environ, NO_MKDOCS_2_WARNING="1", MPLBACKEND="Agg")
    proc = subprocess.run(
        [
            sys.executable,
            "-m",
            "mkdocs",
            "build",
            "--strict",
            "-f",
            str(ROOT / "mkdocs.yml"),
            "-d",
            str(site),
        ],
        cwd=ROOT,
        env=env,
        capture_output=True,
        text=True,
        timeout=900,
    )
    assert proc.returncode == 0, proc.stdout[-3000:] + proc.stderr[-6000:]
    assert "WARNING" not in proc.stderr  # --strict would have aborted; belt and braces
    shown = set()
    for page in site.rglob("*.html"):  # every figure of every page is there (issue 29: validation's was not)
        for src in re.findall(r'<img[^>]*src="([^":]+\.png)"', page.read_text(encoding="utf-8")):
            png = (page.parent / src).resolve()
            assert png.is_file() and png.read_bytes().startswith(PNG), (
                f"{page.relative_to(site)}: {src} missing"
            )
            shown.add(png.relative_to(site.resolve()).as_posix())
    assert (
        "figures/validation_raimondi_boyd.png" in shown
    )  # committed (issue 29), checked by test_docs_current
    for script in EXAMPLES:
        page = site / "tutorials" / script.stem / "index.html"
        assert page.exists(), f"no tutorial page for {script.name}"
        html = page.read_text(encoding="utf-8")
        images = re.findall(r'<img[^>]*src="([^"]+\.png)"', html)
        assert images, f"{script.name}: the tutorial page has no figure"
        for src in images:
            png = (page.parent / src).resolve()
            data = png.read_bytes()
            # a real plot, not an empty canvas: the smallest of ours is ~40 kB
            assert data.startswith(PNG) and len(data) > 10_000, f"{png} is not a plotted PNG"
        assert "savefig" in html and 'id="output"' in html  # the source, then the output section
        assert "Printed when this page was built" in html
        nav = (site / "index.html").read_text(encoding="utf-8")
        assert f"tutorials/{script.stem}/" in nav, f"{script.name} is missing from the navigation"
    api = (site / "api" / "index.html").read_text(encoding="utf-8")
    assert "simulate" in api and "[T14]" in api  # docstrings rendered, theory tags kept literal


def test_a_failing_example_fails_the_build(tmp_path):
    _need_docs_tools()
    from mkdocs.exceptions import PluginError

    hook = _load_hook()
    bad = tmp_path / "99_bad.py"
    bad.write_text("raise SystemExit('boom')\n")
    with pytest.raises(PluginError, match="99_bad.py failed"):
        hook._run(bad, tmp_path)
    quiet = tmp_path / "98_quiet.py"
    quiet.write_text("print('no figure')\n")
    out, _ = hook._run(quiet, tmp_path)
    assert out.strip() == "no figure"  # on_files then refuses it: no .png in the working directory


def test_theory_tags_stay_literal_text():
    _need_docs_tools()
    import markdown

    hook = _load_hook()
    md = markdown.Markdown(extensions=[hook.TheoryTags()])
    html = md.convert("body rates ω [rad/s] [T14]; laws [T60–T62], elements [T14, T16]")
    assert "[T14]" in html and "[T60–T62]" in html and "[T14, T16]" in html and "<a" not in html


def _blocks(text: str, lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", text, re.S)


@pytest.mark.slow
def test_getting_started_commands_in_a_fresh_venv(tmp_path):
    """Follow docs/getting-started.md literally: a copy of the working tree (as a fresh clone
    would be), a new virtual environment, an empty numba cache (as on a fresh machine), then
    every ``bash`` block of the page from the copy's root except the test command, then every
    ``python`` block. Needs PyPI (the dependencies are installed into the new environment)."""
    page = (ROOT / "docs" / "getting-started.md").read_text(encoding="utf-8")
    commands = [c.strip() for c in _blocks(page, "bash") if "pytest" not in c]
    assert commands[0].startswith("python -m pip install -e .")  # the first of the two commands
    assert any(c.startswith("jointdyn run slider-crank") for c in commands)

    clone = tmp_path / "jointdyn"
    ignore = shutil.ignore_patterns(".git", "out", "site", "__pycache__", "*.egg-info", ".venv", "*.nc")
    shutil.copytree(ROOT, clone, ignore=ignore)
    env_dir = tmp_path / "venv"
    venv.EnvBuilder(with_pip=True).create(env_dir)
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env.update(PATH=f"{env_dir / 'bin'}{os.pathsep}{env['PATH']}", VIRTUAL_ENV=str(env_dir), MPLBACKEND="Agg")
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "numba-cache")  # cold: compile everything, as on a new machine

    for cmd in commands:
        proc = subprocess.run(["bash", "-e", "-c", cmd], cwd=clone, env=env, capture_output=True, text=True)
        assert proc.returncode == 0, f"$ {cmd}\n{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    which = subprocess.run(["bash", "-c", "command -v jointdyn"], env=env, capture_output=True, text=True)
    assert which.stdout.strip() == str(env_dir / "bin" / "jointdyn")  # the venv's, not ours
    assert (clone / "out" / "alshaer2005" / "report.html").exists()
    for f in ("results.nc", "timeseries.csv", "summary.json", "moment.png", "orbit.png"):
        assert (clone / "out" / "first-run" / f).exists(), f

    for i, code in enumerate(_blocks(page, "python")):
        script = tmp_path / f"block{i}.py"
        script.write_text(code)
        proc = subprocess.run(
            [str(env_dir / "bin" / "python"), str(script)], cwd=clone, env=env, capture_output=True, text=True
        )
        assert proc.returncode == 0, f"python block {i}:\n{code}\n{proc.stderr[-3000:]}"
    assert (clone / "run.nc").exists()  # written by the Python block


def _pep668_system_python() -> str | None:
    """A python3 (≥ 3.11, not a virtual environment) whose standard library holds the PEP 668
    ``EXTERNALLY-MANAGED`` marker, i.e. a system Python that refuses global installs (Debian 12's
    /usr/bin/python3 is one); None if this machine has none."""
    probe = (
        "import sys, sysconfig, os; print(sys.version_info >= (3, 11) and sys.prefix == sys.base_prefix"
        " and os.path.isfile(os.path.join(sysconfig.get_path('stdlib'), 'EXTERNALLY-MANAGED')))"
    )
    for exe in ("/usr/bin/python3", shutil.which("python3"), "/usr/local/bin/python3"):
        if exe and os.path.isfile(exe):
            r = subprocess.run([exe, "-I", "-c", probe], capture_output=True, text=True)
            if r.stdout.strip() == "True":
                return exe
    return None


@pytest.mark.slow
def test_readme_commands_verbatim_where_global_installs_are_refused(tmp_path):
    """The README's first two ``bash`` blocks, verbatim, in one shell (the activation carries
    over), in a copy of the checkout, with ``python3`` resolving to a real PEP 668 system Python
    (not simulated: the marker is the distribution's own). First a global ``pip install -e .`` with
    that interpreter is shown to be refused, then the README's lines make the venv, install and run
    the main job. The dependencies come from the package index pip is configured with; the numba
    cache starts empty."""
    system = _pep668_system_python()
    if system is None:
        pytest.skip("no PEP 668 system python3 here (Debian ≥ 12 and Ubuntu ≥ 23.04 ship one)")
    blocks = _blocks((ROOT / "README.md").read_text(encoding="utf-8"), "bash")
    venv_line, main_job = blocks[0].strip(), blocks[1].strip()
    assert venv_line == "python3 -m venv .venv && . .venv/bin/activate"
    assert main_job.startswith("python -m pip install -e . && jointdyn reproduce alshaer2005 --out ")

    clone = tmp_path / "jointdyn"
    ignore = shutil.ignore_patterns(".git", "out", "site", "__pycache__", "*.egg-info", ".venv", "*.nc")
    shutil.copytree(ROOT, clone, ignore=ignore)
    sysbin = tmp_path / "system-bin"  # python3 on PATH is the system one, nothing else of ours
    sysbin.mkdir()
    (sysbin / "python3").symlink_to(system)
    drop = ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "PYTHONNOUSERSITE")
    env = {k: v for k, v in os.environ.items() if k not in drop}
    env.update(PATH=f"{sysbin}{os.pathsep}/usr/bin{os.pathsep}/bin", MPLBACKEND="Agg", HOME=str(tmp_path))
    env["NUMBA_CACHE_DIR"] = str(tmp_path / "numba-cache")

    refused = subprocess.run(
        ["bash", "-c", "python3 -m pip install -e ."], cwd=clone, env=env, capture_output=True, text=True
    )
    assert refused.returncode != 0 and "externally-managed-environment" in refused.stderr, refused.stderr[
        -2000:
    ]

    script = f"set -e\n{venv_line}\n{main_job}\ncommand -v jointdyn\n"
    proc = subprocess.run(
        ["bash", "-c", script], cwd=clone, env=env, capture_output=True, text=True, timeout=3600
    )
    assert proc.returncode == 0, f"{proc.stdout[-3000:]}\n{proc.stderr[-3000:]}"
    assert proc.stdout.strip().splitlines()[-1] == str(clone / ".venv" / "bin" / "jointdyn")
    out = clone / main_job.split("--out ")[1].split()[0]
    for f in ("report.html", "summary.csv", "dry.csv", "ensemble_dry.json"):
        assert (out / f).is_file(), f
