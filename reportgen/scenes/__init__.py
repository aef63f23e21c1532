"""Scene kinds, found by being here: every module of this package that defines a
:class:`~reportgen.scenes.base.Scene` subclass with a ``kind`` is a kind.

Adding a kind = one module here + one prose template ``templates/kinds/<kind>.html.j2``
+ one config in ``configs/``.  Nothing else is edited: ``KINDS``, ``reportgen kinds``
and the docs discover it.
"""

from __future__ import annotations

import importlib
import pkgutil

from ..config import ConfigError, SourceConfig
from .base import REGISTRY, Scene

#: modules of this package that are not kinds
_NOT_KINDS = {"base", "catalogue"}


def _discover() -> dict[str, type[Scene]]:
    for info in pkgutil.iter_modules(__path__):
        if info.name not in _NOT_KINDS and not info.name.startswith("_"):
            importlib.import_module(f"{__name__}.{info.name}")
    return dict(sorted(REGISTRY.items(), key=lambda item: (item[1].order, item[0])))


KINDS: dict[str, type[Scene]] = _discover()


def get_kind(kind: str) -> type[Scene]:
    return REGISTRY[kind]


def load_scene(source: SourceConfig) -> Scene:
    """Validate a parsed config into its scene object; ConfigError names every problem."""
    kind = source.data.get("kind")
    if kind is None:
        raise ConfigError([f"{source.label}: key 'kind': required key is missing "
                           f"(one of: {', '.join(KINDS)})"])
    if not isinstance(kind, str) or kind not in REGISTRY:
        raise ConfigError([f"{source.label}: key 'kind': must be one of "
                           f"{', '.join(KINDS)} (got {kind!r})"])
    return REGISTRY[kind].from_source(source)
