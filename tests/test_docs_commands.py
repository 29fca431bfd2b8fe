"""Every documented command and Python snippet runs as written.

The commands are read from the fenced shell blocks of the README, CONTRIBUTING and docs/ and from
the comment lines of examples/ (``# jointdyn …``, ``# Run: jointdyn …``). Default tier: each
``jointdyn`` command is parsed by the CLI's own parser exactly as written (command, options,
choices, types, required arguments), the files it names exist, each ``python -m MODULE``
names a module that exists, and each ``python -c "…"`` line runs from the repository root. Slow
tier (``-m slow``): every command without a placeholder is executed, in reading order, in a scratch
directory holding the repository's ``examples/``, and must exit 0; then each page's ```python
blocks run as one script there.
"""

from __future__ import annotations

import importlib.util
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PAGES = [ROOT / "README.md", ROOT / "CONTRIBUTING.md", *sorted((ROOT / "docs").rglob("*.md"))]
EXAMPLES = sorted(p for p in (ROOT / "examples").iterdir() if p.suffix in (".toml", ".py"))
FENCE = re.compile(r"^```(bash|sh|shell|console)\s*$")
#: words that stand for something the reader supplies
PLACEHOLDER = re.compile(
    r"\b(DIR2?|FILE|MODEL|SWEEP|HOST|PORT|SCHEDULER|JOINT|NAME|PAPER)\b|[\[\]{}<>]|\.\.\.|…"
)


def _join_continuations(lines: list[str]) -> list[tuple[int, str]]:
    out, buf, start = [], "", 0
    for i, ln in enumerate(lines, 1):
        if not buf:
            start = i
        buf += ln.rstrip()
        if buf.endswith("\\"):
            buf = buf[:-1] + " "
            continue
        out.append((start, buf))
        buf = ""
    return out


def _strip_comment(cmd: str) -> str:
    try:
        toks = shlex.split(cmd, comments=True)
    except ValueError:
        return cmd
    return shlex.join(toks)


def documented_commands() -> list[tuple[str, int, str]]:
    """(file, line, command) of every documented jointdyn / python -m command, in page order;
    a ``&&`` chain gives one entry per part."""
    found = []
    for page in PAGES:
        lines, inside, block = page.read_text(encoding="utf-8").splitlines(), False, []
        for i, ln in enumerate(lines, 1):
            if not inside and FENCE.match(ln.strip()):
                inside, block, first = True, [], i + 1
            elif inside and ln.strip().startswith("```"):
                inside = False
                for j, cmd in _join_continuations(block):
                    found += [(page, first + j - 1, c.strip()) for c in cmd.split("&&")]
            elif inside:
                block.append(ln)
    for ex in EXAMPLES:
        for i, ln in enumerate(ex.read_text(encoding="utf-8").splitlines(), 1):
            m = re.match(r"^\s*#\s*(?:Run:\s*)?((?:python -m )?jointdyn .*)$", ln)
            if m:
                found.append((ex, i, m.group(1).strip()))
    out = []
    for page, line, cmd in found:
        cmd = cmd.lstrip("$ ").strip()
        if re.match(r"^(jointdyn|python -[mc])\b", cmd):
            out.append((str(page.relative_to(ROOT)), line, _strip_comment(cmd)))
    return out


COMMANDS = documented_commands()
JOINTDYN = [c for c in COMMANDS if c[2].startswith("jointdyn ")]
MODULES = [c for c in COMMANDS if c[2].startswith("python -m ")]
SNIPPETS = [c for c in COMMANDS if c[2].startswith("python -c ")]


def _id(c):
    return f"{c[0]}:{c[1]}"


def test_the_documentation_holds_commands():
    assert len(JOINTDYN) >= 30 and len(MODULES) >= 5  # the reader finds them where expected


def parse_problem(cmd: str) -> str | None:
    """Why the CLI's own parser refuses ``cmd`` as written (None if it takes it): unknown
    commands and options, bad choices and types, missing arguments, example files that do not
    exist. Placeholder words (DIR, FILE.toml, [--opt N]) stand for arguments: only the option
    names around them are checked."""
    import typer

    from jointdyn.cli import app

    argv = shlex.split(cmd)[1:]
    group = typer.main.get_command(app)
    placeholder = bool(PLACEHOLDER.search(cmd))
    if placeholder:  # [--opt N] is an optional option: its name is checked
        argv = [a.strip("[]") for a in argv if a.strip("[]")]
    if not argv or argv[0].startswith("-"):
        return None
    name, rest = argv[0], argv[1:]
    if name not in group.commands:
        return f"no command {name!r}"
    cmd_obj = group.commands[name]
    if placeholder:
        known = {o for p in cmd_obj.params for o in (*p.opts, *p.secondary_opts)}
        bad = [a for a in rest if a.startswith("--") and a.split("=")[0] not in known]
        return f"{name} has no option {bad[0]!r}" if bad else None
    try:
        ctx = cmd_obj.make_context(name, list(rest))
    except Exception as err:  # typer's own click: its exception classes are private
        if type(err).__name__ == "Exit":
            return None  # --help
        if hasattr(err, "format_message"):
            return f"does not parse: {err.format_message()}"
        raise
    for v in ctx.params.values():
        s = str(v) if isinstance(v, (str, Path)) else ""
        if s.startswith("examples/") and not (ROOT / s).exists():
            return f"{s} does not exist"
    return None


@pytest.mark.parametrize("entry", JOINTDYN, ids=_id)
def test_documented_jointdyn_command_parses_as_written(entry):
    page, line, cmd = entry
    problem = parse_problem(cmd)
    assert problem is None, f"{page}:{line}: `{cmd}`: {problem}"


@pytest.mark.parametrize(
    "cmd, why",
    [
        ("jointdyn runn slider-crank", "no command"),
        ("jointdyn run slider-crank --speeed 3000", "No such option"),
        ("jointdyn bearing-table --ld one", "Invalid value for '--ld'"),
        ("jointdyn bearing-table --eps 0.1", "Missing option"),
        ("jointdyn run examples/no_such_model.toml --out x", "does not exist"),
        ("jointdyn sweep SWEEP.toml --out DIR [--resum]", "--resum"),
    ],
)
def test_the_parse_check_refuses_what_a_user_could_not_run(cmd, why):
    assert why in (parse_problem(cmd) or "")


@pytest.mark.parametrize("entry", MODULES, ids=_id)
def test_documented_module_exists(entry):
    page, line, cmd = entry
    mod = shlex.split(cmd)[2]
    if mod == "pip" or mod == "pytest" or mod == "venv" or mod == "mkdocs":
        return
    sys.path.insert(0, str(ROOT))
    try:
        assert importlib.util.find_spec(mod) is not None, f"{page}:{line}: no module {mod}"
    finally:
        sys.path.remove(str(ROOT))


@pytest.mark.parametrize("entry", SNIPPETS, ids=_id)
def test_documented_python_c_command_runs(entry):
    """A ``python -c "…"`` line of the docs (cheap: the Raimondi–Boyd comparison takes ≈ 3 s) runs
    as written from the repository root, where its relative paths point, and prints something."""
    page, line, cmd = entry
    env = {**os.environ, "MPLBACKEND": "Agg"}
    r = subprocess.run(
        cmd, shell=True, executable="/bin/bash", cwd=ROOT, env=env, capture_output=True, text=True
    )
    assert r.returncode == 0 and r.stdout.strip(), f"{page}:{line}: `{cmd}`: {r.stderr[-2000:]}"


def test_the_docs_hold_a_python_c_command():
    assert any(p == "docs/validation.md" for p, *_ in SNIPPETS)  # the collector still finds it


def shell_lines() -> list[tuple[str, int, str]]:
    """What the slow tier executes, in reading order (README, getting started, the other pages,
    the example files), each command once: jointdyn commands without a placeholder and the
    ``printf … > FILE`` lines that make their inputs. Not executed: a cluster (``--scheduler``),
    ``--help``, installs and test runs (this is one)."""
    order = {"README.md": 0, "docs/getting-started.md": 1}
    entries = sorted(COMMANDS + _printf_lines(), key=lambda c: (order.get(c[0], 2), c[0], c[1]))
    seen, out = set(), []
    for page, line, cmd in entries:
        if not re.match(r"^(jointdyn |printf )", cmd) or cmd in seen:
            continue
        if cmd.startswith("jointdyn ") and (PLACEHOLDER.search(cmd) or re.search(r"--scheduler|--help", cmd)):
            continue
        seen.add(cmd)
        out.append((page, line, cmd))
    return out


def _printf_lines() -> list[tuple[str, int, str]]:
    found = []
    for page in PAGES:
        for i, ln in enumerate(page.read_text(encoding="utf-8").splitlines(), 1):
            if ln.startswith("printf "):
                found.append((str(page.relative_to(ROOT)), i, ln.strip()))
    return found


@pytest.mark.slow
def test_documented_commands_run(tmp_path):
    """Every documented command, as a reader would type it, in one scratch directory holding the
    repository's examples (later pages use earlier pages' outputs, as a reader's directory
    would); ``jointdyn cache clear`` acts on a scratch cache so the other tests keep theirs."""
    (tmp_path / "examples").symlink_to(ROOT / "examples")
    bin_dir = str(Path(sys.executable).parent)
    env = {**os.environ, "MPLBACKEND": "Agg", "PATH": bin_dir + os.pathsep + os.environ.get("PATH", "")}
    lines = shell_lines()
    assert any("reproduce" in c for *_, c in lines) and any(c.startswith("printf") for *_, c in lines)
    for page, line, cmd in lines:
        e = {**env, "XDG_CACHE_HOME": str(tmp_path / "cache")} if cmd.startswith("jointdyn cache") else env
        r = subprocess.run(
            cmd,
            shell=True,
            executable="/bin/bash",
            cwd=tmp_path,
            env=e,
            capture_output=True,
            text=True,
            timeout=1800,
        )
        assert r.returncode == 0, f"{page}:{line}: `{cmd}` exited {r.returncode}: {r.stderr[-2000:]}"
    for page in sorted({p for p, _ in python_blocks()}, key=lambda p: (p != "README.md", p)):
        script = tmp_path / f"snippets_{page.replace('/', '_')}.py"
        script.write_text("\n".join(code for p, code in python_blocks() if p == page), encoding="utf-8")
        r = subprocess.run(
            [sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True, timeout=1800
        )
        assert r.returncode == 0, f"{page}: its Python blocks fail: {r.stderr[-2000:]}"


def python_blocks() -> list[tuple[str, str]]:
    """(page, code) of every ```python block of the README and docs/ (the how-to's blocks are
    run by tests/test_how_to.py, each against its own registry)."""
    out = []
    for page in PAGES:
        rel = str(page.relative_to(ROOT))
        if rel == "docs/how-to-add-a-model.md":
            continue
        text = page.read_text(encoding="utf-8")
        out += [(rel, m.group(1)) for m in re.finditer(r"^```python\n(.*?)^```", text, re.S | re.M)]
    return out


def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.slow
def test_the_dask_block_of_the_sweep_guide_runs(tmp_path):
    """docs/user-guide/sweeps.md's cluster block on this machine: its scheduler and worker lines
    are started and its sweep line is run against them. Substituted: the placeholder SCHEDULER
    → 127.0.0.1, the scheduler's ``--host 0.0.0.0`` → 127.0.0.1 (nothing listens beyond this
    machine) and the port 8786 → a free one; everything else is verbatim. The sweep's 25 cases
    must all finish on the Dask workers."""
    import time

    import xarray as xr

    pytest.importorskip("distributed")
    guide = (ROOT / "docs" / "user-guide" / "sweeps.md").read_text(encoding="utf-8")
    block = next(b for b in re.findall(r"^```bash\n(.*?)^```", guide, re.S | re.M) if "dask scheduler" in b)
    lines = [ln.strip() for ln in block.splitlines() if ln.strip() and not ln.startswith("#")]
    sched, worker, sweep = (
        next(ln for ln in lines if ln.startswith(w)) for w in ("dask scheduler", "dask worker", "jointdyn")
    )
    port = str(_free_port())

    def local(cmd: str) -> str:
        return cmd.replace("SCHEDULER", "127.0.0.1").replace("0.0.0.0", "127.0.0.1").replace("8786", port)

    (tmp_path / "examples").symlink_to(ROOT / "examples")
    bin_dir = str(Path(sys.executable).parent)
    env = {**os.environ, "MPLBACKEND": "Agg", "PATH": bin_dir + os.pathsep + os.environ.get("PATH", "")}
    procs = []
    try:
        for cmd in (sched, worker):
            procs.append(
                subprocess.Popen(
                    shlex.split(local(cmd)),
                    cwd=tmp_path,
                    env=env,
                    stdout=subprocess.DEVNULL,
                    stderr=subprocess.DEVNULL,
                )
            )
            time.sleep(5)
        r = subprocess.run(
            local(sweep), shell=True, cwd=tmp_path, env=env, capture_output=True, text=True, timeout=2400
        )
        assert r.returncode == 0, r.stderr[-3000:]
    finally:
        for p in reversed(procs):
            p.terminate()
            p.wait(timeout=30)
    out = tmp_path / local(sweep).split("--out ")[1].split()[0]
    ds = xr.open_dataset(out / "sweep.nc")
    assert int((ds["error"].values == "").sum()) == ds["error"].size == 25
