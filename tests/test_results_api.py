"""Results API: top-level exports, save/load round trip with checksums, tidy xarray/pandas views
with units, accessors, short reprs."""

import os

import numpy as np
import pytest

import jointdyn
from jointdyn import Results, SimConfig, load, simulate, slider_crank


@pytest.fixture(scope="module")
def dry():
    # 0.1 crank revolution of the dry pin: has contact memory, fast (≈ 0.1 s warm)
    system = slider_crank("dry").compile()
    return simulate(
        system, SimConfig(t_end=0.1 * 2 * np.pi / 523.5987755982989, n_out=73, rtol=1e-7, atol=1e-11)
    )


def test_top_level_exports_are_the_functions_not_modules():
    assert callable(jointdyn.simulate) and jointdyn.simulate.__name__ == "simulate"
    assert jointdyn.load == Results.load
    assert isinstance(jointdyn.__version__, str)
    for name in jointdyn.__all__:
        assert hasattr(jointdyn, name), name


def test_save_load_round_trip_is_bit_exact_and_post_works(dry, tmp_path):
    f = tmp_path / "r.nc"
    dry.save(f)
    assert [p.name for p in tmp_path.iterdir()] == ["r.nc"]  # the temporary file was renamed away
    back = load(f)
    assert isinstance(back, Results)
    for a in ("t", "y", "mem", "qdd", "lam", "eout", "drift"):
        np.testing.assert_array_equal(getattr(back, a), getattr(dry, a), err_msg=a)  # float64 stored as is
    assert back.stats == dry.stats and back.config == dry.config
    assert jointdyn.post.impacts(back, "piston_pin") == jointdyn.post.impacts(dry, "piston_pin")
    assert back.clearance("piston_pin") == pytest.approx(0.5e-3, rel=1e-12)  # 10.5 mm − 10 mm


def test_corrupt_file_raises_one_line_error(dry, tmp_path):
    f = tmp_path / "r.nc"
    dry.save(f)
    import h5py

    with h5py.File(f, "r") as h:  # where the element outputs' (checksummed) data sits in the file
        chunk = h["element_outputs"].id.get_chunk_info(0)
    raw = bytearray(f.read_bytes())
    a, n = chunk.byte_offset, min(chunk.size, 4096)
    raw[a : a + n] = bytes(b ^ 0xFF for b in raw[a : a + n])
    bad = tmp_path / "bad.nc"
    bad.write_bytes(bytes(raw))
    with pytest.raises(ValueError, match="corrupt") as e:
        Results.load(bad)
    assert "\n" not in str(e.value)
    (tmp_path / "short.nc").write_bytes(f.read_bytes()[:4000])
    with pytest.raises(ValueError, match="corrupt"):
        Results.load(tmp_path / "short.nc")


def test_failed_save_leaves_no_file_and_keeps_the_old_one(dry, tmp_path, monkeypatch):
    f = tmp_path / "r.nc"
    dry.save(f)
    before = f.read_bytes()

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(os, "replace", boom)
    with pytest.raises(RuntimeError):
        dry.save(f)
    assert f.read_bytes() == before and [p.name for p in tmp_path.iterdir()] == ["r.nc"]


def test_to_xarray_names_and_units(dry):
    ds = dry.to_xarray()
    assert all("units" in ds[v].attrs for v in ds.variables)
    assert ds["piston_pin.xi"].attrs["units"] == "-" and ds["piston_pin.Fx"].attrs["units"] == "N"
    assert ds["piston_pin.memory.max_penetration"].attrs["units"] == "m"
    assert ds["drive.lambda"].attrs["units"] == "N·m" and ds["crank.phi"].attrs["units"] == "rad"
    np.testing.assert_array_equal(ds["piston_pin.h_min"].values, dry.element("piston_pin", "h_min"))
    np.testing.assert_array_equal(ds["drive.lambda"].values, jointdyn.post.driving_moment(dry))
    raw = dry.to_dataset()
    assert all("units" in raw[v].attrs for v in raw.data_vars)


def test_to_dataframe_element(dry):
    df = dry.to_dataframe(element="piston_pin")
    assert list(df.columns[:3]) == ["ex", "ey", "xi"] and "memory.impacts" in df.columns
    assert df.index.name == "time" and df.attrs["units"]["xi"] == "-"
    with pytest.raises(KeyError, match="elements are"):
        dry.to_dataframe(element="pin")


def test_accessors(dry):
    ex, ey = dry.orbit("piston_pin", frame="world")
    bx, by = dry.orbit("piston_pin")
    # a rotation keeps |e|: agreement to rounding of the 2x2 rotation (a few ulp of ξ ≤ ~1.2)
    np.testing.assert_allclose(np.hypot(ex, ey), np.hypot(bx, by), rtol=0, atol=1e-14)
    np.testing.assert_allclose(np.hypot(ex, ey), dry.element("piston_pin", "xi"), rtol=0, atol=1e-12)
    with pytest.raises(ValueError, match="frame"):
        dry.orbit("piston_pin", frame="rod")
    half = dry.last_revolutions(0.05)
    a = half.crank_angle()
    # 72 samples per 0.1 rev: the last 0.05 rev holds 37 samples, exactly 18° wide (driver exact)
    assert len(half.t) == 37 and np.degrees(a[-1] - a[0]) == pytest.approx(18.0, abs=1e-9)
    with pytest.raises(ValueError, match="revolutions"):
        dry.last_revolutions(2)
    with pytest.raises(KeyError, match="valid"):
        dry.element("piston_pin", "x")


def test_reprs_are_short(dry):
    assert len(repr(dry)) < 400 and "piston_pin" in repr(dry)
    assert dry._repr_html_().startswith("<table>")
