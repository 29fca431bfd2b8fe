"""The inventory of documented commands (``tests/data/documented_commands.toml``): each command the
README, CONTRIBUTING, docs/ and examples/ show is listed with the test that runs it (as written,
in a smaller form, or its computation), or why none does. A newly documented command missing from
the inventory fails here, and so does an entry whose test does not exist or does not run it."""

from __future__ import annotations

import re
import tomllib
from collections import Counter
from pathlib import Path

import pytest
from test_docs_commands import COMMANDS, SNIPPETS, shell_lines

ROOT = Path(__file__).resolve().parents[1]
INVENTORY = ROOT / "tests" / "data" / "documented_commands.toml"
ENTRIES = tomllib.loads(INVENTORY.read_text(encoding="utf-8"))["command"]
BY_TEXT = {e["text"]: e for e in ENTRIES}
STATUSES = {"runs", "reduced", "checked", "ci", "equivalent", "parsed", "not-run"}


def test_every_documented_command_is_in_the_inventory():
    documented = {c for *_, c in COMMANDS}
    missing = sorted(documented - set(BY_TEXT))
    assert not missing, f"add to {INVENTORY.name} (with the test that runs it): {missing}"
    stale = sorted(set(BY_TEXT) - documented)
    assert not stale, f"no longer documented, remove from {INVENTORY.name}: {stale}"
    assert len(BY_TEXT) == len(ENTRIES), "an entry is listed twice"


@pytest.mark.parametrize("entry", ENTRIES, ids=lambda e: e["text"][:60])
def test_each_entry_names_a_test_that_exists_or_says_why_not(entry):
    assert entry["status"] in STATUSES, entry
    page = ROOT / entry["where"]
    assert page.is_file() and entry["text"] in {c for p, _, c in COMMANDS if p == entry["where"]}
    if entry["status"] == "not-run":
        assert entry.get("why") and not entry.get("test"), entry
        return
    if entry["status"] != "runs":
        assert entry.get("why"), f"{entry['status']}: say what is run instead"
    path, name = entry["test"].split("::")
    source = (ROOT / path).read_text(encoding="utf-8")
    assert re.search(rf"^def {name}\(", source, re.M), f"{entry['test']} does not exist"


def test_the_claims_of_the_generic_runners_are_true():
    """An entry that says the slow tier's reader run executes it is among what that test executes;
    ``python -c`` entries are among the snippets run; a parsed entry is a jointdyn line."""
    executed = {c for *_, c in shell_lines()}
    snippets = {c for *_, c in SNIPPETS}
    for e in ENTRIES:
        if e.get("test", "").endswith("::test_documented_commands_run"):
            assert e["text"] in executed, e["text"]
        if e.get("test", "").endswith("::test_documented_python_c_command_runs"):
            assert e["text"] in snippets, e["text"]
        if e["status"] == "parsed":
            assert e["text"].startswith("jointdyn "), e["text"]
    # every command the reader run executes is recorded as run by it
    for c in executed:
        if c.startswith("jointdyn "):
            assert BY_TEXT[c]["status"] == "runs", c


def test_inventory_counts():
    """What the inventory says today (a command moving to 'not-run' shows up in review)."""
    n = Counter(e["status"] for e in ENTRIES)
    assert n["runs"] + n["reduced"] + n["checked"] + n["ci"] + n["equivalent"] >= 50
    assert n["not-run"] <= 4  # the full benchmark table, --peers (Exudyn), two --write timing blocks
