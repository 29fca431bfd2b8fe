"""Which stiff method the lubricated four-bar example should ask for: rodas4 against radau5 at the
file's tolerances, CPU per run (best of 5) and distance to a converged run.

    python -m benchmarks.four_bar_solvers

Rows: the example as shipped (``examples/four_bar_lubricated.toml``, π-film) and with its film
made a finite bearing with Reynolds' film end (the model file of ``benchmarks.targets``). Error:
max |Δλ| / max |λ| of the constraint multipliers against radau5 at rtol 1e-11, atol 1e-14.
"""

from __future__ import annotations

import dataclasses
import tempfile
import time

import numpy as np

from benchmarks.targets import ROOT, _finite_four_bar
from jointdyn.io.modelfile import load_model
from jointdyn.simulation.simulate import simulate


def main() -> None:
    print("| model | solver | rtol | CPU per run [ms] | max abs(Δλ)/peak | RHS evaluations |")
    print("|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as d:
        files = {"π-film (as shipped)": str(ROOT / "examples" / "four_bar_lubricated.toml")}
        files["finite, Reynolds end"] = _finite_four_bar(d)
        for name, path in files.items():
            model, cfg = load_model(path)
            system = model.compile()
            ref = simulate(system, dataclasses.replace(cfg, solver="radau5", rtol=1e-11, atol=1e-14))
            for solver in ("rodas4", "radau5"):
                c = dataclasses.replace(cfg, solver=solver)
                simulate(system, c)  # compiled before timing
                runs = []
                for _ in range(5):
                    t0 = time.process_time()
                    res = simulate(system, c)
                    runs.append((time.process_time() - t0, res))
                cpu, res = min(runs, key=lambda r: r[0])
                err = np.abs(res.lam - ref.lam).max() / np.abs(ref.lam).max()
                rhs = res.stats["rhs_evaluations"]
                print(f"| {name} | {solver} | {c.rtol:g} | {1e3 * cpu:.1f} | {err:.2e} | {rhs} |")


if __name__ == "__main__":
    main()
