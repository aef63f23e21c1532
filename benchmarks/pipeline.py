"""The edit loop, measured whole (see :mod:`reportgen.bench_pipeline`; also
``reportgen bench --pipeline``).

Run from the repository root::

    .venv/bin/python benchmarks/pipeline.py [--scene pendulum_small] [--configs configs]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from reportgen.bench_pipeline import REPO, measure  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--configs", default=str(REPO / "configs"))
    parser.add_argument("--scene", default="pendulum_small",
                        help="the scene edited in the title and physics rows")
    args = parser.parse_args()
    measure(Path(args.configs), args.scene)
    return 0


if __name__ == "__main__":
    sys.exit(main())
