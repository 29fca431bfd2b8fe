"""Features of the paper's four cases (1 crank revolution) pinned by tests/test_golden.py.

Regenerate after an intended change of physics or numerics:

    python tests/golden_features.py   # rewrites tests/data/golden_alshaer2005.json
"""

from __future__ import annotations

import json
from pathlib import Path

from jointdyn.studies.reproduce import PAPER_CASES, run_case

GOLDEN = Path(__file__).parent / "data" / "golden_alshaer2005.json"
REVS = 1.0


def features() -> dict:
    out = {}
    for case in PAPER_CASES:
        res, cols, s = run_case(case, REVS)
        f = {k: float(s[k]) for k in ("peak_moment", "min_moment", "rms_moment")}
        if res.eout.shape[1]:
            f["max_xi"] = float(s["max_xi"])
            f["max_penetration"] = float(s["max_penetration"])
            f["impacts"] = int(s["impacts"])
        out[case.name] = f
    return out


if __name__ == "__main__":
    GOLDEN.write_text(json.dumps(features(), indent=2) + "\n")
    print(f"wrote {GOLDEN}")
