"""One BLAS thread per reportgen process (reportgen.support.threads): the command sets it
before numpy loads, unless the user set a count; the API limits it for the call only."""

from __future__ import annotations

import json
import os
import subprocess
import sys

from reportgen.support.threads import BLAS_THREAD_VARIABLES

PROBE = """
import json, sys
from reportgen.support.threads import one_blas_thread, one_blas_thread_by_default
if sys.argv[1] == "command":
    one_blas_thread_by_default()
import numpy
from threadpoolctl import threadpool_info
def counts():
    return [i["num_threads"] for i in threadpool_info() if i["user_api"] == "blas"]
before = counts()
with one_blas_thread():
    inside = counts()
print(json.dumps({"before": before, "inside": inside, "after": counts()}))
"""


def _probe(mode: str, **env: str) -> dict:
    clean = {k: v for k, v in os.environ.items() if k not in BLAS_THREAD_VARIABLES
             and k != "OMP_NUM_THREADS"}
    proc = subprocess.run([sys.executable, "-c", PROBE, mode], capture_output=True, text=True,
                          env={**clean, **env}, timeout=120, check=True)
    return json.loads(proc.stdout)


def test_the_command_runs_blas_on_one_thread_unless_the_user_says_otherwise():
    assert _probe("command")["before"] == [1]
    two = min(2, os.cpu_count() or 1)  # a BLAS starts no more threads than cores
    assert _probe("command", OPENBLAS_NUM_THREADS="2", MKL_NUM_THREADS="2")["before"] == [two]


def test_the_api_limits_blas_for_the_call_and_gives_the_callers_count_back():
    found = _probe("api", OPENBLAS_NUM_THREADS="2", MKL_NUM_THREADS="2")
    two = [min(2, os.cpu_count() or 1)]
    assert found == {"before": two, "inside": [1], "after": two}


def test_console_main_asks_for_one_thread_before_it_runs_anything():
    from reportgen.commands import cli

    source = cli.console_main.__code__.co_names
    assert source.index("one_blas_thread_by_default") < source.index("main")
