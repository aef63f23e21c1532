"""The path a user walks: config -> archive -> figures -> HTML + PDF, and its guarantees."""

from __future__ import annotations

import hashlib
import re
import shutil

import h5py
import numpy as np
import pytest
from pypdf import PdfReader

from conftest import pendulum_text
from reportgen.archive import store as archive_mod
from reportgen.archive.store import read_archive
from reportgen.kinds.pendulum import PendulumScene
from reportgen.pipeline.stages import run_batch

OSCILLATOR = """
kind = "oscillator"
title = "osc"
[params]
m = 1.0
omega = 2.0
[initial]
q = 1.0
p = 0.0
[run]
t_end = 5.0
samples = 201
study = false
"""


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    """One small batch shared by the read-only tests below."""
    root = tmp_path_factory.mktemp("batch")
    cfg = root / "configs"
    cfg.mkdir()
    (cfg / "pend.toml").write_text(pendulum_text(
        title="<script>alert(1)</script> & <b>bold</b>", extra="""
        [boundary]
        theta0 = 0.1
        theta1 = 0.05
        T = 1.0
        """))
    (cfg / "osc.toml").write_text(OSCILLATOR)
    out = root / "output"
    outcomes = run_batch([str(cfg)], out_root=str(out), jobs=1)
    return root, out, outcomes


def test_batch_writes_every_file(batch):
    _, out, outcomes = batch
    assert [o.status for o in outcomes] == ["ok", "ok"]
    for name in ("pend", "osc"):
        for f in ("run.h5", "report.html", "report.pdf"):
            assert (out / name / f).stat().st_size > 0
    index = (out / "index.html").read_text()
    assert 'href="pend/report.html"' in index and 'href="osc/report.pdf"' in index


def test_archive_layout_matches_spec(batch):
    _, out, _ = batch
    with h5py.File(out / "pend" / "run.h5", "r") as f:
        for key in ("format", "format_version", "kind", "title", "config_sha256", "created",
                    "reportgen_version"):
            assert key in f.attrs
        assert f.attrs["format"] == "reportgen" and f.attrs["kind"] == "pendulum"
        text = f["config"][()].decode()
        assert hashlib.sha256(text.encode()).hexdigest() == f.attrs["config_sha256"]
        assert {"python", "numpy", "scipy", "h5py", "matplotlib", "numba"} <= set(
            f["provenance"].attrs)
        run = f["runs/main"]
        assert run["t"].dtype == np.float64 and run["y"].shape == (1001, 2)
        assert list(run["y"].attrs["columns"]) in (["theta", "theta_dot"],
                                                  [b"theta", b"theta_dot"])
        assert "energy" in run["invariants"]
        for key in ("method", "rtol", "atol", "nfev", "wall_time_s", "status", "message"):
            assert key in run.attrs
        assert {"period", "period_measured"} <= set(f["analysis"].attrs)
        assert run["y"].fletcher32


def test_config_text_archived_exactly(batch):
    root, out, _ = batch
    data = read_archive(out / "pend" / "run.h5")
    assert data.config_text == (root / "configs" / "pend.toml").read_text()


def test_archive_round_trip(tmp_path):
    scene = PendulumScene.from_source(
        __import__("reportgen.scene.config", fromlist=["x"]).parse_config_text(pendulum_text()))
    results = scene.simulate()
    path = tmp_path / "run.h5"
    archive_mod.write_archive(path, kind="pendulum", title="t", scene="s",
                              config_text=scene.source.text, config_sha256=scene.source.sha256,
                              results=results)
    data = read_archive(path)
    assert np.array_equal(data.runs["main"].y, results.runs["main"].y)
    assert np.array_equal(data.runs["main"].t, results.runs["main"].t)
    assert data.runs["main"].columns == ["theta", "theta_dot"]
    assert data.analysis["period"] == results.analysis["period"]
    assert data.analysis["motion"] == "libration"
    assert [c.quantity for c in data.checks] == [c.quantity for c in results.checks]


def test_failed_write_leaves_old_archive_intact(batch, tmp_path, monkeypatch):
    _, out, _ = batch
    target = tmp_path / "run.h5"
    shutil.copy(out / "pend" / "run.h5", target)
    before = target.read_bytes()

    def crash(*args, **kwargs):
        raise RuntimeError("disk on fire")

    monkeypatch.setattr(archive_mod, "_write_contents", crash)
    scene_data = read_archive(target)
    with pytest.raises(RuntimeError):
        archive_mod.write_archive(target, kind="pendulum", title="x", scene="x",
                                  config_text="", config_sha256="", results=None)
    assert target.read_bytes() == before
    assert read_archive(target).config_text == scene_data.config_text
    assert sorted(p.name for p in tmp_path.iterdir()) == ["run.h5"]  # no temp file left


def test_replacing_keeps_previous_archive(tmp_path, write_config, cli):
    cfg = write_config("p", pendulum_text(t_end=2.0, samples=101))
    out = tmp_path / "out"
    assert cli("run", cfg, "--out", out, "--jobs", 1, "--format", "html")[0] == 0
    first = (out / "p" / "run.h5").read_bytes()
    assert cli("run", cfg, "--out", out, "--jobs", 1, "--format", "html", "--force")[0] == 0
    assert (out / "p" / "run.prev.h5").read_bytes() == first


def test_sections_present_and_absent(batch):
    _, out, _ = batch
    pend = (out / "pend" / "report.html").read_text()
    osc = (out / "osc" / "report.html").read_text()
    for section in ("time_series", "phase_portrait", "period", "boundary_value", "energy"):
        assert f'<section id="{section}">' in pend
    assert '<section id="error_vs_runtime">' not in pend  # study = false: not computed, not shown
    for section in ("hamilton", "canonical_swap", "hamilton_jacobi"):
        assert f'<section id="{section}">' in osc
    for absent in ("phase_portrait", "period", "boundary_value", "energy"):
        assert f'<section id="{absent}">' not in osc


def test_pendulum_without_boundary_has_no_bvp_section(tmp_path, write_config, cli):
    cfg = write_config("nobvp", pendulum_text(t_end=2.0, samples=101))
    assert cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")[0] == 0
    html = (tmp_path / "o" / "nobvp" / "report.html").read_text()
    assert 'id="boundary_value"' not in html and 'id="phase_portrait"' in html
    assert "boundary_value" not in h5py.File(tmp_path / "o" / "nobvp" / "run.h5")["analysis"]


def test_sections_narrowed_by_config(tmp_path, write_config, cli):
    cfg = write_config("narrow", pendulum_text(
        t_end=2.0, samples=101, extra='\n[report]\nsections = ["phase_portrait"]\n'))
    assert cli("run", cfg, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")[0] == 0
    html = (tmp_path / "o" / "narrow" / "report.html").read_text()
    ids = [chunk.split('"', 1)[0] for chunk in html.split('<section id="')[1:]]
    assert ids[1:] == ["phase_portrait", "sources", "config"] or \
        ids[1:] == ["phase_portrait", "config"], ids  # after the summary


def test_html_escapes_config_title(batch):
    _, out, _ = batch
    html = (out / "pend" / "report.html").read_text()
    assert "<script>alert(1)</script>" not in html
    assert "&lt;script&gt;alert(1)&lt;/script&gt;" in html
    assert "<b>bold</b>" not in html
    assert "<script" not in html.lower()


def test_html_is_self_contained(batch):
    _, out, _ = batch
    html = (out / "pend" / "report.html").read_text()
    assert html.count("<svg") >= 5
    # namespace URIs inside SVG are names, not loads; nothing may be fetched
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", html)
    assert "<link" not in html and "@import" not in html


def test_pdf_has_pages_and_text(batch):
    _, out, _ = batch
    reader = PdfReader(out / "pend" / "report.pdf")
    assert len(reader.pages) >= 3
    first = reader.pages[0].extract_text()
    assert "Summary" in first and "1 / " in first  # page numbers from @page


def test_figures_saved_as_svg_only_by_default(batch):
    _, out, _ = batch
    figs = {p.name for p in (out / "pend" / "figures").iterdir()}
    assert "phase_portrait-phase.svg" in figs
    assert not any(name.endswith((".pdf", ".png")) for name in figs), figs


def test_report_rebuilt_from_copied_archive_alone(batch, tmp_path, cli):
    _, out, _ = batch
    copy = tmp_path / "elsewhere"
    copy.mkdir()
    shutil.copy(out / "pend" / "run.h5", copy / "run.h5")
    code, _, err = cli("report", copy / "run.h5")
    assert code == 0, err
    for fig in (out / "pend" / "figures").iterdir():
        assert (copy / "figures" / fig.name).read_bytes() == fig.read_bytes(), fig.name
    assert (copy / "report.pdf").exists()


def test_second_run_skips_by_config_hash_and_force_reruns(tmp_path, write_config, cli):
    cfg = write_config("skip", pendulum_text(t_end=2.0, samples=101))
    out = tmp_path / "out"
    cli("run", cfg, "--out", out, "--jobs", 1, "--format", "html")
    stamp = h5py.File(out / "skip" / "run.h5", "r").attrs["created"]
    code, _, err = cli("run", cfg, "--out", out, "--jobs", 1, "--format", "html")
    assert code == 0 and "up to date" in err
    assert not (out / "skip" / "run.prev.h5").exists()
    cfg.write_text(pendulum_text(t_end=3.0, samples=101))
    cli("run", cfg, "--out", out, "--jobs", 1, "--format", "html")
    assert (out / "skip" / "run.prev.h5").exists()  # config changed: re-run
    assert h5py.File(out / "skip" / "run.h5", "r").attrs["created"] >= stamp


def test_one_failing_scene_does_not_stop_the_batch(tmp_path, write_config, cli, monkeypatch):
    good = write_config("good", pendulum_text(t_end=2.0, samples=101))
    bad = write_config("bad", pendulum_text(t_end=2.0, samples=101, theta=0.5))
    original = PendulumScene.simulate

    def simulate(self, progress=None):
        if self.source.name == "bad":
            raise FloatingPointError("simulated crash")
        return original(self, progress)

    monkeypatch.setattr(PendulumScene, "simulate", simulate)
    code, _, err = cli("run", good, bad, "--out", tmp_path / "o", "--jobs", 1, "--format", "html")
    assert code == 1
    assert "simulated crash" in err and "Traceback" not in err
    assert (tmp_path / "o" / "good" / "report.html").exists()
    assert not (tmp_path / "o" / "bad" / "run.h5").exists()
    assert "failed" in (tmp_path / "o" / "index.html").read_text()


def test_inspect_prints_summary(batch, cli):
    _, out, _ = batch
    code, text, _ = cli("inspect", out / "pend" / "run.h5")
    assert code == 0 and "pendulum" in text and "checksums ok" in text


def test_inspect_on_garbage_is_short_error(tmp_path, cli):
    junk = tmp_path / "junk.h5"
    junk.write_bytes(b"not hdf5")
    code, _, err = cli("inspect", junk)
    assert code == 2 and "junk.h5" in err and "Traceback" not in err


def test_kinds_lists_keys_and_sections(cli):
    code, text, _ = cli("kinds")
    assert code == 0
    for word in ("pendulum", "oscillator", "theta_dot", "phase_portrait", "hamilton_jacobi",
                 "dop853"):
        assert word in text


def test_bench_pipeline_refuses_bad_folders_before_measuring(tmp_path, cli):
    """``bench --pipeline`` checks its folders (exit 2, the value named) before the minutes
    of measuring start."""
    configs = tmp_path / "configs"
    configs.mkdir()
    code, _, err = cli("bench", "--pipeline", configs)
    assert code == 2 and "pendulum_small" in err
    (configs / "pendulum_small.toml").write_text("kind = 'pendulum'\n")
    code, _, err = cli("bench", "--pipeline", configs, "--previous", tmp_path / "nowhere")
    assert code == 2 and "nowhere" in err and "not a reportgen source checkout" in err
