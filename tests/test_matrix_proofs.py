"""Textbook ex. 4.1–4.4 for every 2 × 2 and 3 × 3 matrix (reportgen.kinds.rotation.proofs):
each identity's two sides expanded by SymPy to the same polynomial in independent symbols;
a false identity is not "proved"; the numerical checks on random matrices hold to
rounding; a scene nobody shipped with only a [proofs] table shows the section."""

from __future__ import annotations

import h5py
import pytest
import sympy

from reportgen.commands.cli import main
from reportgen.kinds.rotation import proofs
from reportgen.kinds.rotation.results import PROOF_KEYS


@pytest.mark.parametrize("n", [2, 3])
def test_every_identity_is_proved_for_all_n_by_n_matrices(n):
    result = proofs.symbolic(n)
    assert set(result) == set(PROOF_KEYS)
    assert all(ok for ok, _ in result.values()), result
    # the work is real: the left sides expand to polynomials of many terms
    assert result["associative"][1] == n**4 and result["inverse"][1] > n * n


def test_a_false_identity_is_not_proved():
    A, B = proofs._matrix("a", 2), proofs._matrix("b", 2)
    assert not proofs.proved((A * B).T, A.T * B.T)  # the transpose reverses the order
    assert not proofs.proved(A * B, B * A)
    assert not proofs.proved((A * B).det(), A.det() + B.det())
    assert proofs.proved((A * B).T, B.T * A.T)
    assert proofs.proved(A.adjugate() * A, A.det() * sympy.eye(2))


@pytest.mark.parametrize("n", [2, 3])
def test_the_identities_hold_on_random_matrices_to_rounding(n):
    errors = proofs.numeric(n, seed=11)
    assert set(errors) == set(PROOF_KEYS)
    assert max(errors.values()) < 1e-13, errors


def test_the_complex_step_is_an_independent_derivative():
    """d(A⁻¹)/dt by the complex step against the closed form of a 2 × 2 A(t) whose inverse
    is written by hand: A = [[1 + t, t²], [0, 2]], A⁻¹ = [[1/(1+t), −t²/(2(1+t))], [0, ½]]."""
    import numpy as np

    t, h = 0.3, 1e-30
    z = t + 1j * h
    d = np.linalg.inv(np.array([[1 + z, z * z], [0, 2]])).imag / h
    exact = np.array([[-1 / (1 + t) ** 2, -(2 * t * (1 + t) - t * t) / (2 * (1 + t) ** 2)],
                      [0.0, 0.0]])
    assert np.max(np.abs(d - exact)) < 1e-15


def test_a_scene_with_only_proofs_shows_them(tmp_path):
    config = tmp_path / "proofs_only.toml"
    config.write_text('kind = "rotation"\n[proofs]\nsizes = [2]\n[report]\nformats = ["html"]\n',
                      encoding="utf-8")
    assert main(["run", str(config), "--out", str(tmp_path / "out")]) == 0
    folder = tmp_path / "out" / "proofs_only"
    with h5py.File(folder / "run.h5", "r") as f:
        proved = dict(f["analysis/proofs/proved"].attrs)
    assert {k for k in proved if not k.startswith("__")} == {f"{k}_2" for k in PROOF_KEYS}
    assert all(bool(v) for k, v in proved.items() if not k.startswith("__"))
    page = (folder / "report.html").read_text(encoding="utf-8")
    assert '<section id="matrix_proofs">' in page and "3 × 3" not in page


def test_a_size_other_than_2_or_3_is_refused(tmp_path, capsys):
    config = tmp_path / "big.toml"
    config.write_text('kind = "rotation"\n[proofs]\nsizes = [4]\n', encoding="utf-8")
    assert main(["run", str(config), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert "proofs.sizes" in err and "big.toml" in err
