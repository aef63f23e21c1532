"""``reportgen animate``: the motion of a scene as a GIF (and an MP4 where ffmpeg is there).

Drawn from the archive alone by the kind's ``Report.motion`` (its ``kinds/<kind>/motion.py``,
with the shared pieces of :mod:`reportgen.rendering.plots.motion`): frames are spread evenly
over the archived run, ``fps * duration`` of them (at least :data:`MIN_FRAMES`).  GIF
frames are written by Pillow with one palette made from the first frame, so colours do
not flicker; MP4 (H.264) by the ffmpeg of ``imageio-ffmpeg`` (the ``video`` extra).  The
figure's layout is computed on the first frame and then kept, so nothing jumps.
"""

from __future__ import annotations

import io
import sys
from collections.abc import Callable
from pathlib import Path

from ..errors import UsageError
from ..kinds import KINDS, get_kind
from ..scene.report import Report
from ..support.fsutil import atomic_write
from .export import MAX_FIGURE_PIXELS, pixel_problem

MIN_FRAMES = 30
ANIMATION_FORMATS = ("gif", "mp4")
#: pixels of all a GIF's frames, which are held until it is written (a byte each): 4
#: figures' worth (the default, 90 frames of 640 × 480, holds 28 million)
MAX_GIF_PIXELS = 4 * MAX_FIGURE_PIXELS


def ffmpeg_available() -> bool:
    try:
        import imageio_ffmpeg

        imageio_ffmpeg.get_ffmpeg_exe()
    except Exception:  # noqa: BLE001 - not installed, or no binary for this platform
        return False
    return True


def animated_kinds() -> list[str]:
    """The kinds that can animate: those with a ``motion.py`` (:meth:`Report.motion_module`)."""
    return sorted(k for k, cls in KINDS.items()
                  if issubclass(cls, Report) and cls.motion_module() is not None)


def plan_frames(fps: float, duration: float) -> int:
    frames = int(round(fps * duration))
    if frames < MIN_FRAMES:
        raise UsageError(f"--fps {fps:g} × --duration {duration:g} s gives {frames} frames; "
                         f"an animation needs at least {MIN_FRAMES}")
    if frames > 5000:
        raise UsageError(f"--fps {fps:g} × --duration {duration:g} s gives {frames} frames; "
                         "at most 5000")
    return frames


def parse_formats(text: str | None) -> tuple[str, ...]:
    """``--format``: None means GIF, plus MP4 when ffmpeg is available."""
    if text is None:
        return ("gif", "mp4") if ffmpeg_available() else ("gif",)
    items = tuple(dict.fromkeys(f.strip().lower() for f in text.split(",") if f.strip()))
    bad = [f for f in items if f not in ANIMATION_FORMATS]
    if bad or not items:
        raise UsageError(f"--format: expected a comma-separated subset of "
                         f"{','.join(ANIMATION_FORMATS)} (got {text!r})")
    if "mp4" in items and not ffmpeg_available():
        raise UsageError("--format mp4 needs ffmpeg: pip install -e '.[video]' "
                         "(imageio-ffmpeg)")
    return items


def _check_pixels(fig, dpi: int, frames: int, formats: tuple[str, ...]) -> None:
    """A frame over the figures' pixel budget, or a GIF whose frames together are over
    :data:`MAX_GIF_PIXELS`, is a UsageError before anything is drawn."""
    width, height = fig.get_size_inches()
    problem = pixel_problem(width, height, dpi, "a frame")
    if problem is None and "gif" in formats:
        pixels = frames * round(width * dpi) * round(height * dpi)
        if pixels > MAX_GIF_PIXELS:
            problem = (f"a GIF of {frames} frames at --dpi {dpi} holds {pixels / 1e6:.0f} "
                       f"megapixels until written, more than {MAX_GIF_PIXELS / 1e6:.0f}: fewer "
                       "frames (--fps × --duration), a lower --dpi, or --format mp4")
    if problem is not None:
        fig.clear()
        raise UsageError(problem)


def animate(archive: Path, out_dir: Path, *, fps: float = 15.0, duration: float = 6.0,
            dpi: int = 100, formats: tuple[str, ...] = ("gif",),
            progress: Callable[[int, int], None] | None = None) -> list[Path]:
    """Write ``out_dir/animation.<format>`` for each of ``formats``; returns the files."""
    import numpy as np
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from PIL import Image

    from ..archive.store import read_archive

    frames = plan_frames(fps, duration)
    data = read_archive(Path(archive))
    try:
        kind = get_kind(data.kind)
    except KeyError:
        raise UsageError(f"{archive}: kind {data.kind!r} is unknown to this reportgen") from None
    motion = kind.motion(data, frames)
    if motion is None:
        raise UsageError(f"{archive}: a {data.kind} scene has no motion to animate "
                         f"(kinds with one: {', '.join(animated_kinds())})")
    fig = motion.figure
    _check_pixels(fig, dpi, frames, formats)
    canvas = FigureCanvasAgg(fig)
    fig.set_dpi(dpi)

    def rgb(k: int) -> np.ndarray:
        motion.update(k)
        canvas.draw()
        if k == 0:
            fig.set_layout_engine("none")  # keep the first frame's layout for all
        return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()

    first = rgb(0)
    height, width = first.shape[:2]
    width, height = width - width % 2, height - height % 2  # H.264 wants even sizes
    gif_frames: list[Image.Image] = []
    palette = None
    mp4 = None
    out_dir = Path(out_dir)
    out_dir.mkdir(parents=True, exist_ok=True)
    mp4_tmp = out_dir / ".animation.part.mp4"  # ffmpeg picks the format by extension
    if "mp4" in formats:
        import imageio_ffmpeg

        mp4 = imageio_ffmpeg.write_frames(str(mp4_tmp), (width, height), fps=fps,
                                          codec="libx264", pix_fmt_out="yuv420p",
                                          macro_block_size=2, quality=8,
                                          output_params=["-loglevel", "error"])
        mp4.send(None)
    try:
        for k in range(frames):
            image = (first if k == 0 else rgb(k))[:height, :width]
            if "gif" in formats:
                picture = Image.fromarray(image)
                if palette is None:
                    palette = picture.quantize(colors=255, method=Image.Quantize.MEDIANCUT)
                gif_frames.append(picture.quantize(palette=palette, dither=Image.Dither.NONE))
            if mp4 is not None:
                mp4.send(np.ascontiguousarray(image))
            if progress is not None:
                progress(k + 1, frames)
        written = []
        if mp4 is not None:
            mp4.close()
            mp4 = None
            target = out_dir / "animation.mp4"
            mp4_tmp.replace(target)  # same folder: atomic
            written.append(target)
        if gif_frames:
            buf = io.BytesIO()
            gif_frames[0].save(buf, format="GIF", save_all=True, append_images=gif_frames[1:],
                               duration=round(1000.0 / fps), loop=0, optimize=False)
            target = out_dir / "animation.gif"
            atomic_write(target, buf.getvalue())
            written.insert(0, target)
    finally:
        if mp4 is not None:
            mp4.close()
        mp4_tmp.unlink(missing_ok=True)
        fig.clear()
    return written


def terminal_progress(stream=None) -> Callable[[int, int], None]:
    """Frame k of n on ``stream`` (default stderr): in place on a terminal, at each tenth
    otherwise."""
    stream = stream or sys.stderr
    tty = stream.isatty()

    def report(k: int, n: int) -> None:
        if tty:
            stream.write(f"\r  frame {k}/{n}")
            if k == n:
                stream.write("\n")
        elif k == n or k % max(1, n // 10) == 0:
            stream.write(f"  frame {k}/{n}\n")
        stream.flush()

    return report
