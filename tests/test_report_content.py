"""The pendulum_small report says what it said before the edit-loop speed work.

``tests/data/report_content_pendulum_small.json`` was written from release 9b4d653 (the
commit before the staged study budget, SVG-only figures, compiled-once drivers and the
slimmed PDF figures) with ``python tests/report_content.py output/pendulum_small FILE``;
its HTML part was written again for issue 31 (the contents list under the title, the
end time in words in check names, the study table's run count in its method cell) and
for issues 32–33 (citations naming their document, the Sources list, the end variations
of S, the phase-space action and the ω → 0 limit) and issue 41 (the text typeset: real
sub- and superscripts, a × 10ⁿ; library routines in words; the drift's scale), the arrays
kept.
The HTML must have the same sections, headings, figures, fact labels, table headers and
row labels (rows of the timed study excepted), and the archive the same trajectory and
invariants to 1e-12.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from report_content import content

from reportgen.pipeline.stages import run_scene

HERE = Path(__file__).resolve().parent
STORED = HERE / "data" / "report_content_pendulum_small.json"
CONFIG = HERE.parent / "configs" / "pendulum_small.toml"


def test_report_content_unchanged_since_before_the_speed_work(tmp_path):
    outcome = run_scene(str(CONFIG), str(tmp_path), formats=("html",))
    assert outcome.ok, outcome.message
    before = json.loads(STORED.read_text(encoding="utf-8"))
    now = content(tmp_path / "pendulum_small")
    assert now["html"] == before["html"]
    assert set(now["arrays"]) == set(before["arrays"])
    for name, values in before["arrays"].items():
        np.testing.assert_allclose(now["arrays"][name], values, rtol=1e-12, atol=1e-12,
                                   err_msg=name)
