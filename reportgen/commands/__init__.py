"""The command line (:mod:`.cli`) and the commands that are more than a stage: the
stability audit (:mod:`.audit`) and the benchmarks (:mod:`.bench`, :mod:`.bench_nbody`,
:mod:`.bench_pipeline`, :mod:`.bench_single`)."""

from pathlib import Path


def default_paths() -> list[str]:
    """The lecture pack's configs folder (here, else beside the package), as the PATH of a
    command given none; empty when there is none."""
    for candidate in (Path.cwd() / "configs", Path(__file__).resolve().parents[2] / "configs"):
        if candidate.is_dir():
            return [str(candidate)]
    return []

