"""A generating function that depends on time, notes (6.4)–(6.5): K = H + ∂F/∂t integrated
from (Q₀, P₀) follows the image of the H orbit, K with the other sign (the one notes (6.14)
prints for F3) does not, and the words say which sign the runs show and name the misprint
only for F3; F = −Σ pᵢQᵢ is the identity of notes (6.15), said only when (Q, P) = (q, p)."""

from __future__ import annotations

import re

import h5py
import pytest
import sympy

from reportgen.commands.cli import main

OSCILLATOR = """kind = "hamiltonian"
title = "{title}"
[params]
w = 1.0
Omega = {omega}
[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 + w**2*(x**2 + 2*y**2)/2"
[transform]
{transform}
coordinates = ["X", "Y"]
momenta = ["P_X", "P_Y"]
[initial]
x = 1.0
y = 0.2
p_x = 0.0
p_y = 0.7
[run]
t_end = 12.0
study = false
[report]
formats = ["html"]
"""
#: an anisotropic oscillator seen from turning axes, in the F2(q, P, t) form (Goldstein
#: Table 9.1) and in the F3(p, Q, t) form of notes (6.12)–(6.14)
F2 = ('F2 = "P_X*(x*cos(Omega*t) + y*sin(Omega*t)) + P_Y*(-x*sin(Omega*t) + '
      'y*cos(Omega*t))"')
F3 = ('F3 = "-(p_x*(X*cos(Omega*t) - Y*sin(Omega*t)) + p_y*(X*sin(Omega*t) + '
      'Y*cos(Omega*t)))"')


def _run(tmp_path, name, transform, omega):
    (tmp_path / f"{name}.toml").write_text(OSCILLATOR.format(
        title=f"oscillator {name}", transform=transform, omega=omega), encoding="utf-8")
    assert main(["run", str(tmp_path / f"{name}.toml"), "--out", str(tmp_path / "out")]) == 0
    folder = tmp_path / "out" / name
    with h5py.File(folder / "run.h5", "r") as f:
        attrs = dict(f["analysis"].attrs)
    page = (folder / "report.html").read_text(encoding="utf-8")
    return attrs, re.sub(r"<[^>]+>", "", page)  # the words, without the typesetting


@pytest.mark.parametrize("kind, transform", [("F2", F2), ("F3", F3)])
def test_the_sign_of_dF_dt_is_measured_and_named_only_for_F3(tmp_path, kind, transform):
    a, page = _run(tmp_path, kind, transform, 0.4)
    plus, minus = a["transform_run_difference"], a["transform_K_other_sign_difference"]
    assert plus < 1e-8 and minus > 0.1, (plus, minus)
    assert "the sign of ∂F/∂t in K matters" in page
    assert ("misprint" in page) is (kind == "F3")
    assert "identity transformation" not in page
    assert "The orbit in the new coordinates" in page  # as the turning axes see it


def test_a_time_independent_identity_says_so_and_has_no_sign_comparison(tmp_path):
    """The turning F3 at Ω = 0 is F = −Σ pᵢQᵢ."""
    a, page = _run(tmp_path, "identity", F3, 0.0)
    assert a["transform_identity_defect"] == 0.0
    assert "transform_K_other_sign_difference" not in a
    assert "the identity transformation, the generating function F = −Σ piQi of notes (6.15)" \
        in page
    assert "sign of ∂F/∂t" not in page and "The orbit in the new coordinates" not in page


def test_a_turning_frame_gives_K_as_H_minus_Omega_Lz_in_closed_form():
    """K = H + ∂F3/∂t for the turning axes simplifies to H(Q, P) − Ω(X P_Y − Y P_X)."""
    from reportgen.core import canonical
    from reportgen.core.mechanics import PhaseSpace

    space = PhaseSpace.of(["x", "y"])
    x, y = space.q
    px, py = space.p
    H = (px**2 + py**2) / 2 + (x**2 + 2 * y**2) / 2
    ct = canonical.generating_function(space, F3.split(" = ", 1)[1].strip('"'), "F3",
                                       ["X", "Y"], ["P_X", "P_Y"], params={"Omega": 0.4})
    K = canonical.new_hamiltonian(ct, H)
    X, Y = ct.Q
    PX, PY = ct.P
    t = space.t
    c, s = sympy.cos(0.4 * t), sympy.sin(0.4 * t)
    expected = ((PX**2 + PY**2) / 2 + ((X * c - Y * s)**2 + 2 * (X * s + Y * c)**2) / 2
                - 0.4 * (X * PY - Y * PX))
    assert sympy.simplify(sympy.expand_trig(K - expected)) == 0
