"""The heavy top's nutation period as a loop integral round the cut (textbook ex. 4.10), and
the scale of ℘ in u = λ℘ + μ.

References checked here:
- ∫_{x1}^{x2} dx/√(c(x − x1)(x2 − x)(x3 − x)) = 2K(k²)/√(c(x3 − x1)), k² = (x2 − x1)/(x3 − x1):
  the heavy top's T = 4K(k²)/√(β(u3 − u1)) of notes (10.31) (Goldstein §5.7) for any
  leading coefficient c; K from scipy.special.ellipk / ellipkm1 (Cephes), not our Carlson
- lemniscatic lattice g2 = 1, g3 = 0: e = ½, 0, −½, ω1 = Γ(1/4)²/(4√π)      (DLMF 23.5(iii))
- the periodic trapezoidal rule on an analytic integrand converges like exp(−N d), d the
  half-width of the strip of analyticity (Trefethen & Weideman, SIAM Rev. 56 (2014), §3)
- ℘'² = 4℘³ − g2℘ − g3 (DLMF 23.3.10): u = λ℘ + μ solves u̇² = βu³ + … only for βλ = 4
"""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import numpy as np
import pytest
from scipy.special import ellipk, ellipkm1, gamma

from reportgen.core import heavy_top_theory as theory
from reportgen.core import weierstrass as W
from reportgen.kinds import load_scene
from reportgen.scene.config import parse_config_text

REPO = Path(__file__).resolve().parent.parent
I1, I3, MGL = 1.0, 0.5, 1.0


def period_reference(lead, width, gap):
    """4K(k²)/√(c(x3 − x1)) with Cephes' K; near k² = 1 from 1 − k² = gap/(x3 − x1)."""
    span = width + gap
    m1 = gap / span
    k = ellipkm1(m1) if m1 < 0.5 else ellipk(width / span)
    return 4.0 * k / math.sqrt(lead * span)


CUBICS = [(2.0, 0.14, 10.7), (4.0, 0.5, 0.5), (1.3, 1.0, 1e-6), (0.7, 1e-8, 3.0),
          (3.0, 2.0, 0.05)]


@pytest.mark.parametrize("lead, width, gap", CUBICS)
def test_loop_round_the_cut_is_the_real_period(lead, width, gap):
    ref = period_reference(lead, width, gap)
    loop = W.loop_period(lead, width, gap)
    line = W.sine_squared_period(lead, width, gap)
    assert loop.value == pytest.approx(ref, rel=1e-12)
    assert line.value == pytest.approx(ref, rel=1e-12)
    assert abs(loop.imag) <= 1e-14 * ref  # the two sides of the cut give a real period


def test_lemniscatic_half_period_as_a_loop_in_the_wp_plane():
    # DLMF 23.5(iii): 4℘³ − ℘ has roots ½, 0, −½ and ω1 = Γ(1/4)²/(4√π); the loop round
    # [e3, e2] = [−½, 0] (width ½, gap e1 − e2 = ½) is 2ω1
    omega = gamma(0.25) ** 2 / (4 * math.sqrt(math.pi))
    assert W.loop_period(4.0, 0.5, 0.5).value == pytest.approx(2 * omega, rel=1e-14)
    assert W.sine_squared_period(4.0, 0.5, 0.5).value == pytest.approx(2 * omega, rel=1e-14)


@pytest.mark.parametrize("share", [0.125, 0.5, 0.875])
def test_any_ellipse_round_the_cut_gives_the_same_period(share):
    # Cauchy: the loop may be any ellipse between the cut and u3
    lead, width, gap = 1.0, 1.0, 0.3
    a = W.loop_period(lead, width, gap).strip
    loop = W.loop_period(lead, width, gap, rho=share * a)
    assert loop.value == pytest.approx(period_reference(lead, width, gap), rel=1e-12)


def convergence_rate(rule, ref, nodes):
    """−slope of ln|T_N/T − 1| against N, over the errors between 1e-12 and 1e-3."""
    pts = [(n, abs(rule(n) / ref - 1.0)) for n in nodes]
    pts = [(n, e) for n, e in pts if 1e-12 < e < 1e-3]
    assert len(pts) >= 4, pts
    n, e = np.array(pts).T
    return -np.polyfit(n, np.log(e), 1)[0]


def test_trapezoidal_rule_converges_at_the_rate_of_the_strip():
    # Trefethen & Weideman §3: error ~ exp(−N(a − ρ)) on the ellipse ρ, exp(−N a) on the
    # cut (the sin² substitution), a = arccosh((x3 − m)/r) the third root's distance
    lead, width, gap = 1.0, 1.0, 0.3
    ref = period_reference(lead, width, gap)
    loop = W.loop_period(lead, width, gap)
    a, rho = loop.strip, loop.rho
    assert a == pytest.approx(math.acosh((gap + width / 2) / (width / 2)), rel=1e-15)
    rate_loop = convergence_rate(lambda n: W.loop_period(lead, width, gap, nodes=n).value,
                                 ref, range(4, 80, 4))
    rate_line = convergence_rate(lambda n: W.sine_squared_period(lead, width, gap,
                                                                 nodes=n).value,
                                 ref, range(2, 40, 2))
    assert rate_loop == pytest.approx(a - rho, rel=0.1)
    assert rate_line == pytest.approx(a, rel=0.1)


def test_an_ellipse_that_reaches_the_third_root_is_refused():
    a = W.loop_period(1.0, 1.0, 0.3).strip
    with pytest.raises(ValueError, match="ρ"):
        W.loop_period(1.0, 1.0, 0.3, rho=a)
    with pytest.raises(ValueError, match="x1 < x2 < x3"):
        W.loop_period(1.0, 0.0, 0.3)


def test_a_third_root_at_the_cut_is_reported_not_summed():
    # the unstable sleeping top: u3 − u2 ≈ 1e-12 (u2 − u1), a ≈ 2e-6; the rule would need
    # some 60/(a − ρ) ≈ 6e7 nodes, beyond the budget: no value, and it says so
    loop = W.loop_period(2.0, 1.02, 9.8e-13)
    assert not loop.converged and math.isnan(loop.value)
    assert loop.nodes == pytest.approx(60 / (loop.strip - loop.rho), rel=0.01)
    assert loop.nodes > W.PERIOD_MAX_NODES
    line = W.sine_squared_period(2.0, 1.02, 9.8e-13)
    assert not line.converged and math.isnan(line.value)
    # within the budget, near the edge: still to 1e-12
    near = W.loop_period(2.0, 1.0, 1e-7)
    assert near.converged and near.value == pytest.approx(period_reference(2.0, 1.0, 1e-7),
                                                          rel=1e-12)


# ------------------------------------------------------------------------- the top
def fig43_tops(params=(I1, I3, MGL)):
    """The loops, waves and cusps of textbook Fig. 4.3 (the band 50° to 60°)."""
    out = []
    for case in ("loops", "waves", "cusps"):
        start = theory.band_start(*params, math.radians(50), math.radians(60), case)
        c = theory.constants(*params, *start)
        out.append((case, c, theory.roots(c)))
    return out


@pytest.mark.parametrize("params", [(I1, I3, MGL), (2.5, 1.2, 0.8)])
def test_nutation_period_round_the_cut_against_closed_forms(params):
    for case, c, r in fig43_tops(params):
        loops = theory.period_loops(r, c)
        T = theory.nutation_period(r, c)  # 4K(k²)/√(β(u3 − u1)), Carlson
        assert loops.loop.value == pytest.approx(T, rel=1e-12), case
        assert loops.sine_squared.value == pytest.approx(T, rel=1e-12), case
        # independent of our Carlson: Cephes' K
        assert loops.loop.value == pytest.approx(
            period_reference(c.beta, r.w2 - r.w1, r.w1 - r.w3), rel=1e-12), case
        # du/√f(u) = d℘/√(4℘³ − g2℘ − g3) with u = (4/β)℘ + μ: the loop round [e3, e2] is 2ω
        form = theory.weierstrass_form(r, c)
        assert loops.wp_loop.value == pytest.approx(2 * form.omega, rel=1e-13), case


def test_no_loop_without_nutation():
    # steady precession: u1 = u2, no cut
    slow, _fast = theory.steady_precession_rates(I1, I3, MGL, 0.8, 8.0)
    c = theory.constants(I1, I3, MGL, 0.8, 0.0, slow, 8.0)
    assert theory.period_loops(theory.roots(c), c) is None


@pytest.mark.parametrize("params", [(I1, I3, MGL), (2.5, 1.2, 0.8)])
def test_wp_scale_four_over_beta_solves_the_equation_and_beta_does_not(params):
    # u̇² = f(u) = β(u − u1)(u2 − u)(u3 − u) with u = λ℘ + μ: λ²℘'² = βλ³Π(℘ − e_j), and
    # ℘'² = 4Π(℘ − e_j) (DLMF 23.3.10) needs λ = 4/β
    t = np.linspace(0.0, 12.0, 1201)
    for case, c, r in fig43_tops(params):
        form = theory.weierstrass_form(r, c)
        assert form.scale == pytest.approx(4.0 / c.beta, rel=1e-15)
        assert theory.weierstrass_ode_residual(t, form, r, c) <= 1e-12, case
        # textbook ex. 4.10's u = β℘ + c, same ℘: wrong unless β² = 4 (β = 2 1/s²)
        textbook = dataclasses.replace(form, scale=c.beta)
        residual = theory.weierstrass_ode_residual(t, textbook, r, c)
        if math.isclose(c.beta, 2.0, rel_tol=1e-15):
            assert residual <= 1e-12, case  # I1 = Mgl = 1: β = 4/β = 2, a coincidence
        else:
            assert residual >= 0.1, case


def scene_text(name):
    text = (REPO / "configs" / name).read_text()
    return text.replace("[run]\n", "[run]\nstudy = false\n")


def test_fig43_scene_stores_and_shows_the_loop_period():
    s = load_scene(parse_config_text(scene_text("heavy_top_fig4.3.toml")))
    results = s.simulate()
    a = results.analysis
    wp = a["weierstrass"]
    T = a["nutation_period"]
    assert wp["period_loop"] == pytest.approx(T, rel=1e-12)
    assert wp["period_sine_squared"] == pytest.approx(T, rel=1e-12)
    assert wp["omega_loop"] == pytest.approx(wp["omega"], rel=1e-13)
    assert abs(wp["period_loop_imag"]) <= 1e-14 * T
    assert 0 < wp["period_loop_rho"] < wp["period_loop_strip"]
    assert wp["period_loop_nodes"] >= 16 and wp["period_sine_squared_nodes"] >= 16
    assert wp["ode_residual"] <= 1e-12
    # measured from the integrated θ(t), to the run's accuracy
    assert wp["period_loop"] == pytest.approx(a["nutation_period_measured"], rel=1e-9)
    runs = a["band"]["runs"]
    assert set(runs) == {"loops", "waves", "cusps"}
    for run in runs.values():
        assert run["period_loop"] == pytest.approx(run["nutation_period"], rel=1e-12)
    # the ℘ section: the period table, each run's loop, and the note on the scale of ℘
    from reportgen.archive.store import ArchiveData, ConfigView

    data = ArchiveData(path=Path("x.h5"), attrs={}, config_text="", provenance={},
                       analysis=a, runs=results.runs,
                       config=ConfigView.of(s.resolved_config()))
    content = type(s).section_weierstrass(data)
    captions = [t.caption for t in content.tables]
    assert any("loop integral round the cut (textbook ex. 4.10" in c for c in captions)
    period_table = next(t for t in content.tables if t.header[0] == "T computed as")
    assert len(period_table.rows) == 6  # ellipse, sin², ℘ plane, AGM, measured, reference
    band_table = next(t for t in content.tables if t.header[0] == "run")
    assert [row[0] for row in band_table.rows] == ["loops", "waves", "cusps"]
    note = content.notes[-1]
    assert "textbook ex. 4.10 writes u = β℘ + c" in note and "λ = 4/β = 2 s²" in note
    assert "share the number 2" in note  # β = 2 1/s² for I1 = Mgl = 1


def test_the_scale_note_tells_apart_a_top_with_another_beta():
    from reportgen.kinds.heavy_top.report_weierstrass import scaling_note

    note = scaling_note(0.5)
    assert "λ = 4/β = 8 s²" in note and "β = 0.5 1/s²" in note
    assert "share the number" not in note
