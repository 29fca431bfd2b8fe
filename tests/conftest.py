import json
import os
import sys
import time

import pytest

os.environ.setdefault("MPLBACKEND", "Agg")


def pytest_addoption(parser):
    parser.addoption(
        "--cpu-profile",
        metavar="PREFIX",
        default=None,
        help="write one JSON line per test to PREFIX-<worker>.jsonl: CPU seconds of the test's process "
        "and of its waited-for child processes, numba compile seconds, and the functions compiled "
        "and the kernel sets its runs used (sum them: `python tests/cpu_profile.py PREFIX`)",
    )


class _CpuProfile:
    """Per-test CPU [s] (process + waited-for children) and numba compilation [s]: xdist gives
    wall durations only, and on a shared machine wall time measures the load, not the suite."""

    def __init__(self, path):
        from numba.core import event

        self.out = open(path, "w", encoding="utf-8")  # noqa: SIM115 (closed at unconfigure)
        self.depth, self.t0, self.compile, self.funcs = 0, 0.0, 0.0, []
        profile = self

        class _Compiles(event.Listener):
            def on_start(self, ev):
                if profile.depth == 0:
                    profile.t0 = time.process_time()
                profile.depth += 1
                f = getattr(ev.data.get("dispatcher"), "py_func", None)
                name = f"{getattr(f, '__module__', '?')}.{getattr(f, '__qualname__', '?')}"
                profile.funcs.append([name, str(ev.data.get("args"))])

            def on_end(self, ev):
                profile.depth -= 1
                if profile.depth == 0:
                    profile.compile += time.process_time() - profile.t0

        event.register("numba:compile", _Compiles())
        self.sets: set = set()
        self._record_kernel_sets()

    def _record_kernel_sets(self):
        """Every compiled-driver call adds (method, exact Jacobian, type of the element kinds) —
        the kernel set it runs [T175, T373] — to ``self.sets`` (warm or cold alike)."""
        from numba import typeof

        from jointdyn.forces.kernel_set import kernel_kinds
        from jointdyn.integrators import driver

        real, sets = driver.loop, self.sets

        def loop(stepper, exact):
            packed = sys._getframe(1).f_locals.get("P")  # driver.start and driver.drive call it P
            kinds = str(typeof(kernel_kinds(packed.kernels))) if hasattr(packed, "kernels") else "?"
            sets.add((stepper.name, int(exact) if stepper.reuse is not None else 0, kinds))
            return real(stepper, exact)

        driver.loop = loop

    @pytest.hookimpl(hookwrapper=True)
    def pytest_runtest_protocol(self, item, nextitem):
        t0, c0, k0, n0 = os.times(), time.process_time(), self.compile, len(self.funcs)
        self.sets.clear()
        w0 = time.perf_counter()
        yield
        t1 = os.times()
        rec = {
            "id": item.nodeid,
            "cpu": time.process_time() - c0,
            "child": max(0.0, t1.children_user + t1.children_system - t0.children_user - t0.children_system),
            "wall": time.perf_counter() - w0,
            "compile": self.compile - k0,
            "funcs": self.funcs[n0:],
            "sets": sorted(self.sets),
            # the process so far: start-up, collection and the tests (xdist workers may end
            # without pytest_unconfigure, so every line carries it)
            "process": t1.user + t1.system + t1.children_user + t1.children_system,
        }
        self.out.write(json.dumps(rec) + "\n")
        self.out.flush()

    def close(self):
        t = os.times()  # the whole process: start-up, collection and the tests
        self.out.write(
            json.dumps({"process": t.user + t.system + t.children_user + t.children_system}) + "\n"
        )
        self.out.close()


def pytest_configure(config):
    prefix = config.getoption("--cpu-profile")
    controller = getattr(config.option, "numprocesses", None) and not hasattr(config, "workerinput")
    if prefix and not controller:  # under xdist each worker writes its own file
        worker = os.environ.get("PYTEST_XDIST_WORKER", "main")
        config._cpu_profile = _CpuProfile(f"{prefix}-{worker}.jsonl")
        config.pluginmanager.register(config._cpu_profile, "jointdyn-cpu-profile")


def pytest_unconfigure(config):
    profile = getattr(config, "_cpu_profile", None)
    if profile is not None:
        profile.close()
