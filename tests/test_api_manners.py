"""The Python API as a good citizen in a notebook (issue 43): ``reportgen.run`` leaves the
caller's matplotlib alone (every rcParam, and pyplot's backend), draws every run in the
report's own style, and takes numpy numbers in a dict config as plain numbers.  In a fresh
interpreter, where the caller's pyplot already runs a backend other than Agg."""

from __future__ import annotations

import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import numpy as np

from reportgen.scene.config import to_toml

CALLER = textwrap.dedent('''
    import sys
    from pathlib import Path
    import matplotlib
    matplotlib.use("svg")
    import matplotlib.pyplot as plt
    import numpy as np
    matplotlib.rcParams["font.size"] = 17.0
    matplotlib.rcParams["axes.grid"] = False
    matplotlib.rcParams["axes.prop_cycle"] = matplotlib.cycler(color=["k", "r"])
    before = {k: v for k, v in matplotlib.rcParams.items() if k != "backend"}
    import reportgen
    out = Path(sys.argv[1])
    config = {"kind": "pendulum", "title": "numpy numbers",
              "params": {"g": np.float64(9.81), "l": np.float32(1.0)},
              "initial": {"theta": np.float64(0.5)},
              "run": {"t_end": np.float64(2.0), "samples": np.int64(201),
                      "study": np.bool_(False)},
              "report": {"formats": ["html"]}}
    first = reportgen.run(config, out / "a")
    assert first.status == "ok", first.message
    after = {k: v for k, v in matplotlib.rcParams.items() if k != "backend"}
    changed = sorted(k for k in before if before[k] != after[k])
    assert not changed, changed
    assert plt.get_backend() == "svg", plt.get_backend()
    fig = plt.figure()
    plt.plot([0, 1], [0, 1])
    fig.savefig(out / "mine.svg")  # the caller's own figure, with its own backend
    second = reportgen.run(config, out / "b")  # drawn in the report's style again
    assert second.status == "ok"
    a = sorted((out / "a" / "numpy_numbers" / "figures").glob("*.svg"))
    b = sorted((out / "b" / "numpy_numbers" / "figures").glob("*.svg"))
    assert a and [p.name for p in a] == [p.name for p in b]
    assert all(x.read_bytes() == y.read_bytes() for x, y in zip(a, b))
    print("ok")
''')


def test_run_leaves_the_callers_matplotlib_alone_and_takes_numpy_numbers(tmp_path):
    proc = subprocess.run([sys.executable, "-c", CALLER, str(tmp_path)], capture_output=True,
                          text=True, timeout=600)
    assert proc.returncode == 0 and proc.stdout.strip() == "ok", proc.stderr[-3000:]
    assert (tmp_path / "mine.svg").read_text().rstrip().endswith("</svg>")


def test_numpy_numbers_and_arrays_are_written_as_plain_toml():
    text = to_toml({"kind": "normal_modes", "x": np.float64(0.5), "n": np.int64(401),
                    "flag": np.bool_(True), "v": np.array([1.0, 2.5]),
                    "t": {"m": np.array([[1, 2], [3, 4]])}})
    assert "np." not in text and "float64" not in text
    data = tomllib.loads(text)
    assert data["x"] == 0.5 and data["n"] == 401 and data["flag"] is True
    assert data["v"] == [1.0, 2.5] and data["t"]["m"] == [[1, 2], [3, 4]]


def test_a_misspelt_word_for_a_symbol_key_gets_a_guess(tmp_path, capsys):
    """"lenght" is no near spelling of the key ``l``, but of a word of its description
    ("length of the pendulum"): the guess names ``l`` (issue 43, item 9)."""
    from reportgen.commands.cli import main

    config = tmp_path / "typo.toml"
    config.write_text('kind = "pendulum"\n[params]\ng = 9.81\nlenght = 1.0\nmas = 2.0\n'
                      '[initial]\ntheta = 0.5\n[run]\nt_end = 2.0\n', encoding="utf-8")
    assert main(["validate", str(config)]) == 2
    err = capsys.readouterr().err
    assert "key 'params.lenght': unknown key; did you mean 'l'?" in err
    assert "key 'params.mas': unknown key; did you mean 'm'?" in err
    assert "params.l': required key is missing" not in err  # said once, as the guess


def test_inspect_on_a_config_says_what_it_is(tmp_path, capsys):
    from reportgen.commands.cli import main

    config = tmp_path / "scene.toml"
    config.write_text('kind = "pendulum"\n', encoding="utf-8")
    assert main(["inspect", str(config)]) == 2
    err = capsys.readouterr().err
    assert "a scene config (TOML), not an archive" in err and "HDF5" not in err


def _pendulum(theta, **top):
    return {"kind": "pendulum", **top, "params": {"g": 9.81, "l": 1.0},
            "initial": {"theta": theta},
            "run": {"t_end": 1.0, "samples": 101, "study": False},
            "report": {"formats": ["html"]}}


def test_a_rejected_dict_writes_nothing_and_untitled_runs_do_not_collide(tmp_path):
    """Issue 43 item 3: a dict that fails validation leaves the earlier config and its
    archive as they were (``validate`` on the folder still passes); a second untitled dict
    of the same kind with other physics is refused, naming the run it would replace and
    ``name=``, and runs beside it when named; the same untitled dict again, or a titled
    dict's edit, is the edit loop and runs in place."""
    import pytest

    import reportgen
    from reportgen.commands.cli import main
    from reportgen.errors import ConfigError

    out = tmp_path / "out"
    first = reportgen.run(_pendulum(0.5), out)
    assert first.status == "ok", first.message
    folder = out / "pendulum"
    config, archive = folder / "pendulum.toml", (folder / "run.h5").read_bytes()
    written = config.read_bytes()

    with pytest.raises(ConfigError):
        reportgen.run(_pendulum(99.0), out, name="pendulum")  # outside the kind's range
    assert config.read_bytes() == written and (folder / "run.h5").read_bytes() == archive
    assert main(["validate", str(config)]) == 0

    with pytest.raises(ConfigError) as refused:
        reportgen.run(_pendulum(1.0), out)
    message = str(refused.value)
    assert "name=" in message and "pendulum" in message and "other physics" in message
    assert config.read_bytes() == written and (folder / "run.h5").read_bytes() == archive

    again = reportgen.run(_pendulum(0.5), out)  # the same physics: its own folder, current
    assert again.skipped and Path(again.reports[0]).parent == folder
    beside = reportgen.run(_pendulum(1.0), out, name="pendulum_1rad")
    assert beside.status == "ok" and (out / "pendulum_1rad" / "run.h5").exists()
    assert (folder / "run.h5").read_bytes() == archive

    titled = reportgen.run(_pendulum(0.5, title="my pendulum"), out)
    edited = reportgen.run(_pendulum(0.7, title="my pendulum"), out)
    assert titled.status == edited.status == "ok" and not edited.skipped


def test_formats_must_be_a_list_of_formats(tmp_path):
    """Issue 48 H: ``formats="html"`` became ('h', 't', 'm', 'l'), wrote nothing and
    returned ok; now a ConfigError before anything is written."""
    import pytest

    import reportgen
    from reportgen.errors import ConfigError

    for bad in ("html", ["html", "docx"]):
        with pytest.raises(ConfigError, match="formats must be a list"):
            reportgen.run(_pendulum(0.5), tmp_path / "out", formats=bad)
    assert not (tmp_path / "out").exists()


def test_the_api_takes_the_output_folder_lock_as_the_cli_does(tmp_path, capsys):
    """Issue 48 H: the API ran into a folder a `reportgen run` was writing (a sweep run by
    both failed); it now waits for the folder's lock as a second `reportgen run` does."""
    import threading
    import time

    import reportgen
    from reportgen.support.fsutil import output_folder, output_lock

    out = tmp_path / "out"
    held = threading.Event()

    def other_run():
        with output_lock(output_folder(out)):
            held.set()
            time.sleep(1.5)

    thread = threading.Thread(target=other_run)
    thread.start()
    held.wait(10)
    start = time.monotonic()
    outcome = reportgen.run(_pendulum(0.5), out)
    waited = time.monotonic() - start
    thread.join()
    assert outcome.status == "ok" and waited >= 1.0, waited
    assert "waiting for another reportgen run" in capsys.readouterr().err


def test_the_api_stops_a_scene_at_its_time_limit(tmp_path):
    """Issue 48 C, in the API as in run: a Lagrangian of degree 32 (its symbolic work takes
    minutes) given as a dict comes back failed at the time limit, not after minutes, and a
    time limit that is not a positive number is a ConfigError."""
    import time

    import pytest

    import reportgen
    from reportgen.errors import ConfigError

    config = {"kind": "hamiltonian", "title": "degree 32",
              "system": {"coordinates": ["x", "y"],
                         "L": "(x_dot**2 + y_dot**2)*(1 + x**2 + y**2)**15/2 - x**2"},
              "initial": {"x": 0.1, "y": 0.0, "x_dot": 0.0, "y_dot": 0.1},
              "run": {"t_end": 1.0, "samples": 11, "study": False}}
    start = time.monotonic()
    outcome = reportgen.run(config, tmp_path / "out", formats=["html"], time_limit=2)
    assert time.monotonic() - start < 60
    assert outcome.status == "failed" and "time limit of 2 s exceeded" in outcome.message
    with pytest.raises(ConfigError, match="time_limit must be"):
        reportgen.run(config, tmp_path / "out", time_limit=-1)


def test_a_dict_nested_thousands_deep_is_a_config_error_and_writes_nothing(tmp_path):
    """Issue 48 G: a dict 5,000 levels deep raised RecursionError from the API; it is a
    ConfigError naming the key and the rule (a config file may nest 32 deep)."""
    import pytest

    import reportgen
    from reportgen.errors import ConfigError

    deep = leaf = {}
    for _ in range(5000):
        leaf["a"] = {}
        leaf = leaf["a"]
    config = {"kind": "pendulum", "title": "deep", "params": {"g": 9.81, "l": 1.0, "x": deep},
              "initial": {"theta": 1.0}, "run": {"t_end": 1.0, "samples": 21, "study": False}}
    with pytest.raises(ConfigError, match=r"params\.x\.a\.a.*more than 32"):
        reportgen.run(config, out=tmp_path / "out", formats=["html"])
    assert not (tmp_path / "out").exists() or not any((tmp_path / "out").rglob("*.toml"))
