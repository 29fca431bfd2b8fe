"""Interactive (plotly) figures carry the same data, labels and scales as the matplotlib ones."""

import numpy as np
import pytest

pytest.importorskip("plotly")

from jointdyn import SimConfig, simulate, slider_crank  # noqa: E402
from jointdyn.models.slider_crank import SPEED  # noqa: E402
from jointdyn.viz import iplots  # noqa: E402


@pytest.fixture(scope="module")
def dry():
    # half a revolution of the dry pin (impacts within the first ~90°), coarse output
    cfg = SimConfig(t_end=0.5 * 2 * np.pi / SPEED, n_out=181, rtol=1e-7, atol=1e-11)
    return simulate(slider_crank("dry").compile(), cfg)


def test_moment_traces_are_the_data(dry):
    fig = iplots.run_figure(dry, "moment")
    tr = fig.data[0]
    np.testing.assert_array_equal(tr.y, dry.multipliers("drive")[:, 0])  # same numbers, no resampling
    assert tr.name == "drive moment" and fig.layout.xaxis.title.text == "crank angle [deg]"
    assert "c = 0.5 mm" in fig.layout.title.text


def test_orbit_keeps_equal_aspect_and_film_log_scale(dry):
    fig = iplots.run_figure(dry, "orbit", last_revs=0.25)
    assert fig.layout.yaxis.scaleanchor == "x"
    assert fig.data[0].name == "clearance circle (ξ = 1)"
    film = iplots.run_figure(dry, "film")
    # a dry gap goes negative during contact: linear axis, the minimum (a penetration) annotated
    assert film.layout.yaxis.type != "log" and "penetration" in film.layout.yaxis.title.text
    assert film.layout.annotations[0].text.startswith("min -")


def _plot_args(html: str, div: str):
    """The data and layout literals of ``Plotly.newPlot(div, data, layout, …)`` in a page."""
    import json

    dec = json.JSONDecoder()
    i = html.index(f"Plotly.newPlot('{div}', ") + len(f"Plotly.newPlot('{div}', ")
    data, j = dec.raw_decode(html, i)
    layout, _ = dec.raw_decode(html, j + 2)
    return data, layout


def test_reproduction_page_carries_the_runs_and_plotly_js(dry, tmp_path):
    from jointdyn import post
    from jointdyn.studies.reproduce import PAPER_CASES

    case = next(c for c in PAPER_CASES if c.name == "dry")
    out = iplots.reproduction_html({"dry": (dry, None, None, case)}, tmp_path / "i.html", 0.5)
    html = out.read_text(encoding="utf-8")
    assert html.count("<script>") == 3  # plotly.js once (offline page), then the two figures
    data, layout = _plot_args(html, "moment")
    a = dry.crank_angle()
    np.testing.assert_array_equal(data[0]["x"], np.degrees(a - a[0]))  # the numbers, unrounded
    np.testing.assert_array_equal(data[0]["y"], post.driving_moment(dry))
    assert data[0]["name"] == case.label and layout["yaxis"]["title"]["text"] == "moment [N·m]"
    orbit, olay = _plot_args(html, "orbit")
    ex, ey = dry.last_revolutions(0.5).orbit("piston_pin")
    np.testing.assert_array_equal(orbit[1]["x"], ex)
    marks = orbit[2]  # start ○, end × and three heads pointing the way the journal moves [T290]
    assert marks["x"][:2] == [ex[0], ex[-1]] and marks["marker"]["symbol"][:2] == ["circle-open", "x"]
    assert len(marks["x"]) == 5
    for x, y, up in zip(marks["x"][2:], marks["y"][2:], marks["marker"]["angle"][2:]):
        i = int(np.flatnonzero((ex == x) & (ey == y))[0])
        step = np.array([ex[i + 1] - ex[i], ey[i + 1] - ey[i]])
        head = np.array([np.sin(np.radians(up)), np.cos(np.radians(up))])  # plotly: clockwise from up
        assert head @ step / np.linalg.norm(step) > 0.999
    assert olay["yaxis"]["scaleanchor"] == "x"  # e/c drawn at equal aspect


def test_page_literals_cannot_end_the_script_tag():
    assert (
        iplots._js({"name": "a</script>b", "y": np.array([1.0, np.nan])})
        == '{"name": "a<\\/script>b", "y": [1.0, NaN]}'
    )
