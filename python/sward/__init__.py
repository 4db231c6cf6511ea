"""sward from Python: render interactive ground vegetation to numpy arrays, drive it tick by tick, write and read
datasets. API reference: docs/python.md. Frames equal, bit for bit, the files sward-render writes for the same scene
and frame; errors raise sward.Error with the message the command-line tools print.

    import sward
    sim = sward.Simulator("examples/rover-pass.json", overrides={"render.resolution": [96, 64]})
    frame = sim.render()          # dict of numpy arrays: left, right, depth, disparity, semantic, instance, ...
    data = sward.Dataset("out")   # any dataset sward wrote; len(data), data[i] -> dict of numpy arrays
"""
import json
import math
import numbers
import os
import pathlib

import numpy as np

from . import _sward
from ._sward import Error, SEMANTIC_CLASSES

__all__ = ["Error", "Simulator", "Dataset", "write_dataset", "SEMANTIC_CLASSES"]


# Arguments are checked here, before _sward: a wrong type reaching pybind11 raises a TypeError that lists the C++
# signatures of the binding instead of naming the argument.

def _type_error(name, wanted, value):
    return TypeError(f"{name} must be {wanted}, not {type(value).__name__}")


def _integer(name, value, low, high):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise _type_error(name, "an integer", value)
    if not low <= value <= high:
        raise Error(f"{name} must be an integer in [{low}, {high}] (got {value})")
    return int(value)


def _number(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise _type_error(name, "a number", value)
    if not math.isfinite(value):
        raise Error(f"{name} must be a finite number (got {value})")
    return float(value)


def _flag(name, value):
    if not isinstance(value, (bool, np.bool_)):
        raise _type_error(name, "True or False", value)
    return bool(value)


def _text(name, value, wanted, optional=False):
    if (value is None and optional) or isinstance(value, str):
        return value
    raise _type_error(name, wanted, value)


def _path(name, value):
    if not isinstance(value, (str, os.PathLike)):
        raise _type_error(name, "a file or folder path (str or os.PathLike)", value)
    return os.fspath(value)


def _plain(value):
    """numpy scalars and arrays as the Python numbers and lists JSON holds (json.dumps's `default`)."""
    if isinstance(value, (np.generic, np.ndarray)):
        return value.tolist()
    raise TypeError(f"a {type(value).__name__} is not a JSON value")


def _json(name, value):
    """`value` as JSON text: NaN and infinities (which JSON cannot hold) and non-JSON values named."""
    try:
        return json.dumps(value, allow_nan=False, default=_plain)
    except ValueError as e:  # json's "Out of range float values" or "Circular reference detected"
        what = "a number that is not finite (NaN or infinity)" if "float" in str(e) else "a reference to itself"
        raise Error(f"{name} holds {what}, which JSON cannot hold") from None
    except TypeError as e:
        raise TypeError(f"{name}: {e}") from None


def _scene_input(scene, overrides, seed, allow_assets):
    """The (path, text, overrides, seed, allow_assets) a scene given as a file, a dict or None (built-in) becomes."""
    if scene is None:
        path, text = "", None
    elif isinstance(scene, dict):
        path, text = "", _json("scene", scene)
    elif isinstance(scene, (str, os.PathLike)):
        path, text = os.fspath(scene), None
    else:
        raise TypeError("scene must be a file path, a dict or None (the built-in scene)")
    if overrides is not None and not isinstance(overrides, dict):
        raise TypeError('overrides must be a dict of dotted keys, e.g. {"render.samples": 1}')
    if seed is not None:
        seed = _integer("seed", seed, 0, 2**64 - 1)
    if isinstance(allow_assets, (str, bytes, os.PathLike)):  # one folder would be iterated letter by letter
        raise _type_error("allow_assets", "a list of folders", allow_assets)
    folders = [_path("allow_assets[]", a) for a in allow_assets]
    return path, text, _json("overrides", overrides or {}), seed, folders


def _run_options(device, validation, vegetation, time):
    """The checked (device, validation, vegetation, time) of a Simulator or write_dataset."""
    return (_text("device", device, "a device name or index as a str"), _flag("validation", validation),
            _flag("vegetation", vegetation), _number("time", time))


def write_dataset(scene, out, *, overrides=None, frames=None, shard=None, seed=None, overwrite=False, device="",
                  validation=False, vegetation=True, time=0.0, allow_assets=()):
    """Writes the dataset sward-render writes (docs/dataset-format.md): frames "A:B", shard "I/N", resume, etc."""
    _sward.write_dataset(*_scene_input(scene, overrides, seed, allow_assets), _path("out", out),
                         _text("frames", frames, 'a str "A:B"', optional=True),
                         _text("shard", shard, 'a str "I/N"', optional=True), _flag("overwrite", overwrite),
                         *_run_options(device, validation, vegetation, time))


class Simulator:
    """A scene on the GPU, driven tick by tick. Frame f shows the interaction after tick f, at f * time_step."""

    def __init__(self, scene=None, *, overrides=None, seed=None, device="", validation=False, vegetation=True,
                 time=0.0, allow_assets=()):
        self._input = _scene_input(scene, overrides, seed, allow_assets)
        self._options = _run_options(device, validation, vegetation, time)
        self._session = _sward.Session(*self._input, *self._options)

    frame = property(lambda self: self._session.frame, doc="the frame render() shows next (= the next tick)")
    width = property(lambda self: self._session.width)
    height = property(lambda self: self._session.height)
    stereo = property(lambda self: self._session.stereo)
    object_count = property(lambda self: self._session.object_count)
    device_name = property(lambda self: self._session.device_name)
    validation_messages = property(lambda self: self._session.validation_messages)

    def step(self, ticks=1):
        """Runs `ticks` interaction ticks without rendering."""
        self._session.step(_integer("ticks", ticks, 0, 2**32 - 1))

    def render(self):
        """Renders the next frame (with its own tick) to a dict of numpy arrays and advances by one frame."""
        return self._session.render()

    def set_camera(self, position=None, look_at=None, fov=None):
        """A fixed camera from now on: world position and target [x, y, z] in metres, vertical fov in degrees."""
        self._session.set_camera(_point("position", position), _point("look_at", look_at),
                                 None if fov is None else _number("fov", fov))

    def set_object_pose(self, index, position, heading_deg):
        """Object `index` of the scene stands at world [x, y] facing `heading_deg` (from +x towards +y)."""
        if position is None:
            raise _type_error("position", "a list of 2 numbers", position)
        x, y = _point("position", position, 2)
        self._session.set_object_pose(_integer("index", index, 0, 2**63 - 1), x, y, _number("heading_deg", heading_deg))

    def set_colliders(self, colliders):
        """Colliders of your own from the next tick on (replacing earlier ones): a list of dicts with "centre":
        [x, y, z] and the scene's collider keys (shape, kind, radius, force, length, half_extents, cut_height)."""
        if isinstance(colliders, (dict, str)) or not hasattr(colliders, "__iter__"):
            raise _type_error("colliders", "a list of dicts", colliders)
        self._session.set_colliders(_json("colliders", list(colliders)))

    def save_state(self, path):
        self._session.save_state(_path("path", path))

    def restore_state(self, path):
        self._session.restore_state(_path("path", path))

    def write_dataset(self, out, *, frames=None, shard=None, overwrite=False):
        """The dataset of this simulator's scene and options, as sward-render writes it (a separate run)."""
        path, text, overrides, seed, allow = self._input
        _sward.write_dataset(path, text, overrides, seed, allow, _path("out", out),
                             _text("frames", frames, 'a str "A:B"', optional=True),
                             _text("shard", shard, 'a str "I/N"', optional=True), _flag("overwrite", overwrite),
                             *self._options)


_PLY_TYPES = {"float": "<f4", "double": "<f8", "uchar": "u1", "ushort": "<u2", "uint": "<u4"}


# A broken file of a dataset raises sward.Error naming the file and what is wrong with it, never the JSON
# decoder's, numpy's or a dict's own exception (docs/python.md, "Errors and threads").

def _read_json(path, kind=dict):
    """The JSON document of `path`, which must be a `kind`."""
    try:
        document = json.loads(path.read_bytes())
    except OSError as e:
        raise Error(f"{path}: cannot read the file ({e.strerror})") from None
    except UnicodeDecodeError:
        raise Error(f"{path}: not UTF-8 text") from None
    except json.JSONDecodeError as e:
        raise Error(f"{path}: not valid JSON ({e.msg}, line {e.lineno}, column {e.colno})") from None
    if not isinstance(document, kind):
        raise Error(f"{path}: must hold a JSON {'object' if kind is dict else 'array'}")
    return document


def _read_records(path):
    """frames.jsonl: frame number -> its record (one JSON object a line, each with a non-negative "frame")."""
    records = {}
    try:
        lines = path.read_bytes().decode().splitlines()
    except OSError as e:
        raise Error(f"{path}: cannot read the file ({e.strerror})") from None
    except UnicodeDecodeError:
        raise Error(f"{path}: not UTF-8 text") from None
    for number, line in enumerate(lines, 1):
        try:
            record = json.loads(line)
        except json.JSONDecodeError as e:
            raise Error(f"{path} line {number}: not valid JSON ({e.msg}, column {e.colno})") from None
        frame = record.get("frame") if isinstance(record, dict) else None
        if isinstance(frame, bool) or not isinstance(frame, int) or frame < 0:
            raise Error(f"{path} line {number}: not a frame record (a JSON object with a non-negative integer "
                        f"'frame')")
        records[frame] = record
    return records


def _read_ply(path):
    """The point columns of a range sensor's binary PLY as sward writes it (range/range_files.h)."""
    data = path.read_bytes()
    end = data.find(b"end_header\n")
    if not data.startswith(b"ply\n") or end < 0:
        raise Error(f"{path}: not a PLY file (no 'ply' ... 'end_header' header)")
    end += len(b"end_header\n")
    try:
        lines = data[:end].decode("ascii").splitlines()
        fields = [(words[2], _PLY_TYPES[words[1]]) for words in (line.split() for line in lines)
                  if words and words[0] == "property"]
        dtype = np.dtype(fields)
    except (UnicodeDecodeError, IndexError, KeyError, ValueError, TypeError):
        raise Error(f"{path}: its header is not one sward writes (properties of {', '.join(_PLY_TYPES)})") from None
    missing = [n for n in ("x", "y", "z", "wx", "wy", "wz", *_PLY_COLUMNS) if n not in dtype.names]
    if missing:
        raise Error(f"{path}: has no property {missing[0]}")
    if (len(data) - end) % dtype.itemsize:
        raise Error(f"{path}: {len(data) - end} bytes of points are not whole points of {dtype.itemsize} bytes")
    return np.frombuffer(data[end:], dtype=dtype)


_PLY_COLUMNS = ("intensity", "time", "ring", "column", "class", "instance")


def _read_range(root, name, frame):
    """Range sensor `name`'s files of one frame as Simulator.render()["range"] gives them (docs/python.md)."""
    def file(extension):
        return root / _sward.frame_file(_sward.NAMES["range"] + "/" + name, frame, extension)
    out = {}
    ply = file(".ply")
    if ply.is_file():
        points = _read_ply(ply)
        out["xyz"] = np.stack([points["x"], points["y"], points["z"]], axis=1)
        out["world"] = np.stack([points["wx"], points["wy"], points["wz"]], axis=1)
        for key in _PLY_COLUMNS:
            out[key] = points[key].copy()
    scan = file(".json")
    if scan.is_file():
        ranges = _read_json(scan).get("ranges")
        if not isinstance(ranges, list) or not all(r is None or isinstance(r, (int, float)) for r in ranges):
            raise Error(f"{scan}: 'ranges' must be a list of numbers and nulls")
        out["ranges"] = np.array([np.nan if r is None else r for r in ranges], dtype=np.float32)
    depth = file(".exr")
    if depth.is_file():
        out["depth"] = _sward.read_image(str(depth), "Y")
    return out


def _point(name, value, size=3):
    """[x, y, z] (or [x, y]) of numbers as floats; None stays None."""
    if value is None:
        return None
    try:
        values = list(value)
    except TypeError:
        raise _type_error(name, f"a list of {size} numbers", value) from None
    if len(values) != size:
        raise Error(f"{name} must be {size} numbers (got {len(values)})")
    return [_number(f"{name}[{k}]", v) for k, v in enumerate(values)]


class Dataset:
    """A dataset sward wrote, as a sequence of frames: len(), indexing (negative too) and iteration give dicts of
    numpy arrays, the same keys as Simulator.render() plus "disparity_pfm", "disparity_kitti" and "record" (the
    frame's frames.jsonl line); attributes info (dataset.json), manifest (manifest.json, {} for a shard or an
    unfinished run), calib (calib.txt as a dict, stereo), records, frames. Usable as a PyTorch map-style dataset
    without sward depending on torch."""

    def __init__(self, path):
        self.root = pathlib.Path(_path("path", path))
        names = _sward.NAMES
        left = self.root / names["left"]
        if not left.is_dir():
            raise Error(f"{self.root}: not a sward dataset (no {names['left']}/ folder)")
        stems = (_sward.frame_number(p.stem) for p in left.iterdir() if p.suffix == ".exr")
        self.frames = sorted(f for f in stems if f is not None)
        self.stereo = (self.root / names["right"]).is_dir()
        self.records = {}
        log = self.root / names["frame_log"]
        if log.is_file():
            self.records = _read_records(log)
        info = self.root / names["dataset"]
        self.info = _read_json(info) if info.is_file() else {}
        manifest = self.root / names["manifest"]
        self.manifest = _read_json(manifest) if manifest.is_file() else {}
        calib = self.root / names["calib"]
        self.calib = _sward.read_calib(str(calib)) if calib.is_file() else None

    def __len__(self):
        return len(self.frames)

    def __getitem__(self, index):
        if isinstance(index, bool) or not isinstance(index, numbers.Integral):
            raise TypeError(f"Dataset indices are integers, not {type(index).__name__}")
        index = int(index)
        if not -len(self.frames) <= index < len(self.frames):
            raise IndexError(f"frame index {index} out of range for a dataset of {len(self.frames)} frame(s)")
        frame = self.frames[index]
        item = {"frame": frame}
        kinds = [("left", ".exr"), ("depth", ".exr"), ("semantic", ".png"), ("instance", ".exr"), ("preview", ".png")]
        if self.stereo:
            kinds += [("right", ".exr"), ("disparity", ".exr"), ("preview_right", ".png")]
        for kind, extension in kinds:
            item[kind] = _sward.read_image(self._file(kind, frame, extension))
        item["depth"] = item["depth"][..., 0] if item["depth"].ndim == 3 else item["depth"]
        item["instance"] = item["instance"].astype("uint32")  # ids < 2^24: exact in the file's float32
        instance = self._file("instance", frame, ".exr")
        if "tile" in _sward.image_channels(instance):  # a world: ids count within the tile it names
            item["tile"] = _sward.read_image(instance, "tile").astype("uint32")
        for kind in ("normal", "normal_right") if self.stereo else ("normal",):
            normal = self._file(kind, frame, ".exr")
            if os.path.isfile(normal):  # datasets written before normals existed have none
                item[kind] = _sward.read_image(normal)  # HxWx3 float32: camera-frame x, y, z
        if self.stereo:
            item["disparity"] = item["disparity"]
            item["disparity_pfm"] = _sward.read_disparity(self._file("disparity", frame, ".pfm"))
            item["disparity_kitti"] = _sward.read_disparity(self._file("disparity", frame, ".png"))
        if frame in self.records:
            item["record"] = self.records[frame]
        range_root = self.root / _sward.NAMES["range"]
        if range_root.is_dir():
            item["range"] = {sensor.name: _read_range(self.root, sensor.name, frame)
                             for sensor in sorted(range_root.iterdir()) if sensor.is_dir()}
        return item

    def _file(self, kind, frame, extension):
        return str(self.root / _sward.frame_file(_sward.NAMES[kind], frame, extension))
