"""Oscillator scene: closed form, swap transformation (6.6–6.11), Hamilton–Jacobi (7.33–7.38)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from reportgen.archive.store import read_archive, write_archive
from reportgen.core.models import oscillator as core
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

TEXT = """
kind = "oscillator"
[params]
m = 2.0
omega = 1.5
[initial]
q = 1.0
p = 0.5
[run]
t_end = 25.0
samples = 1001
study = false
"""


@pytest.fixture(scope="module")
def results():
    return load_scene(parse_config_text(TEXT)).simulate()


def test_hamilton_equations_against_closed_form(results):
    run = results.runs["main"]
    t = run.t
    # q = q0 cos ωt + p0/(mω) sin ωt; p = p0 cos ωt − m ω q0 sin ωt (Goldstein §8.6 / notes §4)
    q = 1.0 * np.cos(1.5 * t) + 0.5 / 3.0 * np.sin(1.5 * t)
    p = 0.5 * np.cos(1.5 * t) - 3.0 * 1.0 * np.sin(1.5 * t)
    assert np.max(np.abs(run["q"] - q)) < 1e-10
    assert np.max(np.abs(run["p"] - p)) < 1e-10


def test_swap_transformation_is_canonical_on_the_trajectory(results):
    run, swapped = results.runs["main"], results.runs["swapped"]
    # F1 = qQ: p = Q, P = −q (6.8–6.9); integrating K(Q,P) must give the mapped orbit
    assert np.max(np.abs(swapped["Q"] - run["p"])) < 1e-10
    assert np.max(np.abs(swapped["P"] + run["q"])) < 1e-10
    assert results.analysis["swap_max_difference"] < 1e-10


def test_hamilton_jacobi_constants_and_solution(results):
    a = results.analysis
    e0 = 0.5 * 0.5**2 / 2.0 + 0.5 * 2.0 * 1.5**2 * 1.0**2
    assert a["hj_energy"] == pytest.approx(e0, rel=1e-14)
    # β from q0 = √(2E/mω²) sin(ωβ), p0 = √(2mE) cos(ωβ) (7.38)
    beta = math.atan2(2.0 * 1.5 * 1.0, 0.5) / 1.5
    assert a["hj_beta"] == pytest.approx(beta, rel=1e-14)
    assert a["hj_beta_drift"] < 1e-10
    assert a["hj_q_max_difference"] < 1e-10
    q, p = core.hamilton_jacobi_solution(np.array([0.0]), e0, beta, 2.0, 1.5)
    assert q[0] == pytest.approx(1.0) and p[0] == pytest.approx(0.5)


def test_rest_state_is_rejected():
    with pytest.raises(ConfigError, match="initial.q"):
        load_scene(parse_config_text(TEXT.replace("q = 1.0", "q = 0.0").replace("p = 0.5",
                                                                              "p = 0.0")))


@pytest.fixture(scope="module")
def data(results, tmp_path_factory):
    """The archive of ``results`` read back: what the report sees."""
    scene = load_scene(parse_config_text(TEXT))
    path = tmp_path_factory.mktemp("oscillator") / "run.h5"
    write_archive(path, kind=scene.kind, title=scene.title, scene="test", config_text=TEXT,
                  config_sha256="0", results=results, resolved_config=scene.resolved_config())
    return read_archive(path)


def test_report_is_short(data):
    kind = load_scene(parse_config_text(TEXT)).__class__
    assert [s.name for s in kind.chosen_sections(data)] == [
        "hamilton", "canonical_swap", "hamilton_jacobi"]  # study = false drops the diagram


def test_archive_holds_what_the_report_draws(data):
    run, swapped = data.runs["main"], data.runs["swapped"]
    t = run.t
    # closed form on the output grid (notes §4)
    assert np.allclose(run.reference["q"], np.cos(1.5 * t) + 0.5 / 3.0 * np.sin(1.5 * t),
                       rtol=0, atol=1e-14)
    assert np.allclose(run.reference["p"], 0.5 * np.cos(1.5 * t) - 3.0 * np.sin(1.5 * t),
                       rtol=0, atol=1e-14)
    # the swap image of the integrated orbit, Q = p, P = −q (6.7)
    assert np.array_equal(swapped.reference["Q"], run["p"])
    assert np.array_equal(swapped.reference["P"], -run["q"])
    # Hamilton–Jacobi (7.38): q = √(2E/mω²) sin ω(t + β), with E, β from the initial state
    hj = data.analysis["hamilton_jacobi"]
    e0 = 0.5 * 0.5**2 / 2.0 + 0.5 * 2.0 * 1.5**2
    beta = math.atan2(3.0, 0.5) / 1.5
    assert np.allclose(hj["q"], math.sqrt(2 * e0 / (2.0 * 1.5**2)) * np.sin(1.5 * (t + beta)),
                       rtol=0, atol=1e-12)
    assert np.max(np.abs(hj["beta"] - beta)) < 1e-10
    assert np.max(np.abs(hj["energy"] - e0)) < 1e-10 * e0
    kind = load_scene(parse_config_text(TEXT)).__class__
    for name in ("hamilton", "canonical_swap", "hamilton_jacobi"):
        assert getattr(kind, f"section_{name}")(data).figures
