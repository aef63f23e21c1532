"""The report as a person sees it: a real headless Chromium and poppler's rasterizer.

Both come from Debian packages that `make test` installs (chromium, poppler-utils).
"""

from __future__ import annotations

import re
import shutil
import subprocess

import numpy as np
import pytest
from matplotlib import image as mpimg

from conftest import pendulum_text
from reportgen.pipeline.stages import run_batch

CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
PDFTOPPM = shutil.which("pdftoppm")
FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--disable-quic"]

RENDER_CHECK = """
<script>
(function () {
  var svgs = Array.from(document.querySelectorAll("figure svg"));
  var empty = svgs.filter(function (s) {
    var r = s.getBoundingClientRect(); return r.width < 50 || r.height < 50; }).length;
  var eqs = Array.from(document.querySelectorAll(".eq svg"));
  empty += eqs.filter(function (s) {  /* a typeset equation: a line's height, some width */
    var r = s.getBoundingClientRect(); return r.width < 10 || r.height < 8; }).length;
  var imgs = Array.from(document.images);
  var broken = imgs.filter(function (i) { return !i.complete || i.naturalWidth === 0; }).length;
  var d = document.createElement("div"); d.id = "render-check";
  d.textContent = "svgs=" + svgs.length + " eqs=" + eqs.length + " empty=" + empty +
                  " broken=" + broken;
  document.body.appendChild(d);
})();
</script>
"""


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    root = tmp_path_factory.mktemp("browser")
    cfg = root / "shown.toml"
    cfg.write_text(pendulum_text(theta=2.0, t_end=6.0, samples=601, study="true"))
    (outcome,) = run_batch([str(cfg)], out_root=str(root / "out"), jobs=1)
    assert outcome.ok
    return root / "out" / "shown"


def _chromium(args, tmp_path):
    return subprocess.run([CHROMIUM, *FLAGS, f"--user-data-dir={tmp_path / 'profile'}", *args],
                          capture_output=True, text=True, timeout=120)


@pytest.mark.skipif(CHROMIUM is None, reason="chromium not installed (make test installs it)")
def test_html_renders_in_chromium_with_no_broken_figure(report, tmp_path):
    page = tmp_path / "page.html"
    html = (report / "report.html").read_text()
    page.write_text(html.replace("</body>", RENDER_CHECK + "</body>"))
    dom = _chromium(["--virtual-time-budget=5000", "--dump-dom", page.as_uri()], tmp_path).stdout
    found = re.search(r'id="render-check">svgs=(\d+) eqs=(\d+) empty=(\d+) broken=(\d+)', dom)
    assert found, dom[-500:]
    svgs, eqs, empty, broken = map(int, found.groups())
    assert svgs >= 6 and eqs >= 3 and empty == 0 and broken == 0

    shot = tmp_path / "shot.png"
    _chromium(["--window-size=1200,1600", f"--screenshot={shot}", (report / "report.html")
               .as_uri()], tmp_path)
    pixels = mpimg.imread(shot)
    assert pixels.shape[0] == 1600 and pixels.shape[1] == 1200
    assert np.std(pixels[..., :3]) > 0.05  # text and figures, not a blank page


@pytest.mark.skipif(PDFTOPPM is None, reason="pdftoppm not installed (make test installs it)")
def test_pdf_first_page_rasterizes(report, tmp_path):
    subprocess.run([PDFTOPPM, "-r", "50", "-f", "1", "-l", "1", "-png",
                    str(report / "report.pdf"), str(tmp_path / "page")], check=True, timeout=120)
    (png,) = tmp_path.glob("page*.png")
    pixels = mpimg.imread(png)
    assert pixels.shape[0] > 500  # A4 at 50 dpi is 585 px tall
    assert np.std(pixels[..., :3]) > 0.05
