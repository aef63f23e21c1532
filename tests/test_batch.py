"""Batches: local process pool and a real Dask LocalCluster give the same archives."""

from __future__ import annotations

import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive
from reportgen.pipeline.stages import run_batch

distributed = pytest.importorskip("distributed")


@pytest.fixture
def three_configs(tmp_path):
    cfg = tmp_path / "configs"
    cfg.mkdir()
    for name, theta in (("a", 0.3), ("b", 1.5), ("c", 2.8)):
        (cfg / f"{name}.toml").write_text(pendulum_text(theta=theta, t_end=8.0, samples=401))
    return cfg


def _arrays(out, name):
    data = read_archive(out / name / "run.h5")
    return data.runs["main"].t, data.runs["main"].y, data.analysis["period_measured"]


def test_dask_local_cluster_matches_local_run(three_configs, tmp_path):
    local = run_batch([str(three_configs)], out_root=str(tmp_path / "local"), jobs=1,
                      formats=("html",))
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, host="127.0.0.1") as cluster:
        remote = run_batch([str(three_configs)], out_root=str(tmp_path / "dask"),
                           formats=("html",), scheduler=cluster.scheduler_address)
        assert [o.status for o in remote] == ["ok", "ok", "ok"]
        for name in ("a", "b", "c"):
            t1, y1, p1 = _arrays(tmp_path / "local", name)
            t2, y2, p2 = _arrays(tmp_path / "dask", name)
            assert np.array_equal(t1, t2) and np.array_equal(y1, y2) and p1 == p2
            assert (tmp_path / "dask" / name / "report.html").exists()
            assert (tmp_path / "dask" / name / "figures").is_dir()
        assert (tmp_path / "dask" / "index.html").exists()
        # resume: a second submission finds every archive current and runs nothing
        again = run_batch([str(three_configs)], out_root=str(tmp_path / "dask"),
                          formats=("html",), scheduler=cluster.scheduler_address)
        assert all(o.skipped for o in again)
    assert [o.status for o in local] == ["ok", "ok", "ok"]


def test_unreachable_scheduler_is_usage_error(three_configs, tmp_path, cli):
    code, _, err = cli("run", three_configs, "--out", tmp_path / "o",
                       "--scheduler", "tcp://127.0.0.1:9")
    assert code == 2 and "cannot connect" in err


@pytest.mark.parametrize("peer, said", [
    (b"", "no answer from a Dask scheduler within 2 s"),  # accepts, never answers
    (b"\xff" * 64, "not a Dask scheduler"),  # a length field of 2⁶⁴ − 1
])
def test_a_listener_that_is_not_a_scheduler_is_usage_error(three_configs, tmp_path, cli,
                                                          monkeypatch, peer, said):
    """Issue 48 F: a loopback listener that accepts and never answers hung `run` past
    300 s; one that answers with bytes of its own gave exit 1 (MemoryError, "unexpected
    error").  The scheduler's handshake and identity request are bounded: exit 2."""
    import socket
    import threading
    import time

    from reportgen.pipeline import stages

    monkeypatch.setattr(stages, "HANDSHAKE_S", 2.0)
    monkeypatch.setattr(stages._handshake, "__defaults__", (2.0,))
    server = socket.create_server(("127.0.0.1", 0))
    held = []

    def serve():
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            held.append(conn)
            if peer:
                conn.sendall(peer)

    threading.Thread(target=serve, daemon=True).start()
    try:
        start = time.monotonic()
        code, _, err = cli("run", three_configs, "--out", tmp_path / "o", "--scheduler",
                           f"tcp://127.0.0.1:{server.getsockname()[1]}")
        assert code == 2 and said in err and time.monotonic() - start < 60, err
        assert "unexpected error" not in err
    finally:
        server.close()
        for conn in held:
            conn.close()


def test_local_pool_of_two(three_configs, tmp_path):
    outcomes = run_batch([str(three_configs)], out_root=str(tmp_path / "pool"), jobs=2,
                         formats=("html",))
    assert [o.name for o in outcomes] == ["a", "b", "c"]
    assert all(o.ok for o in outcomes)
    t, y, _ = _arrays(tmp_path / "pool", "b")
    assert y.shape == (401, 2)


def test_time_limit_stops_a_scene_and_keeps_the_others(tmp_path, cli):
    cfg = tmp_path / "cfg"
    cfg.mkdir()
    (cfg / "quick.toml").write_text(pendulum_text(t_end=2.0, samples=101))
    # 2e5 periods stored at 1e6 samples with the study on: minutes, far beyond the limit
    (cfg / "slow.toml").write_text(pendulum_text(t_end=4e5, samples=1000001, study="true"))
    # compile (or load) the quick scene's kernels first: a cold compile alone can take ~10 s
    assert cli("run", cfg / "quick.toml", "--out", tmp_path / "warm", "--jobs", 1,
               "--format", "html")[0] == 0
    code, _, err = cli("run", cfg, "--out", tmp_path / "o", "--jobs", 2, "--format", "html",
                       "--time-limit", 10)
    assert code == 1
    assert "time limit of 10 s exceeded" in err
    assert (tmp_path / "o" / "quick" / "report.html").exists()
    assert not (tmp_path / "o" / "slow" / "run.h5").exists()


def test_worker_killed_on_time_limit_is_replaced(tmp_path, cli):
    """One worker runs scene after scene; the one stopped for its time limit is replaced,
    so the scene after the slow one still runs, and no worker outlives the batch."""
    import multiprocessing

    cfg = tmp_path / "cfg"
    cfg.mkdir()
    (cfg / "a_quick.toml").write_text(pendulum_text(t_end=2.0, samples=101))
    (cfg / "b_slow.toml").write_text(pendulum_text(t_end=4e5, samples=1000001, study="true"))
    (cfg / "c_quick.toml").write_text(pendulum_text(t_end=3.0, samples=101))
    assert cli("run", cfg / "a_quick.toml", "--out", tmp_path / "warm", "--jobs", 1,
               "--format", "html")[0] == 0  # kernels compiled before the clock runs
    outcomes = run_batch([str(cfg)], out_root=str(tmp_path / "o"), jobs=1, formats=("html",),
                         time_limit=10)
    assert [(o.name, o.status) for o in outcomes] == [
        ("a_quick", "ok"), ("b_slow", "failed"), ("c_quick", "ok")]
    assert "time limit of 10 s exceeded" in outcomes[1].message
    assert (tmp_path / "o" / "c_quick" / "report.html").exists()
    assert not (tmp_path / "o" / "b_slow" / "run.h5").exists()
    assert multiprocessing.active_children() == []


def test_sweep_blocks_run_on_a_dask_cluster(tmp_path):
    """With --scheduler, a sweep's member blocks are tasks on the cluster (the kept
    members, archive and report are made where the batch runs): the same family as a
    local run, bit for bit, for a compiled ensemble (pendulum) and for members run as
    whole scenes (oscillator)."""
    from test_sweep import OSCILLATOR

    cfg = tmp_path / "cfg"
    cfg.mkdir()
    (cfg / "pend.toml").write_text(pendulum_text(t_end=12.0, samples=301, extra="""
        [sweep]
        initial.theta = { start = 0.1, stop = 3.0, num = 400 }
        store = 1
        block = 100
        """))
    (cfg / "osc.toml").write_text(OSCILLATOR + "[sweep]\nparams.omega = [1.0, 1.5, 2.0]\n"
                                               "store = 0\nblock = 1\n")
    local = run_batch([str(cfg)], out_root=str(tmp_path / "local"), jobs=1, formats=("html",))
    assert all(o.ok for o in local), [o.message for o in local]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None, host="127.0.0.1") as cluster:
        with distributed.Client(cluster.scheduler_address) as client, \
                distributed.get_task_stream(client=client) as stream:
            remote = run_batch([str(cfg)], out_root=str(tmp_path / "dask"), formats=("html",),
                               scheduler=cluster.scheduler_address)
        keys = [str(task["key"]) for task in stream.data]
    assert all(o.ok for o in remote), [o.message for o in remote]
    # one task per block: 4 blocks of 100 pendulums, 3 blocks of one oscillator
    assert sum(k.startswith("reportgen-pend-") for k in keys) == 4, keys
    assert sum(k.startswith("reportgen-osc-") for k in keys) == 3, keys
    for name in ("pend", "osc"):
        a = read_archive(tmp_path / "local" / name / "run.h5").sweep
        b = read_archive(tmp_path / "dask" / name / "run.h5").sweep
        assert list(a.analysis) == list(b.analysis) and list(b.status) == list(a.status)
        for key in a.analysis:
            assert np.array_equal(a.analysis[key], b.analysis[key], equal_nan=True), key
        assert (tmp_path / "dask" / name / "report.html").exists()
