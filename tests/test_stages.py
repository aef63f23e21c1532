"""The staged pipeline: simulate -> figures -> report -> index, each run only when its
inputs changed (content keys), and the index as a gallery of the whole output folder."""

from __future__ import annotations

from pathlib import Path

import h5py
import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.archive.store import ArchiveError, read_archive, summarize
from reportgen.pipeline.stages import run_scene

FIXTURE = Path(__file__).resolve().parent / "data" / "archive_v1_pendulum.h5"


def _arrays(path: Path) -> dict[str, bytes]:
    out = {}

    def visit(name, obj):
        if isinstance(obj, h5py.Dataset) and name.startswith("runs/"):
            out[name] = obj[()].tobytes() if obj.dtype.kind != "O" else repr(obj[()]).encode()

    with h5py.File(path, "r") as f:
        f.visititems(visit)
    return out


def test_title_edit_rerenders_without_simulating(write_config, tmp_path):
    path = write_config("pend", pendulum_text(title="First title"))
    out = tmp_path / "out"
    first = run_scene(str(path), str(out), formats=("html",))
    assert first.ok and first.stages == ["simulate", "report"], first
    archive = out / "pend" / "run.h5"
    before = _arrays(archive)
    figures_before = {p.name: p.stat().st_mtime_ns for p in (out / "pend" / "figures").iterdir()}

    again = run_scene(str(path), str(out), formats=("html",))
    assert again.stages == [] and again.skipped

    path.write_text(pendulum_text(title="A new title"))
    edited = run_scene(str(path), str(out), formats=("html",))
    assert edited.stages == ["restamp", "report"], edited
    assert _arrays(archive) == before  # trajectory bytes unchanged
    data = read_archive(archive)
    assert data.title == "A new title" and "A new title" in data.config_text
    html = (out / "pend" / "report.html").read_text(encoding="utf-8")
    assert "A new title" in html and "First title" not in html
    # the figures stage's key did not change: no figure was redrawn
    assert {p.name: p.stat().st_mtime_ns
            for p in (out / "pend" / "figures").iterdir()} == figures_before


def test_physics_edit_resimulates_and_force_reruns(write_config, tmp_path):
    path = write_config("pend", pendulum_text(t_end=10.0))
    out = tmp_path / "out"
    run_scene(str(path), str(out), formats=("html",))
    key = read_archive(out / "pend" / "run.h5").attrs["physics_key"]
    path.write_text(pendulum_text(t_end=11.0))
    edited = run_scene(str(path), str(out), formats=("html",))
    assert "simulate" in edited.stages
    assert read_archive(out / "pend" / "run.h5").attrs["physics_key"] != key
    forced = run_scene(str(path), str(out), force=True, formats=("html",))
    assert forced.stages == ["simulate", "report"]


def test_report_section_edit_redraws_without_simulating(write_config, tmp_path):
    path = write_config("pend", pendulum_text())
    out = tmp_path / "out"
    run_scene(str(path), str(out), formats=("html",))
    path.write_text(pendulum_text(extra='\n[report]\nsections = ["phase_portrait"]\n'))
    edited = run_scene(str(path), str(out), formats=("html",))
    assert edited.stages == ["restamp", "report"], edited
    html = (out / "pend" / "report.html").read_text(encoding="utf-8")
    assert 'id="phase_portrait"' in html and 'id="time_series"' not in html


def test_figure_exports_on_request_without_simulating(write_config, tmp_path):
    """[report] figure_formats adds standalone PDF/PNG files; asking for them later is a
    report edit (no re-simulation), and the HTML links every file of a figure."""
    path = write_config("pend", pendulum_text(extra='\n[report]\nsections = ["phase_portrait"]\n'))
    out = tmp_path / "out"
    run_scene(str(path), str(out), formats=("html",))
    figures = out / "pend" / "figures"
    assert {p.suffix for p in figures.glob("phase_portrait-*")} == {".svg"}
    path.write_text(pendulum_text(extra='\n[report]\nsections = ["phase_portrait"]\n'
                                        'figure_formats = ["pdf", "png"]\n'))
    edited = run_scene(str(path), str(out), formats=("html",))
    assert edited.stages == ["restamp", "report"], edited
    assert {p.suffix for p in figures.glob("phase_portrait-*")} == {".svg", ".pdf", ".png"}
    assert (figures / "phase_portrait-phase.pdf").read_bytes().startswith(b"%PDF")
    html = (out / "pend" / "report.html").read_text(encoding="utf-8")
    assert 'href="figures/phase_portrait-phase.pdf"' in html
    assert 'href="figures/phase_portrait-phase.png"' in html


def test_index_is_a_gallery_of_the_whole_folder(write_config, tmp_path, cli):
    out = tmp_path / "out"
    a = write_config("first", pendulum_text(theta=0.5))
    b = write_config("second", pendulum_text(theta=1.5))
    assert cli("run", a, "--out", out, "--jobs", "1", "--format", "html")[0] == 0
    assert cli("run", b, "--out", out, "--jobs", "1", "--format", "html")[0] == 0
    index = (out / "index.html").read_text(encoding="utf-8")
    for name in ("first", "second"):
        assert f'id="scene-{name}"' in index
        assert f'href="{name}/report.html"' in index and f'href="{name}/run.h5"' in index
        assert f'src="{name}/figures/' in index  # thumbnail of the first figure
    assert "from the exact 4K(k)√(l/g)" in index and "Plane pendulum" in index
    assert not list(out.glob(".index.html.*"))


@pytest.mark.parametrize("scene", ["inertia_cone", "normal_modes_co2"])
def test_archives_written_before_declared_results_still_render(scene, tmp_path, cli):
    """Archives written by 0.2.0 before kinds declared their results (no units attrs, no
    __quantities__; format_version 2) open and render with today's code: every figure the
    kind draws, from the archive alone."""
    import shutil

    folder = tmp_path / scene
    folder.mkdir()
    archive = folder / "run.h5"
    shutil.copy(Path(__file__).parent / "data" / f"archive_0.2.0_{scene}.h5", archive)
    with h5py.File(archive, "r") as f:
        assert f.attrs["reportgen_version"] == "0.2.0" and "__quantities__" not in f["analysis"].attrs
    data = read_archive(archive)
    assert "__quantities__" not in data.analysis
    code, _, err = cli("report", archive, "--format", "html")
    assert code == 0, err
    figures = sorted(p.name for p in (folder / "figures").glob("*.svg"))
    assert figures and (folder / "report.html").stat().st_size > 10_000
    assert cli("inspect", archive)[0] == 0


def test_fixture_archive_of_format_1_still_opens(tmp_path, cli):
    data = read_archive(FIXTURE)
    assert data.format_version == 1 and data.kind == "pendulum"
    run = data.runs["main"]
    assert run.columns == ["theta", "theta_dot"] and run.y.shape == (101, 2)
    # the stored run is the pendulum released at theta0 = 1 rad from rest
    assert run.y[0, 0] == 1.0 and np.all(np.abs(run.y[:, 0]) <= 1.0 + 1e-9)
    assert "theta_max_error" in data.analysis
    assert "kind      pendulum" in summarize(FIXTURE)
    code, _, err = cli("report", FIXTURE)
    assert code == 2 and "format_version 1" in err and "reportgen run" in err


def test_unreadable_newer_format_is_named(tmp_path):
    path = tmp_path / "new.h5"
    with h5py.File(FIXTURE, "r") as src, h5py.File(path, "w") as dst:
        for key in src:
            src.copy(key, dst)
        dst.attrs.update(dict(src.attrs))
        dst.attrs["format_version"] = 99
    with pytest.raises(ArchiveError, match="newer reportgen"):
        read_archive(path)


def test_physics_key_covers_what_simulate_computes_and_nothing_else():
    """Title and section order do not change the simulate key; asking for a section whose
    data is computed only on request (the study, rigid_body's geometric integrator) does."""
    from reportgen.kinds import load_scene
    from reportgen.scene.config import parse_config_text

    def key(title="A body", t_end=10.0, sections=None):
        text = (f'kind = "rigid_body"\ntitle = "{title}"\n[params]\nI1 = 1.0\nI2 = 2.0\n'
                f'I3 = 3.0\n[initial]\nomega = [0.1, 1.0, 0.1]\n[run]\nt_end = {t_end}\n')
        if sections is not None:
            text += f"[report]\nsections = {sections!r}\n".replace("'", '"')
        return load_scene(parse_config_text(text)).physics_key()

    plain = key()
    assert key(title="Another title") == plain
    assert key(t_end=11.0) != plain
    few = ["polhodes", "invariants"]
    assert key(sections=few) != plain  # neither the study nor the splitting run is wanted
    assert key(sections=["invariants"]) == key(sections=few)
    assert key(sections=[*few, "geometric_integrator"]) != key(sections=few)
    assert key(sections=[*few, "error_vs_runtime"]) != key(sections=few)


def test_figures_in_parallel_and_pdf_worker_give_the_same_report(write_config, tmp_path):
    """The edit loop's single scene draws its figures in forked processes and renders its
    PDF in a worker that imported WeasyPrint early: same files as drawing in one process."""
    from reportgen.rendering.report import FigureHelper, PdfWorker, build_report

    path = write_config("pend", pendulum_text(t_end=4.0, samples=401))
    out = tmp_path / "out"
    outcome = run_scene(str(path), str(out), formats=("html", "pdf"), draw_jobs=2)
    assert outcome.ok and outcome.stages == ["simulate", "report"], outcome
    assert (out / "pend" / "report.pdf").read_bytes().startswith(b"%PDF")
    archive = out / "pend" / "run.h5"
    one, two, three = tmp_path / "one", tmp_path / "two", tmp_path / "three"
    build_report(archive, formats=("html",), out_dir=one, jobs=1)
    worker = PdfWorker()
    try:
        build_report(archive, formats=("html", "pdf"), out_dir=two, jobs=3, pdf_worker=worker)
    finally:
        worker.close()
    helper = FigureHelper()  # started ahead and warmed up, as before a simulation
    try:
        build_report(archive, formats=("html",), out_dir=three, jobs=2, figure_helper=helper)
        answered = helper.result_indices
    finally:
        helper.close()
    figures = sorted(p.name for p in (one / "figures").glob("*.svg"))
    assert len(figures) >= 3
    for other in (two, three):
        assert sorted(p.name for p in (other / "figures").glob("*.svg")) == figures
        for name in figures:
            assert (one / "figures" / name).read_bytes() == (other / "figures" / name).read_bytes()
        assert (one / "report.html").read_bytes() == (other / "report.html").read_bytes()
    assert len(answered) == 1  # the helper took the job (its share may be empty)
    # the helper draws from the first section on, this process from the last back
    assert answered[0] == list(range(len(answered[0])))
    assert (two / "report.pdf").read_bytes().startswith(b"%PDF")


def test_edit_loop_worker_started_only_for_one_edited_scene(write_config, tmp_path):
    """``reportgen run`` forks the PDF worker before validating only when one config is
    newer than its report; an unused worker is stopped at once; the PDF's slim figure
    copies are kept for the next render."""
    from reportgen.pipeline.stages import run_batch
    from reportgen.rendering.pdf import PdfWorker, edit_loop_worker
    from reportgen.support.layout import edited_count

    a = write_config("a", pendulum_text(t_end=2.0, samples=201))
    b = write_config("b", pendulum_text(t_end=3.0, samples=201))
    out = tmp_path / "out"
    assert edited_count([a, b], out) == 2  # no reports yet
    run_batch([str(a), str(b)], out_root=str(out), jobs=2)
    assert edited_count([a, b], out) == 0
    slim = sorted((out / "a" / ".pdf-figures").glob("*.svg"))
    assert slim  # made while drawing, for the PDF

    a.write_text(a.read_text(encoding="utf-8").replace("title = ", "title = 'x' #"),
                 encoding="utf-8")
    assert edited_count([a, b], out) == 1
    assert edit_loop_worker([a, b], out, formats=("html",)) is None  # no PDF wanted
    assert edit_loop_worker([a, b], out, jobs=1) is None  # no second process allowed
    assert edit_loop_worker([a, b], out, scheduler="tcp://127.0.0.1:1") is None
    unused = edit_loop_worker([a, b], out)
    assert isinstance(unused, PdfWorker)
    unused.close()
    assert not unused.proc.is_alive()
    unused.close()  # twice is harmless

    worker = edit_loop_worker([a, b], out)
    try:
        outcomes = run_batch([str(a), str(b)], out_root=str(out), pdf_worker=worker)
    finally:
        worker.close()
    assert [o.stages for o in outcomes] == [["restamp", "report"], []]
    assert (out / "a" / "report.pdf").read_bytes().startswith(b"%PDF")
    assert sorted((out / "a" / ".pdf-figures").glob("*.svg")) == slim


def test_gallery_follows_an_edited_archive(write_config, tmp_path):
    """The index's entries are kept in out/.gallery.json; an archive that changed (a title
    edit re-stamps it) is read again, the others are not."""
    from reportgen.pipeline.stages import run_batch

    a = write_config("a", pendulum_text(title="First title", t_end=2.0, samples=201))
    write_config("b", pendulum_text(title="Other", t_end=2.0, samples=201))
    out = tmp_path / "out"
    run_batch([str(a.parent)], out_root=str(out), jobs=1, formats=("html",))
    assert "First title" in (out / "index.html").read_text()
    assert (out / ".gallery.json").exists()
    a.write_text(a.read_text().replace("First title", "Second title"))
    run_batch([str(a.parent)], out_root=str(out), jobs=1, formats=("html",))
    index = (out / "index.html").read_text()
    assert "Second title" in index and "First title" not in index and "Other" in index


INERTIA_TEXT = """
kind = "inertia"
[shape]
type = "cone"
mass = 1.0
radius = 0.5
height = 1.0
"""


def test_code_stamps_follow_the_code_each_stage_imports(tmp_path):
    """The package is installed editable: after a pull, the same version may run other
    code.  Each kind's simulate stamp hashes the code its simulation imports, its drawing
    stamp the code its report imports: a caption or plot edit in one kind changes only
    that kind's drawing stamp; an edit of its physics or of an integrator it uses changes
    its simulate stamp; an edit of the command line changes neither.  Stamps do not
    depend on where the checkout is."""
    import shutil

    from reportgen.kinds import KINDS
    from reportgen.support import codestamp

    pendulum, other = KINDS["pendulum"], KINDS["inertia"]

    def copy(name):
        pkg = tmp_path / name / "reportgen"
        shutil.copytree(codestamp.PACKAGE, pkg, ignore=shutil.ignore_patterns("__pycache__"))
        return pkg

    def stamps(pkg):
        return {(kind.kind, face): codestamp.code_hash(modules(), package_dir=pkg)
                for kind in (pendulum, other)
                for face, modules in (("simulate", kind.simulation_modules),
                                      ("draw", kind.report_modules))}

    def edited(name, relative):
        pkg = copy(name)
        (pkg / relative).write_text("# edited\n" + (pkg / relative).read_text())
        new = stamps(pkg)
        return {key for key in base if new[key] != base[key]}

    base = stamps(copy("a"))
    assert stamps(copy("b")) == base
    assert base == stamps(codestamp.PACKAGE)
    assert edited("caption", "kinds/pendulum/report.py") == {("pendulum", "draw")}
    assert edited("plot", "kinds/pendulum/plots.py") == {("pendulum", "draw")}
    assert edited("physics", "core/models/pendulum.py") == {("pendulum", "simulate")}
    assert edited("integrator", "core/integrators/compiled.py") == {("pendulum", "simulate")}
    assert edited("declared", "kinds/pendulum/results.py") == {("pendulum", "simulate"),
                                                               ("pendulum", "draw")}
    assert edited("cli", "commands/cli.py") == set()


def test_caption_edit_rerenders_that_kind_only(write_config, tmp_path, monkeypatch):
    """A new drawing stamp of one kind (its caption edited) redraws and renders that
    kind's reports again from their archives, which are kept; other kinds' scenes are
    up to date and no scene simulates."""
    from reportgen.kinds import KINDS

    path = write_config("pend", pendulum_text())
    cone = write_config("cone", INERTIA_TEXT)
    out = tmp_path / "out"
    for config in (path, cone):
        run_scene(str(config), str(out), formats=("html",))
    before = _arrays(out / "pend" / "run.h5")
    figure = next((out / "pend" / "figures").glob("*.svg"))
    figure.write_text("stale")
    assert run_scene(str(path), str(out), formats=("html",)).stages == []
    monkeypatch.setattr(KINDS["pendulum"], "_report_code", "a caption edited", raising=False)
    again = run_scene(str(path), str(out), formats=("html",))
    assert again.stages == ["report"], again
    assert run_scene(str(cone), str(out), formats=("html",)).stages == []
    assert _arrays(out / "pend" / "run.h5") == before
    assert figure.read_text() != "stale"
