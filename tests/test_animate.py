"""``reportgen animate``: a scene's motion as GIF and MP4, drawn from the archive alone."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from conftest import cli_without_core, without_study
from reportgen.rendering.animate import animated_kinds
from reportgen.rendering.plots.motion import frame_samples

REPO = Path(__file__).resolve().parent.parent
#: one shipped scene per kind that has a motion
ONE_PER_KIND = {
    "pendulum": "pendulum_large", "oscillator": "oscillator", "fput": "fput_stiff_soft",
    "heavy_top": "heavy_top_fig4.3c", "rigid_body": "rigid_body_dzhanibekov",
    "central_force": "kepler_e07", "two_center": "two_center_satellite",
    "three_body": "three_body_figure_eight", "normal_modes": "normal_modes_co2",
}


def _run_without_study(stem: str, root: Path) -> Path:
    from reportgen.pipeline.stages import run_scene

    config = without_study(REPO / "configs" / f"{stem}.toml", root / f"{stem}.toml")
    outcome = run_scene(str(config), str(root / "out"))
    assert outcome.status != "failed", outcome.message
    return root / "out" / stem / "run.h5"


def _gif_frames(path: Path) -> list[np.ndarray]:
    image = Image.open(path)
    frames = []
    for k in range(image.n_frames):
        image.seek(k)
        frames.append(np.asarray(image.convert("RGB")))
    return frames


def test_every_kind_with_motion_has_a_config_here():
    assert set(ONE_PER_KIND) == set(animated_kinds())


@pytest.mark.parametrize("kind", sorted(ONE_PER_KIND))
def test_each_kind_animates_from_its_archive_alone(kind, tmp_path):
    archive = _run_without_study(ONE_PER_KIND[kind], tmp_path)
    before = archive.read_bytes()
    out = tmp_path / "anim"
    done = cli_without_core("animate", archive, "--fps", "10", "--duration", "3", "--dpi", "40",
                            "--format", "gif", "--folder", out)
    assert done.returncode == 0, done.stderr
    assert "frame 30/30" in done.stderr  # progress shown
    frames = _gif_frames(out / "animation.gif")
    # Pillow merges a frame identical to the one before it (a mode at rest at its turning
    # point, say); the motion itself must show: at least 30 frames written, most different
    assert len(frames) >= 25
    differ = sum(not np.array_equal(a, b) for a, b in zip(frames, frames[1:], strict=False))
    assert differ >= 0.8 * (len(frames) - 1)
    assert archive.read_bytes() == before


def test_gif_and_mp4_frame_count_rate_and_duration(tmp_path, cli):
    imageio_ffmpeg = pytest.importorskip("imageio_ffmpeg")
    archive = _run_without_study("pendulum_large", tmp_path)
    code, _, err = cli("animate", archive, "--fps", "12", "--duration", "3", "--dpi", "50",
                       "--format", "gif,mp4", "--folder", tmp_path / "a")
    assert code == 0, err
    gif = Image.open(tmp_path / "a" / "animation.gif")
    assert gif.n_frames == 36  # the clock changes every frame: none merged
    assert gif.info["duration"] in (80, 90)  # 1/12 s, in the GIF's hundredths
    frames, seconds = imageio_ffmpeg.count_frames_and_secs(str(tmp_path / "a" / "animation.mp4"))
    assert frames == 36 and seconds == pytest.approx(3.0, abs=0.1)
    assert not list((tmp_path / "a").glob(".*"))  # no temporary file left


def test_the_bob_is_where_the_archive_says(tmp_path, cli):
    """Frame k shows the pendulum at θ of sample frame_samples(N, frames)[k]: the red bob's
    centroid in the left panel, seen from the pivot, points along (sin θ, −cos θ)."""
    from reportgen.archive.store import read_archive

    archive = _run_without_study("pendulum_large", tmp_path)
    code, _, err = cli("animate", archive, "--fps", "10", "--duration", "3", "--dpi", "60",
                       "--format", "gif", "--folder", tmp_path / "a")
    assert code == 0, err
    run = read_archive(archive).runs["main"]
    theta = run.y[:, run.columns.index("theta")]
    idx = frame_samples(len(run.t), 30)
    frames = _gif_frames(tmp_path / "a" / "animation.gif")
    assert len(frames) == 30
    for k in (0, 7, 15, 22, 29):
        left = frames[k][:, : int(0.42 * frames[k].shape[1])].astype(int)  # the swing panel
        red = (left[:, :, 0] > 150) & (left[:, :, 1] < 110) & (left[:, :, 2] < 110)
        pivot = (left.sum(axis=2) < 60)
        pivot[: int(0.2 * len(pivot))] = False  # the clock's text, top left
        assert red.sum() > 20 and pivot.sum() >= 2
        ry, rx = np.argwhere(red).mean(axis=0)
        py, px = np.argwhere(pivot).mean(axis=0)
        angle = np.arctan2(rx - px, ry - py)  # image rows grow downwards: θ from the vertical
        assert abs(np.angle(np.exp(1j * (angle - theta[idx[k]])))) < 0.12


def test_too_few_frames_no_motion_and_missing_archive_exit_2(tmp_path, cli):
    archive = _run_without_study("inertia_cone", tmp_path)
    code, _, err = cli("animate", archive, "--format", "gif", "--folder", tmp_path / "x")
    assert code == 2 and "no motion to animate" in err
    code, _, err = cli("animate", archive, "--fps", "2", "--duration", "5")
    assert code == 2 and "at least 30" in err
    code, _, err = cli("animate", tmp_path / "none.h5", "--format", "gif")
    assert code == 2 and "no such file" in err
    code, _, err = cli("animate", archive, "--format", "avi")
    assert code == 2 and "--format" in err
    assert not (tmp_path / "x").exists() or not any((tmp_path / "x").iterdir())


def test_frame_samples_span_the_run():
    idx = frame_samples(1001, 30)
    assert idx[0] == 0 and idx[-1] == 1000 and len(idx) == 30
    assert np.all(np.diff(idx) > 0)
