"""Textbook ex. 4.2(a)–(c), a basis that is not orthonormal (reportgen.kinds.rotation.basis),
and the notes' Figure 2, the Euler angles (reportgen.kinds.rotation.euler_sketch and
euler_figure), issue 42.

Ex. 4.2 (textbook p. 120; the opening and the markers of (a)–(c) are lost in the text's
extraction) ties an orthonormal êᵢ to a new basis by êᵢ = Σⱼ Aⱼᵢ e′ⱼ.  Then (a) e′ⱼ =
Σᵢ (A⁻¹)ᵢⱼ êᵢ, (b) V′ = AV, (c) V = A⁻¹V′.  A worked case by hand: ê the standard basis,
A = [[2, 1], [0, 1]], so A⁻¹ = [[½, −½], [0, 1]] and e′₁ = (½, 0), e′₂ = (−½, 1) (indeed
ê₁ = 2e′₁ = (1, 0), ê₂ = e′₁ + e′₂ = (0, 1)); the Gram matrix (e′ᵢ · e′ⱼ) = [[¼, −¼],
[−¼, 5/4]]; V = (3, 2) has V′ = AV = (8, 2) (8e′₁ + 2e′₂ = (3, 2)), while its projections
e′ᵢ · V = (3/2, ½) are not its components.

The notes' Figure 2 goes with notes (9.17), R = R₃(ψ)R₁(θ)R₃(φ): z-x-z.  Goldstein's
conversion (Goldstein §4.4, the y-convention): z-y-z angles (φ, θ, ψ) are the z-x-z angles
(φ + π/2, θ, ψ − π/2) of the same rotation.
"""

from __future__ import annotations

import itertools
import math
from html import unescape

import h5py
import numpy as np
import pytest
import sympy
from scipy.linalg import expm

from reportgen.archive.store import read_archive
from reportgen.kinds.rotation import basis, euler_figure, proofs
from reportgen.kinds.rotation.euler_sketch import NOTES_CONVENTION, euler_sketch


def skew(v):
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


# ------------------------------------------------------------------ ex. 4.2(a)–(c)
def test_the_worked_case_by_hand():
    r = basis.on_basis(np.eye(2), [[2.0, 1.0], [0.0, 1.0]], [3.0, 2.0])
    assert np.array_equal(r["prime"], [[0.5, -0.5], [0.0, 1.0]])  # columns e′₁, e′₂
    assert np.array_equal(r["gram"], [[0.25, -0.25], [-0.25, 1.25]])
    assert r["gram_distance"] == 0.75  # |¼ − 1|
    assert np.allclose(r["components_prime"], [8.0, 2.0], rtol=0, atol=1e-15)
    assert np.array_equal(r["projections"], [1.5, 0.5])
    assert r["projection_gap"] == pytest.approx(6.5 / 8.0, rel=1e-15)
    assert max(r["errors"].values()) <= 1e-16


@pytest.mark.parametrize("n", [2, 3])
def test_the_three_relations_are_proved_for_any_bases(n):
    result = proofs.symbolic(n)
    for key in basis.RELATIONS:
        ok, terms = result[key]
        assert ok and terms >= n * n, (key, terms)


@pytest.mark.parametrize("n", [2, 3])
def test_the_other_index_order_is_not_proved(n):
    """The exercise turns on A_ji against A_ij: with the transpose in place of A, (a) and
    (b) are false, and the expansion says so (the proofs are not tautologies)."""
    def symbols(name, rows, cols):
        return sympy.Matrix(rows, cols, lambda i, j: sympy.Symbol(f"{name}{i}{j}", real=True))

    P, A, v = symbols("p", n, n), symbols("a", n, n), symbols("v", n, 1)
    H = P * A  # column i: êᵢ = Σⱼ Aⱼᵢ e′ⱼ
    det, adj = A.det(method="berkowitz"), A.adjugate()
    assert proofs.proved(H * adj, det * P) and not proofs.proved(H * adj.T, det * P)
    assert proofs.proved(P * (A * v), H * v) and not proofs.proved(P * (A.T * v), H * v)
    for key, (left, right) in basis.relations(n).items():  # the module's own forms
        assert proofs.proved(left, right), key


@pytest.mark.parametrize(("n", "seed"), list(itertools.product([2, 3], [0, 4, 11])))
def test_a_random_basis_is_not_orthonormal_and_the_relations_hold(n, seed):
    r = basis.non_orthonormal(n, seed)
    hat = r["hat"]
    assert np.max(np.abs(hat.T @ hat - np.eye(n))) < 1e-15 and np.linalg.det(hat) > 0
    assert r["condition"] < basis.CONDITION_BELOW
    assert r["gram_distance"] > 0.05  # far from orthonormal
    assert r["projection_gap"] > 1e-3  # projections are not the components
    assert max(r["errors"].values()) < 1e-14, r["errors"]
    # the relations again, here: (a) e′ = ê A⁻¹, (b) V = Σ V′ᵢ e′ᵢ with V′ = A (êᵀV)
    A, prime, V = r["matrix"], r["prime"], r["vector"]
    assert np.allclose(prime, hat @ np.linalg.inv(A), rtol=0, atol=1e-14)
    assert np.allclose(prime @ (A @ (hat.T @ V)), V, rtol=0, atol=1e-13)
    again = basis.non_orthonormal(n, seed)  # seeded: the same numbers
    assert all(np.array_equal(again[k], r[k]) for k in ("hat", "matrix", "vector"))


# ------------------------------------------------------------------ the archive and page
CONFIG = """
kind = "rotation"
[euler]
convention = "zyz"
angles = [0.5, 0.8, 0.3]
rates = [0.7, 0.4, 1.5]
duration = 4.0
samples = 21
[proofs]
sizes = [2]
[report]
formats = ["html"]
"""


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    from reportgen.commands.cli import main

    folder = tmp_path_factory.mktemp("basis")
    config = folder / "basis_scene.toml"
    config.write_text(CONFIG, encoding="utf-8")
    assert main(["run", str(config), "--out", str(folder / "out")]) == 0
    return folder / "out" / "basis_scene"


def test_the_archive_holds_the_basis_and_the_sketch_with_units(scene):
    with h5py.File(scene / "run.h5", "r") as f:
        b = f["analysis/proofs/basis"]
        gram = b["gram_2"]
        assert gram.attrs["units"] == "1" and "Gram" in gram.attrs["long_name"]
        assert "gram_distance_3" not in b and "gram_distance_3" not in b.attrs  # sizes = [2]
        for key in basis.RELATIONS:
            assert bool(f["analysis/proofs/proved"].attrs[f"{key}_2"])
        s = f["analysis/euler/sketch"]
        assert s["angles"].attrs["units"] == "rad" and s["body_plane"].attrs["long_name"]
    data = read_archive(scene / "run.h5")
    sketch = data.analysis["euler"]["sketch"]
    assert str(sketch["convention"]) == NOTES_CONVENTION == "zxz"
    # Goldstein's conversion: z-x-z angles (φ + π/2, θ, ψ − π/2)
    assert np.allclose(sketch["angles"], [0.5 + math.pi / 2, 0.8, 0.3 - math.pi / 2],
                       rtol=0, atol=1e-15)
    # the rotation by scipy's expm: R = R_z(φ) R_y(θ) R_z(ψ)
    R = expm(0.5 * skew([0, 0, 1])) @ expm(0.8 * skew([0, 1, 0])) @ expm(0.3 * skew([0, 0, 1]))
    z_body = R[:, 2]
    plane, body_plane = np.asarray(sketch["plane"]), np.asarray(sketch["body_plane"])
    assert np.allclose(np.linalg.norm(body_plane, axis=1), 1.0, atol=1e-15)
    assert np.max(np.abs(body_plane @ z_body)) < 1e-14  # the x′y′ plane
    assert np.max(np.abs(plane[:, 2])) == 0.0  # the xy plane
    # the line of nodes, (cos φ, sin φ, 0) for the z-x-z φ, lies in both planes
    phi = float(sketch["angles"][0])
    node = np.array([math.cos(phi), math.sin(phi), 0.0])
    assert abs(node @ z_body) < 1e-15
    drawn = data.analysis["euler"]["construction"]["zxz"]
    assert np.allclose(drawn["node"], node, atol=1e-15)
    assert np.allclose(drawn["body_axes"], R, atol=1e-14)


def test_the_page_shows_both_with_their_citations(scene):
    from reportgen.scene.citations import problems

    html = (scene / "report.html").read_text(encoding="utf-8")
    words = unescape(html)
    assert (scene / "figures" / "euler_angles-notes_figure_2.svg").is_file()
    assert "notes Fig. 2" in words and "z-x-z convention of notes (9.17)" in words
    assert "these are the same rotation's, converted" in words
    assert "textbook ex. 4.2(a)" in words and "textbook ex. 4.2(c)" in words
    assert "checks of textbook ex. 4.2(a)–(c) on the basis e′ hold" in words
    assert problems(html) == []
    assert (scene / "gate.json").read_text(encoding="utf-8").strip() == "[]"


def test_the_claims_hold_and_catch_wrong_words(scene):
    from reportgen.rendering.report import report_text
    from reportgen.scene.claims import contradictions, said

    data = read_archive(scene / "run.h5")
    text = report_text(data)
    assert contradictions(data, text) == []
    assert {"rotation basis not orthonormal", "rotation sketch z-x-z", "rotation basis checks hold",
            "rotation sketch angles converted"} <= set(said(text))
    wrong = contradictions(data, "These are the angles as given. e′ is orthonormal here to "
                                 "10⁻⁹, drawn for this scene's rotation in the z-y-z convention")
    assert {w.split(":")[0] for w in wrong} == {"rotation sketch angles as given",
                                                "rotation basis orthonormal",
                                                "rotation sketch z-y-z"}


# ------------------------------------------------------------------ the figure's words and layout
def _euler_group(angles, convention="zxz"):
    from reportgen.core import rotations

    angles = np.asarray(angles, dtype=float)
    convert = rotations.zxz_to_zyz if convention == "zxz" else rotations.zyz_to_zxz
    other = "zyz" if convention == "zxz" else "zxz"
    converted = np.stack(convert(angles[:1], angles[1:2], angles[2:]), axis=-1)
    group = {"convention": convention, "path": angles[None], "path_other": converted,
             "construction": {convention: rotations.euler_construction(*angles, convention),
                              other: rotations.euler_construction(*converted[0], other)}}
    group["sketch"] = euler_sketch(group)
    return group


def test_the_caption_follows_the_stored_facts():
    given = _euler_group([0.4, 1.0, 0.2])
    text = euler_figure.caption(given["sketch"], "zxz", given["path"][0])
    assert "These are the angles as given." in text and "negative" not in text
    assert "z-x-z convention of notes (9.17)" in text and "takes the x axis" in text
    negative = _euler_group([-0.4, 1.0, -0.2])
    text = euler_figure.caption(negative["sketch"], "zxz", negative["path"][0])
    assert "φ and ψ are negative here" in text
    still = _euler_group([0.0, 0.5, 0.3])
    assert "φ is below 1°: no arc drawn." in euler_figure.caption(still["sketch"], "zxz",
                                                                 still["path"][0])
    other = dict(given["sketch"], convention="zyz")  # a sketch stored in z-y-z
    text = euler_figure.caption(other, "zyz", given["path"][0])
    assert "z-y-z convention (the Euler angles of notes (9.17) are z-x-z)" in text
    assert "takes the y axis" in text


@pytest.mark.parametrize("angles", [(0.0, 0.0, 0.0), (0.7, 0.0, 0.5), (2.0, 3.0, -2.5),
                                    (-2.5, 1.2, 2.9), (math.pi / 2,) * 3, (0.5, 0.8, 0.3)])
def test_the_figure_passes_the_gate_and_its_labels_do_not_overlap(angles):
    from reportgen.rendering.gate import figure_findings
    from reportgen.rendering.plots.finish import finish_figure

    group = _euler_group(angles)
    (spec,) = euler_figure.figures(group)
    fig = spec.figure
    finish_figure(fig)
    assert figure_findings(fig) == []
    ax = fig.axes[0]
    renderer = fig._get_renderer()
    boxes = [t.get_window_extent(renderer) for t in ax.texts]
    words = [t.get_text() for t in ax.texts]
    assert all(w.startswith("$") and w.endswith("$") for w in words), words  # mathtext
    drawn_arcs = sum(abs(a) >= math.radians(1.0) for a in angles)
    assert len(words) == 7 + drawn_arcs
    for (i, a), (j, b) in itertools.combinations(enumerate(boxes), 2):
        assert not a.overlaps(b), (words[i], words[j])
    assert all(ax.bbox.contains(*b.p0) and ax.bbox.contains(*b.p1) for b in boxes)
