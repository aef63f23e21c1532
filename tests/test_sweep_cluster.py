"""Sweeps beyond one machine: a sweep's member blocks on a real Dask cluster (a
``distributed.LocalCluster`` on loopback, two worker processes of one thread each).

A worker SIGKILLed mid-sweep loses the blocks it held; they are run again elsewhere and
the family equals a local run bit for bit.  A client SIGKILLed mid-sweep leaves its
finished blocks on disk; the scheduler drops its tasks and the next run resumes them.
No more blocks are out on the cluster than the window allows.  A block that keeps
failing, or a cluster with no worker, ends the sweep with a message, never a hang.

The reference of every comparison is the same config run here with no scheduler (the
members are independent, so where a block runs cannot change a bit of it).
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time
import warnings

import numpy as np
import pytest

from conftest import pendulum_text
from reportgen.archive.store import read_archive
from reportgen.pipeline import stages
from reportgen.pipeline.stages import run_batch, run_scene
from reportgen.scene import sweep as sweep_module

distributed = pytest.importorskip("distributed")

MEMBERS, BLOCK = 60_000, 1500  # 40 blocks of ~50 ms each on one worker thread
BLOCKS = MEMBERS // BLOCK
SWEEP = pendulum_text(t_end=12.0, samples=301, extra=f"""
    [sweep]
    initial.theta = {{ start = 0.01, stop = 3.1, num = {MEMBERS} }}
    store = 1
    block = {BLOCK}
    """)


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=":0", host="127.0.0.1") as cluster, \
            distributed.Client(cluster.scheduler_address) as client:
        client.wait_for_workers(2, timeout=60)
        yield cluster, client


@pytest.fixture(scope="module")
def local(tmp_path_factory):
    """The reference: the same sweep run here, no scheduler."""
    folder = tmp_path_factory.mktemp("local")
    cfg = folder / "fam.toml"
    cfg.write_text(SWEEP)
    outcome = run_scene(str(cfg), str(folder / "out"), formats=("html",))
    assert outcome.ok, outcome.message
    return read_archive(folder / "out" / "fam" / "run.h5").sweep


def _config(tmp_path):
    cfg = tmp_path / "cfg"
    cfg.mkdir()
    (cfg / "fam.toml").write_text(SWEEP)
    return cfg / "fam.toml"


def _same_bits(a, b) -> None:
    """Every member's results and status equal bit for bit (floats as their 64 bits)."""
    assert a.size == b.size == MEMBERS
    assert list(a.analysis) == list(b.analysis)
    for name in a.analysis:
        assert np.array_equal(a.analysis[name].view(np.uint64),
                              b.analysis[name].view(np.uint64)), name
    for name in a.values:
        assert np.array_equal(a.values[name].view(np.uint64), b.values[name].view(np.uint64))
    assert np.array_equal(a.status.astype(str), b.status.astype(str))
    assert np.array_equal(a.message.astype(str), b.message.astype(str))


def _our_tasks(dask_scheduler) -> int:
    """On the scheduler: the sweep's tasks it holds now (in flight or finished, not yet
    fetched)."""
    return sum(str(key).startswith("reportgen-fam-") for key in dask_scheduler.tasks)


class _Sampler:
    """The scheduler's count of the sweep's tasks, sampled every 20 ms in a thread."""

    def __init__(self, client):
        self.client, self.counts = client, []
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, daemon=True)
        self._thread.start()

    def _run(self):
        while not self._stop.wait(0.02):
            self.counts.append(self.client.run_on_scheduler(_our_tasks))

    def stop(self) -> list[int]:
        self._stop.set()
        self._thread.join()
        return self.counts


def test_a_killed_worker_s_blocks_are_run_again_and_the_family_is_bit_identical(
        cluster, local, tmp_path, monkeypatch):
    cluster, client = cluster
    cfg = _config(tmp_path)
    pids = client.run(os.getpid)
    victim = sorted(pids)[0]
    held: list = []
    saved = []
    save = sweep_module._save_block

    def save_then_kill(path, block):  # the client saves each block as it comes back
        save(path, block)
        saved.append(path.name)
        if len(saved) == 8:  # mid-sweep: SIGKILL one worker process with what it holds
            held.extend(client.processing(workers=[victim]).get(victim, []))
            os.kill(pids[victim], signal.SIGKILL)

    monkeypatch.setattr(sweep_module, "_save_block", save_then_kill)
    sampler = _Sampler(client)
    outcomes = run_batch([str(cfg)], out_root=str(tmp_path / "dask"), formats=("html",),
                         scheduler=cluster.scheduler_address, time_limit=120)
    counts = sampler.stop()
    assert [o.status for o in outcomes] == ["ok"], [o.message for o in outcomes]
    assert held, "the killed worker held no block: nothing was lost"
    assert len(saved) == BLOCKS  # every block once, those of the lost worker included
    remote = read_archive(tmp_path / "dask" / "fam" / "run.h5").sweep
    _same_bits(remote, local)
    assert set(remote.status) == {"ok"}
    # bounded: never more than 2 blocks per worker thread out at once (2 workers x 1
    # thread; while the lost one is replaced its blocks may briefly count twice)
    assert counts and max(counts) <= 2 * 2 + 2 < BLOCKS, max(counts)


def test_a_killed_client_resumes_from_its_blocks_on_the_cluster(cluster, local, tmp_path):
    """The client is ``reportgen run --scheduler`` in a process of its own, SIGKILLed once
    10 of the 40 blocks are on disk, then run again."""
    cluster, client = cluster
    cfg = _config(tmp_path)
    out = tmp_path / "dask"
    command = [sys.executable, "-m", "reportgen", "run", str(cfg), "--out", str(out),
               "--format", "html", "--scheduler", cluster.scheduler_address]
    proc = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                            start_new_session=True)
    try:
        deadline = time.monotonic() + 90
        while (proc.poll() is None and time.monotonic() < deadline
               and len(list(out.glob("fam/.sweep-*/block-*.npz"))) < 10):
            time.sleep(0.01)
        assert proc.poll() is None, ("the client ended before it was killed: "
                                     + proc.stderr.read().decode()[-2000:])
        os.killpg(proc.pid, signal.SIGKILL)  # the client and anything it started
    finally:
        if proc.poll() is None:
            os.killpg(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
    kept = list(out.glob("fam/.sweep-*/block-*.npz"))
    assert 10 <= len(kept) < BLOCKS and not (out / "fam" / "run.h5").exists()
    # the scheduler forgets a lost client's tasks: no block runs on for nobody
    deadline = time.monotonic() + 20
    while client.run_on_scheduler(_our_tasks) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert client.run_on_scheduler(_our_tasks) == 0
    again = subprocess.run(command, capture_output=True, text=True, timeout=300)
    assert again.returncode == 0, again.stderr[-2000:]
    remote = read_archive(out / "fam" / "run.h5").sweep
    assert int(remote.attrs["resumed"]) == len(kept) * BLOCK
    _same_bits(remote, local)
    assert not list(out.glob("fam/.sweep-*"))  # the archive holds them now


def _failing_scene(config_text):
    """On a worker, in place of stages._sweep_scene: a scene whose block 3000:4500
    always raises (this module is pickled by value, so workers need no tests/ folder)."""
    from reportgen.pipeline import stages as s

    scene = s._unpatched_sweep_scene(config_text)

    class Broken:
        def sweep_block(self, lo, hi, values):
            if lo == 3000:
                raise RuntimeError("this block always fails")
            return scene.sweep_block(lo, hi, values)

    return Broken()


def _patch_workers(client, broken: bool) -> None:
    def patch():
        from reportgen.pipeline import stages as s

        if not hasattr(s, "_unpatched_sweep_scene"):
            s._unpatched_sweep_scene = s._sweep_scene
        s._sweep_scene = _failing_scene if broken else s._unpatched_sweep_scene

    client.run(patch)


def test_a_block_that_keeps_failing_ends_the_sweep_naming_it(cluster, tmp_path,
                                                             monkeypatch):
    import cloudpickle

    cluster, client = cluster
    cloudpickle.register_pickle_by_value(sys.modules[__name__])
    _patch_workers(client, broken=True)
    try:
        t0 = time.monotonic()
        outcomes = run_batch([str(_config(tmp_path))], out_root=str(tmp_path / "dask"),
                             formats=("html",), scheduler=cluster.scheduler_address,
                             time_limit=120)
        took = time.monotonic() - t0
    finally:
        _patch_workers(client, broken=False)
        cloudpickle.unregister_pickle_by_value(sys.modules[__name__])
    (outcome,) = outcomes
    assert outcome.status == "failed" and took < 60
    assert (f"members 3000:4500 of the sweep failed on the Dask cluster "
            f"{stages.SWEEP_BLOCK_TRIES} times, last: RuntimeError: this block always "
            "fails") in outcome.message, outcome.message
    assert "a rerun resumes them" in outcome.message
    assert not (tmp_path / "dask" / "fam" / "run.h5").exists()


def test_a_cluster_without_workers_ends_at_the_time_limit(tmp_path):
    with distributed.LocalCluster(n_workers=0, processes=True, dashboard_address=":0",
                                  host="127.0.0.1") as empty:
        t0 = time.monotonic()
        (outcome,) = run_batch([str(_config(tmp_path))], out_root=str(tmp_path / "dask"),
                               formats=("html",), scheduler=empty.scheduler_address,
                               time_limit=3)
        took = time.monotonic() - t0
    assert outcome.status == "failed" and took < 3 + 2 * stages.SWEEP_POLL_S + 10
    assert "time limit of 3 s exceeded on the Dask cluster" in outcome.message, \
        outcome.message


def test_text_of_ten_million_members_is_fixed_width_and_read_as_shared_strings(
        tmp_path, monkeypatch):
    """A sweep's status and message are fixed-width UTF-8 (no Python string per member
    on reading, so the archive check's limit on variable-length text does not apply;
    shown with the limit lowered to 10), decoded by xarray, read back as one string
    object per distinct value."""
    xr = pytest.importorskip("xarray")
    import h5py

    from reportgen.archive import check
    from reportgen.archive.store import write_archive
    from reportgen.scene.results import Results
    from reportgen.scene.sweep import SweepData

    monkeypatch.setattr(check, "MAX_STRINGS", 10)
    status = np.array(["ok", "échoué", "ok"] * 10, dtype=object)
    sweep = SweepData(values={"initial.theta": np.linspace(0.1, 1.0, 30)},
                      analysis={"period": np.arange(30.0)}, status=status,
                      message=np.where(status == "ok", "", "pas de période").astype(object),
                      attrs={"paths": '["initial.theta"]', "shape": "[30]"})
    results = Results()
    results.sweep = sweep
    path = tmp_path / "run.h5"
    write_archive(path, kind="pendulum", title="t", scene="t", config_text="x = 1",
                  config_sha256="0", results=results)
    with h5py.File(path) as f:
        assert h5py.check_string_dtype(f["sweep/status"].dtype).length == len("échoué".encode())
    back = read_archive(path).sweep
    assert list(back.status) == list(status) and list(back.message) == list(sweep.message)
    assert len({id(s) for s in back.status}) == 2  # shared, not one per member
    assert back.counts() == {"ok": 20, "échoué": 10}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with xr.open_dataset(path, group="sweep", engine="h5netcdf", phony_dims="sort") as ds:
            assert list(ds["status"].values) == list(status)
    with h5py.File(path, "a") as f:  # the same 30 strings variable-length: over the limit
        del f["sweep/message"]
        f["sweep"].create_dataset("message", data=sweep.message, dtype=h5py.string_dtype())
    with pytest.raises(Exception, match="more than the 10"):
        read_archive(path)


def test_text_codes_give_back_every_value():
    """Codes into distinct values (how blocks travel and how the archive is written):
    ``names[codes[i]]`` is the i-th value as text, checked against the values themselves
    for few distinct values (found by vectorised comparison), many (one by one), StrEnum
    statuses and UTF-8 bytes."""
    from reportgen.core.integrators.status import Status
    from reportgen.scene.sweep import text_array, text_codes

    rng = np.random.default_rng(7)
    few = rng.choice(np.array(["ok", "no_period", "max_steps"], dtype=object), 10_000)
    many = np.array([f"member {i} failed" for i in rng.integers(0, 500, 3000)], dtype=object)
    cases = [few, many, np.array([Status.OK, "ok", Status.NO_PERIOD], dtype=object),
             np.array(["é".encode(), b"ok", "é".encode()]), np.zeros(0, dtype=object)]
    for values in cases:
        codes, names = text_codes(values)
        expected = [v.decode() if isinstance(v, bytes) else str(v) for v in values]
        assert [names[c] for c in codes] == expected
        assert len(names) == len(set(expected)) and list(text_array(codes, names)) == expected
    assert text_codes(few)[0].dtype == np.uint8 and text_codes(many)[0].dtype == np.uint16
