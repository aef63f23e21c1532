"""What a config's archive will hold, against what its reader takes: limits that agree.

The validating reader (:mod:`reportgen.archive.check`) refuses an archive with a dataset
of more than ``MAX_DATASET_ELEMENTS`` numbers or more than ``MAX_TOTAL_ELEMENTS`` in all
(:mod:`reportgen.archive.limits`).
A config whose archive it would refuse is a config error, said before anything runs (a
sweep keeping 50 members of 10⁶ samples wrote a 1.1 GB archive its own reader refused),
from the config alone: no symbolic work, for it is checked before a time limit starts.

The estimate is an upper bound from the kind's declared results
(:meth:`~reportgen.scene.simulation.Simulation.budget_schema`) and the config: each stored run holds
``samples`` rows of its time, its state, a reference of each state column and its
invariants; a single run's ``/analysis`` arrays on the time axis add their rows; a sweep
keeps its ``store`` members' main runs and one entry per member of each swept value, its
status, message and member number (its members' results are counted as they come back,
:func:`reportgen.scene.sweep.block_fits`).  Kinds say what the schema cannot
(:meth:`~reportgen.scene.simulation.Simulation.stored_runs`,
:meth:`~reportgen.scene.simulation.Simulation.stored_columns`,
:meth:`~reportgen.scene.simulation.Simulation.dimension_size`).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from ..archive.limits import MAX_DATASET_ELEMENTS, MAX_TOTAL_ELEMENTS

#: a sweep's arrays of one entry per member besides its swept values: status, message,
#: and the dimension scale ``member``
FAMILY_ARRAYS = 3


@dataclass(frozen=True)
class ArchiveEstimate:
    """Numbers an archive will hold, at most (:func:`archive_estimate`).

    Attributes
    ----------
    runs : int
        In its stored runs: ``stored_runs`` × (``samples`` × ``row`` + ``columns``, the
        names of the state's components).
    analysis : int
        In ``/analysis`` arrays on the time axis.
    family : int
        In a sweep's per-member arrays (its members' results not counted).
    largest : int
        In its largest dataset (a run's ``y``, or a per-member array).
    stored_runs, samples, columns, row : int
        What ``runs`` is made of: runs kept, rows of each, state columns, numbers a row.
    """

    runs: int = 0
    analysis: int = 0
    family: int = 0
    largest: int = 0
    stored_runs: int = 0
    samples: int = 0
    columns: int = 0
    row: int = 0

    @property
    def total(self) -> int:
        return self.runs + self.analysis + self.family


def archive_estimate(scene: Any) -> ArchiveEstimate:
    """The numbers the archive of ``scene`` (a validated scene) will hold, at most."""
    spec = scene.sweep
    family = spec.size * (len(spec.axes) + FAMILY_ARRAYS) if spec is not None else 0
    run = getattr(scene.config, "run", None)
    schema = scene.budget_schema() if hasattr(scene, "budget_schema") else None
    if run is None or schema is None:
        return ArchiveEstimate(family=family, largest=spec.size if spec is not None else 0)
    samples, columns = run.samples, scene.stored_columns()
    row = 1 + 2 * columns + len(schema.invariants)  # t, y, reference, invariants
    analysis = 0
    if spec is None:
        stored = scene.stored_runs()
        for q in schema.analysis:
            if "t" in q.dims:
                others = 1
                for dim in q.dims:
                    if dim != "t":
                        size = scene.dimension_size(dim)
                        others *= size if size is not None else max(columns, 1)
                analysis += samples * others
    else:  # a family keeps its members' main runs; its /analysis is not on their time
        stored = len(spec.stored_members())
    largest = max(samples * columns, spec.size if spec is not None else 0)
    return ArchiveEstimate(runs=stored * (samples * row + columns), analysis=analysis,
                           family=family, largest=largest, stored_runs=stored, samples=samples,
                           columns=columns, row=row)


def archive_problems(scene: Any) -> list[str]:
    """One line naming the config, the key, the rule and the value if the archive of
    ``scene`` would hold more than its reader takes, else nothing."""
    e = archive_estimate(scene)
    label, spec = scene.source.label, scene.sweep
    if e.samples * e.columns > MAX_DATASET_ELEMENTS:
        return [f"{label}: key 'run.samples': {e.samples} samples × {e.columns} state columns "
                f"= {e.samples * e.columns:.3g} numbers in one run, more than the "
                f"{MAX_DATASET_ELEMENTS:.0e} the archive's reader takes in one dataset; at "
                f"most {MAX_DATASET_ELEMENTS // e.columns} samples (got {e.samples})"]
    if e.total <= MAX_TOTAL_ELEMENTS:
        return []
    if spec is not None and e.runs >= e.family:
        return [f"{label}: key 'sweep.store': {e.stored_runs} stored runs × {e.samples} "
                f"samples × {e.row} numbers a sample = {e.runs:.3g} numbers, more than the "
                f"{MAX_TOTAL_ELEMENTS:.0e} the archive's reader takes in all; keep fewer "
                f"members whole or lower run.samples (got {spec.store})"]
    if spec is not None:
        return [f"{label}: key 'sweep': {spec.size} members × {len(spec.axes) + FAMILY_ARRAYS} "
                f"arrays = {e.family:.3g} numbers, more than the {MAX_TOTAL_ELEMENTS:.0e} the "
                f"archive's reader takes in all (got {spec.size} members)"]
    per_sample = e.stored_runs * e.row + e.analysis // max(e.samples, 1)
    return [f"{label}: key 'run.samples': {e.stored_runs} runs × {e.samples} samples × "
            f"{e.row} numbers a sample, and {e.analysis:.3g} in arrays on the time axis = "
            f"{e.total:.3g} numbers, more than the {MAX_TOTAL_ELEMENTS:.0e} the archive's "
            f"reader takes in all; at most {MAX_TOTAL_ELEMENTS // per_sample} samples "
            f"(got {e.samples})"]
