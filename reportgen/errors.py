"""The errors the command line turns into exit status 2, importable without the heavy
modules (so ``reportgen run`` can start work before it imports pydantic or h5py)."""

from __future__ import annotations


class ConfigError(Exception):
    """One or more problems in a scene configuration (exit status 2)."""

    def __init__(self, problems: list[str]):
        self.problems = problems
        super().__init__("\n".join(problems))


class UsageError(Exception):
    """Bad command-line usage (exit status 2)."""


class ReportError(Exception):
    """A report cannot be rendered from this archive (exit status 2)."""
