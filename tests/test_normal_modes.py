"""Normal modes (notes ch. 5 §5.1; Goldstein ch. 6): eigenproblem, molecules, chains, evolution."""

from __future__ import annotations

import math

import h5py
import numpy as np
import pytest

from reportgen.core import normal_modes as core
from reportgen.kinds import load_scene
from reportgen.kinds.normal_modes.results import MOLECULAR_OMEGA
from reportgen.scene.config import ConfigError, parse_config_text

M_O, M_C, M_H = core.ELEMENT_MASSES["O"], core.ELEMENT_MASSES["C"], core.ELEMENT_MASSES["H"]
# a molecule's default units (u, Å, mdyn/Å): its ω are stored in rad/s, this many per unit
# of the eigenproblem in those units
OMEGA_UNIT = MOLECULAR_OMEGA


def scene(text: str):
    return load_scene(parse_config_text(text))


def simulate(text: str):
    return scene(text).simulate()


def co2_text(k=16.0, kb=0.57, axis="x", extra=""):
    pos = {"x": (1.16, 0, 0), "z": (0, 0, 1.16), "d": (0.67, 0.67, 0.67)}[axis]
    return f"""
kind = "normal_modes"
[[atoms]]
element = "O"
position = [{-pos[0]}, {-pos[1]}, {-pos[2]}]
[[atoms]]
element = "C"
position = [0.0, 0.0, 0.0]
[[atoms]]
element = "O"
position = [{pos[0]}, {pos[1]}, {pos[2]}]
[[bonds]]
atoms = [0, 1]
k = {k}
[[bonds]]
atoms = [1, 2]
k = {k}
[[angles]]
atoms = [0, 1, 2]
k = {kb}
{extra}
"""


# ------------------------------------------------------------------ eigenproblem
def test_three_textbook_steps_agree_with_generalized_eigh():
    rng = np.random.default_rng(6)
    n = 7
    B = rng.normal(size=(n, n))
    M = B @ B.T + n * np.eye(n)  # non-diagonal kinetic matrix
    C = rng.normal(size=(n, n))
    A = C @ C.T
    w1, v1 = core.generalized_modes(M, A)
    w3, v3 = core.three_step_modes(M, A)
    assert np.max(np.abs(w1 - w3)) / np.max(w1) < 1e-12
    # both sets are M-orthonormal and solve A η = ω² M η
    for w, v in ((w1, v1), (w3, v3)):
        assert np.max(np.abs(v.T @ M @ v - np.eye(n))) < 1e-12
        assert np.max(np.abs(A @ v - M @ v * w)) / np.max(np.abs(A)) < 1e-12
    # same modes up to sign (the spectrum is non-degenerate)
    overlap = np.abs(v1.T @ M @ v3)
    assert np.max(np.abs(overlap - np.eye(n))) < 1e-9


def test_unstable_equilibrium_raises_instead_of_sqrt_of_negative():
    with pytest.raises(ValueError, match="unstable equilibrium"):
        core.omega_from_omega2(np.array([-0.5, 1.0]))


# ------------------------------------------------------------ Hessian of the force field
def _hessian_case(name):
    if name == "co2 (linear angle)":
        x = np.array([[-1.16, 0, 0], [0, 0, 0], [1.16, 0, 0]])
        return core.Molecule(np.array([M_O, M_C, M_O]), x, ((0, 1, 16.0), (1, 2, 16.0)),
                             ((0, 1, 2, 0.57),))
    if name == "h2o (bent)":
        half = math.radians(104.5) / 2
        x = np.array([[-math.sin(half), math.cos(half), 0], [0, 0, 0],
                      [math.sin(half), math.cos(half), 0]]) * 0.9572
        return core.Molecule(np.array([M_H, M_O, M_H]), x, ((0, 1, 8.45), (1, 2, 8.45)),
                             ((0, 1, 2, 0.76),))
    # a random non-planar, unsymmetric 4-atom molecule with an oblique linear chain part
    rng = np.random.default_rng(3)
    x = rng.normal(size=(4, 3))
    x[3] = x[1] + 0.8 * (x[1] - x[0]) / np.linalg.norm(x[1] - x[0])  # 0–1–3 is linear
    return core.Molecule(np.array([1.0, 2.0, 3.0, 4.0]), x,
                         ((0, 1, 1.3), (1, 2, 0.7), (1, 3, 2.1), (2, 3, 0.4)),
                         ((0, 1, 2, 0.3), (2, 1, 3, 0.9), (0, 1, 3, 0.5), (1, 2, 3, 0.2)))


@pytest.mark.parametrize("name", ["co2 (linear angle)", "h2o (bent)", "random 4-atom"])
def test_analytic_hessian_matches_finite_differences(name):
    mol = _hessian_case(name)
    A = mol.hessian()
    H = core.finite_difference_hessian(mol.potential, mol.positions.ravel(), h=1e-4)
    # central differences: error O(h²) ≈ 1e-8 of the largest entry
    assert np.max(np.abs(A - H)) < 1e-6 * np.max(np.abs(A))
    assert np.allclose(A, A.T, atol=0.0)


# ------------------------------------------------------------------------- CO2
@pytest.fixture(scope="module")
def co2():
    return simulate(co2_text())


def test_co2_frequencies_and_counting(co2):
    a = co2.analysis
    assert a["unit_system"] == "molecular"
    w = a["frequencies"] / OMEGA_UNIT  # in the config's units
    assert np.all(np.diff(w) >= 0)
    assert a["n_zero_modes"] == 5 and a["n_vibrational"] == 4  # 3n − 5 for a linear molecule
    assert a["n_rigid_rotations"] == 2 and a["linear"]
    assert a["n_longitudinal"] == 2 and a["n_transverse"] == 2  # n − 1 and 2(n − 2)
    types = list(a["mode_type"])
    assert types[:5] == ["translation"] * 3 + ["rotation"] * 2
    k = 16.0
    w_sym = w[types.index("longitudinal, symmetric stretch")]
    w_asym = w[types.index("longitudinal, antisymmetric stretch")]
    # Goldstein §6.4, linear triatomic: ω² = k/m_O and (k/m_O)(1 + 2 m_O/m_C)
    assert w_sym == pytest.approx(math.sqrt(k / M_O), rel=1e-12)
    assert w_asym == pytest.approx(math.sqrt(k / M_O * (1 + 2 * M_O / M_C)), rel=1e-12)
    # bend: ω² = (2 k_θ/(m_O r²))(1 + 2 m_O/m_C) (linear-bend coordinate, COM at rest)
    bend = [w[i] for i, t in enumerate(types) if t.startswith("transverse")]
    ref = math.sqrt(2 * 0.57 / (M_O * 1.16**2) * (1 + 2 * M_O / M_C))
    assert bend == pytest.approx([ref, ref], rel=1e-12)
    assert all(c.rel_error < 1e-12 for c in co2.checks)


@pytest.mark.parametrize("axis", ["x", "z", "d"])
def test_co2_degenerate_bend_basis_is_in_plane_and_out_of_plane(axis):
    res = simulate(co2_text(axis=axis))
    a = res.analysis
    types = list(a["mode_type"])
    groups = a["degenerate_group"]
    i_in = types.index("transverse (in-plane)")
    i_out = types.index("transverse (out-of-plane)")
    assert groups[i_in] == groups[i_out]  # reported as one degenerate set
    frame = a["frame"]
    for i, normal in ((i_in, frame[2]), (i_out, frame[1])):
        d = a["modes"][:, i].reshape(3, 3)
        assert np.max(np.abs(d @ normal)) < 1e-12 * np.max(np.abs(d))
    # and the pair is M-orthonormal
    M = a["mass_matrix"]
    pair = a["modes"][:, [i_in, i_out]]
    assert np.max(np.abs(pair.T @ M @ pair - np.eye(2))) < 1e-12


@pytest.mark.parametrize("split", [0.0, 1e-9, 1e-6])
def test_nearly_degenerate_stretch_and_bend_keep_their_labels(split):
    k = 16.0
    # tune k_θ so that ω_bend² = (1 + split) k/m_O = (1 + split) ω_sym²
    kb = (1 + split) * k * 1.16**2 / (2 * (1 + 2 * M_O / M_C))
    a = simulate(co2_text(k=k, kb=kb)).analysis
    types = list(a["mode_type"])[5:]
    assert sorted(types) == sorted(["longitudinal, symmetric stretch",
                                    "longitudinal, antisymmetric stretch",
                                    "transverse (in-plane)", "transverse (out-of-plane)"])
    w = a["frequencies"][5:] / OMEGA_UNIT
    w_sym = w[types.index("longitudinal, symmetric stretch")]
    assert w_sym == pytest.approx(math.sqrt(k / M_O), rel=1e-12)
    for t in ("transverse (in-plane)", "transverse (out-of-plane)"):
        assert w[types.index(t)] == pytest.approx(math.sqrt((1 + split) * k / M_O), rel=1e-12)


# ------------------------------------------------------------------------- H2O
def test_h2o_counting_and_herzberg_closed_forms():
    res = simulate('kind = "normal_modes"\npreset = "h2o"\n')
    a = res.analysis
    assert a["n_zero_modes"] == 6 and a["n_vibrational"] == 3  # 3n − 6
    assert not a["linear"]
    assert a["rigid_residual"] < 1e-14
    types = list(a["mode_type"])[6:]
    assert sorted(types) == ["antisymmetric stretch", "bend", "symmetric stretch"]
    assert [c.quantity for c in res.checks][1:] == [
        "ω antisymmetric stretch", "ω₁² + ω₂² (symmetric block)", "ω₁² ω₂² (symmetric block)"]
    assert all(c.rel_error < 1e-12 for c in res.checks)


def test_missing_angle_leaves_a_floppy_mode_and_flags_the_report():
    base = scene('kind = "normal_modes"\npreset = "h2o"\n').config.model_dump()
    toml = 'kind = "normal_modes"\n'
    for atom in base["atoms"]:
        toml += f'[[atoms]]\nelement = "{atom["element"]}"\nposition = {atom["position"]}\n'
    toml += "[[bonds]]\natoms = [0, 1]\nk = 8.45\n[[bonds]]\natoms = [1, 2]\nk = 8.45\n"
    res = simulate(toml)
    a = res.analysis
    assert a["n_zero_modes"] == 7 and a["n_floppy"] == 1
    assert res.status == "unstable" and "zero-frequency" in res.message
    assert np.all(np.isfinite(a["frequencies"]))


# ------------------------------------------------------------- chains and pendula
@pytest.mark.parametrize("n", [1, 7, 60])
def test_chain_matches_closed_form(n):
    res = simulate(f'kind = "normal_modes"\npreset = "chain"\n[chain]\nn = {n}\nm = 2.5\nk = 3.0\n')
    a = res.analysis
    j = np.arange(1, n + 1)
    # ω_j = 2√(k/m) sin(jπ/(2(N+1))), fixed ends (notes §5.1; Goldstein §6.4)
    exact = 2 * math.sqrt(3.0 / 2.5) * np.sin(j * math.pi / (2 * (n + 1)))
    assert np.max(np.abs(a["frequencies"] - exact) / exact) < 1e-12
    assert a["n_zero_modes"] == 0
    if n > 1:
        nodes = [int(t.split()[0]) for t in a["mode_type"]]
        assert nodes == list(range(n))  # mode j has j − 1 nodes


def test_standing_waves_are_the_fixed_chain_modes():
    # η_s ∝ sin(jsπ/(N+1)) solves A η = ω_j² M η with ω_j = 2√(k/m) sin(jπ/(2(N+1)))
    # (notes §5.1; Goldstein §6.4)
    n, m, k = 9, 2.0, 5.0
    M, A = core.chain_matrices(np.full(n, m), np.full(n + 1, k))
    w = core.chain_exact_frequencies(n, m, k)
    for j in range(1, n + 1):
        eta = core.chain_standing_wave(n, j, np.arange(1, n + 1))
        assert np.max(np.abs(A @ eta - w[j - 1] ** 2 * (M @ eta))) < 1e-12 * k
    # the drawn curves: scaled to 1 at the masses, signed like the computed modes
    modes = core.solve_modes(M, A).modes
    s, waves = core.chain_standing_waves(modes[:, :4], n_points=101)
    assert s[0] == 0.0 and s[-1] == n + 1 and waves.shape == (101, 4)
    at_masses = core.chain_standing_waves(modes[:, :4], n_points=n + 2)[1][1:-1]
    assert np.allclose(np.max(np.abs(at_masses), axis=0), 1.0, rtol=1e-12)
    unit = modes[:, :4] / np.max(np.abs(modes[:, :4]), axis=0)
    assert np.max(np.abs(at_masses - unit)) < 1e-12


def test_free_chain_has_one_translation_zero_mode():
    a = simulate('kind = "normal_modes"\n[chain]\nn = 5\nends = "free"\n').analysis
    assert a["n_zero_modes"] == 1
    exact = 2 * np.sin(np.arange(5) * math.pi / 10)  # 2√(k/m) sin(jπ/(2N))
    assert np.max(np.abs(a["frequencies"] - exact)) < 1e-12


def test_coupled_pendula_frequencies():
    a = simulate('kind = "normal_modes"\npreset = "coupled_pendula"\n').analysis
    # Goldstein §6.3-type pair: ω1 = √(g/l) in phase, ω2 = √(g/l + 2k/m) out of phase
    assert a["frequencies"] == pytest.approx([math.sqrt(9.81), math.sqrt(9.81 + 1.0)], rel=1e-13)
    assert list(a["mode_type"]) == ["in phase", "out of phase"]


def test_matrices_input_reproduces_the_molecule():
    mol = simulate(co2_text()).analysis
    M, A = mol["mass_matrix"], mol["hessian"]

    def mat(x):
        return "[" + ", ".join("[" + ", ".join(repr(float(v)) for v in row) + "]" for row in x) + "]"

    a = simulate(f'kind = "normal_modes"\nM = {mat(M)}\nA = {mat(A)}\n').analysis
    assert a["n_zero_modes"] == 5  # counted from the spectrum, nothing projected
    assert np.max(np.abs(a["frequencies"] - mol["frequencies"] / OMEGA_UNIT)) < 1e-7


# --------------------------------------------------------------------- validation
BAD = [
    ("[[atoms]]\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\n"
     "position = [1.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\nposition = [2.0, 0.5, 0.0]\n"
     "[[bonds]]\natoms = [0, 1]\nk = 1.0\n[[bonds]]\natoms = [1, 5]\nk = 1.0\n",
     "key 'bonds.1.atoms': index 5 out of range (3 atoms"),
    ("[[atoms]]\nmass = -1.0\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\n"
     "position = [1.0, 0.0, 0.0]\n", "atoms.0.mass"),
    ("[[atoms]]\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\n"
     "position = [1.0, 0.0, 0.0]\n[[bonds]]\natoms = [0, 1]\nk = 0.0\n", "bonds.0.k"),
    ("[[atoms]]\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 2.0\n"
     "position = [0.0, 0.0, 0.0]\n", "key 'atoms.1.position': same position as atoms[0]"),
    ("[[atoms]]\nelement = \"Xx\"\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 2.0\n"
     "position = [1.0, 0.0, 0.0]\n", "key 'atoms.0.element': unknown element"),
    ("[[atoms]]\nmass = 1.0\nposition = [0.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\n"
     "position = [1.0, 0.0, 0.0]\n[[atoms]]\nmass = 1.0\nposition = [2.0, 0.0, 0.0]\n"
     "[[angles]]\natoms = [0, 2, 1]\nk = 1.0\n", "key 'angles.0.atoms': θ0 = 0"),
    ("M = [[1.0, 0.1], [0.0, 1.0]]\nA = [[1.0, 0.0], [0.0, 1.0]]\n", "key 'M': not symmetric"),
    ("M = [[1.0, 0.0], [0.0, -1.0]]\nA = [[1.0, 0.0], [0.0, 1.0]]\n",
     "key 'M': not positive definite"),
    ("M = [[1.0, 0.0], [0.0, 1.0]]\nA = [[1.0, 2.0], [2.0, 1.0]]\n",
     "key 'A': unstable equilibrium, ω² = -1 < 0"),
    ("M = [[1.0, 0.0], [0.0, 1.0]]\nA = [[1.0, 0.0], [0.0, 1.0]]\n[chain]\nn = 2\n",
     "give exactly one system"),
    ("[chain]\nn = 3\n[run]\nt_end = 1.0\n", "key 'run': a normal-mode scene integrates only"),
    ("[chain]\nn = 3\n[evolve]\ndisplacement = [0.1, 0.0]\nt_end = 1.0\n",
     "key 'evolve.displacement': expected 3 numbers"),
    ("[chain]\nn = 3\nk = -2.0\n", "chain.k"),
]


@pytest.mark.parametrize("body, message", BAD, ids=[m[:32] for _, m in BAD])
def test_bad_input_names_the_key(body, message):
    with pytest.raises(ConfigError) as exc:
        scene('kind = "normal_modes"\n' + body)
    assert message in str(exc.value)


# ---------------------------------------------------------------- archive and report
def test_co2_archive_has_the_spec_entries_and_no_runs(write_config, cli, tmp_path):
    cfg = write_config("co2", 'kind = "normal_modes"\npreset = "co2"\n')
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    with h5py.File(tmp_path / "o" / "co2" / "run.h5") as f:
        assert "runs" not in f or len(f["runs"]) == 0  # a normal-mode scene integrates nothing
        assert "study" not in f or len(f["study"]) == 0
        an = f["analysis"]
        w = an["frequencies"][()]
        modes = an["modes"][()]
        M = an["mass_matrix"][()]
        assert np.all(np.diff(w) >= 0)
        assert np.max(np.abs(modes.T @ M @ modes - np.eye(9))) < 1e-12  # columns mass-normalized
        assert int(an.attrs["n_zero_modes"]) == 5 and int(an.attrs["n_vibrational"]) == 4
        # what the mode figures draw: the vibrations in the drawing frame, stored
        frame = an["frame"][()]
        disp = an["drawing/displacements"][()]
        assert disp.shape == (4, 3, 3)
        assert np.allclose(disp[0], modes[:, 5].reshape(3, 3) @ frame.T, rtol=0, atol=1e-15)
        assert np.allclose(an["drawing/positions"][()][:, 0], [-1.16, 0.0, 1.16], atol=1e-12)
    html = (tmp_path / "o" / "co2" / "report.html").read_text()
    assert "Mode shapes" in html and "Counting the modes" in html
    assert "Time evolution" not in html and "Error against run time" not in html
    figs = sorted(p.name for p in (tmp_path / "o" / "co2" / "figures").iterdir())
    assert "mode_shapes-modes.svg" in figs and "mode_shapes-snapshots.svg" in figs


def test_kinds_lists_zero_based_indices(cli):
    code, out, _ = cli("kinds")
    assert code == 0 and "normal_modes" in out and "zero-based" in out


# ------------------------------------------------------------------------ evolution
def test_coupled_pendula_beats_direct_against_modal():
    res = simulate('kind = "normal_modes"\npreset = "coupled_pendula"\n'
                   '[evolve]\ndisplacement = [0.1, 0.0]\nt_end = 30.0\n'
                   '[run]\nsamples = 601\nstudy = false\n')
    run = res.runs["main"]
    w1, w2 = math.sqrt(9.81), math.sqrt(9.81 + 1.0)
    # one pendulum displaced: φ1,2 = 0.05 (cos ω1 t ± cos ω2 t)  (beats, Goldstein §6.3)
    phi1 = 0.05 * (np.cos(w1 * run.t) + np.cos(w2 * run.t))
    phi2 = 0.05 * (np.cos(w1 * run.t) - np.cos(w2 * run.t))
    assert np.max(np.abs(run["phi1"] - phi1)) < 1e-10
    assert np.max(np.abs(run["phi2"] - phi2)) < 1e-10
    assert res.analysis["evolution_max_error"] < 1e-10
    assert not res.analysis["stiff"]
    assert run.status == "ok"
    # the modal superposition is archived as the run's reference (the report redraws it)
    assert np.max(np.abs(run.reference["phi1"] - phi1)) < 1e-14
    assert np.max(np.abs(run.reference["phi2"] - phi2)) < 1e-14
    assert "modal superposition" in run.attrs["reference_label"]


def test_modal_superposition_is_exact_with_zero_modes_and_velocity():
    a = simulate(co2_text()).analysis
    M, A = a["mass_matrix"], a["hessian"]
    rng = np.random.default_rng(1)
    q0, v0 = rng.normal(size=9) * 0.01, rng.normal(size=9) * 0.01
    t = np.linspace(0.0, 3.0, 7)
    w = a["frequencies"] / OMEGA_UNIT  # the units of M and A
    q, v = core.modal_evolution(a["modes"], w, M, q0, v0, t)
    assert np.allclose(q[0], q0, atol=1e-15) and np.allclose(v[0], v0, atol=1e-15)
    # satisfies M q̈ + A q = 0: compare q̈ by central differences of the exact solution
    h = 1e-4
    qp, _ = core.modal_evolution(a["modes"], w, M, q0, v0, t + h)
    qm, _ = core.modal_evolution(a["modes"], w, M, q0, v0, t - h)
    acc = (qp - 2 * q + qm) / h**2
    assert np.max(np.abs(acc @ M.T + q @ A.T)) < 1e-6


STIFF = """
kind = "normal_modes"
title = "heavy mass on a soft spring, light mass on a stiff spring"
M = [[1.0, 0.0], [0.0, 0.01]]
A = [[10001.0, -10000.0], [-10000.0, 10000.0]]
[evolve]
displacement = [0.1, 0.1]
t_end = {t_end}
[run]
samples = 401
study = {study}
"""


def test_stiff_case_is_detected_and_integrated_implicitly_with_study():
    res = simulate(STIFF.format(t_end=4.0, study="true"))
    a = res.analysis
    assert a["stiffness_ratio"] > 1e3 and a["stiff"]
    assert "stiff" in res.message
    run = res.runs["main"]
    assert run.attrs["method"] == "gauss6" and "stiff" in run.attrs["method_reason"]
    assert a["evolution_max_error"] < 1e-8
    rows = res.study
    methods = {m.decode() if isinstance(m, bytes) else m for m in rows["method"]}
    assert {"gauss6", "dop853", "rk4"} <= methods
    status = [s.decode() if isinstance(s, bytes) else s for s in rows["status"]]
    name = [m.decode() if isinstance(m, bytes) else m for m in rows["method"]]
    # the implicit method is stable at steps where the explicit fixed-step RK4 blows up
    assert any(n == "rk4" and s != "ok" for n, s in zip(name, status, strict=True))
    gauss_ok = [r for r, n, s in zip(rows, name, status, strict=True) if n == "gauss6" and s == "ok"]
    assert gauss_ok and max(float(r["h"]) for r in gauss_ok) * 1e3 > 2.8  # ω_max h > RK4 bound


def test_molecule_evolution_report_with_rigid_drift(write_config, cli, tmp_path):
    # CO2 with one O pushed along the axis and the whole molecule drifting in y:
    # the translation zero mode moves uniformly, the rest oscillates (modal superposition)
    cfg = write_config("co2_evolve", co2_text(extra="""
[evolve]
displacement = [[0.02, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]]
velocity = [[0.0, 0.01, 0.0], [0.0, 0.01, 0.0], [0.0, 0.01, 0.0]]
t_end = 20.0
[run]
samples = 801
study = false
"""))
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err
    with h5py.File(tmp_path / "o" / "co2_evolve" / "run.h5") as f:
        y = f["runs/main/y"][()]
        t = f["runs/main/t"][()]
        assert float(f["analysis"].attrs["evolution_max_error"]) < 1e-9
    # centre-of-mass y moves as 0.01 t exactly (translation zero mode)
    m = np.array([M_O, M_C, M_O])
    ycm = y[:, [1, 4, 7]] @ m / m.sum()
    assert np.max(np.abs(ycm - 0.01 * t)) < 1e-9
    html = (tmp_path / "o" / "co2_evolve" / "report.html").read_text()
    assert "Time evolution" in html and "Error against run time" not in html


def test_audit_case_is_reported_stiff():
    from reportgen.commands.audit import audit_case
    from reportgen.kinds.normal_modes import NormalModesScene

    result = audit_case(NormalModesScene.audit_cases()[0])
    assert result.verdict == "stiff"
    assert result.runs[0].used == "gauss6" and result.runs[0].error < 1e-8


def test_only_a_stiff_scene_is_told_about_stiffness_next_to_its_diagram(write_config, cli,
                                                                         tmp_path):
    """The work-precision section explains the stability bound of explicit methods only
    where the scene is stiff (a report leaves out what its scene does not need)."""
    from reportgen.archive.store import read_archive
    from reportgen.kinds.normal_modes import NormalModesScene

    cfg = write_config("stiff", STIFF.format(t_end=4.0, study="true"))
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, err  # auto chose an implicit method: ok
    html = (tmp_path / "o" / "stiff" / "report.html").read_text()
    assert "This scene is stiff (ω" in html
    assert "Error against run time" in html
    data = read_archive(tmp_path / "o" / "stiff" / "run.h5")
    assert any("stability bound" in n for n in
               NormalModesScene.section_error_vs_runtime(data).notes)
    data.analysis["stiff"] = False
    assert not any("stability bound" in n for n in
                   NormalModesScene.section_error_vs_runtime(data).notes)


# -------------------------------------------------------------------------- units
# CODATA 2018: u = 1.66053906660e-27 kg, c = 299792458 m/s; 1 mdyn/Å = 100 N/m
U_KG, C_CM = 1.66053906660e-27, 2.99792458e10


def test_co2_frequencies_in_rad_per_second_and_wavenumbers(co2):
    """The preset's molecular units (u, Å, mdyn/Å) give real units: ω² = k/m_O for the
    symmetric stretch (Goldstein §6.4) with k = 1600 N/m and m_O in kg, ν̃ = ω/(2πc)."""
    a = co2.analysis
    types = list(a["mode_type"])
    i = types.index("longitudinal, symmetric stretch")
    omega = math.sqrt(16.0 * 100.0 / (M_O * U_KG))  # rad/s, from SI alone
    assert a["frequencies"][i] == pytest.approx(omega, rel=1e-12)
    assert a["wavenumbers"][i] == pytest.approx(omega / (2 * math.pi * C_CM), rel=1e-12)
    assert a["wavenumbers"][i] == pytest.approx(1302.8, abs=0.1)  # cm⁻¹
    assert {c.unit for c in co2.checks if c.quantity.startswith("ω")} == {"rad/s"}


def test_a_molecule_in_si_units_is_not_rescaled():
    # the same CO₂ in kg, m and N/m: ω = √(k/m_O) directly, in rad/s
    m_o, m_c = M_O * U_KG, M_C * U_KG
    text = f"""
kind = "normal_modes"
units = "SI"
[[atoms]]
mass = {m_o!r}
position = [-1.16e-10, 0.0, 0.0]
[[atoms]]
mass = {m_c!r}
position = [0.0, 0.0, 0.0]
[[atoms]]
mass = {m_o!r}
position = [1.16e-10, 0.0, 0.0]
[[bonds]]
atoms = [0, 1]
k = 1600.0
[[bonds]]
atoms = [1, 2]
k = 1600.0
"""
    a = simulate(text).analysis
    i = list(a["mode_type"]).index("longitudinal, symmetric stretch")
    assert a["unit_system"] == "SI"
    assert a["frequencies"][i] == pytest.approx(math.sqrt(1600.0 / m_o), rel=1e-12)
    assert a["wavenumbers"][i] == pytest.approx(1302.8, abs=0.1)


def test_a_chain_is_dimensionless_by_default():
    res = simulate('kind = "normal_modes"\npreset = "chain"\n')
    assert res.analysis["unit_system"] == "dimensionless" and "wavenumbers" not in res.analysis
    assert {c.unit for c in res.checks} == {"dimensionless"}
    pendula = simulate('kind = "normal_modes"\npreset = "coupled_pendula"\n')
    assert pendula.analysis["unit_system"] == "SI"
    assert {c.unit for c in pendula.checks} == {"rad/s"}


@pytest.mark.parametrize(("body", "message"), [
    ('units = "molecular"\npreset = "chain"\n', "key 'units': 'molecular' (u, Å, mdyn/Å) is for atoms"),
    ('units = "dimensionless"\npreset = "coupled_pendula"\n', "key 'units': pendula are given in SI"),
    ('units = "SI"\npreset = "co2"\n', "key 'atoms.0': units = 'SI' needs `mass`"),
    ('units = "cgs"\npreset = "co2"\n', "units"),
])
def test_a_unit_system_that_does_not_fit_is_refused(body, message):
    with pytest.raises(ConfigError) as exc:
        scene('kind = "normal_modes"\n' + body)
    assert message in str(exc.value)


def test_spectrum_axes_carry_their_units(write_config, cli, tmp_path):
    from reportgen.archive.store import read_archive
    from reportgen.kinds.normal_modes import NormalModesScene

    for name, body in (("co2", 'preset = "co2"\n'), ("chain", 'preset = "chain"\n'),
                       ("pendula", 'preset = "coupled_pendula"\n')):
        cfg = write_config(name, 'kind = "normal_modes"\n' + body)
        code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
        assert code == 0, err
        data = read_archive(tmp_path / "o" / name / "run.h5")
        content = NormalModesScene.section_spectrum(data)
        label = content.figures[0].figure.axes[0].get_xlabel()
        header = content.tables[0].header
        assert (label, header[1]) == {
            "co2": ("wavenumber [cm⁻¹]", "ω [rad/s]"),
            "chain": ("angular frequency ω (dimensionless)", "ω (dimensionless)"),
            "pendula": ("angular frequency ω [rad/s]", "ω [rad/s]")}[name]
        assert ("ν̃ [cm⁻¹]" in header) == (name == "co2")
