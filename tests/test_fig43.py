"""Fig. 4.3 as the textbook prints it: loops, waves and cusps on the band θ1 = 50°,
θ2 = 60°, each locus once round the band; laid out again for a slide (a row of three,
text ≥ 14 pt, nothing overlapping) and for print (2 + 1); the θ(t) legend off the data."""

from __future__ import annotations

import math
import re

import numpy as np
import pytest
from PIL import Image

from conftest import REPO, without_study
from reportgen.archive.store import read_archive
from reportgen.commands.cli import main
from reportgen.rendering.export import SIZES, SLIDE_MIN_FONT, _scale_text, sized_figures
from reportgen.rendering.plots.layout import Grid, Size, panel_grid

THETA1, THETA2 = math.radians(50.0), math.radians(60.0)  # the textbook's band
CASES = ("loops", "waves", "cusps")
SINGLE = {"heavy_top_fig4.3a": "loops", "heavy_top_fig4.3b": "waves",
          "heavy_top_fig4.3c": "cusps"}


@pytest.fixture(scope="module")
def archives(tmp_path_factory):
    """The four shipped Fig. 4.3 configs run (study off, HTML only): name -> run.h5."""
    root = tmp_path_factory.mktemp("fig43")
    out = {}
    for name in ("heavy_top_fig4.3", *SINGLE):
        config = without_study(REPO / "configs" / f"{name}.toml", root / f"{name}.toml")
        assert main(["run", str(config), "--out", str(root / "out"), "--jobs", "1"]) == 0
        out[name] = root / "out" / name / "run.h5"
    return out


@pytest.fixture(scope="module")
def fig43(archives):
    return read_archive(archives["heavy_top_fig4.3"])


def test_every_shipped_fig43_config_is_on_the_band_50_to_60_degrees(archives, fig43):
    band = fig43.analysis["band"]
    assert abs(band["theta_min"] - THETA1) <= 1e-6 and abs(band["theta_max"] - THETA2) <= 1e-6
    runs = {name: band["runs"][name] for name in CASES}
    for name, single in SINGLE.items():
        runs[name] = read_archive(archives[name]).analysis
        assert runs[name]["case"] == single
    for name, a in runs.items():
        # θ1 = arccos u2, θ2 = arccos u1: the roots of f(u) (10.31) in the archive
        assert abs(math.acos(a["u2"]) - THETA1) <= 1e-6, name
        assert abs(math.acos(a["u1"]) - THETA2) <= 1e-6, name
        # and the integrated θ(t) turns on them
        assert abs(a["theta_min_measured"] - THETA1) <= 1e-6, name
        assert abs(a["theta_max_measured"] - THETA2) <= 1e-6, name
    for name in CASES:
        assert band["runs"][name]["case"] == name


def test_presets_are_the_band_runs_of_fig43():
    # fig4.3a/b/c: released at rest in θ on 50° with the φ̇0, ω3 band_start solves for
    import tomllib

    from reportgen.core import heavy_top_theory as theory
    from reportgen.kinds.heavy_top.config import PRESETS

    for letter, case in zip("abc", CASES, strict=True):
        theta, theta_dot, phi_dot, omega3 = theory.band_start(1.0, 0.5, 1.0, THETA1, THETA2,
                                                              case, None)
        ini = PRESETS[f"fig4.3{letter}"]["initial"]
        assert ini["theta"] == pytest.approx(theta, abs=1e-15) and ini["theta_dot"] == 0.0
        assert ini["phi_dot"] == pytest.approx(phi_dot, rel=1e-14, abs=1e-15)
        assert ini["omega3"] == pytest.approx(omega3, rel=1e-14)
    written = tomllib.loads((REPO / "configs" / "heavy_top_fig4.3a.toml").read_text())
    for key, value in PRESETS["fig4.3a"]["initial"].items():
        assert written["initial"][key] == pytest.approx(value, rel=1e-14, abs=1e-15)


def test_each_panel_goes_once_round_the_band_in_whole_nutation_periods(fig43):
    band = fig43.analysis["band"]
    drawn = {}
    for name in CASES:
        r, run = band["runs"][name], fig43.runs[name]
        stop, periods = int(r["locus_stop"]), int(r["locus_periods"])
        dphi = abs(r["precession_per_period"])
        # the fewest whole periods whose precession covers 2π
        assert periods * dphi >= 2 * math.pi > (periods - 1) * dphi
        # and the drawn stretch holds them: Δφ of the archived φ(t) ≥ 2π
        assert abs(run["phi"][stop - 1] - run["phi"][0]) >= 2 * math.pi
        assert run.t[stop - 1] >= periods * r["nutation_period"]
        assert run.t[stop - 2] < periods * r["nutation_period"]
        drawn[name] = periods
    # on this band (T = 1.3534, 3.3375, 2.1729 s; Δφ = 0.28326, 1.5728, 0.70592 rad)
    assert drawn == {"loops": 23, "waves": 4, "cusps": 9}


@pytest.mark.parametrize("name", list(SINGLE))
def test_each_single_case_run_goes_once_round_the_band(archives, name):
    run = read_archive(archives[name]).runs["main"]
    assert abs(run["phi"][-1] - run["phi"][0]) >= 2 * math.pi


#: matplotlib's mathtext draws a sub- or superscript at this fraction of its text's size
SCRIPT_SCALE = 0.7


def _plain(text: str) -> str:
    """A figure text as written before typesetting: ``ω$_{3}$ =`` as ``ω3 =``."""
    return re.sub(r"\$[_^]\{([^}]*)\}\$", r"\1", text)


def _texts(fig):
    """(text, font size [pt], bounding box in display coordinates) of every visible,
    non-empty text of ``fig`` (titles, annotations, legends)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.text import Text

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    renderer = canvas.get_renderer()
    return [(t.get_text(), t.get_fontsize(), t.get_window_extent(renderer))
            for t in fig.findobj(Text) if t.get_visible() and t.get_text().strip()]


def _overlaps(texts):
    return [(a[0], b[0]) for i, a in enumerate(texts) for b in texts[i + 1:]
            if a[2].overlaps(b[2])]


def _figure(data, size, pattern="fig4_3*"):
    """The one figure of ``data``'s report matching ``pattern``, as exported at ``size``."""
    (fig_id, fig), = ((i, f) for i, f in sized_figures(data, size, only=(pattern,))
                      if f is not None)
    return fig


def _slide_fig43(data, size=SIZES["slide"]):
    return _figure(data, size)


def test_slide_lays_fig43_out_as_a_row_with_large_text_and_no_overlap(fig43):
    fig = _slide_fig43(fig43)
    assert tuple(fig.get_size_inches()) == pytest.approx((10.0, 5.625))
    texts = _texts(fig)
    subtitles = [t for t in texts if _plain(t[0]).startswith("ω3 =")]
    assert len(subtitles) == 3
    assert not _overlaps(texts)  # subtitles, panel labels, circle labels: none touch
    inside = fig.bbox
    for text, size, box in texts:
        assert size >= SLIDE_MIN_FONT, text
        assert inside.x0 <= box.x0 and box.x1 <= inside.x1, text
        assert inside.y0 <= box.y0 and box.y1 <= inside.y1, text
    # a row of three spheres, each a third of the slide's width
    axes = fig.axes
    assert len(axes) == 3
    assert len({round(ax.get_position().y0, 6) for ax in axes}) == 1
    for ax in axes:
        assert ax.get_position().width >= 0.3


def test_overlap_and_font_checks_catch_what_the_stretched_figure_did(fig43):
    # seeded failures: the same three subtitles at 14 pt in a box too narrow for a row
    fig = _slide_fig43(fig43, Size("narrow", 4.0, 3.0, min_font=SLIDE_MIN_FONT))
    assert any(_plain(a).startswith("ω3") and _plain(b).startswith("ω3")
               for a, b in _overlaps(_texts(fig)))
    # and the report's figure stretched to the slide, its text scaled (the old export)
    fig = _figure(fig43, SIZES["report"])
    fig.set_size_inches(10.0, 5.625)
    _scale_text(fig, SIZES["slide"].text_scale)
    assert min(size for _, size, _ in _texts(fig)) < SLIDE_MIN_FONT


def test_slide_export_from_the_shipped_config(archives, tmp_path, cli):
    out = tmp_path / "slide"
    code, _, err = cli("figures", archives["heavy_top_fig4.3"], "--size", "slide", "--dpi",
                       "80", "--format", "png,svg", "--only", "fig4_3*", "--folder", out)
    assert code == 0, err
    assert Image.open(out / "fig4_3-fig4_3.png").size == (800, 450)
    svg = (out / "fig4_3-fig4_3.svg").read_text()
    sizes = [float(s) for s in re.findall(r"font-size: ([\d.]+)px", svg)]
    assert len(sizes) >= 12  # SVG px are points here
    # every glyph at the slide's size, but a sub- or superscript (ω₃, 10⁻¹⁵: mathtext draws
    # scripts at 0.7 of the text they belong to, which is itself at least that size)
    for size in sizes:
        assert size >= SLIDE_MIN_FONT or any(
            abs(size / SCRIPT_SCALE - other) < 0.05 and other >= SLIDE_MIN_FONT
            for other in sizes), size


def test_print_and_report_layouts(fig43):
    fig = _figure(fig43, SIZES["print"])
    width, height = fig.get_size_inches()
    assert width == pytest.approx(6.5) and height <= 6.5
    a, b, c = (ax.get_position() for ax in fig.axes)
    assert a.y0 == pytest.approx(b.y0) and c.y1 < a.y0  # 2 + 1
    assert 0.5 * (c.x0 + c.x1) == pytest.approx(0.5, abs=1e-9)  # the third centred
    assert not _overlaps(_texts(fig))
    # the report: the page's text width, a row, subtitles at 9 pt (were 7 pt on the page)
    fig = _figure(fig43, SIZES["report"])
    assert fig.get_size_inches()[0] == pytest.approx(7.0)
    assert len({round(ax.get_position().y0, 6) for ax in fig.axes}) == 1
    texts = _texts(fig)
    assert min(size for _, size, _ in texts) >= 9.0 and not _overlaps(texts)


def test_panel_grid_picks_the_arrangement_for_the_shape():
    aspect, head = 1.94, 0.9  # Fig. 4.3's cap, two subtitle lines at 14 pt
    assert panel_grid(3, aspect, 10.0, 5.625, head=head).rows == 1  # 16:9: a row
    assert panel_grid(3, aspect, 6.5, 6.5, head=head).rows == 2  # print: 2 + 1
    assert panel_grid(3, aspect, 3.0, 9.0, head=head).rows == 3  # tall: stacked
    assert Grid(2, 2, 1.0).slots(3) == [(0, 0.0), (0, 1.0), (1, 0.5)]


def test_theta_legend_is_off_the_data(archives):
    data = read_archive(archives["heavy_top_fig4.3a"])
    fig = _figure(data, SIZES["report"], "time_series*")
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    canvas = FigureCanvasAgg(fig)
    canvas.draw()
    legend = fig.legends[0].get_window_extent(canvas.get_renderer())
    for ax in fig.axes:
        assert not legend.overlaps(ax.get_window_extent())
    assert np.ptp(fig.axes[0].lines[0].get_ydata()) > 0.1  # θ(t) fills its axes
