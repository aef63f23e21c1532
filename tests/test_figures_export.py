"""``reportgen figures``: a scene's figures as PNG, SVG and PDF at a chosen size, drawn
from the archive alone (never re-simulated), PNG resolution recorded in the file."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from PIL import Image

from conftest import cli_without_core, pendulum_text
from reportgen.rendering.export import parse_size


@pytest.fixture(scope="module")
def archive(tmp_path_factory):
    """One small pendulum run (HTML only, no study), shared by the tests below."""
    from reportgen.commands.cli import main

    root = tmp_path_factory.mktemp("figures")
    config = root / "pend.toml"
    config.write_text(pendulum_text(t_end=5.0, samples=401,
                                    extra='[report]\nformats = ["html"]\n'))
    assert main(["run", str(config), "--out", str(root / "out")]) == 0
    return root / "out" / "pend" / "run.h5"


def _report_figure_ids(archive: Path) -> list[str]:
    sections = json.loads((archive.parent / "figures" / "sections.json").read_text())
    sections = sections.get("sections", sections)
    return [f["id"] for s in sections for f in s["figures"]]


def _pdf_page_size(path: Path) -> tuple[float, float]:
    box = re.search(rb"/MediaBox\s*\[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", path.read_bytes())
    return float(box.group(1)), float(box.group(2))


def test_slide_size_every_figure_in_three_formats_from_the_archive_alone(archive, tmp_path):
    before = archive.read_bytes()
    out = tmp_path / "slides"
    # core made unimportable: the export draws from the archive only
    done = cli_without_core("figures", archive, "--size", "slide", "--dpi", "120", "--folder", out)
    assert done.returncode == 0, done.stderr
    ids = _report_figure_ids(archive)
    assert ids
    assert sorted(p.name for p in out.iterdir()) == sorted(
        f"{i}.{fmt}" for i in ids for fmt in ("png", "svg", "pdf"))
    for fig_id in ids:
        png = Image.open(out / f"{fig_id}.png")
        assert png.size == (1200, 675)  # 10 x 5.625 in at 120 dpi
        assert png.info["dpi"] == pytest.approx((120, 120), abs=0.05)  # pHYs: whole dots per metre
        svg = (out / f"{fig_id}.svg").read_text()
        assert 'width="720pt"' in svg and 'height="405pt"' in svg
        assert "<text" in svg  # text stays text
        assert _pdf_page_size(out / f"{fig_id}.pdf") == pytest.approx((720, 405))
    assert archive.read_bytes() == before


def test_print_size_keeps_each_figures_aspect_ratio(archive, tmp_path, cli):
    code, _, err = cli("figures", archive, "--size", "print", "--format", "pdf",
                       "--folder", tmp_path)
    assert code == 0, err
    report_svgs = archive.parent / "figures"
    for pdf in tmp_path.glob("*.pdf"):
        own = (report_svgs / f"{pdf.stem}.svg").read_text()
        w, h = (float(v) for v in re.search(r'width="([\d.]+)pt" height="([\d.]+)pt"',
                                            own).groups())
        width, height = _pdf_page_size(pdf)
        assert width == pytest.approx(6.5 * 72)
        assert height == pytest.approx(6.5 * 72 * h / w, abs=0.5)


def test_default_folder_size_in_its_name_and_only_filter(archive, cli):
    ids = _report_figure_ids(archive)
    code, _, err = cli("figures", archive, "--size", "4x3", "--format", "png",
                       "--only", ids[0], "--dpi", "50")
    assert code == 0, err
    folder = archive.parent / "figures-4x3"
    assert [p.name for p in folder.iterdir()] == [f"{ids[0]}.png"]
    assert Image.open(folder / f"{ids[0]}.png").size == (200, 150)


def test_from_a_config_runs_the_scene_only_when_its_archive_is_missing(write_config, tmp_path,
                                                                       cli):
    config = write_config("p2", pendulum_text(t_end=3.0, samples=201,
                                              extra='[report]\nformats = ["html"]\n'))
    root = tmp_path / "runs"
    code, _, err = cli("figures", config, "--root", root, "--format", "svg")
    assert code == 0, err
    assert "missing; running" in err
    archive = root / "p2" / "run.h5"
    stamp = archive.stat().st_mtime_ns
    code, _, err = cli("figures", config, "--root", root, "--format", "svg")
    assert code == 0, err
    assert "running" not in err and archive.stat().st_mtime_ns == stamp
    assert list((root / "p2" / "figures-report").glob("*.svg"))


@pytest.mark.parametrize("args, message", [
    (["--size", "3x"], "--size"),
    (["--size", "100x2"], "between 1 and 40"),
    (["--format", "png,gif"], "--format"),
    (["--only", "no-such-figure*"], "no figure of"),
])
def test_bad_options_exit_2_and_write_nothing(archive, tmp_path, cli, args, message):
    out = tmp_path / "never"
    code, _, err = cli("figures", archive, "--folder", out, *args)
    assert code == 2 and message in err
    assert not out.exists()  # nothing written, not even the folder


def test_bad_dpi_missing_file_and_bad_config_exit_2(tmp_path, write_config, cli):
    with pytest.raises(SystemExit) as exc:
        cli("figures", tmp_path / "x.h5", "--dpi", "5")
    assert exc.value.code == 2
    code, _, err = cli("figures", tmp_path / "nothing.h5")
    assert code == 2 and "no such file" in err
    bad = write_config("bad", pendulum_text(t_end=-1.0))
    code, _, err = cli("figures", bad, "--root", tmp_path / "runs")
    assert code == 2 and "t_end" in err
    assert not (tmp_path / "runs").exists()


def test_parse_size():
    assert parse_size("slide").inches((6.4, 4.0)) == (10.0, 5.625)
    assert parse_size("print").inches((6.4, 4.0)) == (6.5, 6.5 * 4.0 / 6.4)
    assert parse_size("report").inches((6.4, 4.0)) == (6.4, 4.0)
    assert parse_size("8x4.5").inches((1, 1)) == (8.0, 4.5)
