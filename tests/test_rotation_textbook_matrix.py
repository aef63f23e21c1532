"""The ``rotation`` kind's textbook matrix (textbook ex. 4.5) against closed forms, its relation
to Goldstein's passive matrix (Goldstein (4.62)), and angles shown in degrees.

References recomputed here, independently of reportgen:
- the active rotation by Φ about n, R = cos Φ 1 + (1 − cos Φ) n nᵀ + sin Φ [n]× = exp(Φ[n]×)
  (Rodrigues; textbook ex. 4.5), by scipy's expm of the generator;
- a quarter turn about e_z takes e_x to e_y: R = [[0, −1, 0], [1, 0, 0], [0, 0, 1]];
- a third of a turn about (1, 1, 1)/√3 permutes the axes x → y → z → x;
- Goldstein (4.62), r′ = r cos Φ + n (n·r)(1 − cos Φ) + (r × n) sin Φ, is passive: its matrix
  A = Rᵀ = R(n, −Φ), so a quarter turn about e_z gives A e_x = −e_y.
"""

from __future__ import annotations

import html
import math
import re

import numpy as np
import pytest
from scipy.linalg import expm

from reportgen.archive.store import read_archive


def skew(v):
    """[v]× with [v]× w = v × w."""
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def visible(page: str) -> str:
    body = page.split("<body", 1)[-1].split('<section id="config">', 1)[0]
    return " ".join(html.unescape(re.sub(r"<[^>]+>", " ", body)).split())


def run(cli, write_config, tmp_path, name, text):
    cfg = write_config(name, 'kind = "rotation"\n' + text)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    folder = tmp_path / "o" / name
    return (read_archive(folder / "run.h5"),
            (folder / "report.html").read_text(encoding="utf-8"))


def test_quarter_turn_about_z_takes_x_to_y(tmp_path, write_config, cli):
    data, page = run(cli, write_config, tmp_path, "quarter", """
        [axis_angle]
        axis = [0.0, 0.0, 1.0]
        angle = 1.5707963267948966
        vector = [1.0, 0.0, 0.0]
        """)
    a = data.analysis["axis_angle"]
    # the active rotation by π/2 about e_z, written out: e_x -> e_y, e_y -> −e_x
    R = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
    assert np.allclose(a["matrix_textbook"], R, atol=1e-15)
    assert np.allclose(a["turned_vector"], [0.0, 1.0, 0.0], atol=1e-15)
    assert np.allclose(a["arc_turned"][-1], [0.0, 1.0, 0.0], atol=1e-15)
    # Goldstein (4.62): e_x × e_z = −e_y, so the passive r′ = −e_y and A = Rᵀ
    assert np.allclose(a["rotated_vector"], [0.0, -1.0, 0.0], atol=1e-15)
    assert np.allclose(a["matrix_formula"], R.T, atol=1e-15)
    assert a["errors"]["textbook_vs_goldstein"] <= 1e-15
    # the page shows R (its second row is "1 0 0"), not A (whose second row is "-1 0 0")
    text = visible(page)
    assert "textbook ex. 4.5" in text and "Goldstein (4.62)" in text
    assert "angle Φ 90° (1.5708" in text
    assert "(0, 1, 0): r turned by Φ about n" in text


@pytest.mark.parametrize("axis, angle", [([1.0, 1.0, 1.0], 2 * math.pi / 3),
                                         ([0.3, -0.4, 1.2], 0.7),
                                         ([-2.0, 0.5, 0.1], 3.0)])
def test_textbook_matrix_is_exp_of_the_generator_and_goldsteins_transpose(
        tmp_path, write_config, cli, axis, angle):
    data, _ = run(cli, write_config, tmp_path, "turn", f"""
        [axis_angle]
        axis = {axis!r}
        angle = {angle!r}
        vector = [0.2, 1.0, -0.5]
        """)
    a = data.analysis["axis_angle"]
    n = np.asarray(axis) / np.linalg.norm(axis)
    R = expm(angle * skew(n))  # scipy, knows nothing of Rodrigues' formula
    assert np.allclose(a["matrix_textbook"], R, atol=1e-14)
    assert np.allclose(a["matrix_expm"], R, atol=1e-14)
    assert np.allclose(a["matrix_quaternion"], R, atol=1e-14)
    # Goldstein's A is the same turn the other way round: A = Rᵀ = exp(−Φ[n]×)
    assert np.allclose(a["matrix_formula"], expm(-angle * skew(n)), atol=1e-14)
    r = np.array([0.2, 1.0, -0.5])
    assert np.allclose(a["turned_vector"], R @ r, atol=1e-14)
    assert np.allclose(a["rotated_vector"], R.T @ r, atol=1e-14)
    # the declared result: ‖R − Aᵀ‖ at round-off
    assert 0.0 <= a["errors"]["textbook_vs_goldstein"] <= 4e-16
    if axis == [1.0, 1.0, 1.0]:  # x -> y -> z -> x: columns e_y, e_z, e_x
        assert np.allclose(a["matrix_textbook"], [[0, 0, 1], [1, 0, 0], [0, 1, 0]],
                           atol=1e-15)


def test_a_sign_error_in_the_textbook_matrix_fails_the_scene(tmp_path, write_config,
                                                             monkeypatch):
    """The relation check bites: the textbook's matrix with the sign of sin Φ flipped (which
    is Goldstein's A, not R) fails R against Aᵀ, exp(Φ[n]×) and the quaternion."""
    from reportgen.kinds.rotation import simulation
    from reportgen.pipeline.stages import run_scene

    exact = simulation.textbook_matrix
    monkeypatch.setattr(simulation, "textbook_matrix", lambda n, Phi: exact(n, -Phi))
    cfg = write_config("flipped", 'kind = "rotation"\npreset = "axis_angle"\n')
    outcome = run_scene(str(cfg), str(tmp_path / "o"), formats=("html",))
    assert outcome.status == "failed"
    for name in ("textbook_vs_goldstein", "formula_vs_expm", "formula_vs_quaternion"):
        assert f"axis_angle/{name}" in outcome.message


def test_euler_angles_are_shown_in_degrees(tmp_path, write_config, cli):
    _, page = run(cli, write_config, tmp_path, "eul", """
        [euler]
        convention = "zxz"
        angles = [0.5, 0.8, 0.3]
        samples = 5
        """)
    text = visible(page)
    # 0.5 rad = 28.6479°, 0.8 rad = 45.8366°, 0.3 rad = 17.1887°; the z-y-z angles of the
    # same rotation are φ − 90°, θ, ψ + 90° (Goldstein's y-convention)
    assert "28.6479°, 45.8366°, 17.1887° (0.5, 0.8, 0.3 rad)" in text
    # (the page's minus sign is U+2212)
    assert (f"{math.degrees(0.5) - 90:.6g}°, 45.8366°, {math.degrees(0.3) + 90:.6g}°"
            .replace("-", "−")) in text
