"""Scene kinds, found by being here: every package ``reportgen/kinds/<kind>/`` whose
``__init__`` defines a :class:`~reportgen.scene.base.Scene` subclass with a ``kind`` is a
kind.

A kind's package holds its config schema and presets (``config.py``), its declared
results (``results.py``), its simulation (``simulation.py``), its report (``report.py``),
its plots and its prose template (``template.html.j2``).  Adding a kind = one new folder
here and one config in ``configs/``; ``reportgen kinds``, ``validate``, ``run`` and the
docs discover it.  Shared machinery never names a kind.
"""

from __future__ import annotations

import importlib
import pkgutil

from ..scene.base import REGISTRY, Scene
from ..scene.budget import archive_problems
from ..scene.config import ConfigError, SourceConfig, did_you_mean


def _discover() -> dict[str, type[Scene]]:
    for info in pkgutil.iter_modules(__path__):
        if info.ispkg and not info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{info.name}")
    return dict(sorted(REGISTRY.items(), key=lambda item: (item[1].order, item[0])))


KINDS: dict[str, type[Scene]] = _discover()


def get_kind(kind: str) -> type[Scene]:
    return REGISTRY[kind]


def load_scene(source: SourceConfig) -> Scene:
    """Validate a parsed config into its scene object; ConfigError names every problem,
    an archive larger than its reader takes included
    (:func:`reportgen.scene.budget.archive_problems`)."""
    kind = source.data.get("kind")
    if kind is None:
        raise ConfigError([f"{source.label}: key 'kind': required key is missing "
                           f"(one of: {', '.join(KINDS)})"])
    if not isinstance(kind, str) or kind not in REGISTRY:
        raise ConfigError([f"{source.label}: key 'kind': must be one of {', '.join(KINDS)}"
                           f"{did_you_mean(kind, KINDS)} (got {kind!r})"])
    scene = REGISTRY[kind].from_source(source)
    problems = archive_problems(scene)
    if problems:
        raise ConfigError(problems)
    return scene


class _KindsPackage(type(importlib)):
    """This package, callable: ``reportgen.kinds()`` is the Python API's listing
    (:func:`reportgen.api.kinds`), which the package's name shadows once imported.
    Imported on call by a computed name: the API imports this package, not the other way
    round, and no kind's code stamp follows it (see reportgen/__init__.py)."""

    def __call__(self) -> list[dict]:
        return importlib.import_module(f"{__name__.rpartition('.')[0]}.api").kinds()


importlib.import_module(__name__).__class__ = _KindsPackage
