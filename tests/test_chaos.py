"""Chaos tools: Lyapunov exponents against closed forms, sections, spectra, ensembles, CLI."""

import csv
import json
import math
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from jointdyn.cli import app
from jointdyn.io.modelfile import load_model
from jointdyn.models import slider_crank as sc
from jointdyn.studies.ensemble import band, convergence, revolution_stats
from jointdyn.studies.lyapunov import batch_stderr, benettin, system_lyapunov
from jointdyn.studies.poincare import bushing_frame, journal_relative_state, plane_crossing, stroboscopic
from jointdyn.studies.runs import run_shipped
from jointdyn.studies.spectra import amplitude_spectrum, run_spectra

EXAMPLES = Path(__file__).resolve().parents[1] / "examples"
OMEGA_N = 2 * math.pi  # [rad/s] of examples/oscillator_*.toml
ZETA = 0.05  # [-] of examples/oscillator_damped.toml
runner = CliRunner()


def _oscillator(name):
    model, _ = load_model(EXAMPLES / name)
    return model.compile()


@pytest.mark.parametrize("time_scale", [1 / OMEGA_N, 0.3])
def test_damped_oscillator_exponent_is_minus_zeta_omega(time_scale):
    # both exponents of m ẍ + d ẋ + k x = 0 are −ζω_n [T129]; tolerance 1 % is the issue's
    # requirement (measured: 0.04 % with the matched time scale, ≈ 0.7 % with 0.3 s, the
    # bounded oscillation of the weighted norm over 200 s)
    r = system_lyapunov(
        _oscillator("oscillator_damped.toml"),
        tau=1.0,
        n_segments=200,
        time_scale=time_scale,
        discard_segments=0,
    )
    assert r.exponent == pytest.approx(-ZETA * OMEGA_N, rel=0.01)


@pytest.mark.parametrize("time_scale", [1 / OMEGA_N, 0.3])
def test_undamped_oscillator_exponent_is_zero(time_scale):
    # the flow is a rotation in (x, ẋ/ω_n): λ = 0 [T129]; the bound is 1e-3·ω_n
    # (measured |λ| ≈ 2e-7 1/s: integration error only)
    r = system_lyapunov(
        _oscillator("oscillator_undamped.toml"),
        tau=1.0,
        n_segments=200,
        time_scale=time_scale,
        discard_segments=0,
    )
    assert abs(r.exponent) < 1e-3 * OMEGA_N


def test_benettin_core_on_a_linear_map_with_known_stretching():
    # ẋ = diag(a, b) x over τ exactly: λ₁ = max(a, b) for a generic start [T125]
    a, b = 0.7, -1.3

    def advance(x, t0, t1):
        return x * np.exp(np.array([a, b]) * (t1 - t0))

    r = benettin(
        advance,
        lambda u, v: float(np.linalg.norm(v - u)),
        lambda u, v, f: u + f * (v - u),
        np.zeros(2),  # the fixed point: the deviation evolves exactly linearly
        np.array([0.6e-8, 0.8e-8]),
        0.0,
        0.5,
        100,
        1e-8,
        discard_segments=20,
    )
    assert r.exponent == pytest.approx(
        a, rel=1e-9
    )  # the b-component decays by e^-1 per segment: gone after 20
    assert r.stderr < 1e-9


def test_batch_stderr_of_white_noise():
    # white noise of unit variance, 10 000 samples: s.e. of the mean = 1/100 (±10 % for 20 batches)
    x = np.random.default_rng(3).standard_normal(10_000)
    se, b = batch_stderr(x, 20)
    assert b == 20 and se == pytest.approx(0.01, rel=0.35)  # χ² spread of a 20-batch estimate: ±0.32 at 2σ


def test_sections_of_a_sine_are_exact():
    t = np.linspace(0, 10, 20001)
    w = 2.0
    series = {"x": np.sin(w * t), "v": w * np.cos(w * t)}
    sec = stroboscopic(series, w * t, math.pi / 2, t)  # every period at phase π/2: x = 1, v = 0
    assert np.allclose(sec.values["x"], 1.0, atol=1e-12) and np.allclose(sec.values["v"], 0.0, atol=1e-9)
    pc = plane_crossing(series, "x", 0.0, t, direction=1)  # upward zeros at t = kπ
    assert np.allclose(pc.t, np.pi * np.arange(1, pc.t.size + 1), atol=1e-7)  # linear interpolation: O(h²)
    assert np.allclose(pc.values["v"], w, rtol=1e-6)


def test_journal_relative_velocity_matches_finite_differences():
    # central differences of e converge to the analytic ė at second order: halving h divides the
    # difference by ≈ 4 (measured 3.1–3.3: both runs also differ by the tolerance-level noise);
    # at h = T/3600 the measured difference is 5e-4 (ex) and 4e-5 (ey) of the peak rate
    err = {}
    for spr in (1800, 3600):
        # radau5 named: state error scales ([T186]), whose tolerance-level noise is the one measured
        # above (auto's clearance scales at 300·rtol [T188] leave more)
        res, _, _ = run_shipped(
            "slider-crank", "alshaer2005", 1.0, samples_per_rev=spr, solver="radau5", rtol=1e-8, atol=1e-12
        )
        st = journal_relative_state(res, "piston_pin")
        assert np.allclose(st["ex"], res.element("piston_pin", "ex"), atol=1e-15)
        b = bushing_frame(st)  # the rod-eye frame [T350]: u = A(φ_rod)ᵀ e, u̇ with the frame's rotation
        c = res.clearance("piston_pin")
        ub = res.orbit("piston_pin", frame="bushing")
        assert np.allclose(b["ex"] / c, ub[0], atol=1e-12) and np.allclose(b["ey"] / c, ub[1], atol=1e-12)
        for frame, s in (("world", st), ("bushing", b)):
            for k in ("ex", "ey"):
                fd = np.gradient(s[k], res.t)
                err[spr, frame, k] = (
                    np.abs(fd[5:-5] - s[k + "_dot"][5:-5]).max() / np.abs(s[k + "_dot"]).max()
                )
    for frame in ("world", "bushing"):
        for k in ("ex", "ey"):
            assert err[1800, frame, k] / err[3600, frame, k] > 2.8 and err[3600, frame, k] < 1e-3, (frame, k)


def test_spectrum_of_the_perfect_slider_crank_matches_the_kinematics():
    # slider x(φ) = r cos φ + √(l² − r² sin² φ): the rod term has only even harmonics, so
    # ẍ has harmonic 1 of amplitude r ω² exactly and no odd harmonics ≥ 3 [T130]; harmonic 2
    # from the Fourier coefficient of the exact x(φ) by a 4096-point trapezoidal rule (spectral)
    res, _, _ = run_shipped("slider-crank", "perfect", 4.0, samples_per_rev=720, rtol=1e-11, atol=1e-13)
    sp = run_spectra(res, transient_revs=1, body="slider")
    h, a = sp["harmonic"], sp["body_x_acceleration"]
    r, l, w = sc.CRANK_LENGTH, sc.ROD_LENGTH, sc.SPEED
    assert a[h == 1][0] == pytest.approx(r * w * w, rel=1e-7)  # integration error of q̈, rtol 1e-11
    assert a[h == 3][0] < 1e-7 * r * w * w and a[h == 5][0] < 1e-7 * r * w * w
    phi = np.linspace(0, 2 * np.pi, 4096, endpoint=False)
    x = r * np.cos(phi) + np.sqrt(l * l - (r * np.sin(phi)) ** 2)
    a2 = 4 * w * w * 2 * abs(np.mean(x * np.exp(-2j * phi)))
    assert a[h == 2][0] == pytest.approx(a2, rel=1e-7)
    assert np.all(a[(h % 1) != 0] < 1e-7 * r * w * w)  # periodic: nothing between harmonics


def test_amplitude_spectrum_of_a_cosine():
    n, revs = 720, 3
    x = 2.5 + 4.0 * np.cos(2 * np.pi * 5 * np.arange(n * revs) / n + 0.3)
    h, a = amplitude_spectrum(x, revs)
    assert a[0] == pytest.approx(2.5) and a[h == 5][0] == pytest.approx(4.0)
    assert np.all(a[(h != 0) & (h != 5)] < 1e-12)


def test_revolution_stats_of_the_periodic_perfect_joint():
    res, _, summ = run_shipped("slider-crank", "perfect", 3.0, samples_per_rev=720)
    st = revolution_stats(res, transient_revs=1, element=None)
    assert st["peak_moment"].size == 2
    assert np.allclose(st["peak_moment"], summ["peak_moment"], rtol=1e-6)  # periodic: every revolution alike
    assert np.allclose(st["rms_moment"], st["rms_moment"][0], rtol=1e-6)
    with pytest.raises(ValueError, match="transient_revs"):
        revolution_stats(res, transient_revs=3, element=None)


def test_revolution_stats_count_impacts_of_the_dry_joint():
    res, _, summ = run_shipped("slider-crank", "dry", 3.0, samples_per_rev=720, rtol=1e-8, atol=1e-11)
    st = revolution_stats(res, 0)
    assert st["impacts"].sum() == summ["impacts"]  # the counter is exact over accepted steps
    assert st["max_penetration"].max() <= summ["max_penetration"] + 1e-15  # samples ≤ the peak of δ(t) [T202]


def test_convergence_check_detects_a_shift():
    rng = np.random.default_rng(0)
    same = {"a": {"m": rng.normal(0, 1, 400)}, "b": {"m": rng.normal(0, 1, 400)}}
    moved = {"a": {"m": rng.normal(0, 1, 400)}, "b": {"m": rng.normal(1.0, 1, 400)}}
    assert convergence(same)["m"]["converged"]
    c = convergence(moved)["m"]
    assert not c["converged"] and c["z"] > 5  # a 1σ shift with n = 400: z ≈ 0.5/0.06 ≈ 8
    b = band(np.arange(101.0))
    assert (b["p5"], b["median"], b["p95"]) == (5.0, 50.0, 95.0)


def test_cli_lyapunov_on_a_model_file(tmp_path):
    out = tmp_path / "lyap"
    args = ["lyapunov", str(EXAMPLES / "oscillator_damped.toml"), "--tau", "1", "--segments", "100"]
    r = runner.invoke(app, [*args, "--time-scale", str(1 / OMEGA_N), "--discard", "0", "--out", str(out)])
    assert r.exit_code == 0, r.output
    s = json.loads((out / "summary.json").read_text())
    assert s["largest_lyapunov_exponent"] == pytest.approx(-ZETA * OMEGA_N, rel=0.01)  # the 1 %
    assert (out / "lyapunov.png").exists() and (out / "lyapunov.csv").exists()
    r = runner.invoke(app, ["lyapunov", str(EXAMPLES / "oscillator_damped.toml"), "--out", str(out)])
    assert r.exit_code == 2 and "--tau" in r.output


def test_cli_poincare_and_spectrum(tmp_path):
    out = tmp_path / "dry"
    r = runner.invoke(app, ["run", "slider-crank", "--joint", "dry", "--revs", "6", "--out", str(out)])
    assert r.exit_code == 0, r.output
    for cmd in (
        ["poincare", str(out), "--transient-revs", "1"],
        ["spectrum", str(out), "--transient-revs", "1"],
    ):
        r = runner.invoke(app, cmd)
        assert r.exit_code == 0, r.output
    rows = (out / "poincare.csv").read_text().splitlines()
    assert rows[0].startswith("t,ex_bushing_over_c") and len(rows) == 1 + 6  # revolutions 1…6 at angle 0
    # the section is the saved run's bushing-frame orbit at the section times [T290, T350]: an
    # independent path (the run's own timeseries.csv columns, written when the run was saved)
    with open(out / "timeseries.csv", newline="") as f:
        ts = list(csv.DictReader(f))
    col = {k.split(" [")[0]: k for k in ts[0]}
    t_run = np.array([float(r[col["time"]]) for r in ts])
    for row in csv.DictReader(rows):
        i = int(np.argmin(np.abs(t_run - float(row["t"]))))
        assert abs(t_run[i] - float(row["t"])) < 1e-9  # a section time is an output sample
        for k in ("ex_bushing_over_c", "ey_bushing_over_c"):
            assert float(row[k]) == pytest.approx(float(ts[i][col[k]]), rel=1e-8, abs=1e-9), k
    r = runner.invoke(app, ["poincare", str(out), "--transient-revs", "1", "--plane", "ey_bushing_over_c=0"])
    assert r.exit_code == 0, r.output
    rows = [list(map(float, x.split(","))) for x in (out / "poincare.csv").read_text().splitlines()[1:]]
    assert rows and all(abs(row[2]) < 1e-12 for row in rows)  # ey/c interpolated onto the plane
    r = runner.invoke(app, ["poincare", str(out), "--transient-revs", "1", "--plane", "colour=0"])
    assert r.exit_code == 2 and "ey_bushing_over_c" in r.output
    assert (out / "spectrum.png").exists()


def test_cli_bifurcation_small(tmp_path):
    f = tmp_path / "b.toml"
    f.write_text(
        '[base]\njoint = "dry"\nrtol = 1e-7\natol = 1e-10\n[bifurcation]\nparameter = "clearance"\n'
        "values = [2e-4, 4e-4]\ntransient_revs = 1\nrecord_revs = 2\n"
    )
    out = tmp_path / "bif"
    r = runner.invoke(app, ["bifurcation", str(f), "--out", str(out), "--workers", "1"])
    assert r.exit_code == 0, r.output
    import xarray as xr

    ds = xr.load_dataset(out / "bifurcation.nc", engine="h5netcdf")
    assert ds["ex_bushing_over_c"].shape == (2, 2) and np.isfinite(ds["ex_bushing_over_c"]).all()
    assert (ds["error"] == "").all() and (out / "bifurcation.png").exists()
    f.write_text('[bifurcation]\nparameter = "colour"\nvalues = [1.0]\n')
    r = runner.invoke(app, ["bifurcation", str(f), "--out", str(out)])
    assert r.exit_code == 2 and "clearance" in r.output


@pytest.mark.slow
def test_ueda_oscillator_matches_the_published_exponent():
    # Ueda (1979) ẍ + 0.05 ẋ + x³ = 7.5 cos t: λ₁ = 0.0999 1/s (Sprott, Chaos and Time-Series
    # Analysis, 2003, p. 429; 4th-order Runge–Kutta, h = 0.001) [T129]. Ours over 3000
    # forcing periods; tolerance 3 standard errors of our batch means (measured s.e. ≈ 0.003)
    from jointdyn.studies.lyapunov import ode_lyapunov

    def f(t, x):
        return [x[1], -(x[0] ** 3) - 0.05 * x[1] + 7.5 * math.cos(t)]

    r = ode_lyapunov(f, [2.5, 0.0], 2 * math.pi, 3000, transient=200 * math.pi, rtol=1e-10, atol=1e-12)
    assert abs(r.exponent - 0.0999) < 3 * r.stderr


@pytest.mark.slow
@pytest.mark.parametrize("joint, sign", [("dry", 1), ("alshaer2005", -1)])
def test_slider_crank_exponent_signs(joint, sign):
    # the dry joint is chaotic (λ₁ > 0), the lubricated one settles on a periodic orbit (λ₁ < 0);
    # 3 standard errors of the batch means away from 0 (values in docs/user-guide/chaos.md)
    T = 2 * math.pi / sc.SPEED
    system = sc.slider_crank(joint).compile()
    rtol = 1e-9 if joint == "dry" else 1e-8
    r = system_lyapunov(
        system,
        tau=T / 16,
        n_segments=16 * 30,
        transient=10 * T,
        time_scale=1 / sc.SPEED,
        rtol=rtol,
        atol=rtol * 1e-3,
    )
    assert sign * r.exponent > 3 * r.stderr


def test_sweep_array_output_is_the_runs_own_section(tmp_path):
    # a sweep case with [output.poincare] returns the stroboscopic section of its run: the same
    # numbers (bit for bit: same deterministic run) as sectioning a direct run [T136]
    from jointdyn.studies.bifurcation import section_arrays
    from jointdyn.studies.runs import run_shipped
    from jointdyn.studies.sweep import run_sweep
    from jointdyn.studies.sweep_spec import SweepSpec

    base = {"joint": "dry", "rtol": 1e-7, "atol": 1e-10, "revs": 3, "samples_per_rev": 72}
    poincare = {"transient_revs": 1, "record_revs": 2, "section_angle": 0.0}
    spec = SweepSpec(base=base, grid={"clearance": [3e-4]}, arrays={"poincare": poincare})
    ds = run_sweep(spec, tmp_path / "s", workers=1)
    assert ds["poincare_ex_bushing_over_c"].dims == ("clearance", "rev") and list(ds["rev"].values) == [1, 2]
    res, _, _ = run_shipped(
        "slider-crank", "dry", 3, model_kw={"clearance": 3e-4}, rtol=1e-7, atol=1e-10, samples_per_rev=72
    )
    direct = section_arrays(res, 1, 2, 0.0)
    for k in ("ex_bushing_over_c", "eydot_bushing_over_cw", "impacts_per_rev"):
        np.testing.assert_array_equal(ds[f"poincare_{k}"].values[0], direct[k])


def test_reproduce_ensemble_quotes_the_per_revolution_statistics_of_its_runs():
    # the README/report numbers of the dry case are medians and 5–95 % quantiles of the pooled
    # per-revolution samples [T120, T135]: recomputed here from direct runs of the same cases
    # (replica 0 unperturbed, replica 1 perturbed with seed 1) — equal to round-off
    from jointdyn.studies.ensemble import _run_case
    from jointdyn.studies.reproduce_ensemble import dry_ensemble, ensemble_markdown, ensemble_rows

    kw = {"rtols": (1e-7,), "replicas": 2, "revs": 4, "transient_revs": 1, "samples_per_rev": 720}
    ens = dry_ensemble(workers=1, **kw)
    pooled = {}
    for seed in (0, 1):
        for k, v in _run_case("slider-crank", {"joint": "dry"}, 4, 1, 1e-7, seed, 720).items():
            pooled.setdefault(k, []).extend(v)
    rows = {r["quantity"]: r for r in ensemble_rows(ens)}
    for k, scale in (("peak_moment", 1.0), ("rms_moment", 1.0), ("impacts", 1.0), ("max_penetration", 1e6)):
        x = np.asarray(pooled[k]) * scale
        assert rows[k]["n"] == 6
        assert rows[k]["median"] == pytest.approx(np.median(x), rel=1e-12)
        assert rows[k]["p5"] == pytest.approx(np.quantile(x, 0.05), rel=1e-12)
        assert rows[k]["p95"] == pytest.approx(np.quantile(x, 0.95), rel=1e-12)
    table = ensemble_markdown(ens)
    assert "peak crank moment [N·m]" in table and "rtol 1e-07" in table


def test_bifurcation_on_a_dask_cluster_equals_the_local_run(tmp_path):
    # the diagram is a sweep [T136]: on a Dask LocalCluster it gives the same section points,
    # bit for bit (same compiled code, same inputs), as on local processes
    distributed = pytest.importorskip("distributed", reason="the [dist] extra is needed for Dask")
    from jointdyn.studies.bifurcation import BifurcationSpec, run_bifurcation

    spec = BifurcationSpec(
        base={"joint": "dry", "rtol": 1e-7, "atol": 1e-10},
        parameter="clearance",
        values=(2e-4, 4e-4),
        transient_revs=1,
        record_revs=2,
    )
    local = run_bifurcation(spec, tmp_path / "local", workers=1)
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, host="127.0.0.1", dashboard_address=None, processes=True
    ) as cluster:
        dask = run_bifurcation(spec, tmp_path / "dask", scheduler=cluster.scheduler_address)
    for k in ("ex_bushing_over_c", "eydot_bushing_over_cw", "impacts_per_rev"):
        np.testing.assert_array_equal(local[k].values, dask[k].values)
    assert local["ex_bushing_over_c"].shape == (2, 2) and np.isfinite(local["ex_bushing_over_c"]).all()
