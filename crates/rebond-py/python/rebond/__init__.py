"""rebond: an impulse-based 3D rigid-body physics engine, from Python.

``World`` is one world, its state read and written as NumPy ``float32`` arrays; ``Batch`` holds
copies of a world stepped in parallel on every core with the GIL released. See docs/python.md.
"""

from ._rebond import (
    Batch,
    RayHit,
    SceneError,
    StateError,
    StepError,
    World,
    __version__,
    builtin_scenes,
)

__all__ = [
    "Batch",
    "RayHit",
    "SceneError",
    "StateError",
    "StepError",
    "World",
    "__version__",
    "builtin_scenes",
]
