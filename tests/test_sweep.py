"""Sweeps ([sweep]): a family of runs from one config, in one archive; resumable."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive
from reportgen.kinds import load_scene
from reportgen.pipeline.stages import run_scene
from reportgen.scene.config import ConfigError, parse_config_text
from reportgen.scene.content import fmt
from reportgen.scene.sweep import SweepBlock, parse_sweep, partial_folder

OSCILLATOR = """
kind = "oscillator"
title = "oscillator family"

[params]
m = 2.0
omega = 1.5

[initial]
q = 1.0
p = 0.0

[run]
t_end = 6.0
samples = 301
study = false
"""


def test_parse_lists_ranges_and_dotted_keys():
    spec, problems = parse_sweep({"initial": {"theta": {"start": 0.1, "stop": 0.5, "num": 5}},
                                  "params.l": [1.0, 2.0], "store": 3}, "f.toml")
    assert problems == [] and spec.paths == ["initial.theta", "params.l"]
    assert spec.shape == (5, 2) and spec.size == 10 and spec.store == 3
    values = spec.values()
    assert np.allclose(values["initial.theta"], np.repeat([0.1, 0.2, 0.3, 0.4, 0.5], 2))
    assert np.allclose(values["params.l"], np.tile([1.0, 2.0], 5))  # grid: last key fastest
    assert list(spec.stored_members()) == [0, 4, 9]  # spread evenly, first and last kept
    log, _ = parse_sweep({"params.l": {"start": 1.0, "stop": 100.0, "num": 3,
                                       "spacing": "log"}}, "f.toml")
    assert np.allclose(log.values()["params.l"], [1.0, 10.0, 100.0])
    paired, _ = parse_sweep({"a.x": [1.0, 2.0], "a.y": [3.0, 4.0], "zip": True}, "f.toml")
    assert paired.size == 2 and list(paired.values()["a.y"]) == [3.0, 4.0]


@pytest.mark.parametrize("table, key, words", [
    ({"initial.theta": {"start": 0.1, "stop": 1.0}}, "sweep.initial.theta", "a range is"),
    ({"initial.theta": {"start": 0.1, "stop": 1.0, "num": 0}}, "sweep.initial.theta.num",
     "whole number"),
    ({"initial.theta": [1.0, "b"]}, "sweep.initial.theta.1", "finite number"),
    ({"initial.theta": [1.0, math.nan]}, "sweep.initial.theta.1", "finite number"),
    ({"initial.theta": {"start": math.nan, "stop": 1.0, "num": 3}},
     "sweep.initial.theta.start", "finite number"),
    ({"initial.theta": {"start": 0.1, "stop": math.inf, "num": 3}},
     "sweep.initial.theta.stop", "finite number"),
    ({"initial.theta": {"start": 0.1, "stop": 1.0, "num": 3, "colour": 1.5}},
     "sweep.initial.theta.colour", "unknown key of a range"),
    ({"initial": {"theta": {"start": 0.1, "stop": 1.0, "num": 3, "colour": 1.5}}},
     "sweep.initial.theta.colour", "unknown key of a range"),
    ({"initial.theta": 0.5}, "sweep.initial.theta", "a list of values or a range"),
    ({"params.l": {"start": -1.0, "stop": 1.0, "num": 3, "spacing": "log"}}, "sweep.params.l",
     "log range"),
    ({"a.x": [1.0, 2.0], "a.y": [1.0], "zip": True}, "sweep.zip", "same number"),
    ({"store": 5}, "sweep", "names no swept key"),
    ({"initial.theta": [1.0], "store": -1}, "sweep.store", "whole number"),
])
def test_bad_tables_name_the_key_the_rule_and_the_value(table, key, words):
    spec, problems = parse_sweep(table, "f.toml")
    assert spec is None and len(problems) >= 1
    assert f"f.toml: key '{key}'" in problems[0] and words in problems[0], problems
    assert "(got " in problems[0]


@pytest.mark.parametrize("line, words", [
    ("params.l = [1.0, -1.0]", ["params.l = -1", "key 'params.l'"]),
    ("params.q = [1.0, 2.0]", ["params.q", "q"]),
])
def test_invalid_members_are_config_errors_naming_the_member(write_config, cli, tmp_path,
                                                            line, words):
    path = write_config("bad", pendulum_text(extra=f"[sweep]\n{line}\n"))
    code, _, err = cli("run", path, "--out", tmp_path / "out")
    assert code == 2, err
    assert "key 'sweep': the member with" in err and all(w in err for w in words), err
    assert not (tmp_path / "out" / "bad" / "run.h5").exists()


def test_generic_sweep_archive_and_report(write_config, tmp_path):
    """A kind without a compiled ensemble: members run as whole scenes; the archive holds
    the family on the dimension ``member`` (xarray, no phony dimensions), the kept
    members' runs and a report of the family's sections only."""
    xr = pytest.importorskip("xarray")
    path = write_config("osc", OSCILLATOR + "[sweep]\nparams.omega = [1.0, 1.5, 2.0]\n"
                                            "store = 2\n")
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    archive = tmp_path / "out" / "osc" / "run.h5"
    data = read_archive(archive)
    sweep = data.sweep
    assert sweep.size == 3 and list(sweep.status) == ["ok"] * 3
    assert list(sweep.values["params.omega"]) == [1.0, 1.5, 2.0]
    assert sorted(data.runs) == ["member_0", "member_2"]
    # each member is the scene with its value: the kept runs oscillate at their omega
    for name, omega in (("member_0", 1.0), ("member_2", 2.0)):
        run = data.runs[name]
        assert np.allclose(run.y[:, 0], np.cos(omega * run.t), atol=1e-9)
    for group in ("sweep", "sweep/values", "sweep/analysis"):
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with xr.open_dataset(archive, group=group, engine="h5netcdf",
                                 phony_dims="sort") as ds:
                assert set(ds.dims) == {"member"}, (group, ds.dims)
                assert all(ds[v].dims == ("member",) for v in ds.data_vars)
    html = (tmp_path / "out" / "osc" / "report.html").read_text()
    assert 'id="sweep_results"' in html and 'id="sweep_members"' in html
    assert 'id="time_series"' not in html  # single-run sections are not repeated
    assert not partial_folder(archive.parent, data.attrs["physics_key"]).exists()


def test_killed_sweep_resumes_at_its_first_unfinished_block(write_config, tmp_path,
                                                            monkeypatch):
    """Finished blocks survive a crash; the next run reads them and runs only the rest,
    and the result equals an uninterrupted run."""
    from reportgen.kinds.oscillator import OscillatorScene

    text = OSCILLATOR + "[sweep]\nparams.omega = { start = 1.0, stop = 2.0, num = 5 }\n" \
                        "store = 0\nblock = 2\n"
    path = write_config("osc", text)
    whole = run_scene(str(path), str(tmp_path / "whole"), formats=("html",))
    assert whole.ok
    calls = []
    original = OscillatorScene.sweep_block

    def crash_on_third_block(self, lo, hi, values):
        calls.append(lo)
        if lo == 4:
            raise KeyboardInterrupt  # stands in for kill -9 (nothing after it runs)
        return original(self, lo, hi, values)

    monkeypatch.setattr(OscillatorScene, "sweep_block", crash_on_third_block)
    with pytest.raises(KeyboardInterrupt):
        run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    folder = tmp_path / "out" / "osc"
    scene = load_scene(parse_config_text(text, path))
    partial = partial_folder(folder, scene.physics_key())
    assert sorted(p.name for p in partial.glob("block-*.npz")) == [
        "block-000000.npz", "block-000001.npz"]
    assert not (folder / "run.h5").exists()
    monkeypatch.setattr(OscillatorScene, "sweep_block", original)
    calls.clear()
    monkeypatch.setattr(OscillatorScene, "sweep_block",
                        lambda self, lo, hi, values: calls.append(lo)
                        or original(self, lo, hi, values))
    again = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert again.ok and calls == [4]  # only the unfinished block ran
    resumed, reference = read_archive(folder / "run.h5").sweep, \
        read_archive(tmp_path / "whole" / "osc" / "run.h5").sweep
    assert int(resumed.attrs["resumed"]) == 4
    for name, values in reference.analysis.items():
        assert np.array_equal(values, resumed.analysis[name], equal_nan=True), name
    assert not partial.exists()


def test_sweep_is_part_of_the_physics_key(write_config):
    base = pendulum_text(extra="[sweep]\ninitial.theta = [0.5, 1.0]\n")
    other = pendulum_text(extra="[sweep]\ninitial.theta = [0.5, 1.1]\n")
    key = [load_scene(parse_config_text(t)).physics_key() for t in (base, other)]
    assert key[0] != key[1]
    resolved = load_scene(parse_config_text(base)).resolved_config()["sweep"]
    assert resolved == {"initial.theta": [0.5, 1.0], "zip": False, "store": 5, "block": 0,
                        "max_points": 2000}
    spec, problems = parse_sweep(resolved, "f.toml")  # itself a valid table
    assert problems == [] and spec.resolved() == resolved


def test_member_block_failures_are_the_members_own():
    """A member whose config is invalid inside the grid (not at a corner) gets its own
    status; the others have results."""
    from reportgen.scene.sweep import generic_block

    def make(assignments):
        if assignments["x"] == 2.0:
            raise ConfigError(["f.toml: key 'x': bad (got 2.0)"])

        class Member:
            def simulate(self):
                from reportgen.scene.results import Results
                return Results(analysis={"double": 2 * assignments["x"], "text": "no"})
        return Member()

    block = generic_block(make, {"x": np.array([1.0, 2.0, 3.0])})
    assert isinstance(block, SweepBlock)
    assert list(block.status) == ["ok", "invalid", "ok"]
    assert list(block.analysis) == ["double"]
    assert list(block.labels["text"]) == ["no", "", "no"]  # text results are labels
    assert block.analysis["double"][0] == 2.0 and math.isnan(block.analysis["double"][1])


def test_pendulum_period_sweep_of_2000_members(write_config, tmp_path):
    """The issue's family: 2000 amplitudes from rest in one config, one compiled ensemble;
    every member's period within 1e-9 of 4K(k)√(l/g), k = sin(θ0/2) (DLMF 19.2.8,
    22.19.4; scipy's ellipk takes m = k²), through the archive and the report."""
    from scipy.special import ellipk

    path = write_config("family", pendulum_text(t_end=12.0, samples=601, extra="""
        [sweep]
        initial.theta = { start = 0.01, stop = 3.1, num = 2000 }
        store = 2
        """))
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    data = read_archive(tmp_path / "out" / "family" / "run.h5")
    sweep = data.sweep
    theta = sweep.values["initial.theta"]
    assert sweep.size == 2000 and np.all(sweep.ok)
    exact = 4.0 * ellipk(np.sin(theta / 2) ** 2) * math.sqrt(1.0 / 9.81)
    rel = np.abs(sweep.analysis["period_measured"] / exact - 1)
    assert rel.max() < 1e-9, (rel.max(), theta[np.argmax(rel)])
    assert np.allclose(sweep.analysis["period"], exact, rtol=1e-12)  # the stored reference
    assert sorted(data.runs) == ["member_0", "member_1999"]
    assert data.checks and data.checks[0].rel_error == pytest.approx(rel.max(), rel=1e-6)
    html = (tmp_path / "out" / "family" / "report.html").read_text()
    assert 'id="period_family"' in html and "2000 of 2000" in html
    # the members' run time leaves out the start-up (imports, the ensemble's compiled
    # code), which the headline states beside it when it is 0.01 s or more (with numba's
    # cache warm it can be a millisecond, and the headline leaves it out)
    start_up = sweep.attrs["members_start_up_s"]
    assert 0.0 < start_up and sweep.attrs["members_wall_time_s"] > 0.0
    said = (f"start-up (imports, compiled code from numba's cache or compiled anew) "
            f"{fmt(start_up, 2)} s more")
    assert (said in html.replace("&#39;", "'")) == (start_up >= 0.01), start_up


def test_heavy_top_spin_family_keeps_each_members_case(write_config, tmp_path):
    """A kind without an ensemble, swept through its cases: the text result ``case`` is
    kept per member (/sweep/labels/case), released from rest (φ̇0 = 0) the top draws cusps
    (Goldstein §5.7: the upper circle is reached with φ̇ = 0), and the family sections and
    the kept members' loci are in the report."""
    path = write_config("tops", """
        kind = "heavy_top"
        title = "tops"
        [params]
        I1 = 1.0
        I3 = 0.5
        Mgl = 1.0
        [initial]
        theta = 1.0
        theta_dot = 0.0
        phi_dot = 0.0
        omega3 = 6.0
        [run]
        t_end = 10.0
        samples = 1000
        study = false
        [sweep]
        initial.phi_dot = [-1.0, 0.0, 0.3]
        store = 3
        """)
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    data = read_archive(tmp_path / "out" / "tops" / "run.h5")
    case = list(data.sweep.labels["case"])
    assert case[1] == "cusps" and case[0] == "loops" and case[2] == "waves", case
    assert np.all(data.sweep.analysis["theta1"] <= data.sweep.analysis["theta2"])
    html = (tmp_path / "out" / "tops" / "report.html").read_text()
    assert 'id="nutation_family"' in html and 'id="loci_family"' in html
    assert "loops → cusps" in html and "cusps → waves" in html


def test_normal_modes_spectrum_across_a_family(write_config, tmp_path):
    """A member's short arrays (its spectrum) become one result per element; coupled
    pendula: ω1² = g/l, ω2² = g/l + 2k/m (Goldstein §6.3) at every swept k."""
    path = write_config("pair", """
        kind = "normal_modes"
        preset = "coupled_pendula"
        title = "pair"
        [pendula]
        n = 2
        m = 1.0
        l = 1.0
        g = 9.81
        k = 0.5
        [sweep]
        pendula.k = [0.5, 1.0, 2.0]
        store = 0
        """)
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    sweep = read_archive(tmp_path / "out" / "pair" / "run.h5").sweep
    k = sweep.values["pendula.k"]
    assert np.allclose(sweep.analysis["frequencies_1"], math.sqrt(9.81), rtol=1e-12)
    assert np.allclose(sweep.analysis["frequencies_2"], np.sqrt(9.81 + 2 * k), rtol=1e-12)
    html = (tmp_path / "out" / "pair" / "report.html").read_text()
    assert 'id="frequencies_family"' in html and 'id="sweep_members"' not in html


def test_kepler_family_period_against_eccentricity(write_config, tmp_path):
    """Paired keys (zip): pericentre distance and speed of orbits with one semi-major axis
    (a = 1, k/μ = 1: T = 2π for every e, Kepler's third law, Goldstein eq. 3.31).  The
    circle has no pericentre to time: no measured period (it was 0.51 from round-off)."""
    es = [0.0, 0.3, 0.6]
    xs = [1.0 - e for e in es]
    vys = [math.sqrt((1 + e) / (1 - e)) for e in es]
    path = write_config("kep", f"""
        kind = "central_force"
        title = "kep"
        [params]
        m1 = 1.0
        m2 = 1.0
        k = 0.5
        [initial]
        x = 1.0
        y = 0.0
        vx = 0.0
        vy = 1.0
        [run]
        t_end = {6 * math.pi}
        samples = 6001
        study = false
        [sweep]
        zip = true
        initial.x = {xs}
        initial.vy = {vys}
        store = 0
        """)
    outcome = run_scene(str(path), str(tmp_path / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    a = read_archive(tmp_path / "out" / "kep" / "run.h5").sweep.analysis
    assert np.allclose(a["eccentricity"], es, atol=1e-12)
    assert np.allclose(a["period"], 2 * math.pi, rtol=1e-12)
    assert math.isnan(a["period_measured"][0])
    assert np.allclose(a["period_measured"][1:], 2 * math.pi, rtol=1e-9)
    html = (tmp_path / "out" / "kep" / "report.html").read_text()
    assert 'id="kepler_family"' in html and "2 of 3" in html


@pytest.mark.parametrize("name", ["pendulum_period_sweep", "heavy_top_spin_family",
                                  "hamiltonian_henon_heiles_section_family",
                                  "two_center_section_family"])
def test_every_broken_key_of_a_shipped_sweep_is_named(name, tmp_path, cli):
    """Each value of the resolved [sweep] table broken in turn (NaN for a number, 7 for a
    string or boolean), and an unknown key added to each of its tables: validate exits 2
    naming that very key (as tests/test_fuzz_config.py does at random for every table)."""
    from pathlib import Path

    from test_fuzz_config import _without_none

    from reportgen.scene.config import read_config, to_toml

    path = Path(__file__).resolve().parent.parent / "configs" / f"{name}.toml"
    doc = _without_none(load_scene(read_config(path)).resolved_config())
    sweep = doc["sweep"]
    cases = []
    for key, value in sweep.items():
        if isinstance(value, dict):
            for sub, item in value.items():
                broken = math.nan if isinstance(item, (int, float)) and not isinstance(
                    item, bool) else 7
                cases.append(({key: {**value, sub: broken}}, f"sweep.{key}.{sub}"))
            cases.append(({key: {**value, "colour": 1.5}}, f"sweep.{key}.colour"))
        else:
            broken = math.nan if isinstance(value, (int, float)) and not isinstance(
                value, bool) else 7
            cases.append(({key: broken}, f"sweep.{key}"))
    cases.append(({"colour": 1.5}, "sweep.colour"))
    for i, (change, key) in enumerate(cases):
        target = tmp_path / f"case{i}.toml"
        target.write_text(to_toml({**doc, "sweep": {**sweep, **change}}))
        code, out, err = cli("validate", target)
        assert code == 2, (key, out, err)
        assert f"{target}: key '{key}'" in err, (key, err)


def test_swept_values_take_units_as_the_key_itself_does(write_config, cli):
    """Issue 43: ``start = "5 deg"`` is 5° in the swept key's declared unit (rad), as
    ``theta = "5 deg"`` is; a list may mix text and plain numbers (the declared unit);
    a unit of the wrong dimension, and unit text on a key that declares no unit, exit 2
    naming the key and the rule."""
    def sweep_of(table: str):
        return load_scene(parse_config_text(pendulum_text() + f"\n[sweep]\n{table}\n")).sweep

    spec = sweep_of('initial.theta = { start = "5 deg", stop = "90 deg", num = 4 }')
    assert np.allclose(spec.values()["initial.theta"], np.radians([5.0, 33.3333333, 61.6666667,
                                                                   90.0]), rtol=1e-8)
    spec = sweep_of('initial.theta = ["30 deg", 0.5, "1000 mrad"]')
    assert spec.values()["initial.theta"].tolist() == pytest.approx([math.pi / 6, 0.5, 1.0])
    log = sweep_of('params.l = { start = "50 cm", stop = "2 m", num = 3, spacing = "log" }')
    assert log.values()["params.l"].tolist() == pytest.approx([0.5, 1.0, 2.0])

    wrong = write_config("wrong", pendulum_text() + '\n[sweep]\ninitial.theta = '
                                                    '{ start = "5 deg", stop = "2 kg", num = 3 }\n')
    code, _, err = cli("validate", wrong)
    assert code == 2 and "sweep.initial.theta.stop" in err and "mass" in err, err
    free = write_config("free", """
        kind = "hamiltonian"
        [params]
        k = 1.0
        [system]
        coordinates = ["x"]
        H = "p_x**2/2 + k*x**2/2"
        [initial]
        x = 1.0
        p_x = 0.0
        [run]
        t_end = 5.0
        [sweep]
        params.k = ["2 N/m", 3.0]
        """)
    code, _, err = cli("validate", free)
    assert code == 2 and "sweep.params.k.0" in err and "declares no unit" in err, err
