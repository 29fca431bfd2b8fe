"""What the docs and the example files say about themselves is true: a file shown in the docs is
shown verbatim, an example's comments match its settings, and its "Run:" line does not collide
with the README's main job."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

from typer.testing import CliRunner

from jointdyn.cli import app

ROOT = Path(__file__).resolve().parents[1]


def test_the_sweep_file_in_the_guide_is_the_shipped_file_verbatim():
    guide = (ROOT / "docs" / "user-guide" / "sweeps.md").read_text(encoding="utf-8")
    block = re.search(r"```toml\n# examples/sweep_clearance_viscosity\.toml[^\n]*\n(.*?)```", guide, re.S)
    assert block, "the guide no longer shows the shipped sweep file"
    shipped = (ROOT / "examples" / "sweep_clearance_viscosity.toml").read_text(encoding="utf-8")
    assert block.group(1) == shipped


def test_example_comments_name_the_solver_the_file_uses():
    for path in sorted((ROOT / "examples").glob("*.toml")):
        text = path.read_text(encoding="utf-8")
        solver = tomllib.loads(text).get("simulation", {}).get("solver", "auto")
        comments = " ".join(line.lstrip("# ") for line in text.splitlines() if line.lstrip().startswith("#"))
        for named in re.findall(r"asks for the [\w-]+ solver (\w+)", comments):
            assert named == solver, f"{path.name}: the comment says {named}, the file uses {solver}"
        # the library's default is solver = "auto" (radau5 for a lubricated bearing, else dopri5)
        assert not re.search(r"(rodas4|ros34pw2) is the default", comments), path.name


def test_example_run_lines_do_not_write_into_the_main_job_directory():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    main_out = re.search(r"jointdyn reproduce alshaer2005 --out (\S+)", readme).group(1)
    for path in sorted((ROOT / "examples").glob("*.toml")):
        for out in re.findall(r"--out (\S+)", path.read_text(encoding="utf-8")):
            assert not out.rstrip("/").startswith(main_out.rstrip("/")), f"{path.name}: --out {out}"


def test_plot_help_lists_every_thing_it_draws():
    text = CliRunner().invoke(app, ["plot", "--help"], terminal_width=200).output
    for what in ("moment", "orbit", "film", "contact", "energy", "pressure"):
        assert what in text, what


VENV = "python3 -m venv .venv && . .venv/bin/activate"


def _bash_blocks(text: str) -> list[str]:
    return [b.strip() for b in re.findall(r"^```bash\n(.*?)^```", text, re.S | re.M)]


def test_ci_run_is_what_the_readme_says():
    """README: `.ci/run` installs chromium when it is missing, then runs exactly the second command
    (issue 29: the description was not exact). The script's command line is the README's test
    block verbatim, and its only other action is the chromium install the README names."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    blocks = _bash_blocks(readme)
    test_cmd = next(b for b in blocks if "pytest" in b)
    lines = [ln.strip() for ln in (ROOT / ".ci" / "run").read_text(encoding="utf-8").splitlines()]
    code = [ln for ln in lines if ln and not ln.startswith("#")]
    assert code[-1] == test_cmd
    others = [ln for ln in code[:-1] if not ln.startswith(("set -", "cd ", "if ", "fi", "||", "("))]
    assert others == [], others  # nothing else runs
    assert "chromium" in "".join(code) and "`.ci/run` installs Debian's `chromium`" in " ".join(
        readme.split()
    )
    assert "runs exactly the second command" in " ".join(readme.split())


def test_every_install_page_makes_the_venv_first_and_states_the_test_duration():
    """The README, the docs home and getting started all say to make a virtual environment first
    (PEP 668) with the same line, and state what the test command costs."""
    for page in ("README.md", "docs/index.md", "docs/getting-started.md"):
        text = " ".join((ROOT / page).read_text(encoding="utf-8").split())
        assert VENV in text and "PEP 668" in text, page
        assert "650 CPU-seconds" in text and "3 min warm" in text, page
    assert _bash_blocks((ROOT / "README.md").read_text(encoding="utf-8"))[0] == VENV
