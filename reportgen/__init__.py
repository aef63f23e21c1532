"""reportgen: config-driven simulator and report generator for classical mechanics."""

import os as _os

__version__ = "0.2.0"

# Our drivers loop over states of 2 to ~20 components through LLVM's loop vectorizer,
# which wraps every such loop in runtime alias and trip-count checks that cost more than
# the vector loop saves at these sizes: without it the shared DOP853 driver takes 1.1-1.5x
# fewer ns per evaluation (benchmarks/README.md, "Loop vectorization").  Set before numba
# reads its configuration (numba reloads it when a NUMBA_* variable changes, so this also
# holds if numba was imported first); a value the user set is kept.  DOP853 on a state of
# 10 or more components runs a twin compiled with the vectorizer on
# (reportgen.core.integrators.kernels.WIDE_STATE).
_os.environ.setdefault("NUMBA_LOOP_VECTORIZE", "0")
