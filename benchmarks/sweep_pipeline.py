"""A 2000-member pendulum sweep end to end: ``reportgen run`` of one config (CLI, archive,
figures, HTML and PDF report) against Python loops of scipy DOP853 runs of the same
members, measured in one call.

Run ``python benchmarks/sweep_pipeline.py [repeats]`` (default 3 for ours; each scipy
loop runs once: it takes tens of seconds).

The sweep: theta0 in [0.01, 3.1] from rest, g = 9.81, l = 1 (``CONFIG`` below; the
members, their exact periods and the scipy loop are ``sweep_pendulum.py``'s).  Each
member's period is compared with T = 4 K(k) sqrt(l/g), k = sin(theta0 / 2) (DLMF 19.2.8,
22.19(i)).  The loops are the scripts a user would write, a plain Python right-hand side
and ``solve_ivp(..., method="DOP853", events=upward)`` per member:

* *at the config's settings*: over the config's ``t_end`` at its rtol 1e-12, atol 1e-14,
  the period from the first two upward crossings of theta (what one run per member of
  this scene would compute);
* *least work*: rtol 1e-10, atol 1e-12, stopped at the second crossing (``terminal = 2``),
  horizon 2.2 T: scipy's cheapest way to a period, with a larger error than ours.

``reportgen run`` is timed as a whole process (``--force``: every stage runs) after one
untimed run that fills numba's cache; the median of ``repeats`` is quoted.
"""

from __future__ import annotations

import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from sweep_pendulum import THETA0, G, L, max_error, scipy_periods

T_END = 12.0
CONFIG = f"""kind = "pendulum"
title = "Period against amplitude: 2000 members"

[params]
g = {G}
l = {L}

[initial]
theta = 1.0

[run]
t_end = {T_END}
samples = 1201

[sweep]
initial.theta = {{ start = 0.01, stop = 3.1, num = 2000 }}
store = 5
"""


def ours(repeats: int) -> tuple[float, float]:
    """(median wall time of ``reportgen run``, max period error read from the archive)."""
    from reportgen.archive.store import read_archive

    with tempfile.TemporaryDirectory(prefix="reportgen-sweep-") as tmp:
        config = Path(tmp) / "pendulum_period_sweep.toml"
        config.write_text(CONFIG, encoding="utf-8")
        command = [sys.executable, "-m", "reportgen", "run", str(config), "--out",
                   str(Path(tmp) / "out"), "--force"]
        subprocess.run(command, check=True, capture_output=True)  # fills numba's cache
        times = []
        for _ in range(repeats):
            t = time.perf_counter()
            subprocess.run(command, check=True, capture_output=True)
            times.append(time.perf_counter() - t)
        data = read_archive(Path(tmp) / "out" / config.stem / "run.h5")
        sweep = data.sweep
        assert np.allclose(sweep.values["initial.theta"], THETA0)
        return float(np.median(times)), max_error(sweep.analysis["period_measured"])


def main(repeats: int = 3) -> None:
    t_ours, err_ours = ours(repeats)
    rows = []
    for label, rtol, atol, least in (("scipy loop at the config's settings (rtol 1e-12)",
                                      1e-12, 1e-14, False),
                                     ("scipy loop, least work (rtol 1e-10, terminal)",
                                      1e-10, 1e-12, True)):
        t = time.perf_counter()
        periods = scipy_periods(THETA0, rtol, atol, t_end=None if least else T_END)
        rows.append((label, time.perf_counter() - t, max_error(periods)))
    print(f"pendulum period sweep, {THETA0.size} members, error = max |T / (4K(k)sqrt(l/g)) - 1|")
    print(f"  {'run':52s} {'wall time':>10s} {'max error':>10s} {'ratio':>8s}")
    print(f"  {'reportgen run (CLI, archive, figures, HTML, PDF)':52s} {t_ours:8.2f} s "
          f"{err_ours:10.2e} {'1':>8s}")
    for label, t, err in rows:
        print(f"  {label:52s} {t:8.2f} s {err:10.2e} {t / t_ours:7.1f}x")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 3)
