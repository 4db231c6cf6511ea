# Type stubs of the sward package (PEP 561: py.typed beside them), for mypy --strict and editors. They describe
# python/sward/__init__.py and docs/python.md; keep the three together.
import os
import pathlib
from types import TracebackType
from typing import Any, Callable, Dict, Iterable, Iterator, List, Mapping, Optional, Sequence, Union, overload

import numpy as np
import numpy.typing as npt

__version__: str

__all__ = [
    "__version__", "Error", "ArgumentError", "Simulator", "Recorder", "Dataset", "write_dataset", "SEMANTIC_CLASSES",
]

# A scene: a file path, a dict in the scene format, or None (the built-in scene).
_Scene = Union[str, "os.PathLike[str]", Mapping[str, Any], None]
_Path = Union[str, "os.PathLike[str]"]
_Point = Sequence[float]
# write_dataset's progress: True (a line on stderr) or a callable(rendered, total).
_Progress = Union[None, bool, Callable[[int, int], object]]
# A frame: render()'s dict, and a Dataset item (its keys plus disparity_pfm, disparity_kitti, record). Values are
# numpy arrays but "frame" (int), "auto_exposure" (dict of floats), "range" (sensor name -> dict of arrays) and
# "record" (frames.jsonl's line).
Frame = Dict[str, Any]

class Error(RuntimeError):
    """Every failure of sward: the message the command-line tools print after '<tool>: error: '."""

class ArgumentError(Error, ValueError):
    """An argument of the right type with a value out of range: a sward.Error and a ValueError."""

SEMANTIC_CLASSES: Dict[str, int]

def write_dataset(
    scene: _Scene,
    out: _Path,
    *,
    overrides: Optional[Mapping[str, Any]] = None,
    frames: Optional[str] = None,
    shard: Optional[str] = None,
    seed: Optional[int] = None,
    overwrite: bool = False,
    device: str = "",
    validation: bool = False,
    vegetation: bool = True,
    time: float = 0.0,
    allow_assets: Iterable[_Path] = (),
    progress: _Progress = None,
) -> None: ...

class Simulator:
    def __init__(
        self,
        scene: _Scene = None,
        *,
        overrides: Optional[Mapping[str, Any]] = None,
        seed: Optional[int] = None,
        device: str = "",
        validation: bool = False,
        vegetation: bool = True,
        time: float = 0.0,
        allow_assets: Iterable[_Path] = (),
    ) -> None: ...
    @property
    def frame(self) -> int: ...
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def stereo(self) -> bool: ...
    @property
    def object_count(self) -> int: ...
    @property
    def device_name(self) -> str: ...
    @property
    def validation_messages(self) -> int: ...
    @property
    def classes(self) -> Dict[str, int]: ...
    @property
    def closed(self) -> bool: ...
    def close(self) -> None: ...
    def __enter__(self) -> "Simulator": ...
    def __exit__(
        self,
        exc_type: Optional[type],
        exc: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> None: ...
    def step(self, ticks: int = 1) -> None: ...
    def render(self) -> Frame: ...
    def set_camera(
        self, position: Optional[_Point] = None, look_at: Optional[_Point] = None, fov: Optional[float] = None
    ) -> None: ...
    def set_object_pose(self, index: int, position: _Point, heading_deg: float) -> None: ...
    def set_colliders(self, colliders: Iterable[Mapping[str, Any]]) -> None: ...
    def save_state(self, path: _Path) -> None: ...
    def restore_state(self, path: _Path) -> None: ...
    def write_dataset(
        self,
        out: _Path,
        *,
        frames: Optional[str] = None,
        shard: Optional[str] = None,
        overwrite: bool = False,
        progress: _Progress = None,
    ) -> None: ...
    # Drive, then record (python/sward/_recorder.py)
    def record(self, out: _Path, *, overwrite: bool = False) -> "Recorder": ...
    def drive(
        self, vehicle: int = 0, *, throttle: float = 0.0, steer: float = 0.0, brake: float = 0.0
    ) -> Dict[str, Any]: ...
    def set_wind(self, **keys: Any) -> None: ...
    def set_sun(self, **keys: Any) -> None: ...
    def set_sky(self, **keys: Any) -> None: ...
    def reset(self, *, seed: Optional[int] = None, overrides: Optional[Mapping[str, Any]] = None) -> None: ...

class Recorder:
    out: str
    def __init__(self, sim: Simulator, out: _Path, *, overwrite: bool = False) -> None: ...
    @property
    def frames(self) -> List[int]: ...
    @property
    def closed(self) -> bool: ...
    def close(self) -> None: ...
    def __enter__(self) -> "Recorder": ...
    def __exit__(
        self,
        exc_type: Optional[type],
        exc: Optional[BaseException],
        traceback: Optional[TracebackType],
    ) -> bool: ...

class Dataset:
    root: pathlib.Path
    frames: List[int]
    stereo: bool
    records: Dict[int, Dict[str, Any]]
    info: Dict[str, Any]
    manifest: Dict[str, Any]
    calib: Optional[Dict[str, Any]]
    classes: Dict[str, int]
    int_dtype: Optional[np.dtype[Any]]
    def __init__(self, path: _Path, *, int_dtype: Union[None, str, npt.DTypeLike] = None) -> None: ...
    def __len__(self) -> int: ...
    @overload
    def __getitem__(self, index: int) -> Frame: ...
    @overload
    def __getitem__(self, index: np.integer[Any]) -> Frame: ...
    @overload
    def __getitem__(self, index: slice) -> "Dataset": ...
    def __iter__(self) -> Iterator[Frame]: ...
