"""The heavy top's nutation band in degrees, and its citations naming their document.

The band's turning circles θ1 = arccos u2, θ2 = arccos u1 (notes (10.31)) are shown in
degrees where a lecturer reads them (facts, captions, table captions), with radians beside
where the number also enters a formula.  A band config asks for θmin, θmax in radians and the
release is solved so that they are the turning circles (textbook Fig. 4.3), so the degrees
shown are math.degrees of the configured values, recomputed here.
"""

from __future__ import annotations

import html
import math
import re
import textwrap

import pytest


def visible(page: str) -> str:
    """The words a reader sees, without figures, equations, the configuration listing and the
    headline checks table (its rows are the simulation's checks, cited there)."""
    for pattern in (r"<svg.*?</svg>", r"<style.*?</style>", r'<pre class="config">.*?</pre>',
                    r"<head>.*?</head>", r'<table class="checks">.*?</table>'):
        page = re.sub(pattern, " ", page, flags=re.S)
    page = re.sub(r"</?su[bp]>", "", page)  # typeset subscripts (θ<sub>1</sub>) read as θ1
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", page)).split())


def report(cli, tmp_path, name, text) -> str:
    cfg = tmp_path / f"{name}.toml"
    cfg.write_text(textwrap.dedent(text).lstrip(), encoding="utf-8")
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    return visible((tmp_path / "o" / name / "report.html").read_text(encoding="utf-8"))


def deg(x: float) -> str:
    """Six significant figures, as the report's fmt prints them (no trailing zeros)."""
    return f"{math.degrees(x):.6g}"


@pytest.fixture(scope="module")
def band_page(tmp_path_factory):
    from reportgen.commands.cli import main

    tmp = tmp_path_factory.mktemp("band")
    cfg = tmp / "band.toml"
    cfg.write_text(textwrap.dedent("""
        kind = "heavy_top"
        [params]
        I1 = 1.0
        I3 = 0.5
        Mgl = 1.0
        [band]
        theta_min = 0.6
        theta_max = 1.1
        case = "loops"
        [run]
        t_end = 10.0
        samples = 1000
        study = false
        """).lstrip(), encoding="utf-8")
    assert main(["run", str(cfg), "--out", str(tmp / "o"), "--jobs", "1", "--format",
                 "html"]) == 0
    return visible((tmp / "o" / "band" / "report.html").read_text(encoding="utf-8"))


def test_band_asked_for_is_shown_in_degrees_with_radians_beside(band_page):
    # 0.6 rad = 34.3775°, 1.1 rad = 63.0254°
    assert f"θmin = {deg(0.6)}° (0.6 rad), θmax = {deg(1.1)}° (1.1 rad)" in band_page
    # the turning circles of the solved release are the band (to round-off at 6 figures)
    assert (f"θ1 = arccos u2 = {deg(0.6)}° (0.6 rad), θ2 = arccos u1 = {deg(1.1)}° (1.1 rad)"
            in band_page)  # the nutation locus's facts
    assert (f"upper turning circle θ1 = arccos u2 = {deg(0.6)}°, dash-dotted: the lower one "
            f"θ2 = arccos u1 = {deg(1.1)}°" in band_page)  # its caption
    assert f"loops between θ1 = {math.degrees(0.6):.3g}° and θ2 = 63°" in band_page  # prose
    assert "0.6 rad, θmax = 1.1 rad" not in band_page


def test_possible_spins_name_the_band_in_degrees():
    from reportgen.core import heavy_top_theory as theory
    from reportgen.kinds.heavy_top import report as top_report

    spins = theory.band_spins(1.0, 0.5, 1.0, 0.6, 1.1)
    band = {"theta_min": spins.theta_min, "theta_max": spins.theta_max,
            "omega3_cusps": spins.omega3_cusps, "omega3_waves_min": spins.omega3_waves_min,
            "sigma": spins.sigma}
    # the band in degrees, the spins in rad/s: a² = βc1/d gives ω3 = 4.13432 rad/s for cusps
    # on this band (tests/test_mechanics_figures_gate.py)
    assert top_report._spins_in_words(band).startswith(
        f"on the band [{deg(0.6)}°, {deg(1.1)}°] cusps need |ω3| = 4.13432 rad/s")


def test_citations_name_their_document(band_page):
    # every equation number of the notes' §10 is cited "notes (10.n)", every figure of the
    # textbook "textbook Fig. 4.3", its exercise "textbook ex. 4.10" / "textbook exercise"
    assert "notes (10.31)" in band_page and "textbook Fig. 4.3" in band_page
    assert not re.search(r"(?<!notes )\(10\.\d+", band_page), re.findall(
        r".{30}(?<!notes )\(10\.\d+.{10}", band_page)
    assert not re.search(r"(?<!textbook )Fig\.\s4\.\d", band_page), re.findall(
        r".{30}(?<!textbook )Fig\.\s4\.\d", band_page)
    assert not re.search(r"(?<!textbook )(?:ex\.|[Ee]xercises?) 4\.\d", band_page)


def test_steady_top_has_one_turning_circle_in_degrees(cli, tmp_path):
    page = report(cli, tmp_path, "steady", """
        kind = "heavy_top"
        preset = "steady_fast"
        [run]
        t_end = 5.0
        study = false
        """)
    # the preset precesses steadily at θ0 = 1 rad = 57.2958°: u1 = u2, one circle
    assert f"θ1 = θ2 = {deg(1.0)}° (no nutation)" in page
    assert f"θ0 = {deg(1.0)}° (1 rad)" in page
    assert f"Steady precession at θ0 = {deg(1.0)}°, notes (10.45)" in page
