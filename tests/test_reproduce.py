"""`jointdyn reproduce alshaer2005`: files, summary, and the report renders in a browser."""

import csv
import re
import shutil
import subprocess

import pytest

from jointdyn.studies.reproduce import SUMMARY_COLUMNS, reproduce_alshaer2005


@pytest.fixture(scope="module")
def quick_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("repro")
    runs = reproduce_alshaer2005(out, beyond=False, revs=0.25)
    return out, runs


def test_files_and_summary(quick_run):
    out, runs = quick_run
    for name in ("perfect", "dry", "ott", "alshaer2005"):
        assert (out / f"{name}.csv").stat().st_size > 0
        assert (out / f"moment_{name}.png").stat().st_size > 1000
    for name in ("dry", "ott", "alshaer2005"):
        assert (out / f"orbit_{name}.png").exists()
    with open(out / "summary.csv") as f:
        rows = list(csv.DictReader(f))
    assert tuple(rows[0]) == SUMMARY_COLUMNS
    assert [r["case"] for r in rows] == ["perfect", "dry", "ott", "alshaer2005"]
    with open(out / "ott.csv") as f:
        header = next(csv.reader(f))
    # units in the headers; the orbit in the bushing frame [T290]
    assert header[:5] == [
        "t [s]",
        "crank_angle [rad]",
        "crank_moment [N·m]",
        "ex_bushing_over_c [-]",
        "ey_bushing_over_c [-]",
    ]


def _browser():
    for b in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(b):
            return shutil.which(b)
    return None


def test_report_renders_with_images_in_headless_browser(quick_run, tmp_path):
    browser = _browser()
    if browser is None:  # .ci/run installs Debian's chromium; a bare dev machine may not have it
        pytest.skip("no headless chromium on this machine (apt-get install chromium)")
    out, _ = quick_run
    page = (out / "report.html").read_text()
    probe = (
        "<script>window.addEventListener('load',()=>{const n=[...document.images]"
        ".filter(i=>i.complete&&i.naturalWidth>0).length;document.body.setAttribute('data-loaded',n);"
        "document.body.setAttribute('data-total',document.images.length);"
        "document.body.setAttribute('data-sw',document.documentElement.scrollWidth);"
        "document.body.setAttribute('data-iw',window.innerWidth)});</script></body>"
    )
    test_page = tmp_path / "probe.html"
    test_page.write_text(page.replace("</body>", probe))
    flags = [
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        f"--user-data-dir={tmp_path / 'profile'}",
        "--virtual-time-budget=10000",
    ]
    dom = subprocess.run(
        [browser, *flags, "--window-size=1400,1000", "--dump-dom", test_page.as_uri()],
        capture_output=True,
        text=True,
        timeout=120,
    ).stdout
    loaded = int(re.search(r'data-loaded="(\d+)"', dom).group(1))
    total = int(re.search(r'data-total="(\d+)"', dom).group(1))
    assert total >= 8 and loaded == total
    # issue 29: the summary table overflowed a 1400 px window; nothing may be wider than the window
    sw, iw = (int(re.search(rf'data-{k}="(\d+)"', dom).group(1)) for k in ("sw", "iw"))
    assert 0 < sw <= iw, (sw, iw)
    shot = tmp_path / "shot.png"
    subprocess.run(
        [browser, *flags, f"--screenshot={shot}", "--window-size=1200,2000", test_page.as_uri()],
        capture_output=True,
        timeout=120,
    )
    assert shot.stat().st_size > 20_000  # a rendered page with figures, not a blank one
