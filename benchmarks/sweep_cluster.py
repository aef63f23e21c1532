"""A pendulum sweep on a real local Dask cluster, with a client and a worker killed.

``python benchmarks/sweep_cluster.py [--members N] [--kill-client-at F] [--kill-worker-at F]``
(default 10⁷ members: ``configs/pendulum_period_sweep.toml`` with ``num = N``).

1. Starts ``dask scheduler --host 127.0.0.1 --port P --no-dashboard`` and two
   ``dask worker tcp://127.0.0.1:P --nworkers 1 --nthreads 1 --no-dashboard`` as
   subprocesses (loopback only).  Every process this script starts dies with it: its own
   process group, killed on exit, Ctrl-C or SIGTERM, and PR_SET_PDEATHSIG set (SIGKILL of
   this script kills them too).
2. Runs the client, ``reportgen run CONFIG --scheduler tcp://127.0.0.1:P --out CLUSTER``,
   as a subprocess and kills it (SIGKILL, its whole process group) once a fraction
   ``--kill-client-at`` of the member blocks is on disk.
3. Runs the same command again: it resumes from the blocks on disk.  When a fraction
   ``--kill-worker-at`` of the blocks is on disk, one ``dask worker`` (its nanny and its
   worker process) is killed with SIGKILL: the blocks it held are re-run by the other
   worker and the sweep ends with every member.
4. Runs the same config with no scheduler (``reportgen run CONFIG --out LOCAL``), the
   local reference.
5. Compares the two archives' ``/sweep`` arrays bit for bit (every float as its 64 bits,
   status and message as text) and prints wall times, members/s and the peak resident
   memory (VmHWM of /proc/<pid>/status, polled every 0.1 s) of each process: the client
   and the processes it starts (figure helper, PDF renderer), the scheduler, each
   worker's nanny and worker process.

All runs use ``--time-limit 0`` (the default 600 s limit would stop a slow 10⁷-member
local run on a busy machine).  A JSON summary goes to ``OUT/summary.json``.
"""

from __future__ import annotations

import argparse
import contextlib
import ctypes
import json
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

import h5py
import numpy as np
import psutil

ROOT = Path(__file__).resolve().parents[1]
CONFIG = ROOT / "configs" / "pendulum_period_sweep.toml"
PR_SET_PDEATHSIG = 1


def _die_with_parent() -> None:
    """In a child before exec: its own process group, SIGKILL when this script dies."""
    os.setpgid(0, 0)
    with contextlib.suppress(OSError, AttributeError):
        ctypes.CDLL("libc.so.6", use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)


class Processes:
    """Every process started here, killed (by process group) when the script ends."""

    def __init__(self):
        self.started: list[subprocess.Popen] = []

    def start(self, args: list[str], log: Path, **kw) -> subprocess.Popen:
        fh = open(log, "ab")  # noqa: SIM115 - closed with the process
        proc = subprocess.Popen(args, stdout=fh, stderr=subprocess.STDOUT,
                                preexec_fn=_die_with_parent, **kw)
        proc.log = fh
        self.started.append(proc)
        return proc

    @staticmethod
    def kill(proc: subprocess.Popen) -> None:
        with contextlib.suppress(ProcessLookupError, PermissionError):
            os.killpg(proc.pid, signal.SIGKILL)
        with contextlib.suppress(subprocess.TimeoutExpired):
            proc.wait(timeout=10)
        proc.log.close()

    def close(self) -> None:
        for proc in reversed(self.started):
            self.kill(proc)


class Memory:
    """Peak resident memory of processes and their descendants, polled in a thread."""

    def __init__(self):
        self.roles: dict[int, str] = {}  # pid -> role
        self.peak: dict[int, int] = {}  # pid -> VmHWM [kB], last seen
        self.trees: dict[str, int] = {}  # role prefix -> root pid
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._poll, daemon=True)
        self._thread.start()

    def watch(self, role: str, pid: int) -> None:
        self.trees[role] = pid

    def _poll(self) -> None:
        while not self._stop.wait(0.1):
            for role, root in list(self.trees.items()):
                try:
                    top = psutil.Process(root)
                    tree = [top, *top.children(recursive=True)]
                except psutil.Error:
                    continue
                for proc in tree:
                    try:
                        text = Path(f"/proc/{proc.pid}/status").read_text()
                        hwm = int(re.search(r"VmHWM:\s+(\d+)", text).group(1))
                        if proc.pid not in self.roles:
                            name = " ".join(proc.cmdline()[:4])[:80]
                            self.roles[proc.pid] = (role if proc.pid == root
                                                    else f"{role} child: {name}")
                    except (OSError, AttributeError, psutil.Error):
                        continue
                    self.peak[proc.pid] = max(self.peak.get(proc.pid, 0), hwm)

    def stop(self) -> dict[str, float]:
        self._stop.set()
        self._thread.join()
        return {f"{self.roles[pid]} (pid {pid})": kb / 1024 for pid, kb in self.peak.items()
                if pid in self.roles}


def vm_hwm(pid: int) -> float:
    """The peak resident memory [MiB] of a live process (nan once it has gone)."""
    try:
        text = Path(f"/proc/{pid}/status").read_text()
    except OSError:
        return float("nan")
    return int(re.search(r"VmHWM:\s+(\d+)", text).group(1)) / 1024


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def write_config(folder: Path, members: int, block: int) -> Path:
    text = CONFIG.read_text(encoding="utf-8")
    text = re.sub(r"num = \d+", f"num = {members}", text)
    count = f"{members:,}".replace(",", " ")
    text = re.sub(r'title = "[^"]*"', f'title = "Pendulum family — period against '
                  f'amplitude, {count} members"', text)
    text = text.replace("2000 members", f"{count} members")
    if block:
        text = text.replace("store = 5", f"store = 5\nblock = {block}")
    path = folder / "pendulum_period_sweep_big.toml"
    path.write_text(text, encoding="utf-8")
    return path


def blocks_on_disk(out: Path, scene: str) -> int:
    return sum(1 for _ in (out / scene).glob(".sweep-*/block-*.npz"))


def sweep_arrays(path: Path) -> dict[str, np.ndarray]:
    """Every /sweep array that holds the family's results, by name."""
    out = {}
    with h5py.File(path, "r") as f:
        g = f["sweep"]
        out["status"] = g["status"].asstr()[()] if g["status"].dtype.kind == "S" \
            else g["status"][()].astype(str)
        out["message"] = g["message"].asstr()[()] if g["message"].dtype.kind == "S" \
            else g["message"][()].astype(str)
        for sub in ("values", "analysis"):
            for name, ds in g[sub].items():
                out[f"{sub}/{name}"] = ds[()]
        out["attrs"] = {k: (v.item() if hasattr(v, "item") else v) for k, v in g.attrs.items()}
    return out


def identical(a: np.ndarray, b: np.ndarray) -> bool:
    """Bit for bit: floats compared as their 64-bit patterns (NaN included)."""
    if a.dtype.kind == "f" and b.dtype.kind == "f":
        return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))
    return a.shape == b.shape and bool(np.all(a == b))


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--members", type=int, default=10_000_000)
    ap.add_argument("--block", type=int, default=0, help="members per block (0: automatic)")
    ap.add_argument("--kill-client-at", type=float, default=0.25)
    ap.add_argument("--kill-worker-at", type=float, default=0.6)
    ap.add_argument("--out", type=Path, default=None, help="folder (default: a temporary one)")
    ap.add_argument("--format", default="html,pdf")
    args = ap.parse_args()

    procs = Processes()
    memory = Memory()

    def stop(signum, frame):
        raise KeyboardInterrupt

    signal.signal(signal.SIGTERM, stop)
    work = args.out or Path(tempfile.mkdtemp(prefix="reportgen-cluster-"))
    work.mkdir(parents=True, exist_ok=True)
    summary: dict = {"members": args.members, "folder": str(work)}
    try:
        return run(args, work, procs, memory, summary)
    except KeyboardInterrupt:
        print("interrupted: every process started here is killed", file=sys.stderr)
        return 130
    finally:
        procs.close()
        summary["peak_rss_mib"] = memory.stop()
        (work / "summary.json").write_text(json.dumps(summary, indent=2, default=str))
        print("\npeak resident memory (VmHWM) [MiB]:")
        for role, mib in sorted(summary["peak_rss_mib"].items()):
            print(f"  {mib:8.0f}  {role}")
        print(f"summary: {work / 'summary.json'}")


def run(args, work: Path, procs: Processes, memory: Memory, summary: dict) -> int:
    from distributed import Client

    cfg = write_config(work, args.members, args.block)
    scene = cfg.stem
    port = free_port()
    address = f"tcp://127.0.0.1:{port}"
    bin_dir = Path(sys.executable).parent
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    scheduler = procs.start([str(bin_dir / "dask"), "scheduler", "--host", "127.0.0.1",
                             "--port", str(port), "--no-dashboard"], work / "scheduler.log",
                            env=env)
    memory.watch("scheduler", scheduler.pid)
    workers = []
    for i in (1, 2):
        w = procs.start([str(bin_dir / "dask"), "worker", address, "--nworkers", "1",
                         "--nthreads", "1", "--no-dashboard", "--name", f"worker-{i}",
                         "--local-directory", str(work / f"worker-{i}")],
                        work / f"worker-{i}.log", env=env)
        memory.watch(f"worker-{i}", w.pid)
        workers.append(w)
    t0 = time.perf_counter()
    observer = Client(address, timeout="30s")
    observer.wait_for_workers(2, timeout=120)
    print(f"cluster up at {address}: 2 workers in {time.perf_counter() - t0:.1f} s",
          flush=True)
    by_name = {info["name"]: addr for addr, info in
               observer.scheduler_info(n_workers=-1)["workers"].items()}
    pids = observer.run(os.getpid)
    from reportgen.kinds import load_scene
    from reportgen.scene.config import read_config

    spec = load_scene(read_config(cfg)).sweep
    nblocks = -(-spec.size // spec.block_size(1024))
    summary["blocks"] = nblocks
    print(f"{args.members} members in {nblocks} blocks", flush=True)
    cluster_out, local_out = work / "cluster", work / "local"
    client_cmd = [str(bin_dir / "reportgen"), "run", str(cfg), "--scheduler", address,
                  "--out", str(cluster_out), "--time-limit", "0", "--format", args.format]

    # 1. the client, killed once a share of the blocks is on disk
    t0 = time.perf_counter()
    client = procs.start(client_cmd, work / "client-1.log", env=env)
    memory.watch("client (killed)", client.pid)
    target = max(1, int(args.kill_client_at * nblocks))
    while client.poll() is None and blocks_on_disk(cluster_out, scene) < target:
        time.sleep(0.05)
    if client.poll() is not None:
        print(f"client ended before the kill (exit {client.returncode})", file=sys.stderr)
        return 1
    streaming = vm_hwm(client.pid)
    procs.kill(client)
    killed_at = time.perf_counter() - t0
    on_disk = blocks_on_disk(cluster_out, scene)
    summary["client_kill"] = {"after_s": killed_at, "blocks_on_disk": on_disk,
                              "client_peak_mib": streaming}
    print(f"client SIGKILLed after {killed_at:.1f} s with {on_disk} of {nblocks} blocks on "
          f"disk (its peak memory {streaming:.0f} MiB)", flush=True)
    time.sleep(1.0)
    left = sum(len(v) for v in observer.processing().values())
    summary["client_kill"]["tasks_left_on_cluster_1s_later"] = left
    print(f"  1 s later the scheduler has {left} of its tasks processing", flush=True)

    # 2. resumed; one worker killed on the way
    t0 = time.perf_counter()
    client = procs.start(client_cmd, work / "client-2.log", env=env)
    memory.watch("client (resumed)", client.pid)
    target = max(on_disk + 1, int(args.kill_worker_at * nblocks))
    while client.poll() is None and blocks_on_disk(cluster_out, scene) < target:
        time.sleep(0.05)
    victim = by_name["worker-2"]
    held = observer.processing(workers=[victim]).get(victim, [])
    vpid = pids[victim]
    os.kill(vpid, signal.SIGKILL)  # the worker process, then its nanny: the worker is gone
    procs.kill(workers[1])
    worker_kill_s = time.perf_counter() - t0
    on_disk = blocks_on_disk(cluster_out, scene)
    summary["worker_kill"] = {"after_s": worker_kill_s, "blocks_on_disk": on_disk,
                              "tasks_on_it": [str(k) for k in held], "worker_pid": vpid}
    print(f"worker-2 (pid {vpid} and its nanny) SIGKILLed {worker_kill_s:.1f} s into the "
          f"resumed run, {on_disk} of {nblocks} blocks on disk; it held {len(held)} "
          f"tasks: {', '.join(str(k).split('-', 3)[-1] for k in held)}", flush=True)
    while client.poll() is None and blocks_on_disk(cluster_out, scene) < nblocks:
        time.sleep(0.05)
    streaming = vm_hwm(client.pid)  # before the family is read back from disk
    summary["client_peak_while_blocks_stream_mib"] = streaming
    print(f"all blocks on disk after {time.perf_counter() - t0:.1f} s; the client's peak "
          f"memory so far {streaming:.0f} MiB", flush=True)
    code = client.wait()
    resumed_wall = time.perf_counter() - t0
    procs.kill(client)
    after = observer.nthreads()
    summary["resumed_run"] = {"exit": code, "wall_s": resumed_wall,
                              "workers_after": len(after)}
    print(f"resumed client ended (exit {code}) after {resumed_wall:.1f} s; the cluster now "
          f"has {len(after)} worker(s)", flush=True)
    observer.close()
    if code != 0:
        print((work / "client-2.log").read_text()[-3000:], file=sys.stderr)
        return 1

    # 3. the same config here, no scheduler
    t0 = time.perf_counter()
    local = procs.start([str(bin_dir / "reportgen"), "run", str(cfg), "--out", str(local_out),
                         "--time-limit", "0", "--format", args.format],
                        work / "local.log", env=env)
    memory.watch("local run", local.pid)
    code = local.wait()
    local_wall = time.perf_counter() - t0
    procs.kill(local)
    summary["local_run"] = {"exit": code, "wall_s": local_wall}
    print(f"local run ended (exit {code}) after {local_wall:.1f} s", flush=True)
    if code != 0:
        return 1

    # 4. bit for bit
    a = sweep_arrays(cluster_out / scene / "run.h5")
    b = sweep_arrays(local_out / scene / "run.h5")
    names = sorted(k for k in a if k != "attrs")
    same = {k: (k in b and identical(a[k], b[k])) for k in names}
    statuses = dict(zip(*np.unique(a["status"], return_counts=True), strict=True))
    summary.update({
        "identical": same, "all_identical": all(same.values()) and set(names) == set(
            k for k in b if k != "attrs"),
        "status_counts": {str(k): int(v) for k, v in statuses.items()},
        "cluster_attrs": a["attrs"], "local_attrs": b["attrs"],
        "archive_mib": {"cluster": (cluster_out / scene / "run.h5").stat().st_size / 2**20,
                        "local": (local_out / scene / "run.h5").stat().st_size / 2**20},
        "gate": {w: json.loads((o / scene / "gate.json").read_text())
                 for w, o in (("cluster", cluster_out), ("local", local_out))}})
    ca, la = a["attrs"], b["attrs"]
    print(f"\nmembers {a['status'].size} (cluster) / {b['status'].size} (local); "
          f"status {summary['status_counts']}")
    print(f"bit-identical /sweep arrays: {summary['all_identical']} "
          f"({', '.join(f'{k} {v}' for k, v in same.items())})")
    print(f"cluster, resumed run: {ca['resumed']} members resumed from disk, "
          f"{args.members - ca['resumed']} run in {ca['members_wall_time_s']:.1f} s "
          f"({(args.members - ca['resumed']) / ca['members_wall_time_s']:.0f} members/s); "
          f"whole command {resumed_wall:.1f} s")
    print(f"local: {args.members} members in {la['members_wall_time_s']:.1f} s "
          f"({args.members / la['members_wall_time_s']:.0f} members/s); whole command "
          f"{local_wall:.1f} s")
    print(f"archives: {summary['archive_mib']['cluster']:.1f} MiB (cluster), "
          f"{summary['archive_mib']['local']:.1f} MiB (local); gate {summary['gate']}")
    return 0 if summary["all_identical"] else 1


if __name__ == "__main__":
    sys.exit(main())
