"""Words that follow the scene's own facts (issue 41), ``hamiltonian`` kind.

Each false statement a reviewer found, on a config of the same shape that nobody shipped:
the report now states the true case, chosen by a stored classification with its threshold,
and what it said before is gone; every claim its report makes holds against its archive
(``claimgen.contradictions_of``).  The studies are off.
"""

from __future__ import annotations

import math
import tomllib
from pathlib import Path

import numpy as np
import pytest

import claimgen
from reportgen.core.integrators.stability import assess_run, relative_drift
from reportgen.scene.results import RunRecord

UNSEEN = Path(__file__).resolve().parent / "data" / "unseen"


def _unseen(name: str, **run) -> dict:
    config = tomllib.loads((UNSEEN / f"{name}.toml").read_text(encoding="utf-8"))
    config["run"].update({"study": False, **run})
    return config


@pytest.fixture(scope="module")
def toda(tmp_path_factory):
    """The periodic Toda lattice of three particles with P = Σp = 0 (tests/data/unseen)."""
    config = _unseen("hamiltonian_toda", t_end=30.0, samples=1501)
    data = claimgen.run_config(config, tmp_path_factory.mktemp("toda"))
    from reportgen.rendering.report import report_text
    from reportgen.scene.claims import contradictions

    text = report_text(data)
    return data, text, contradictions(data, text)


# ------------------------------------------- 1. a conserved quantity that starts at 0
def test_toda_total_momentum_at_zero_is_judged_against_its_terms(toda):
    """P = p₁ + p₂ + p₃ starts at 0: its round-off was divided by its own size (drift 1,
    "unstable", exit 1).  Now its absolute drift is measured against the largest sum of
    the sizes of its terms along the run, Σ|pᵢ|, archived as its scale."""
    data, text, found = toda
    run = data.runs["main"]
    assert data.status == "ok" and run.attrs["status"] == "ok", run.attrs["message"]
    P = np.asarray(run.invariants["P"])
    assert abs(P[0]) <= 1e-15  # at rest as a whole: round-off about 0
    y = np.asarray(run.y)
    sizes = np.max(np.sum(np.abs(y[:, 3:]), axis=1))  # Σ|p_i|, the terms of P
    assert run.attrs["scale_P"] == pytest.approx(sizes, rel=1e-12)
    # measured: 7.5e-16 of Σ|p| (and H, I₃ to ~5e-12 of their scales)
    assert run.attrs["drift_P"] <= 1e-13
    assert run.attrs["drift_I3"] <= 1e-9 and run.attrs["drift_H"] <= 1e-9
    assert "drifted by" not in run.attrs["message"]
    # the report says what each drift is relative to
    assert "the largest sum of the sizes of its terms along the run" in text
    assert "the energy scale max(|H(0)|, |T(0)|, |V(0)|)" in text
    assert found == [], found


def test_relative_drift_uses_the_declared_scale_never_the_initial_value():
    """core.integrators.stability: with a declared scale the drift is absolute over it."""
    rounding = np.array([0.0, 3e-17, -2e-16, 1e-16])
    assert relative_drift(rounding) == pytest.approx(1.0, rel=0.5)  # own size: round-off
    assert relative_drift(rounding, scale=2.0) == pytest.approx(1e-16)


@pytest.mark.parametrize("drift, verdict", [(1e-16, "ok"), (1e-3, "unstable")])
def test_a_quantity_starting_at_zero_is_unstable_only_when_it_drifts(drift, verdict):
    """A legitimately drifting run still comes out unstable: drift 1e-3 of its scale 2.0
    is above the bound 1e-6 of rtol 1e-10; round-off is not."""
    t = np.linspace(0.0, 1.0, 5)
    record = RunRecord(t=t, y=np.zeros((5, 2)), columns=["q", "p"],
                       invariants={"P": drift * 2.0 * t}, attrs={"h": math.nan})
    assess_run(record, rtol=1e-10, scales={"P": 2.0})
    assert record.attrs["status"] == verdict
    if verdict == "unstable":
        assert "of its declared scale 2" in record.attrs["message"]


# ------------------------------------------------------ 2. H given, or L given
def test_h_given_is_not_said_to_come_from_a_lagrangian(toda):
    data, text, _ = toda
    assert data.config["system"]["L"] is None
    assert "took the Hamiltonian as the configuration gives it" in text
    assert "Legendre transform" not in text
    assert "from a Lagrangian" not in text


def test_l_given_is_said_to_come_through_the_legendre_transform(tmp_path):
    """A charged particle in a magnetic field, given by L (tests/data/unseen): its H mixes
    coordinates and momenta, and its canonical L_z starts at 0 and is conserved."""
    found, text = claimgen.contradictions_of(
        _unseen("hamiltonian_charged_particle", t_end=20.0, samples=801), tmp_path)
    assert "from the Lagrangian the configuration gives, through the Legendre transform" \
        in text
    assert "took the Hamiltonian as" not in text
    assert "no: H mixes coordinates and momenta" in text
    assert "kinetic and potential parts split, so" not in text
    assert found == [], found


# --------------------------------------------- 3. "separable" named correctly
def test_split_hamiltonian_is_named_by_its_structure_not_separable(toda):
    """Toda's H = Σp²/2 + Σ exp(qᵢ − qᵢ₊₁) is T(p) + V(q), which is not separable (its
    Hamilton–Jacobi equation does not separate in these coordinates)."""
    data, text, _ = toda
    assert data.analysis["kinetic_potential_split"] is True
    assert "separable" not in data.analysis
    assert "H = T(p) + V(q), kinetic and potential parts split" in text
    assert "yes: kinetic and potential parts split" in text
    assert "H separable" not in text and ", separable)" not in text


def test_polar_kepler_is_not_split(tmp_path):
    config = {"kind": "hamiltonian", "params": {"k": 1.0},
              "system": {"coordinates": ["r", "phi"],
                         "H": "p_r**2/2 + p_phi**2/(2*r**2) - k/r"},
              "initial": {"r": 1.0, "phi": 0.3, "p_r": 0.1, "p_phi": 0.9},
              "run": {"t_end": 10.0, "samples": 401, "study": False}}
    found, text = claimgen.contradictions_of(config, tmp_path)
    assert "no: H mixes coordinates and momenta" in text
    assert "kinetic and potential parts split" not in text.replace(
        "H = T(p) + V(q), its kinetic and potential parts split", "")
    assert "φ (its conjugate momentum is conserved)" in text
    assert "the largest |momentum| along the run" in text
    assert found == [], found


# ------------------------------------------ 4. conserved for these constants' values
def test_observable_conserved_at_equal_constants(tmp_path):
    """L_z of an oscillator with ω_x = ω_y written as two constants: {L_z, H} is
    (ω_y² − ω_x²) x y with symbols, zero at their values; it was called "not conserved"."""
    config = {"kind": "hamiltonian", "params": {"wx": 1.3, "wy": 1.3},
              "system": {"coordinates": ["x", "y"],
                         "L": "(x_dot**2 + y_dot**2)/2 - (wx**2*x**2 + wy**2*y**2)/2"},
              "observables": {"Lz": "x*y_dot - y*x_dot"},
              "initial": {"x": 0.7, "y": 0.2, "x_dot": 0.1, "y_dot": -0.5},
              "run": {"t_end": 10.0, "samples": 401, "study": False}}
    data = claimgen.run_config(config, tmp_path)
    assert data.analysis["conserved_Lz"] is True
    assert "Lz" in data.runs["main"].invariants and "observables" not in data.analysis


def test_toda_names_conserved_and_moving_observables(toda):
    data, text, _ = toda
    a = data.analysis
    assert a["conserved_P"] and a["conserved_I3"] and not a["conserved_spacing"]
    assert "observables conserved ({f, H} + ∂f/∂t simplifies to 0)" in text
    assert "observables not conserved ({f, H} + ∂f/∂t ≠ 0)" in text
    assert "none: H depends on every coordinate" in text


# ------------------------------------------------------ 5. regular, with its threshold
def test_regular_orbit_states_the_threshold(toda):
    data, text, _ = toda
    a = data.analysis
    assert a["chaos_growth_threshold"] == 1e6 and a["separation_growth"] < 1e6
    assert "below the 10⁶× that marks exponential divergence" in text
    assert "(no exponential divergence)" not in text
