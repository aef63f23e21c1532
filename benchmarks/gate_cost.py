"""What the document gate costs (reportgen/rendering/gate.py): the page rules on a laid-out
12-page document and the figure rules on a four-axes figure with 80,000 points.  A
timing, so a script and not a test (timed unit tests flake on shared machines).

    python benchmarks/gate_cost.py
"""

from __future__ import annotations

import io
import time

import numpy as np
import weasyprint
from matplotlib.figure import Figure

from reportgen.rendering.gate import figure_findings, page_findings


def best_of(fn, repeats: int = 5) -> float:
    times = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    body = "<p>" + " ".join(["pendulum"] * 500) + "</p>"
    page = ("<html><body><h1>t</h1>" + body * 12
            + "<table><tr><td>1.0</td></tr></table>" * 50
            + '<section id="config"><pre>kind = "pendulum"</pre></section></body></html>')
    doc = weasyprint.HTML(string=page).render()
    fig = Figure(figsize=(8, 6), layout="constrained")
    x = np.linspace(0, 10, 20_000)
    for i, ax in enumerate(fig.subplots(2, 2).ravel()):
        for k in range(4):
            ax.plot(x, np.sin(x + k + i), label=f"run {k}")
        ax.set(xlabel="time t [s]", ylabel="θ [rad]")
        ax.legend(loc="best")
    fig.savefig(io.BytesIO(), format="svg")
    print(f"page rules:   {best_of(lambda: page_findings(doc)) * 1e3:7.1f} ms "
          f"({len(doc.pages)} pages)")
    print(f"figure rules: {best_of(lambda: figure_findings(fig)) * 1e3:7.1f} ms "
          "(4 axes, 16 lines, 80,000 points)")


if __name__ == "__main__":
    main()
