"""A surface of section built from many orbits: the crossings of every member of a
``hamiltonian`` sweep as per-member point sets (``/sweep/points/poincare``), capped, resumable,
on the energy surface, and drawn only where the members cross."""

from __future__ import annotations

import shutil
import warnings

import h5py
import numpy as np
import pytest

from reportgen.archive.store import read_archive
from reportgen.kinds import load_scene
from reportgen.kinds.hamiltonian import HamiltonianScene
from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import parse_config_text
from reportgen.scene.sweep import parse_sweep, partial_folder

ENERGY = 0.125
#: Hénon & Heiles, Astron. J. 69, 73 (1964), eq. (7), at E = 1/8 (their Fig. 3); p_x is
#: solved for each member so that H = energy.  Δt = 0.025 between samples: the cubic
#: Hermite crossings then lie within ~1e-9 of the energy surface.
HENON_HEILES = f"""
kind = "hamiltonian"
title = "Hénon–Heiles family"

[system]
coordinates = ["x", "y"]
H = "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3"

[initial]
x = 0.0
y = 0.0
p_y = 0.0
energy = {ENERGY!r}

[section]
coordinate = "x"
value = {{value}}
axes = ["y", "p_y"]

[run]
t_end = 200.0
samples = 8001
study = false

[report]
formats = ["html"]

[sweep]
initial.y = [-0.3, 0.0, 0.3, 0.5]
store = 0
max_points = {{cap}}
block = {{block}}
"""
#: crossings kept per member in the capped family: fewer than the ~30 of each orbit
CAP = 20


def henon_heiles(value: float = 0.0, cap: int = CAP, block: int = 0) -> str:
    return HENON_HEILES.format(value=value, cap=cap, block=block)


def hamiltonian_energy(state: np.ndarray) -> np.ndarray:
    """H of Hénon–Heiles at rows (x, y, p_x, p_y), written out here, not by reportgen."""
    x, y, px, py = state.T
    return (px**2 + py**2) / 2 + (x**2 + y**2) / 2 + x**2 * y - y**3 / 3


@pytest.fixture(scope="module")
def family(tmp_path_factory):
    """The capped family, run once: (config path, scene folder)."""
    root = tmp_path_factory.mktemp("family")
    path = root / "hh.toml"
    path.write_text(henon_heiles())
    outcome = run_scene(str(path), str(root / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    return path, root / "out" / "hh"


def test_crossings_round_trip_capped(family):
    """Each member's first CAP crossings, bit for bit as its own run finds them, with the
    member index of every row; ``poincare_points`` counts them all."""
    path, folder = family
    sweep = read_archive(folder / "run.h5").sweep
    pts = sweep.points["poincare"]
    assert pts.attrs["max_points"] == CAP and list(pts.attrs["axes"]) == ["y", "p_y"]
    assert pts.components == ("x", "y", "p_x", "p_y")
    member = np.asarray(pts.member)
    assert np.all(np.diff(member) >= 0) and set(member) == {0, 1, 2, 3}
    total = sweep.analysis["poincare_points"]
    kept = pts.counts(sweep.size)
    assert np.all(total > CAP), total  # every orbit crossed more often than kept
    assert list(kept) == [CAP] * sweep.size
    scene = load_scene(parse_config_text(path.read_text(), path))
    for i in (0, 3):
        alone = scene.member({"initial.y": float(sweep.values["initial.y"][i])}).simulate()
        found = alone.analysis["poincare"]
        assert total[i] == len(found["t"])
        rows = member == i
        for name in ("t", "u", "v", "state"):
            assert np.array_equal(pts.columns[name][rows], np.asarray(found[name])[:CAP]), name


def test_crossings_lie_on_each_members_energy_surface(family):
    """Physics: at every stored crossing x = 0, p_x > 0 (crossed with x increasing) and
    H(x, y, p_x, p_y) = E to 1e-9 (each member's p_x was solved so that H = E)."""
    _, folder = family
    sweep = read_archive(folder / "run.h5").sweep
    pts = sweep.points["poincare"]
    state = pts.columns["state"]
    assert np.allclose(sweep.analysis["H0"], ENERGY, rtol=0, atol=1e-15)
    assert np.max(np.abs(state[:, 0])) < 1e-10
    assert np.all(state[:, 2] > 0)
    assert np.max(np.abs(hamiltonian_energy(state) - ENERGY)) < 1e-9
    # u, v are the plotted columns y, p_y of the same state
    assert np.array_equal(pts.columns["u"], state[:, 1])
    assert np.array_equal(pts.columns["v"], state[:, 3])
    assert np.max(sweep.analysis["poincare_H_error"]) < 1e-9


def test_xarray_opens_the_points_with_named_dimensions(family):
    xr = pytest.importorskip("xarray")
    _, folder = family
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with xr.open_dataset(folder / "run.h5", group="sweep/points/poincare",
                             engine="h5netcdf", phony_dims="sort") as ds:
            assert set(ds.dims) == {"point", "component"}, ds.dims
            assert ds["member"].dims == ("point",) and ds["t"].dims == ("point",)
            assert ds["state"].dims == ("point", "component")
            assert list(ds["component"].values) == ["x", "y", "p_x", "p_y"]
            assert ds.sizes["point"] == 4 * CAP
            assert set(np.unique(ds["member"].values)) == {0, 1, 2, 3}


def test_family_section_only_where_members_cross(family, tmp_path):
    """The family's surface of section (with the capping said) is in the sweep's report,
    the single-run section is not; a family whose members never reach the surface, and
    an archive of a sweep without /sweep/points (older), read and report without it."""
    _, folder = family
    html = (folder / "report.html").read_text()
    assert 'id="poincare_family"' in html and 'id="poincare"' not in html
    assert f"the first {CAP} crossings of each orbit" in html

    far = tmp_path / "far.toml"  # x never reaches 5 on this energy surface
    far.write_text(henon_heiles(value=5.0))
    outcome = run_scene(str(far), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    data = read_archive(tmp_path / "out" / "far" / "run.h5")
    assert len(data.sweep.points["poincare"].member) == 0
    assert list(data.sweep.analysis["poincare_points"]) == [0.0] * 4
    assert 'id="poincare_family"' not in (tmp_path / "out" / "far" / "report.html").read_text()

    old = tmp_path / "old.h5"
    shutil.copy(folder / "run.h5", old)
    with h5py.File(old, "a") as f:
        del f["sweep/points"]
    data = read_archive(old)
    assert data.sweep.points == {} and data.sweep.size == 4
    assert [s.name for s in HamiltonianScene.chosen_sections(data)] == ["sweep_results"]


def test_resume_after_a_killed_block_keeps_the_points(tmp_path, monkeypatch):
    """Blocks of one member: the run killed in its third block resumes there, and the
    points equal an uninterrupted run's, member indices included."""
    path = tmp_path / "hh.toml"
    path.write_text(henon_heiles(block=1))
    whole = run_scene(str(path), str(tmp_path / "whole"), formats=("html",))
    assert whole.ok, whole.message
    original = HamiltonianScene.sweep_block

    def killed_in_third_block(self, lo, hi, values):
        if lo == 2:
            raise KeyboardInterrupt  # stands in for kill -9
        return original(self, lo, hi, values)

    monkeypatch.setattr(HamiltonianScene, "sweep_block", killed_in_third_block)
    with pytest.raises(KeyboardInterrupt):
        run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    scene = load_scene(parse_config_text(path.read_text(), path))
    partial = partial_folder(tmp_path / "out" / "hh", scene.physics_key())
    assert len(list(partial.glob("block-*.npz"))) == 2
    ran = []
    monkeypatch.setattr(HamiltonianScene, "sweep_block",
                        lambda self, lo, hi, values: ran.append(lo)
                        or original(self, lo, hi, values))
    again = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert again.ok and ran == [2, 3]
    resumed = read_archive(tmp_path / "out" / "hh" / "run.h5").sweep
    reference = read_archive(tmp_path / "whole" / "hh" / "run.h5").sweep
    assert int(resumed.attrs["resumed"]) == 2
    got, want = resumed.points["poincare"], reference.points["poincare"]
    assert np.array_equal(got.member, want.member) and set(got.member) == {0, 1, 2, 3}
    assert got.components == want.components and got.attrs == want.attrs
    for name, values in want.columns.items():
        assert np.array_equal(got.columns[name], values), name


@pytest.mark.parametrize("value", [-1, 1.5, True, "many", 10**7])
def test_max_points_must_be_a_whole_number_in_range(value):
    spec, problems = parse_sweep({"initial.y": [0.1], "max_points": value}, "f.toml")
    assert spec is None and "f.toml: key 'sweep.max_points'" in problems[0], problems
