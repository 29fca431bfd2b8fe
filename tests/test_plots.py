"""Figures: what the axes show (not pixels): crank-angle axis, last revolutions read 0–360°,
display units and ascending sweep axes, orbit frame, refusals, never overwriting a run's files."""

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pytest
import xarray as xr

from jointdyn import SimConfig, simulate, slider_crank
from jointdyn.models.slider_crank import SPEED
from jointdyn.viz import plots


@pytest.fixture(scope="module")
def lub():
    # 2 revolutions of the lubricated pin, 180 samples per revolution (coarse output is enough here)
    cfg = SimConfig(t_end=2 * 2 * np.pi / SPEED, n_out=361, solver="rodas4", rtol=1e-6, atol=1e-10)
    return simulate(slider_crank("alshaer2005").compile(), cfg)


def test_last_revolution_axis_reads_0_to_360(lub):
    ax = plots.run_figure(lub, "moment", last_revs=1)
    x = ax.lines[0].get_xdata()
    # the driver is exact: the window starts at 360° and ends at 720°, shown as 0…360° (1e-9 deg rounding)
    assert x[0] == pytest.approx(0.0, abs=1e-9) and x[-1] == pytest.approx(360.0, abs=1e-9)
    assert ax.get_xlabel().startswith("crank angle [deg]")
    assert "0.5 mm" in ax.get_title() and "0.4 Pa·s" in ax.get_title() and "5000 rpm" in ax.get_title()
    assert ax.get_legend().get_texts()[0].get_text() == "drive moment"  # the driver's name
    plt.close("all")


def test_orbit_frames_and_default_window(lub):
    ax = plots.run_figure(lub, "orbit")
    path = ax.lines[1]  # lines[0] is the clearance circle
    ex, ey = lub.last_revolutions(1).orbit("piston_pin")
    np.testing.assert_array_equal(path.get_xdata(), ex)  # default: last revolution, bushing frame
    assert "bushing frame" in ax.get_xlabel()
    ax.figure.canvas.draw()  # tick labels are formatted at draw time
    assert [t.get_text() for t in ax.get_xticklabels()] == ["−1.0", "−0.5", "0.0", "0.5", "1.0"]
    ax2 = plots.run_figure(lub, "orbit", frame="world", last_revs=2)
    assert len(ax2.lines[1].get_xdata()) == len(lub.t)
    plt.close("all")


def test_film_is_log_with_minimum_annotated(lub):
    ax = plots.run_figure(lub, "film")
    assert ax.get_yscale() == "log"
    h = lub.element("piston_pin", "h_min") * 1e6
    assert any(f"{h.min():.3g} µm" in t.get_text() for t in ax.texts)
    plt.close("all")


def test_contact_refused_without_contact_law_and_overlay_labels(lub, tmp_path):
    with pytest.raises(ValueError, match="no journal element with a contact law"):
        plots.run_figure(lub, "contact")
    ax = plots.run_figure([lub, lub], "moment", labels=["a", "b"], last_revs=1)
    assert [t.get_text() for t in ax.get_legend().get_texts()] == ["a", "b"]
    plt.close("all")


def test_plot_run_never_overwrites_the_runs_figures(lub, tmp_path):
    lub.save(tmp_path / "results.nc")
    (tmp_path / "moment.png").write_bytes(b"original")
    out = plots.plot_run(tmp_path, "moment")
    assert out.name == "plot_moment.png" and out.stat().st_size > 10_000
    assert (tmp_path / "moment.png").read_bytes() == b"original"
    with pytest.raises(ValueError, match="overwrite"):
        plots.plot_run(tmp_path, "moment", out=tmp_path / "moment.png")


def test_sweep_heat_map_display_units_and_ascending_axes():
    da = xr.DataArray(
        np.arange(6.0).reshape(2, 3),
        dims=("clearance", "viscosity"),
        coords={"clearance": [5e-4, 2.5e-5], "viscosity": [1.0, 0.1, 0.4]},
        name="peak_moment",
    )
    ax = plots.sweep_metric(da)
    ax.figure.canvas.draw()
    assert [t.get_text() for t in ax.get_yticklabels()] == ["25", "500"]  # µm, ascending
    assert [t.get_text() for t in ax.get_xticklabels()] == ["0.1", "0.4", "1"]
    assert ax.get_ylabel() == "clearance [µm]" and ax.get_xlabel() == "viscosity [Pa·s]"
    # cell (c = 25 µm, μ = 0.1) holds the value stored at clearance 2.5e-5, viscosity 0.1: 4
    assert ax.texts[0].get_text() == "4"
    plt.close("all")
