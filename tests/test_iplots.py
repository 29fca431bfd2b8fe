"""Interactive (plotly) figures carry the same data, labels and scales as the matplotlib ones."""

import numpy as np
import pytest

pytest.importorskip("plotly")

from jointdyn import SimConfig, iplots, simulate, slider_crank  # noqa: E402
from jointdyn.models.slider_crank import SPEED  # noqa: E402


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
