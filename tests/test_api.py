"""The Python API (reportgen.run / open / kinds, Run.to_xarray) and xarray on archives."""

from __future__ import annotations

import doctest
import math
import re
import subprocess
import sys
import warnings
from pathlib import Path

import h5py
import numpy as np
import pytest

import reportgen
from reportgen import api
from reportgen.archive.h5io import ArchiveError
from reportgen.errors import ConfigError

ROOT = Path(__file__).resolve().parent.parent

PENDULUM = {"kind": "pendulum", "title": "Pendulum — API test (θ0 = 0.3)",
            "params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 0.3},
            "run": {"t_end": 4.0, "samples": 401}}
SWEEP = {"kind": "pendulum", "title": "Three swings",
         "params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 1.0},
         "run": {"t_end": 6.0, "samples": 601},
         "sweep": {"initial": {"theta": {"start": 0.1, "stop": 1.5, "num": 3}}}}


@pytest.fixture(scope="module")
def out(tmp_path_factory):
    root = tmp_path_factory.mktemp("api")
    single = reportgen.run(PENDULUM, out=root, formats=("html",))
    family = reportgen.run(SWEEP, out=root, formats=("html",))
    assert single.ok and family.ok, (single.message, family.message)
    return root, single, family


def _files(root: Path) -> set[Path]:
    return {p for p in root.rglob("*") if p.is_file()}


def test_doctests(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    result = doctest.testmod(api, extraglobs={"tmp": tmp_path},
                             optionflags=doctest.ELLIPSIS | doctest.IGNORE_EXCEPTION_DETAIL)
    assert result.attempted >= 10 and result.failed == 0


def test_run_from_dict_writes_its_source_inside_out(out):
    root, single, _ = out
    assert single.name == "pendulum_api_test_0_0_3"
    source = root / single.name / f"{single.name}.toml"
    assert "theta = 0.3" in source.read_text(encoding="utf-8")
    assert Path(single.folder) == root / single.name
    assert all(root in p.parents for p in _files(root))


def test_run_twice_skips_the_stages(out):
    root, single, _ = out
    again = reportgen.run(PENDULUM, out=root, formats=("html",))
    assert again.ok and again.stages == []


def test_run_from_a_toml_file_and_a_folder(tmp_path):
    cfg = tmp_path / "in" / "swing.toml"
    cfg.parent.mkdir()
    from reportgen.scene.config import to_toml

    cfg.write_text(to_toml(PENDULUM), encoding="utf-8")
    one = reportgen.run(cfg, out=tmp_path / "o", formats=("html",))
    assert one.ok and one.name == "swing"
    many = reportgen.run(cfg.parent, out=tmp_path / "o", formats=("html",))
    assert [o.name for o in many] == ["swing"] and many[0].stages == []


@pytest.mark.parametrize("name", ["../escape", ".hidden", "a/b"])
def test_a_scene_name_leading_out_of_out_is_a_config_error(tmp_path, name):
    out = tmp_path / "out"
    with pytest.raises(ConfigError):
        reportgen.run(PENDULUM, out=out, name=name, formats=("html",))
    assert not _files(tmp_path)


def test_a_bad_config_raises_config_error_with_one_line(tmp_path):
    bad = {**PENDULUM, "initial": {"theta": "high"}}
    with pytest.raises(ConfigError) as err:
        reportgen.run(bad, out=tmp_path, name="bad", formats=("html",))
    message = str(err.value)
    assert "\n" not in message and "theta" in message
    assert not (tmp_path / "bad" / "run.h5").exists()


def test_open_reads_attributes(out):
    _, single, _ = out
    r = reportgen.open(single.folder)
    assert isinstance(r, reportgen.Run)
    assert (r.kind, r.title, r.status) == ("pendulum", PENDULUM["title"], "ok")
    assert r.behaviour.startswith("libration")
    assert r.config["params"]["g"] == 9.81 and r.config["initial"]["theta"] == 0.3
    assert isinstance(r.config, dict) and type(r.config["params"]) is dict
    assert all(isinstance(v.value, (bool, int, float, str)) for v in r.results.values())
    # the exact period 4K(k)·sqrt(l/g), k = sin(θ0/2)
    from scipy.special import ellipk

    exact = 4 * ellipk(math.sin(0.15) ** 2) * math.sqrt(1.0 / 9.81)
    assert float(r.results["period"]) == pytest.approx(exact, rel=1e-12)
    assert r.checks and {"quantity", "value", "reference", "abs_error", "rel_error", "unit",
                         "source"} <= set(r.checks[0])


def test_to_xarray_main_run(out):
    _, single, _ = out
    ds = reportgen.open(Path(single.folder) / "run.h5").to_xarray()
    assert list(ds.sizes) == ["t"] and ds.sizes["t"] == 401
    assert ds.t.attrs["units"] == "s"
    assert ds.theta.attrs == {"units": "rad", "long_name": "angle from the downward vertical",
                              "symbol": "\\theta"}
    assert ds.theta_dot.attrs["units"] == "rad/s"
    assert float(ds.theta[0]) == 0.3
    # against the stored exact solution, and energy conserved (the invariant)
    np.testing.assert_allclose(ds.theta, ds.reference_theta, atol=1e-9)
    assert float(abs(ds.energy - ds.energy[0]).max()) < 1e-9 * abs(float(ds.energy[0]))
    for name, var in ds.variables.items():
        assert "units" in var.attrs and "long_name" in var.attrs, name
    for key, value in ds.attrs.items():
        assert not isinstance(value, bytes), key
    assert ds.attrs["behaviour"].startswith("libration")


def test_to_xarray_sweep(out):
    _, _, family = out
    r = reportgen.open(family.folder)
    ds = r.to_xarray()
    assert dict(ds.sizes) == {"member": 3}
    np.testing.assert_allclose(ds.initial_theta, [0.1, 0.8, 1.5])
    assert ds.initial_theta.attrs["units"] == "rad"
    assert "initial_theta" in ds.coords
    assert ds.status.dtype.kind == "U" and list(ds.status.values) == ["ok"] * 3
    from scipy.special import ellipk

    exact = [4 * ellipk(math.sin(a / 2) ** 2) * math.sqrt(1 / 9.81) for a in (0.1, 0.8, 1.5)]
    np.testing.assert_allclose(ds.period, exact, rtol=1e-12)
    assert ds.period.attrs["units"] == "s"
    np.testing.assert_allclose(ds.period_measured.sel(member=2), exact[2], rtol=1e-8)
    assert r.behaviour is None


def test_repr_html_shows_title_status_headline_and_figures(out):
    _, single, _ = out
    page = reportgen.open(single.folder)._repr_html_()
    assert "Pendulum — API test (θ<sub>0</sub> = 0.3)" in page and "ok" in page  # typeset
    assert "libration" in page and "period" in page  # the headline facts
    assert 1 <= page.count("<svg") <= api.REPR_FIGURES
    # the kind's signature figures, as the gallery card's (issue 43): the phase portrait
    # first, then the period, not the first files alphabetically (energy, the study)
    shown = re.findall(r"<div style='max-width:40em' title='([^']+)'>", page)
    assert shown == ["phase_portrait-phase.svg", "period-period.svg"], shown


def test_repr_html_without_figures(out, tmp_path):
    _, single, _ = out
    alone = tmp_path / "run.h5"
    alone.write_bytes((Path(single.folder) / "run.h5").read_bytes())
    page = reportgen.open(alone)._repr_html_()
    assert "<svg" not in page and "period" in page


@pytest.mark.parametrize("damage", ["garbage", "truncated", "missing"])
def test_open_a_bad_file_raises_the_archive_error(out, tmp_path, damage):
    _, single, _ = out
    path = tmp_path / "run.h5"
    good = (Path(single.folder) / "run.h5").read_bytes()
    if damage == "garbage":
        path.write_bytes(b"not an archive" * 100)
    elif damage == "truncated":
        path.write_bytes(good[: len(good) // 2])
    with pytest.raises(ArchiveError):
        reportgen.open(path)


def test_open_an_archive_missing_its_config_raises(out, tmp_path):
    _, single, _ = out
    path = tmp_path / "run.h5"
    path.write_bytes((Path(single.folder) / "run.h5").read_bytes())
    with h5py.File(path, "r+") as f:
        del f["config"]
    with pytest.raises(ArchiveError, match="config"):
        reportgen.open(path)


def test_kinds_lists_every_kind_with_presets_and_keys():
    from reportgen.kinds import KINDS

    listing = reportgen.kinds()
    assert [k["name"] for k in listing] == list(KINDS)
    for entry in listing:
        assert entry["summary"] == KINDS[entry["name"]].summary
        assert entry["presets"] == list(KINDS[entry["name"]].presets)
        assert {"kind", "title"} <= {k["key"] for k in entry["keys"]}
    pendulum = {k["key"]: k for k in listing[[k["name"] for k in listing].index("pendulum")]
                ["keys"]}
    assert pendulum["params.g"]["units"] == "m/s^2"
    assert pendulum["params.g"]["description"] == "gravitational acceleration"
    assert pendulum["params.m"]["default"] == "default 1.0"
    assert "large_amplitude" in listing[0]["presets"]


def test_import_reportgen_stays_light():
    code = ("import sys, reportgen\nprint(' '.join(sorted(m for m in sys.modules)))")
    loaded = set(subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                                check=True).stdout.split())
    heavy = {"reportgen.api", "h5py", "xarray", "numpy", "numba", "reportgen.kinds"}
    assert not loaded & heavy, sorted(loaded & heavy)
    assert callable(reportgen.run) and "open" in dir(reportgen)
    with pytest.raises(AttributeError):
        reportgen.no_such_thing  # noqa: B018


# ------------------------------------------------------------- xarray directly
def _open_group_quietly(path: Path, group: str):
    import xarray as xr

    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the phony_dims warning (or any other) fails
        return xr.open_dataset(path, group=group, engine="h5netcdf")


def _assert_named_dims_and_units(path: Path, group: str):
    from pages import unit_problems

    with _open_group_quietly(path, group) as ds:
        assert not [d for d in ds.dims if str(d).startswith("phony")], ds.dims
        assert not unit_problems(ds), (path, group, unit_problems(ds))


def test_xarray_opens_fresh_archives_without_phony_dims(out):
    _, single, family = out
    for group in ("runs/main", "study/error_vs_runtime", "checks"):
        _assert_named_dims_and_units(Path(single.folder) / "run.h5", group)
    for group in ("sweep", "sweep/values", "sweep/analysis"):
        _assert_named_dims_and_units(Path(family.folder) / "run.h5", group)


# every shipped archive and every variant: tests/test_shipped_pages.py


# ------------------------------------------------------------------- notebook
def test_example_notebook_runs(tmp_path, monkeypatch):
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    notebook = nbformat.read(ROOT / "docs" / "example.ipynb", as_version=4)
    monkeypatch.chdir(tmp_path)
    nbclient.NotebookClient(notebook, timeout=120, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [o for cell in notebook.cells if cell.cell_type == "code"
               for o in cell.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    assert any("image/png" in o.get("data", {}) for o in outputs)  # the plot was drawn
    assert all(tmp_path in p.parents for p in _files(tmp_path))


# ------------------------------------------------------- groups, /analysis, point sets
CO2 = {"kind": "normal_modes", "title": "CO₂ — API test", "preset": "co2",
       "report": {"formats": ["html"]}}
SECTIONS = {"kind": "hamiltonian", "title": "Hénon–Heiles sections — API test",
            "system": {"coordinates": ["x", "y"],
                       "H": "(p_x**2 + p_y**2)/2 + (x**2 + y**2)/2 + x**2*y - y**3/3"},
            "initial": {"x": 0.0, "y": 0.0, "p_y": 0.0, "energy": 0.125},
            "section": {"coordinate": "x", "axes": ["y", "p_y"]},
            "run": {"t_end": 60.0, "samples": 6001, "study": False},
            "sweep": {"initial": {"y": {"start": -0.2, "stop": 0.2, "num": 3}}, "store": 0},
            "report": {"formats": ["html"]}}


def test_a_kind_without_a_run_opens_as_its_analysis(tmp_path):
    """Normal modes integrate nothing: ``to_xarray()`` is ``/analysis`` on named
    dimensions; the CO₂ frequencies against the textbook's closed form (ω² = k/m,
    (k/m)(1 + 2m/M) for the linear triatomic, Goldstein §6.4) through the dataset."""
    done = reportgen.run(CO2, out=tmp_path)
    assert done.ok, done.message
    r = reportgen.open(done.folder)
    ds = r.to_xarray()
    assert ds.identical(r.to_xarray("analysis").assign_attrs(ds.attrs))
    assert "frequencies" in ds and ds.frequencies.dims == ("mode",)
    assert ds.frequencies.attrs["units"] == "rad/s" and "mode" in ds.coords
    from pages import unit_problems

    assert not unit_problems(ds), unit_problems(ds)
    assert not [d for d in ds.dims if str(d).startswith("phony")]
    with pytest.raises(ValueError, match="no group 'nowhere'.*analysis"):
        r.to_xarray("nowhere")
    # one numbering for modes: the report's mode k is the archive's mode k (issue 43)
    n = ds.sizes["mode"]
    np.testing.assert_array_equal(ds.mode, np.arange(1, n + 1))
    zero = int(ds.attrs.get("n_zero_modes", r.results["n_zero_modes"].value))
    first = zero + 1  # the first vibration: the report's table starts there
    page = (Path(done.folder) / "report.html").read_text(encoding="utf-8")
    rows = re.findall(r'<tr><td[^>]*><span class="nw">(\d+)</span></td><td[^>]*>'
                      r'<span class="nw">([\d.]+)[^<\d]*10<sup>(\d+)</sup>', page)
    assert [int(k) for k, _, _ in rows] == list(range(first, n + 1)), rows
    for k, mantissa, exponent in rows:  # the spectrum table's ω of mode k, to 6 digits
        shown = float(mantissa) * 10.0 ** int(exponent)
        assert ds.frequencies.sel(mode=int(k)).item() == pytest.approx(shown, rel=1e-5), k
    # the bend (mode 6, twice) is the lowest of CO₂'s vibrations, the stretches above it
    omega = ds.frequencies.sel(mode=first).item()
    assert omega == ds.frequencies.where(ds.frequencies > 0).min().item()


FORMULA = {"kind": "hamiltonian", "title": "Formula oscillator — API units",
           "system": {"coordinates": ["x"], "H": "p_x**2/2 + x**2/2"},
           "observables": {"x2": "x**2"}, "initial": {"x": 1.0, "p_x": 0.0},
           "run": {"t_end": 3.0, "samples": 301, "study": False},
           "report": {"formats": ["html"]}}


def test_results_carry_units_descriptions_and_symbols(out):
    """``run.results``: each scalar result with the unit, words and symbol its kind declares
    (the pendulum's exact period in s), a number as before (``float``, ``.value``) and as a
    pint Quantity."""
    _, single, _ = out
    r = reportgen.open(single.folder)
    period = r.results["period"]
    assert (period.unit, period.symbol) == ("s", "T") and "period" in period.description
    assert float(period) == period.value == r.results.period.value
    assert period.quantity.to("ms").magnitude == pytest.approx(1e3 * period.value, rel=1e-15)
    assert str(period) == f"{period.value} s" and f"{period:.3f}" == f"{period.value:.3f}"
    assert r.results.values_only()["period"] == period.value
    behaviour = r.results["behaviour"]
    assert isinstance(behaviour.value, str) and behaviour.unit == ""
    with pytest.raises(TypeError):
        behaviour.quantity  # noqa: B018


def test_a_config_units_quantity_says_so_beside_a_unit_pint_reads(tmp_path):
    """A formula system works in its author's units: its time is "1" (pint reads it) with
    ``config_units`` saying what it is, in the archive, in ``to_xarray`` and in
    ``run.results``; pint-xarray quantifies every group of the tree."""
    pytest.importorskip("pint_xarray")
    from pages import assert_tree_quantifies

    done = reportgen.run(FORMULA, out=tmp_path)
    assert done.ok, done.message
    r = reportgen.open(done.folder)
    t = r.to_xarray().t
    assert t.attrs["units"] == "1" and t.attrs["config_units"] == "config units of time"
    assert r.to_xarray().x.attrs["config_units"].startswith("config units")
    with h5py.File(r.h5) as f:
        assert f["runs/main/t"].attrs["config_units"] == "config units of time"
    assert r.results["H0"].unit == "1" and r.results["H0"].config_units.startswith("config")
    assert r.results["H0"].value == pytest.approx(0.5, rel=1e-15)  # H = x²/2 at x = 1
    assert_tree_quantifies(r.h5)
    # the observables' group opened alone has t with its values and units (x² = cos² t)
    with _open_group_quietly(r.h5, "analysis/observables") as ds:
        np.testing.assert_array_equal(ds.t, r.to_xarray().t)
        assert ds.t.attrs["config_units"] == "config units of time"
        np.testing.assert_allclose(ds.x2, np.cos(ds.t) ** 2, atol=1e-8)


def test_to_datatree_is_every_group_and_reads_earlier_formats(out):
    """The tree holds every group of the archive; the checks are named, typed columns (text
    as str) equal to ``run.checks``; archives of formats 1 and 2 open as trees too, their
    compound tables as groups of columns, without a warning."""
    _, single, _ = out
    r = reportgen.open(single.folder)
    tree = r.to_datatree()
    with h5py.File(r.h5) as f:
        groups = {"/"}
        f.visititems(lambda n, o: groups.add("/" + n) if isinstance(o, h5py.Group) else None)
    assert set(tree.groups) == groups
    checks = tree["checks"].to_dataset()
    assert checks.quantity.dtype.kind == "U" and checks.rel_error.dtype == np.float64
    assert list(checks.quantity.values) == [c["quantity"] for c in r.checks]
    np.testing.assert_array_equal(checks.value, [c["value"] for c in r.checks])
    study = tree["study/error_vs_runtime"].to_dataset()
    assert study.cached.dtype == bool and study.method.dtype.kind == "U"
    assert study.wall_time_s.attrs["units"] == "s" and study.tolerance.attrs["units"] == "1"
    for old in sorted((ROOT / "tests" / "data").glob("archive_*.h5")):
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            old_tree = reportgen.open(old).to_datatree()
        table = old_tree["checks"].to_dataset()
        assert table.quantity.dtype.kind == "U" and table.sizes["check"] >= 1, old
        assert "checks" not in old_tree.to_dataset(), old


def test_analysis_arrays_on_t_carry_the_runs_times(out):
    """An ``/analysis`` array declared on ``t`` has the main run's times as its coordinate,
    with their units, in its own group (a group opened alone, not only in the tree)."""
    _, single, _ = out
    path = Path(single.folder) / "run.h5"
    with h5py.File(path, "r") as f:
        on_t = []
        f["analysis"].visititems(lambda n, o: on_t.append(n) if isinstance(o, h5py.Dataset)
                                 and o.dims[0].keys() == ["t"] else None)
        times = f["runs/main/t"][()]
    assert on_t, "the pendulum stores arrays on t (its phase portrait, energy error)"
    for name in on_t:
        group = "analysis/" + name.rpartition("/")[0] if "/" in name else "analysis"
        with _open_group_quietly(path, group) as ds:
            np.testing.assert_array_equal(ds.t, times)
            assert ds.t.attrs["units"] == "s"
    # and the readers do not take the index datasets for results
    data = reportgen.open(path).data
    assert "t" not in data.analysis
    assert all("t" not in v for v in data.analysis.values() if isinstance(v, dict))


def test_a_sweeps_point_sets_join_its_dataset(tmp_path):
    """Surface-of-section crossings, a varying number per member, join the sweep's
    dataset on their own dimension with the member each belongs to; every crossing
    lies on x = 0 (the section) to the root finder's tolerance."""
    done = reportgen.run(SECTIONS, out=tmp_path)
    assert done.ok, done.message
    ds = reportgen.open(done.folder).to_xarray()
    sets = [d[: -len("_point")] for d in ds.dims if str(d).endswith("_point")]
    assert sets, list(ds.dims)
    name = sets[0]
    member = ds[f"{name}_member"]
    assert member.dims == (f"{name}_point",)
    assert set(np.unique(member.values)) <= set(ds.member.values.tolist())
    counts = np.bincount(member.values, minlength=ds.sizes["member"])
    assert (counts > 3).all()  # each orbit crosses the section several times by t = 60
    state = ds[f"{name}_state"]
    x = state.sel({f"{name}_component": "x"})
    assert float(abs(x).max()) < 1e-9
    assert done.folder.endswith("henon_heiles_sections_api_test")  # é -> e in the name
