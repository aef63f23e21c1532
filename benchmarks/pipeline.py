"""The edit loop, measured whole (see :mod:`reportgen.commands.bench_pipeline`; also
``reportgen bench --pipeline``).

Run from the repository root::

    .venv/bin/python benchmarks/pipeline.py [--scene pendulum_small] [--configs configs]
        [--previous DIR]   # DIR: a checkout of an earlier release, e.g. git worktree add
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from reportgen.commands.bench_pipeline import REPO, measure  # noqa: E402


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--configs", default=str(REPO / "configs"))
    parser.add_argument("--scene", default="pendulum_small",
                        help="the scene edited in the title and physics rows")
    parser.add_argument("--previous", default=None,
                        help="a source checkout of an earlier release, measured alongside")
    args = parser.parse_args()
    measure(Path(args.configs), args.scene, Path(args.previous) if args.previous else None)
    return 0


if __name__ == "__main__":
    sys.exit(main())
