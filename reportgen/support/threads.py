"""One BLAS thread per reportgen process.

reportgen's parallelism is processes (``--jobs``, the PDF worker, Dask workers), and its
linear algebra is small (3 × 3 rotations, a molecule's Hessian, the 96-point Chebyshev
fits of the time-ordered exponential).  A BLAS that starts its own threads on such sizes
only waits on them, worst when the other cores are busy with our other processes: one
96 × 96 least-squares fit (``numpy.polynomial.chebyshev.chebfit``) took 129 ms with
OpenBLAS's default two threads beside a busy second core and 1.9 ms with one.  So every
reportgen process runs its BLAS on one thread, as Dask's workers do
(``distributed.nanny.pre-spawn-environ`` sets the same variables to 1).

The command line sets the variables before numpy is loaded (a user's own setting wins);
the Python API, running in the caller's process, limits BLAS to one thread for the call
only (:func:`one_blas_thread`, through threadpoolctl) and gives the caller's setting back.
"""

from __future__ import annotations

import contextlib
import os
from collections.abc import Iterator

#: the thread-count variables of the BLAS libraries numpy and scipy are built with
#: (OpenBLAS, MKL, BLIS, Apple's Accelerate)
BLAS_THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "BLIS_NUM_THREADS",
                         "VECLIB_MAXIMUM_THREADS")


def one_blas_thread_by_default() -> None:
    """Ask for one BLAS thread in this process (if numpy is not loaded yet) and in every
    process it starts, unless the user set a count."""
    for name in BLAS_THREAD_VARIABLES:
        os.environ.setdefault(name, "1")


@contextlib.contextmanager
def one_blas_thread() -> Iterator[None]:
    """BLAS on one thread inside the block, in this process and the processes it forks;
    the previous counts are restored after it."""
    import numpy  # noqa: F401 - threadpoolctl limits the libraries already loaded
    from threadpoolctl import threadpool_limits

    with threadpool_limits(limits=1, user_api="blas"):
        yield
