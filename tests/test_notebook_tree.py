"""Issue 43, what it must show: a notebook executed headless (nbclient) that runs a scene
from a dict of numpy numbers, shows its author's own matplotlib figure after the run,
opens the archive as one xarray tree, quantifies it with pint-xarray, sweeps an amplitude
given in degrees and verifies the archive, every number checked against its closed form
inside the notebook (an assertion there fails the cell, and so this test)."""

from __future__ import annotations

import json
import textwrap
from pathlib import Path

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("pint_xarray")

CELLS = [
    # 1. a scene from a dict of numpy numbers (np.float64, np.int64), html only, no study
    """
    import warnings

    import matplotlib.pyplot as plt
    import numpy as np
    import reportgen

    scene = {"kind": "pendulum", "title": "Notebook swing",
             "params": {"g": np.float64(9.81), "l": np.float64(1.0)},
             "initial": {"theta": np.float64(0.5), "theta_dot": np.float64(0.0)},
             "run": {"t_end": np.float64(4.0), "samples": np.int64(401), "study": False}}
    outcome = reportgen.run(scene, out="out", formats=("html",))
    assert outcome.ok, outcome.message
    outcome.name, outcome.status
    """,
    # 2. the author's own figure, after the run: shown inline
    """
    fig, ax = plt.subplots(figsize=(3, 2))
    ax.plot(np.linspace(0, 1, 20), np.linspace(0, 1, 20) ** 2, label="mine")
    ax.legend()
    plt.show()
    """,
    # 3. the archive as one tree: every group, no warning; the checks as typed columns
    """
    import xarray as xr

    run = reportgen.open(outcome.folder)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        raw = xr.open_datatree(run.h5, engine="h5netcdf")
    tree = run.to_datatree()
    assert set(raw.groups) == set(tree.groups), (raw.groups, tree.groups)
    checks = tree["checks"].to_dataset()
    assert checks["quantity"].dtype.kind == "U" and checks["rel_error"].dtype == np.float64
    main = tree["runs/main"].to_dataset()
    assert float(main.y.sel(component="theta")[0]) == 0.5
    sorted(tree.groups)[:6]
    """,
    # 4. pint-xarray on every group; the exact period 4K(k)sqrt(l/g), k = sin(theta0/2)
    """
    import pint_xarray  # noqa: F401
    from scipy.special import ellipk

    quantified = {node.path: node.to_dataset().pint.quantify() for node in tree.subtree}
    energy = quantified["/runs/main"]["energy"]
    assert str(energy.pint.units) == "joule", energy.pint.units
    period = run.results["period"]
    exact = 4 * ellipk(np.sin(0.25) ** 2) * np.sqrt(1.0 / 9.81)
    assert abs(float(period) - exact) < 1e-12 * exact, (float(period), exact)
    assert period.unit == "s" and period.quantity.to("ms").magnitude == 1e3 * period.value
    t_ms = quantified["/runs/main"]["t"].pint.to("ms")
    assert float(t_ms[-1].pint.magnitude) == 4000.0
    len(quantified), str(period)
    """,
    # 5. a sweep given in degrees: the swept values in radians, periods against K(k)
    """
    family = {"kind": "pendulum", "title": "Notebook amplitudes",
              "params": {"g": 9.81, "l": 1.0}, "initial": {"theta": 0.1},
              "run": {"t_end": np.float64(3.0), "samples": np.int64(301), "study": False},
              "sweep": {"initial": {"theta": {"start": "5 deg", "stop": "45 deg",
                                              "num": np.int64(3)}}}}
    swept = reportgen.run(family, out="out", formats=("html",))
    assert swept.ok, swept.message
    ds = reportgen.open(swept.folder).to_xarray()
    amplitudes = np.deg2rad([5.0, 25.0, 45.0])
    np.testing.assert_allclose(ds.initial_theta, amplitudes, rtol=1e-15)
    exact = 4 * ellipk(np.sin(amplitudes / 2) ** 2) * np.sqrt(1 / 9.81)
    np.testing.assert_allclose(ds.period, exact, rtol=1e-12)
    ds.initial_theta.attrs["units"]
    """,
    # 6. the archive re-verified: re-simulated from its own config, every number compared
    """
    import json

    verification = reportgen.verify(run.h5)
    assert verification.identical, verification.differences[:3]
    print(json.dumps({"verdict": verification.verdict, "compared": verification.compared,
                      "period": float(period), "groups": len(quantified)}))
    """,
]


def test_the_notebook_runs_a_dict_shows_its_figure_quantifies_sweeps_and_verifies(
        tmp_path, monkeypatch):
    notebook = nbformat.v4.new_notebook()
    notebook.cells = [nbformat.v4.new_code_cell(textwrap.dedent(code).strip())
                      for code in CELLS]
    monkeypatch.chdir(tmp_path)
    nbclient.NotebookClient(notebook, timeout=120, kernel_name="python3",
                            resources={"metadata": {"path": str(tmp_path)}}).execute()
    outputs = [cell.get("outputs", []) for cell in notebook.cells]
    errors = [o for cell in outputs for o in cell if o.get("output_type") == "error"]
    assert not errors, errors
    # the author's figure, drawn after reportgen.run, is shown (a PNG in the display data)
    assert any("image/png" in o.get("data", {}) for o in outputs[1]), outputs[1]
    assert not any("image/png" in o.get("data", {}) for o in outputs[0])
    facts = json.loads("".join(o.get("text", "") for o in outputs[-1]
                               if o.get("output_type") == "stream"))
    assert facts["verdict"] == "identical" and facts["compared"] > 50
    assert facts["groups"] >= 5
    # everything the notebook wrote is below its own folder
    assert all(tmp_path in p.parents for p in Path(tmp_path).rglob("*") if p.is_file())
