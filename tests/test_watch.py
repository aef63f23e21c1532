"""reportgen watch: the edit loop in one process writes what ``run`` writes, only the
stages an edit touches run, a bad edit writes nothing, and Ctrl-C stops it cleanly."""

from __future__ import annotations

import queue
import signal
import subprocess
import sys
import threading
import time

import h5py

from conftest import pendulum_text


class _Lines:
    """The stderr lines of a running process, read on a thread."""

    def __init__(self, proc: subprocess.Popen):
        self.seen: list[str] = []
        self._queue: queue.Queue = queue.Queue()
        threading.Thread(target=self._read, args=(proc,), daemon=True).start()

    def _read(self, proc):
        for line in proc.stderr:
            self._queue.put(line.rstrip("\n"))

    def wait_for(self, text: str, timeout: float = 180.0) -> str:
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            try:
                line = self._queue.get(timeout=0.5)
            except queue.Empty:
                continue
            self.seen.append(line)
            if text in line:
                return line
        raise AssertionError(f"no line with {text!r} in {timeout} s; saw:\n" + "\n".join(self.seen))


def _arrays(path) -> dict[str, bytes]:
    out = {}
    with h5py.File(path, "r") as f:
        f.visititems(lambda name, obj: out.__setitem__(name, obj[()].tobytes())
                     if isinstance(obj, h5py.Dataset) and obj.dtype.kind == "f" else None)
    return out


def test_watch_reruns_what_an_edit_touches(write_config, tmp_path):
    cfg = write_config("pend", pendulum_text(t_end=2.0, samples=201, title="first"))
    write_config("other", pendulum_text(t_end=1.0, samples=101, title="other"))
    out = tmp_path / "out"
    proc = subprocess.Popen([sys.executable, "-m", "reportgen", "watch", str(tmp_path),
                             "--out", str(out), "--interval", "0.1"],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    lines = _Lines(proc)
    try:
        lines.wait_for("first run")
        lines.wait_for("--- done")
        report = out / "pend" / "report.html"
        assert "first" in report.read_text(encoding="utf-8")
        assert (out / "pend" / "report.pdf").exists() and (out / "other" / "report.pdf").exists()
        before = _arrays(out / "pend" / "run.h5")

        time.sleep(0.05)  # a modification time the first snapshot cannot already hold
        cfg.write_text(cfg.read_text(encoding="utf-8").replace('"first"', '"second"'),
                       encoding="utf-8")
        lines.wait_for("pend.toml changed")
        lines.wait_for("physics unchanged: report re-rendered")
        lines.wait_for("--- done")
        assert "second" in report.read_text(encoding="utf-8")
        assert _arrays(out / "pend" / "run.h5") == before  # restamped, not re-simulated

        good = report.read_bytes()
        cfg.write_text(cfg.read_text(encoding="utf-8").replace("t_end = 2", "t_end = -2"),
                       encoding="utf-8")
        lines.wait_for("t_end")  # the validation message names the key
        lines.wait_for("not run: fix the config")
        assert report.read_bytes() == good  # nothing written

        cfg.write_text(cfg.read_text(encoding="utf-8").replace("t_end = -2", "t_end = 3"),
                       encoding="utf-8")
        lines.wait_for("pend.toml changed")
        lines.wait_for("--- done")
        assert _arrays(out / "pend" / "run.h5") != before  # the physics edit re-simulated
    finally:
        proc.send_signal(signal.SIGINT)
        try:
            # generous: once (1 of ~10 full runs) the stop took over 30 s on 2 loaded cores
            code = proc.wait(timeout=90)
        except subprocess.TimeoutExpired:
            proc.kill()
            raise
    lines.wait_for("watch stopped", timeout=10)
    assert code == 0


def test_watch_stopped_by_sigterm_exits_143(write_config, tmp_path):
    """Issue 48 I: Ctrl-C is how a watch ends (status 0, above); SIGTERM stops it as it
    stops any command, with 128 + 15 (it exited 0)."""
    write_config("pend", pendulum_text(t_end=1.0, samples=101, title="first")
                 + '\n[report]\nformats = ["html"]\n')
    proc = subprocess.Popen([sys.executable, "-m", "reportgen", "watch", str(tmp_path),
                             "--out", str(tmp_path / "out"), "--interval", "0.1"],
                            stderr=subprocess.PIPE, stdout=subprocess.DEVNULL, text=True)
    lines = _Lines(proc)
    try:
        lines.wait_for("--- done")
        proc.send_signal(signal.SIGTERM)
        code = proc.wait(timeout=90)
    finally:
        if proc.poll() is None:
            proc.kill()
    lines.wait_for("watch stopped", timeout=10)
    assert code == 128 + signal.SIGTERM
