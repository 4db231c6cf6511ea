"""sward from Python: render interactive ground vegetation to numpy arrays, drive it tick by tick, write and read
datasets. API reference: docs/python.md. Frames equal, bit for bit, the files sward-render writes for the same scene
and frame; errors raise sward.Error with the message the command-line tools print.

    import sward
    sim = sward.Simulator("examples/rover-pass.json", overrides={"render.resolution": [96, 64]})
    frame = sim.render()          # dict of numpy arrays: left, right, depth, disparity, semantic, instance, ...
    data = sward.Dataset("out")   # any dataset sward wrote; len(data), data[i] -> dict of numpy arrays
"""
import contextlib
import copy
import json
import math
import numbers
import operator
import os
import pathlib
import re
import sys

import numpy as np

from . import _sward
from ._sward import Error
from ._recorder import DriveAndRecord, Recorder

__all__ = ["__version__", "Error", "ArgumentError", "Simulator", "Recorder", "Dataset", "write_dataset",
           "SEMANTIC_CLASSES"]

__version__ = _sward.__version__  # CMakeLists.txt's project() version, as importlib.metadata.version("sward")


class ArgumentError(Error, ValueError):
    """An argument of the right type with a value out of range (step(-1), seed=-1, time=nan): a sward.Error, and a
    ValueError as Python's own functions raise for such values."""


class _Classes(dict):
    """SEMANTIC_CLASSES: a dict whose missing key names where a scene's own class names are."""

    def __missing__(self, key):
        raise KeyError(f"{key!r} is not one of sward's class names ({', '.join(map(repr, self))}); a scene's "
                       f"plant categories by their names ('grass', 'ferns', ...) are in Simulator.classes and "
                       f"Dataset.classes")


SEMANTIC_CLASSES = _Classes(_sward.SEMANTIC_CLASSES)  # class name -> pixel value of the semantic images


# Arguments are checked here, before _sward: a wrong type reaching pybind11 raises a TypeError that lists the C++
# signatures of the binding instead of naming the argument.

def _type_error(name, wanted, value):
    return TypeError(f"{name} must be {wanted}, not {type(value).__name__}")


def _integer(name, value, low, high):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise _type_error(name, "an integer", value)
    if not low <= value <= high:
        raise ArgumentError(f"{name} must be an integer in [{low}, {high}] (got {value})")
    return int(value)


def _number(name, value):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        raise _type_error(name, "a number", value)
    if not math.isfinite(value):
        raise ArgumentError(f"{name} must be a finite number (got {value})")
    return float(value)


# The C++ core's messages name the command-line options; from Python they name the arguments.
_ARGUMENT_WORDS = {"--frames": "frames", "--shard": "shard", "--overwrite": "overwrite=True", "--out": "out",
                   "--seed": "seed", "--time": "time", "--device": "device", "--allow-assets": "allow_assets",
                   "--no-vegetation": "vegetation=False", "--camera": "set_camera(position)",
                   "--look-at": "set_camera(look_at)", "--fov": "set_camera(fov)", "--samples": "render.samples",
                   "--resolution": "render.resolution"}


@contextlib.contextmanager
def _python_words():
    """Re-raises the core's sward.Error with its option names (--frames) as the Python arguments (frames)."""
    try:
        yield
    except Error as e:
        message = str(e)
        words = re.sub(r"--[a-z][a-z-]*", lambda m: _ARGUMENT_WORDS.get(m.group(0), m.group(0)), message)
        if words == message:
            raise
        raise type(e)(words) from None


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
                  validation=False, vegetation=True, time=0.0, allow_assets=(), progress=None):
    """Writes the dataset sward-render writes (docs/dataset-format.md): frames "A:B", shard "I/N", resume, etc.
    progress: True for a line on stderr, or a callable(rendered, total) called before each frame and at the end.
    Ctrl-C stops it within a frame (KeyboardInterrupt; the run removes the files it created, as on any failure)."""
    _write(_scene_input(scene, overrides, seed, allow_assets), _run_options(device, validation, vegetation, time),
           out, frames, shard, overwrite, progress)


def _progress_line(rendered, total):
    """progress=True: one line on stderr, rewritten in place, ended when the run is."""
    sys.stderr.write(f"\rsward: {rendered} of {total} frames rendered" + ("\n" if rendered == total else ""))
    sys.stderr.flush()


def _write(scene_input, run_options, out, frames, shard, overwrite, progress):
    arguments = (_path("out", out), _text("frames", frames, 'a str "A:B"', optional=True),
                 _text("shard", shard, 'a str "I/N"', optional=True), _flag("overwrite", overwrite))
    if progress is True:
        progress = _progress_line
    elif progress is not None and (progress is False or not callable(progress)):
        raise _type_error("progress", "None, True or a callable(rendered, total)", progress)
    with _python_words():
        _sward.write_dataset(*scene_input, *arguments, *run_options, progress)


def _scene_name(scene):
    if scene is None:
        return "the built-in scene"
    return "a scene dict" if isinstance(scene, dict) else repr(os.fspath(scene))


class Simulator(DriveAndRecord):
    """A scene on the GPU, driven tick by tick. Frame f shows the interaction after tick f, at f * time_step.
    close() (or a with block) releases the device at once; a closed Simulator raises sward.Error."""

    def __init__(self, scene=None, *, overrides=None, seed=None, device="", validation=False, vegetation=True,
                 time=0.0, allow_assets=()):
        self._session = None
        self._input = _scene_input(scene, overrides, seed, allow_assets)
        self._options = _run_options(device, validation, vegetation, time)
        self._name = _scene_name(scene)
        with _python_words():
            self._session = _sward.Session(*self._input, *self._options)

    def _live(self):
        if self._session is None:
            raise Error("this Simulator is closed")
        return self._session

    frame = property(lambda self: self._live().frame, doc="the frame render() shows next (= the next tick)")
    width = property(lambda self: self._live().width)
    height = property(lambda self: self._live().height)
    stereo = property(lambda self: self._live().stereo)
    object_count = property(lambda self: self._live().object_count)
    device_name = property(lambda self: self._live().device_name)
    validation_messages = property(lambda self: self._live().validation_messages)
    classes = property(lambda self: self._live().classes,
                       doc="class name -> semantic pixel value, with the scene's plant categories by name")
    closed = property(lambda self: self._session is None, doc="whether close() has released the simulator")

    def close(self):
        """Releases the device, the renderer and the simulation now (not at garbage collection). Idempotent."""
        self._session = None

    def __enter__(self):
        self._live()
        return self

    def __exit__(self, *exception):
        self.close()

    def __repr__(self):
        if self._session is None:
            return f"<sward.Simulator of {self._name}, closed>"
        s = self._session
        rig = "stereo" if s.stereo else "mono"
        return f"<sward.Simulator of {self._name}, {s.width}x{s.height} {rig}, frame {s.frame}, on {s.device_name!r}>"

    def step(self, ticks=1):
        """Runs `ticks` interaction ticks without rendering (Ctrl-C stops it within a tick)."""
        ticks = _integer("ticks", ticks, 0, 2**32 - 1)
        with _python_words():
            self._live().step(ticks)

    def render(self):
        """Renders the next frame (with its own tick) to a dict of numpy arrays and advances by one frame."""
        return self._live().render()

    def set_camera(self, position=None, look_at=None, fov=None):
        """A fixed camera from now on: world position and target [x, y, z] in metres, vertical fov in degrees."""
        session = self._live()
        with _python_words():
            session.set_camera(_point("position", position), _point("look_at", look_at),
                               None if fov is None else _number("fov", fov))

    def set_object_pose(self, index, position, heading_deg):
        """Object `index` of the scene stands at world [x, y] facing `heading_deg` (from +x towards +y)."""
        session = self._live()
        if position is None:
            raise _type_error("position", "a list of 2 numbers", position)
        x, y = _point("position", position, 2)
        session.set_object_pose(_integer("index", index, 0, 2**63 - 1), x, y, _number("heading_deg", heading_deg))

    def set_colliders(self, colliders):
        """Colliders of your own from the next tick on (replacing earlier ones): a list of dicts with "centre":
        [x, y, z] and the scene's collider keys (shape, kind, radius, force, length, half_extents, cut_height)."""
        session = self._live()
        if isinstance(colliders, (dict, str)) or not hasattr(colliders, "__iter__"):
            raise _type_error("colliders", "a list of dicts", colliders)
        session.set_colliders(_json("colliders", list(colliders)))

    def save_state(self, path):
        """Writes the interaction state (tick, every plant's dynamic record, the ruts) to `path`."""
        self._live().save_state(_path("path", path))

    def restore_state(self, path):
        """Continues from a state save_state wrote; `frame` becomes its tick."""
        self._live().restore_state(_path("path", path))

    def write_dataset(self, out, *, frames=None, shard=None, overwrite=False, progress=None):
        """The dataset of this simulator's scene and options, as sward-render writes it (a separate run)."""
        _write(self._input, self._options, out, frames, shard, overwrite, progress)


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
        if "tile" in points.dtype.names:  # a world of several tiles: instance ids count within a tile
            out["tile"] = points["tile"].copy()
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
        raise ArgumentError(f"{name} must be {size} numbers (got {len(values)})")
    return [_number(f"{name}[{k}]", v) for k, v in enumerate(values)]


def _int_dtype(value):
    """Dataset's int_dtype: None (the files' types), or int32 / int64 for every array of uint16 or uint32 values."""
    if value is None:
        return None
    try:
        dtype = np.dtype(value)
    except TypeError:
        raise _type_error("int_dtype", "None, 'int32' or 'int64'", value) from None
    if dtype not in (np.dtype(np.int32), np.dtype(np.int64)):
        raise ArgumentError(f"int_dtype must be None, 'int32' or 'int64' (got {dtype})")
    return dtype


def _signed(value, dtype):
    """The arrays of `value` (a dict, nested) with uint16 / uint32 values as `dtype` (all values fit int32)."""
    if isinstance(value, dict):
        return {k: _signed(v, dtype) for k, v in value.items()}
    if isinstance(value, np.ndarray) and value.dtype in (np.uint16, np.uint32):
        return value.astype(dtype)
    return value


class Dataset:
    """A dataset sward wrote, as a sequence of frames: len(), indexing (negative and numpy integers too), slicing
    (a Dataset of those frames) and iteration give dicts of numpy arrays, the same keys as Simulator.render() plus
    "disparity_pfm", "disparity_kitti" and "record" (the frame's frames.jsonl line); attributes info
    (dataset.json), manifest (manifest.json, {} for a shard or an unfinished run), calib (calib.txt as a dict,
    stereo), classes (class name -> semantic value, the scene's categories by name), records, frames. Usable as a
    PyTorch map-style dataset without sward depending on torch; int_dtype="int64" (or "int32") gives the uint16 and
    uint32 arrays (instance, tile, range ring / column / instance), which torch has no tensors of, as that type."""

    def __init__(self, path, *, int_dtype=None):
        self.root = pathlib.Path(_path("path", path))
        self.int_dtype = _int_dtype(int_dtype)
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
        classes = self.root / names["classes"]
        self.classes = _read_classes(classes) if classes.is_file() else dict(SEMANTIC_CLASSES)

    def __len__(self):
        return len(self.frames)

    def __iter__(self):
        return (self[i] for i in range(len(self.frames)))

    def __repr__(self):
        frames = f"frames {self.frames[0]}..{self.frames[-1]}" if self.frames else "no frames"
        return (f"<sward.Dataset {str(self.root)!r}: {len(self.frames)} of {frames}, "
                f"{'stereo' if self.stereo else 'mono'}>")

    def __getitem__(self, index):
        if isinstance(index, slice):
            view = copy.copy(self)
            view.frames = self.frames[index]
            return view
        if isinstance(index, (bool, np.bool_)):
            raise TypeError("Dataset indices are integers or slices, not bool")
        try:
            index = operator.index(index)  # int, numpy integers, 0-d integer arrays
        except TypeError:
            raise TypeError(f"Dataset indices are integers or slices, not {type(index).__name__}") from None
        if not -len(self.frames) <= index < len(self.frames):
            raise IndexError(f"frame index {index} out of range for a dataset of {len(self.frames)} frame(s)")
        item = self._item(self.frames[index])
        return item if self.int_dtype is None else _signed(item, self.int_dtype)

    def _item(self, frame):
        item = {"frame": frame}
        kinds = [("left", ".exr"), ("depth", ".exr"), ("semantic", ".png"), ("instance", ".exr"), ("preview", ".png")]
        if self.stereo:
            kinds += [("right", ".exr"), ("disparity", ".exr"), ("preview_right", ".png")]
        for kind, extension in kinds:
            item[kind] = _sward.read_image(self._file(kind, frame, extension))
        item["instance"] = item["instance"].astype("uint32")  # ids < 2^24: exact in the file's float32
        instance = self._file("instance", frame, ".exr")
        if "tile" in _sward.image_channels(instance):  # a world: ids count within the tile it names
            item["tile"] = _sward.read_image(instance, "tile").astype("uint32")
        # datasets written before normals and the right view's truth existed have none of these files
        for kind in ("normal", "normal_right", "depth_right", "disparity_right") if self.stereo else ("normal",):
            file = self._file(kind, frame, ".exr")
            if os.path.isfile(file):
                item[kind] = _sward.read_image(file)  # normals HxWx3 float32: camera-frame x, y, z
        for kind in ("depth", "depth_right", "disparity", "disparity_right"):
            if kind in item and item[kind].ndim == 3:  # one channel: HxW as render() gives it
                item[kind] = item[kind][..., 0]
        if self.stereo:
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


def _read_classes(path):
    """classes.json as Simulator.classes gives it: every class by its name, then each plant category by the scene's
    name for it ("scene_name") where that is not a class name already."""
    entries = _read_json(path).get("classes")
    if not isinstance(entries, list) or not all(isinstance(e, dict) and isinstance(e.get("name"), str) and
                                                isinstance(e.get("id"), int) for e in entries):
        raise Error(f"{path}: 'classes' must be a list of objects with a 'name' and an integer 'id'")
    classes = {e["name"]: e["id"] for e in entries}
    for e in entries:
        if isinstance(e.get("scene_name"), str) and e["scene_name"] not in classes:
            classes[e["scene_name"]] = e["id"]
    return classes
