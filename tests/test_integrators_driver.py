"""The shared compiled step-control loop: slicing into many calls is invisible, progress is
reported, SIGINT/SIGTERM stop a run cleanly with partial results."""

import os
import signal
import subprocess
import sys
import textwrap
import time

import numpy as np
import pytest

from jointdyn.errors import Interrupted
from jointdyn.integrators.common import INTERRUPTED
from jointdyn.models import slider_crank as sc
from jointdyn.models.slider_crank import slider_crank_config
from jointdyn.simulation.simulate import simulate

CASES = [("dry", "dopri5"), ("dry", "rodas4"), ("alshaer2005", "rodas4"), ("alshaer2005", "ros34pw2")]


@pytest.mark.parametrize("joint,solver", CASES)
def test_many_small_calls_equal_one_call(joint, solver):
    """Every piece of step-control state is carried across calls: bit-identical trajectories."""
    system = sc.slider_crank(joint).compile()
    cfg = slider_crank_config(joint, 0.1, solver=solver)
    one = simulate(system, cfg, step_budget=10**12)
    calls = []
    many = simulate(system, cfg, step_budget=7, progress=calls.append)
    assert np.array_equal(one.y, many.y)
    assert np.array_equal(one.mem, many.mem)
    assert one.stats == many.stats
    # 7 attempts per call: at least (accepted + rejected)/7 returns to Python, each reported
    steps = one.stats["accepted_steps"] + one.stats["rejected_steps"]
    assert len(calls) >= steps // 7
    assert calls == sorted(calls) and calls[-1] == pytest.approx(1.0, abs=1e-12)
    if joint == "dry":  # the case exercises contact onsets (memory carried across calls)
        assert one.mem[-1, 0, 2] >= 1


def test_handlers_restored_after_run():
    before = signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)
    system = sc.slider_crank("perfect").compile()
    simulate(system, slider_crank_config("perfect", 0.05))
    assert (signal.getsignal(signal.SIGINT), signal.getsignal(signal.SIGTERM)) == before


CHILD = textwrap.dedent(
    """
    import sys, time
    from jointdyn.errors import Interrupted
    from jointdyn.models import slider_crank as sc
    from jointdyn.models.slider_crank import slider_crank_config
    from jointdyn.simulation.simulate import simulate

    joint, solver = sys.argv[1], sys.argv[2]
    system = sc.slider_crank(joint).compile()
    simulate(system, slider_crank_config(joint, 0.01, solver=solver))  # compile outside the timing
    said = []

    def progress(f):
        if not said:
            said.append(1)
            print("running", flush=True)

    try:
        simulate(system, slider_crank_config(joint, 500.0, solver=solver), progress=progress)
        print("finished")
    except Interrupted as e:
        r = e.results
        print("interrupted", e.signal, e.t, len(r.t), r.status, r.t[-1], time.time(), flush=True)
    """
)


@pytest.mark.parametrize(
    "sig,joint,solver",
    [
        (signal.SIGINT, "dry", "dopri5"),
        (signal.SIGTERM, "alshaer2005", "rodas4"),
        (signal.SIGINT, "ott", "scipy-radau"),
    ],
)
def test_signal_stops_run_with_partial_results(sig, joint, solver):
    env = dict(os.environ)
    p = subprocess.Popen(
        [sys.executable, "-c", CHILD, joint, solver],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        env=env,
    )
    try:
        line = p.stdout.readline()  # waits for compilation (cold cache: up to minutes)
        assert line.strip() == "running", p.stderr.read()
        time.sleep(1.0)
        t_sent = time.time()
        p.send_signal(sig)
        out, err = p.communicate(timeout=60)
    finally:
        if p.poll() is None:
            p.kill()
    assert p.returncode == 0, err
    assert "Traceback" not in err and "SystemError" not in err, err
    word, name, t, n, status, t_last, t_done = out.split()
    assert word == "interrupted" and name == signal.Signals(sig).name
    assert int(status) == INTERRUPTED
    assert 0 < float(t) < 500 * 2 * np.pi / sc.SPEED
    assert int(n) > 1 and float(t_last) <= float(t)  # the samples computed so far are kept
    # one compiled call lasts ≈ 0.05 s (simulate.SLICE_SECONDS); allow for a loaded 2-core machine
    assert float(t_done) - t_sent < 2.0


def test_interrupted_in_process(monkeypatch):
    """The exception carries the partial results (status INTERRUPTED), the time and the name."""
    system = sc.slider_crank("dry").compile()
    cfg = slider_crank_config("dry", 0.5)

    def progress(f):
        if f > 0.2:
            os.kill(os.getpid(), signal.SIGTERM)

    with pytest.raises(Interrupted) as ei:
        simulate(system, cfg, progress=progress, step_budget=50)
    e = ei.value
    assert e.signal == "SIGTERM" and e.results.status == INTERRUPTED
    assert 0.2 * cfg.t_end < e.t < cfg.t_end
    assert e.results.t[-1] <= e.t and np.isfinite(e.results.y).all()


def test_scipy_path_keeps_the_samples_before_an_interrupt():
    """solve_ivp is cut by a terminal event at the step where the stop is seen: every sample
    computed before it is kept, identical to the uninterrupted run's."""
    system = sc.slider_crank("ott").compile()
    cfg = slider_crank_config("ott", 2.0, solver="scipy-radau")  # long enough for several reports
    full = simulate(system, cfg)

    def progress(f):
        if 0.3 < f < 1.0:
            os.kill(os.getpid(), signal.SIGTERM)

    with pytest.raises(Interrupted) as ei:
        simulate(system, cfg, progress=progress)
    part = ei.value.results
    n = len(part.t)
    assert part.status == INTERRUPTED and 0.3 * cfg.t_end < ei.value.t < cfg.t_end
    assert 0.3 * len(full.t) < n < len(full.t) and part.t[-1] <= ei.value.t
    assert np.array_equal(part.y, full.y[:n]) and np.array_equal(part.t, full.t[:n])
