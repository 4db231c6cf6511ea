"""sward from Python: render interactive ground vegetation to numpy arrays, drive it tick by tick, write and read
datasets. API reference: docs/python.md. Frames equal, bit for bit, the files sward-render writes for the same scene
and frame; errors raise sward.Error with the message the command-line tools print.

    import sward
    sim = sward.Simulator("examples/rover-pass.json", overrides={"render.resolution": [96, 64]})
    frame = sim.render()          # dict of numpy arrays: left, right, depth, disparity, semantic, instance, ...
    data = sward.Dataset("out")   # any dataset sward wrote; len(data), data[i] -> dict of numpy arrays
"""
import json
import os
import pathlib

import numpy as np

from . import _sward
from ._sward import Error, SEMANTIC_CLASSES

__all__ = ["Error", "Simulator", "Dataset", "write_dataset", "SEMANTIC_CLASSES"]


def _scene_input(scene, overrides, seed, allow_assets):
    """The (path, text, overrides, seed, allow_assets) a scene given as a file, a dict or None (built-in) becomes."""
    if scene is None:
        path, text = "", None
    elif isinstance(scene, dict):
        path, text = "", json.dumps(scene, allow_nan=False)
    elif isinstance(scene, (str, os.PathLike)):
        path, text = os.fspath(scene), None
    else:
        raise TypeError("scene must be a file path, a dict or None (the built-in scene)")
    if overrides is not None and not isinstance(overrides, dict):
        raise TypeError('overrides must be a dict of dotted keys, e.g. {"render.samples": 1}')
    return path, text, json.dumps(overrides or {}, allow_nan=False), seed, [os.fspath(a) for a in allow_assets]


def write_dataset(scene, out, *, overrides=None, frames=None, shard=None, seed=None, overwrite=False, device="",
                  validation=False, vegetation=True, time=0.0, allow_assets=()):
    """Writes the dataset sward-render writes (docs/dataset-format.md): frames "A:B", shard "I/N", resume, etc."""
    _sward.write_dataset(*_scene_input(scene, overrides, seed, allow_assets), os.fspath(out), frames, shard,
                         overwrite, device, validation, vegetation, float(time))


class Simulator:
    """A scene on the GPU, driven tick by tick. Frame f shows the interaction after tick f, at f * time_step."""

    def __init__(self, scene=None, *, overrides=None, seed=None, device="", validation=False, vegetation=True,
                 time=0.0, allow_assets=()):
        self._input = _scene_input(scene, overrides, seed, allow_assets)
        self._options = dict(device=device, validation=validation, vegetation=vegetation, time=float(time))
        self._session = _sward.Session(*self._input, device, validation, vegetation, float(time))

    frame = property(lambda self: self._session.frame, doc="the frame render() shows next (= the next tick)")
    width = property(lambda self: self._session.width)
    height = property(lambda self: self._session.height)
    stereo = property(lambda self: self._session.stereo)
    object_count = property(lambda self: self._session.object_count)
    device_name = property(lambda self: self._session.device_name)
    validation_messages = property(lambda self: self._session.validation_messages)

    def step(self, ticks=1):
        """Runs `ticks` interaction ticks without rendering."""
        self._session.step(int(ticks))

    def render(self):
        """Renders the next frame (with its own tick) to a dict of numpy arrays and advances by one frame."""
        return self._session.render()

    def set_camera(self, position=None, look_at=None, fov=None):
        """A fixed camera from now on: world position and target [x, y, z] in metres, vertical fov in degrees."""
        self._session.set_camera(_point(position), _point(look_at), None if fov is None else float(fov))

    def set_object_pose(self, index, position, heading_deg):
        """Object `index` of the scene stands at world [x, y] facing `heading_deg` (from +x towards +y)."""
        x, y = (float(v) for v in position)
        self._session.set_object_pose(int(index), x, y, float(heading_deg))

    def set_colliders(self, colliders):
        """Colliders of your own from the next tick on (replacing earlier ones): a list of dicts with "centre":
        [x, y, z] and the scene's collider keys (shape, kind, radius, force, length, half_extents, cut_height)."""
        self._session.set_colliders(json.dumps(list(colliders), allow_nan=False))

    def save_state(self, path):
        self._session.save_state(os.fspath(path))

    def restore_state(self, path):
        self._session.restore_state(os.fspath(path))

    def write_dataset(self, out, *, frames=None, shard=None, overwrite=False):
        """The dataset of this simulator's scene and options, as sward-render writes it (a separate run)."""
        path, text, overrides, seed, allow = self._input
        _sward.write_dataset(path, text, overrides, seed, allow, os.fspath(out), frames, shard, overwrite,
                             self._options["device"], self._options["validation"], self._options["vegetation"],
                             self._options["time"])


_PLY_TYPES = {"float": "<f4", "double": "<f8", "uchar": "u1", "ushort": "<u2", "uint": "<u4"}


def _read_range(root, name, frame):
    """Range sensor `name`'s files of one frame as Simulator.render()["range"] gives them (docs/python.md)."""
    def file(extension):
        return root / _sward.frame_file(_sward.NAMES["range"] + "/" + name, frame, extension)
    out = {}
    ply = file(".ply")
    if ply.is_file():
        data = ply.read_bytes()
        end = data.index(b"end_header\n") + len(b"end_header\n")
        fields = [(words[2], _PLY_TYPES[words[1]]) for words in (line.split() for line in data[:end].decode().splitlines())
                  if words and words[0] == "property"]
        points = np.frombuffer(data[end:], dtype=np.dtype(fields))
        out["xyz"] = np.stack([points["x"], points["y"], points["z"]], axis=1)
        out["world"] = np.stack([points["wx"], points["wy"], points["wz"]], axis=1)
        for key in ("intensity", "time", "ring", "column", "class", "instance"):
            out[key] = points[key].copy()
    scan = file(".json")
    if scan.is_file():
        ranges = json.loads(scan.read_text())["ranges"]
        out["ranges"] = np.array([np.nan if r is None else r for r in ranges], dtype=np.float32)
    depth = file(".exr")
    if depth.is_file():
        out["depth"] = _sward.read_image(str(depth), "Y")
    return out


def _point(value):
    return None if value is None else [float(v) for v in value]


class Dataset:
    """A dataset sward wrote, as a sequence of frames: len(), indexing (negative too) and iteration give dicts of
    numpy arrays, the same keys as Simulator.render() plus "disparity_pfm", "disparity_kitti" and "record" (the
    frame's frames.jsonl line); attributes info (dataset.json), manifest (manifest.json, {} for a shard or an
    unfinished run), calib (calib.txt as a dict, stereo), records, frames. Usable as a PyTorch map-style dataset
    without sward depending on torch."""

    def __init__(self, path):
        self.root = pathlib.Path(path)
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
            for line in log.read_text().splitlines():
                record = json.loads(line)
                self.records[record["frame"]] = record
        info = self.root / names["dataset"]
        self.info = json.loads(info.read_text()) if info.is_file() else {}
        manifest = self.root / names["manifest"]
        self.manifest = json.loads(manifest.read_text()) if manifest.is_file() else {}
        calib = self.root / names["calib"]
        self.calib = _sward.read_calib(str(calib)) if calib.is_file() else None

    def __len__(self):
        return len(self.frames)

    def __getitem__(self, index):
        if not isinstance(index, int):
            raise TypeError("Dataset indices are integers")
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
