"""Scene kinds, registered in one place: ``KINDS`` maps a config's ``kind`` to its class.

Adding a kind = one module here + one prose template ``templates/kinds/<kind>.html.j2``
+ one config in ``configs/``, and one line below.
"""

from __future__ import annotations

from ..config import ConfigError, SourceConfig
from .base import Scene
from .central_force import CentralForceScene
from .fput import FputScene
from .heavy_top import HeavyTopScene
from .inertia import InertiaScene
from .normal_modes import NormalModesScene
from .oscillator import OscillatorScene
from .pendulum import PendulumScene
from .rigid_body import RigidBodyScene
from .three_body import ThreeBodyScene
from .two_center import TwoCenterScene

KINDS: dict[str, type[Scene]] = {
    cls.kind: cls
    for cls in (
        PendulumScene,
        OscillatorScene,
        CentralForceScene,
        ThreeBodyScene,
        TwoCenterScene,
        RigidBodyScene,
        HeavyTopScene,
        NormalModesScene,
        FputScene,
        InertiaScene,
    )
}


def get_kind(kind: str) -> type[Scene]:
    return KINDS[kind]


def load_scene(source: SourceConfig) -> Scene:
    """Validate a parsed config into its scene object; ConfigError names every problem."""
    kind = source.data.get("kind")
    if kind is None:
        raise ConfigError([f"{source.label}: key 'kind': required key is missing "
                           f"(one of: {', '.join(KINDS)})"])
    if not isinstance(kind, str) or kind not in KINDS:
        raise ConfigError([f"{source.label}: key 'kind': must be one of "
                           f"{', '.join(KINDS)} (got {kind!r})"])
    return KINDS[kind].from_source(source)
