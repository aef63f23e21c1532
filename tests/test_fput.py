"""FPUT stiff–soft chain (Hairer, Lubich & Wanner, GNI 2nd ed., §I.5.1, eqs. I.5.1–I.5.3)."""

from __future__ import annotations

import h5py
import numpy as np
import pytest

from reportgen.core.integrators import integrate
from reportgen.core.models import fput as core
from reportgen.kinds import load_scene
from reportgen.scene.config import ConfigError, parse_config_text

OMEGA = 50.0
M = 3
N = 2 * M

GNI_TEXT = """
kind = "fput"
preset = "gni"
[run]
t_end = 200.0
samples = 4001
study = false
"""


@pytest.fixture(scope="module")
def gni():
    """The standard data of GNI §I.5.1 (m = 3, ω = 50, t_end = 200) with dop853 at rtol 1e-12."""
    return load_scene(parse_config_text(GNI_TEXT)).simulate()


def _y0():
    q, p = core.gni_initial(M, OMEGA)
    return np.array(q + p)


def test_rhs_is_minus_gradient_of_energy_and_jac_is_its_derivative():
    model = core.model(M, OMEGA)
    rng = np.random.default_rng(7)
    for _ in range(3):
        y = rng.normal(scale=0.7, size=2 * N)
        f = model.f(0.0, y)
        assert np.array_equal(f[:N], y[N:])  # q' = p
        h = 1e-6
        grad = np.empty(N)
        for k in range(N):
            e = np.zeros(N)
            e[k] = h
            grad[k] = (core.energy(y[:N] + e, y[N:], OMEGA)[0]
                       - core.energy(y[:N] - e, y[N:], OMEGA)[0]) / (2 * h)
        np.testing.assert_allclose(f[N:], -grad, rtol=1e-6, atol=1e-6 * np.max(np.abs(grad)))
        jac = model.jacobian(0.0, y)
        fd = np.column_stack([(model.f(0.0, y + h * e) - model.f(0.0, y - h * e)) / (2 * h)
                              for e in np.eye(2 * N)])
        np.testing.assert_allclose(jac, fd, rtol=1e-6, atol=1e-6 * np.max(np.abs(jac)))
    # separable split agrees with rhs
    y = rng.normal(size=2 * N)
    out = np.empty(N)
    model.separable.kick(y[:N], model.params, out)
    np.testing.assert_array_equal(out, model.f(0.0, y)[N:])


def test_energy_conserved_and_oscillatory_energy_adiabatic(gni):
    run = gni.runs["main"]
    a = gni.analysis
    assert run.attrs["method"] == "dop853" and run.status == "ok"
    e = run.invariants["energy"]
    # H is exactly conserved by the flow (GNI eq. I.5.1); measured drift 8e-11
    assert np.max(np.abs(e - e[0])) / e[0] < 1e-9
    total = a["oscillatory_energy_total"]
    # I(t) = I(0) + O(1/ω) (GNI §I.5.1, Fig. I.5.2): measured ω·max|I − I(0)| = 93 with
    # I(0) = 600.25, i.e. a relative wobble of 3.1e-3 = 0.16/ω
    # I_1(0) = ½ (y_{1,1}² + ω² x_{1,1}²), x_{1,1} = (1/ω − 1)/√2, y_{1,1} = (1 − 1)/√2 = 0
    assert a["oscillatory_energies"][0, 0] == pytest.approx(0.5 * OMEGA**2 * (1 / OMEGA - 1) ** 2 / 2,
                                                            rel=1e-14)
    dev = np.max(np.abs(total - total[0]))
    assert dev <= 0.25 * total[0] / OMEGA
    assert a["oscillatory_energy_deviation_times_omega"] == pytest.approx(OMEGA * dev)
    assert a["oscillatory_energy_relative_deviation_times_omega"] == pytest.approx(
        OMEGA * dev / total[0])
    # the lower panel of the energy-exchange figure is stored: ω (I(t) − I(0)) / I(0)
    scaled = a["oscillatory_energy_scaled_deviation"]
    np.testing.assert_allclose(scaled, OMEGA * (total - total[0]) / total[0], rtol=1e-14,
                               atol=1e-12)
    assert np.max(np.abs(scaled)) == pytest.approx(
        a["oscillatory_energy_relative_deviation_times_omega"], rel=1e-14)
    assert len(gni.checks) == 1 and gni.checks[0].rel_error < 1e-9


def test_energy_exchange_between_stiff_springs(gni):
    a = gni.analysis
    t = gni.runs["main"].t
    osc, total = a["oscillatory_energies"], a["oscillatory_energy_total"]
    assert osc.shape == (len(t), M)
    # all of I starts in the first stiff spring (GNI data: only spring 1 is stretched/moving)
    assert osc[0, 0] == pytest.approx(total[0], rel=1e-14)
    assert osc[0, 1] == 0.0 and osc[0, 2] == 0.0
    # GNI Fig. I.5.2: I_1 gives its energy to I_2 (and on to I_3) on the slow scale t ~ ω;
    # measured: I_1 < 0.7 I first at t = 32.6, min I_1 = 0.055 I, max I_2 = 0.55 I, max I_3 = 0.92 I
    below = np.flatnonzero(osc[:, 0] < 0.7 * total)
    assert below.size
    k = below[0]
    assert 20.0 < t[k] < 50.0 and a["exchange_time"] == t[k]
    assert osc[k, 1] > 0.2 * total[0]
    assert np.min(osc[:, 0]) < 0.1 * total[0]
    assert np.max(osc[:, 1]) > 0.5 * total[0]
    assert np.max(osc[:, 2]) > 0.5 * total[0]


def test_symplectic_method_has_bounded_energy_error():
    # yoshida6 with h = 0.5/ω (ωh = 0.5, inside its stability interval): measured max relative
    # energy error 6.7e-5 in the first 10 % and 6.0e-5 in the last 10 % of t ∈ [0, 200]
    model = core.model(M, OMEGA)
    t = np.linspace(0.0, 200.0, 2001)
    sol = integrate(model, _y0(), t, method="yoshida6", h=0.5 / OMEGA)
    assert sol.status == "ok"
    e = core.energy(sol.y[:, :N], sol.y[:, N:], OMEGA)
    err = np.abs(e - e[0]) / e[0]
    tenth = len(t) // 10
    assert 0 < err.max() < 1e-3
    assert err[-tenth:].max() <= 2 * err[:tenth].max()


@pytest.mark.parametrize(("table", "key"), [
    ('[initial]\nq = [1.0, 0.02, 0.0, 0.0]', "initial.q"),
    ('[initial]\np = [1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0]', "initial.p"),
    ('[params]\nomega = 0.0', "omega"),
    ('[params]\nomega = -50.0', "omega"),
    ('[params]\nm = 0', "m"),
])
def test_bad_config_names_the_key(table, key):
    text = f'kind = "fput"\n{table}\n[run]\nt_end = 1.0\n'
    with pytest.raises(ConfigError) as err:
        load_scene(parse_config_text(text))
    assert key in str(err.value)


def test_cli_end_to_end(write_config, cli, tmp_path):
    cfg = write_config("fput_small", """
        kind = "fput"
        title = "FPUT small"
        [params]
        m = 3
        omega = 50.0
        [run]
        t_end = 5.0
        samples = 201
        study = false
    """)
    code, out, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 0, out + err
    archives = list((tmp_path / "o").rglob("run.h5"))
    assert len(archives) == 1
    with h5py.File(archives[0]) as f:
        columns = [c.decode() if isinstance(c, bytes) else str(c)
                   for c in f["runs/main/y"].attrs["columns"]]
        assert f["runs/main/y"].shape == (201, 12)
        assert f["analysis/oscillatory_energies"].shape == (201, 3)
        assert f["analysis/oscillatory_energy_total"].shape == (201,)
    assert columns == [f"q{i}" for i in range(1, 7)] + [f"p{i}" for i in range(1, 7)]


def test_a_failed_taylor_run_at_rtol_1e_300_gets_its_report_and_one_line(tmp_path, cli):
    """Issue 48 G: FPUT with taylor at rtol 1e-300 ends non-finite; its report crashed on
    the NaN energies ("cannot convert float NaN to integer", exit 1 with a traceback in
    error.log); now the report is written, says failed, and prints no nan."""
    from reportgen.kinds.fput.report import FputReport

    assert FputReport.percent(float("nan")) == "—" and FputReport.percent(2.5) == "250"
    config = tmp_path / "fput_taylor.toml"
    config.write_text('kind = "fput"\ntitle = "fput taylor"\npreset = "gni"\n'
                      '[report]\nformats = ["html"]\n'
                      '[run]\nmethod = "taylor"\nrtol = 1e-300\nstudy = false\n')
    code, out, err = cli("run", config, "--out", tmp_path / "out", "--jobs", "1")
    assert code == 1 and "non-finite" in out + err and "Traceback" not in out + err
    page = (tmp_path / "out" / "fput_taylor" / "report.html").read_text(encoding="utf-8")
    import re

    assert "failed" in page and not re.search(r"\bnan\b", page, re.I)
