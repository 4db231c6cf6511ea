"""The Python module (docs/python.md) against sward-render: frames bitwise equal to the CLI's files, the Dataset
reader on every file kind, a collider moved from Python leaving a track, save / restore, bad input raising the
CLI's message. Run by CTest (Python.Module) with PYTHONPATH=build/python, SWARD_RENDER and SWARD_TEST_SCENE."""
import json
import os
import pathlib
import _thread
import ast
import subprocess
import threading
import time

import numpy as np
import pytest

import sward

RENDER = os.environ["SWARD_RENDER"]
# The GPU test scene, small: a stereo rig, a rover driving through the grass (tracks from tick 0).
SMALL = {"render.resolution": [96, 64], "render.samples": 1, "sequence.frames": 3}
KINDS = ["left", "right", "depth", "disparity", "semantic", "instance", "normal", "normal_right", "preview",
         "preview_right", "depth_right", "disparity_right"]


def scene_with(tmp, changes):
    document = json.loads(pathlib.Path(os.environ["SWARD_TEST_SCENE"]).read_text())
    for dotted, value in changes.items():
        node = document
        *parents, last = dotted.split(".")
        for part in parents:
            node = node.setdefault(part, {})
        node[last] = value
    path = tmp / "scene.json"
    path.write_text(json.dumps(document))
    return path


def bitwise_equal(a, b):
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.fixture(scope="module")
def cli_dataset(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("cli")
    scene = scene_with(tmp, SMALL)
    subprocess.run([RENDER, str(scene), "--out", str(tmp / "out"), "--quiet"], check=True, capture_output=True)
    return scene, sward.Dataset(tmp / "out")


def test_frames_equal_the_cli_files_bitwise(cli_dataset):
    scene, data = cli_dataset
    assert len(data) == 3 and data.stereo
    sim = sward.Simulator(scene)
    for index in range(len(data)):
        frame, files = sim.render(), data[index]
        assert frame["frame"] == files["frame"] == index
        for kind in KINDS:
            assert bitwise_equal(frame[kind], files[kind]), f"frame {index}: {kind}"
        assert frame["left"].dtype == np.float32 and frame["left"].shape == (64, 96, 4)
        for depth, normal in ((frame["depth"], frame["normal"]), (frame["depth_right"], frame["normal_right"])):
            hit = np.isfinite(depth)  # unit where a surface is seen, 0 for the sky
            assert np.abs(np.linalg.norm(normal[hit], axis=-1) - 1).max() < 1e-5 and not normal[~hit].any()
    assert sim.validation_messages == 0


def test_dataset_reader_reads_every_file_kind(cli_dataset):
    _, data = cli_dataset
    item = data[-1]
    assert item["frame"] == 2 and item["record"]["frame"] == 2
    assert bitwise_equal(item["disparity_pfm"], item["disparity"])  # PFM: float32 as written, 0 = no value
    assert np.abs(item["disparity_kitti"] - item["disparity"]).max() <= 1 / 256  # KITTI: 1/256 pixel steps
    assert item["semantic"].dtype == np.uint8 and item["instance"].dtype == np.uint32
    assert item["preview"].shape == (64, 96, 3) and item["preview"].dtype == np.uint8
    normal, hit = item["normal"], np.isfinite(item["depth"])
    assert normal.shape == (64, 96, 3) and normal.dtype == np.float32
    assert np.abs(np.linalg.norm(normal[hit], axis=-1) - 1).max() < 1e-5 and not normal[~hit].any()
    assert data.calib["width"] == 96 and data.info["fingerprint"]["resolution"] == "96x64"
    assert set(data.manifest["files"]) >= {"left/000002.exr", "disparity/000002.pfm", "frames.jsonl", "calib.txt"}
    with pytest.raises(IndexError):
        data[3]


def test_torch_data_loader_batches_a_dataset_with_int_dtype(cli_dataset):
    """Debian's torch 1.13 (python3-torch; skipped without it) refuses uint32 arrays: int_dtype="int64" batches."""
    torch = pytest.importorskip("torch")
    _, data = cli_dataset
    with pytest.raises(TypeError, match="uint32"):
        next(iter(torch.utils.data.DataLoader(data, batch_size=3)))
    batch = next(iter(torch.utils.data.DataLoader(sward.Dataset(data.root, int_dtype="int64"), batch_size=3)))
    assert batch["instance"].dtype == torch.int64 and tuple(batch["instance"].shape) == (3, 64, 96)
    assert (batch["instance"][2].numpy() == data[2]["instance"]).all() and batch["frame"].tolist() == [0, 1, 2]


def stub_names(tree):
    """The names a stub module (ast) defines: {name: set of member names} for classes, None for the rest."""
    names = {}
    for node in tree.body:
        if isinstance(node, ast.ClassDef):
            names[node.name] = {n.name for n in node.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))}
            names[node.name] |= {n.target.id for n in node.body if isinstance(n, ast.AnnAssign)}
        elif isinstance(node, ast.FunctionDef):
            names[node.name] = None
        elif isinstance(node, (ast.AnnAssign, ast.Assign)):
            for target in [node.target] if isinstance(node, ast.AnnAssign) else node.targets:
                names[target.id] = None
    return names


def test_the_type_stubs_name_every_public_name():
    """python/sward/__init__.pyi (what mypy and editors read instead of the code) has every name of __all__ and every
    public member of the public classes: an API added without its stub fails here, naming it."""
    tree = ast.parse((pathlib.Path(sward.__file__).parent / "__init__.pyi").read_text())
    stubs = stub_names(tree)
    stub_all = next(ast.literal_eval(n.value) for n in tree.body if isinstance(n, ast.Assign)
                    and n.targets[0].id == "__all__")
    assert sorted(stub_all) == sorted(sward.__all__)  # `from sward import *` the same with and without the stubs
    for name in sward.__all__:
        assert name in stubs, f"sward.{name} has no stub in python/sward/__init__.pyi"
        value = getattr(sward, name)
        if isinstance(value, type) and not issubclass(value, BaseException):
            public = {m for m in dir(value) if not m.startswith("_")} | {"__init__"}
            missing = public - stubs[name]
            assert not missing, f"sward.{name}'s {sorted(missing)} have no stub in python/sward/__init__.pyi"


def test_a_dataset_slices_takes_numpy_indices_and_names_its_classes(cli_dataset):
    _, data = cli_dataset
    part = data[1:]
    assert isinstance(part, sward.Dataset) and part.frames == [1, 2] and len(data) == 3
    assert [item["frame"] for item in part] == [1, 2] and data[::2].frames == [0, 2]
    assert bitwise_equal(data[np.int64(2)]["left"], part[np.int32(-1)]["left"])
    assert repr(data).endswith(": 3 of frames 0..2, stereo>")
    # PyTorch has no uint16 / uint32 tensors: int_dtype gives int64 (or int32) arrays of the same values
    signed = sward.Dataset(data.root, int_dtype="int64")[0]
    assert signed["instance"].dtype == np.int64 and (signed["instance"] == data[0]["instance"]).all()
    assert bitwise_equal(signed["left"], data[0]["left"])
    # the scene's plant categories by name, as the simulator gives them
    assert data.classes["grass"] == sward.SEMANTIC_CLASSES["vegetation category 1"]
    assert data.classes["felled"] == sward.SEMANTIC_CLASSES["felled"]
    with pytest.raises(KeyError, match="Simulator.classes and Dataset.classes"):
        sward.SEMANTIC_CLASSES["grass"]
    with pytest.raises(TypeError, match="integers or slices, not float"):
        data[1.0]
    with pytest.raises(sward.ArgumentError, match=r"int_dtype must be None, 'int32' or 'int64' \(got uint8\)"):
        sward.Dataset(data.root, int_dtype=np.uint8)


def test_write_dataset_from_python_equals_the_cli(cli_dataset, tmp_path):
    scene, _ = cli_dataset
    calls = []
    sward.write_dataset(scene, tmp_path / "py", frames="1:3", progress=lambda *done: calls.append(done))
    assert calls == [(0, 2), (1, 2), (2, 2)]  # before each frame renders, then when all are written
    cli = json.loads((scene.parent / "out" / "manifest.json").read_text())["files"]
    ours = json.loads((tmp_path / "py" / "manifest.json").read_text())["files"]
    assert ours and all(cli[name] == digest for name, digest in ours.items())


def test_a_step_and_a_render_show_what_the_cli_shows(cli_dataset):
    scene, data = cli_dataset
    with sward.Simulator(scene) as sim:
        assert sim.classes["grass"] == data.classes["grass"] and sim.classes["felled"] == data.classes["felled"]
        sim.step(2)
        assert sim.frame == 2 and repr(sim).startswith(f"<sward.Simulator of {str(scene)!r}, 96x64 stereo, frame 2")
        assert bitwise_equal(sim.render()["left"], data[2]["left"])
    assert sim.closed and repr(sim).endswith("closed>")
    with pytest.raises(sward.Error, match="^this Simulator is closed$"):
        sim.render()
    sim.close()  # again: nothing


def test_ctrl_c_stops_a_long_step_and_write_dataset_within_a_frame(cli_dataset, tmp_path):
    """KeyboardInterrupt within a tick of step() and a frame of write_dataset, not after the whole call."""
    scene, _ = cli_dataset
    sim = sward.Simulator(scene)
    for call in (lambda: sim.step(10**6),
                 lambda: sward.write_dataset(scene, tmp_path / "out", overrides={"sequence.frames": 1000})):
        timer = threading.Timer(1.0, _thread.interrupt_main)
        start = time.monotonic()
        timer.start()
        with pytest.raises(KeyboardInterrupt):
            call()
        timer.join()
        assert time.monotonic() - start < 20
    assert 0 < sim.frame < 10**6
    assert not (tmp_path / "out").exists()  # an interrupted run removes what it created, as on any failure


def test_a_collider_moved_from_python_leaves_a_track(tmp_path):
    sim = sward.Simulator(scene_with(tmp_path, {**SMALL, "vehicles": []}))
    sim.set_camera(position=[50, 46, 7], look_at=[50, 51, 0])  # looking down on the box's way
    felled = sward.SEMANTIC_CLASSES["felled"]
    assert not (sim.render()["semantic"] == felled).any()
    for x in np.linspace(48, 52, 6):  # a heavy box dragged across the view, reaching through the ground
        sim.set_colliders([{"shape": "box", "centre": [float(x), 51.0, 0.0], "half_extents": [0.5, 0.5, 6.0],
                            "force": 5.0}])
        sim.render()
    sim.set_colliders([])
    sim.step(3)  # gone, and the plants it felled stay down
    assert (sim.render()["semantic"] == felled).sum() > 0


def test_save_and_restore_continue_bitwise(tmp_path):
    sim = sward.Simulator(scene_with(tmp_path, SMALL))
    sim.step(1)
    sim.save_state(tmp_path / "state.bin")
    first = sim.render()
    sim.render()
    sim.restore_state(tmp_path / "state.bin")
    assert sim.frame == 1
    again = sim.render()
    assert all(bitwise_equal(first[k], again[k]) for k in KINDS)


def test_a_world_dataset_names_the_tile_of_each_plant_pixel(cli_dataset, tmp_path):
    # Two tiles of the world side by side in view: x = 100 m is their border.
    scene = scene_with(tmp_path, {**SMALL, "sequence.frames": 1, "world": {"tiles": [2, 2]},
                                  "camera.position": [97, 46, 0], "camera.look_at": [104, 52, 0]})
    subprocess.run([RENDER, str(scene), "--out", str(tmp_path / "out"), "--quiet"], check=True, capture_output=True)
    item = sward.Dataset(tmp_path / "out")[0]
    frame = sward.Simulator(scene).render()
    assert bitwise_equal(item["tile"], frame["tile"].astype("uint32"))
    assert {1, 2} <= set(np.unique(item["tile"]).tolist())  # tile index + 1: (0, 0) and (1, 0)
    assert "tile" not in cli_dataset[1][0]  # one tile: no tile channel


def test_a_world_state_of_another_seed_is_refused_at_restore(tmp_path):
    """At restore_state, naming both seeds: not at the render where a tile of the file first becomes resident."""
    scene = scene_with(tmp_path, {**SMALL, "sequence.frames": 1, "world": {"tiles": [2, 2]}})
    sim = sward.Simulator(scene, seed=5)
    sim.step(1)
    sim.save_state(tmp_path / "world.state")
    with pytest.raises(sward.Error, match=r"world.state: the world state was saved from a world of seed 5; "
                                          r"this scene's seed is 6$"):
        sward.Simulator(scene, seed=6).restore_state(tmp_path / "world.state")
    sward.Simulator(scene, seed=5).restore_state(tmp_path / "world.state")


def test_set_camera_and_a_scene_dict(tmp_path):
    document = json.loads(scene_with(tmp_path, SMALL).read_text())
    sim = sward.Simulator(document, overrides={"vehicles": []})
    before = sim.render()["depth"]
    sim.set_camera(position=[50, 40, 8], look_at=[50, 50, 0])
    assert not bitwise_equal(before, sim.render()["depth"])


def test_an_object_posed_from_python_moves_in_the_image(tmp_path):
    rover = str(pathlib.Path(os.environ["SWARD_TEST_SCENE"]).parents[2] / "examples/assets/rover.gltf")
    document = json.loads(scene_with(tmp_path, SMALL).read_text())
    document.update(vehicles=[], objects=[{"model": rover, "path": {"points": [[50, 51]]}}])
    sim = sward.Simulator(document)
    sim.set_camera(position=[50, 46, 4], look_at=[50, 51, 0])
    object_id = 16_000_000  # instance id of object 0 (docs/dataset-format.md)

    def columns():
        return np.nonzero((sim.render()["instance"] == object_id).any(axis=0))[0]

    before = columns()
    sim.set_object_pose(0, [48.5, 51], heading_deg=90)
    after = columns()
    assert before.size and after.size and after.mean() < before.mean()  # moved to -x: left in the image
    with pytest.raises(sward.Error, match="no object 1"):
        sim.set_object_pose(1, [0, 0], 0)


def test_rendering_releases_the_gil(tmp_path):
    sim = sward.Simulator(scene_with(tmp_path, SMALL))
    ticks, done = [0], threading.Event()

    def render():
        sim.render()
        done.set()

    worker = threading.Thread(target=render)
    worker.start()
    while not done.is_set():  # this thread keeps running while the other renders
        ticks[0] += 1
        time.sleep(0.001)
    worker.join()
    assert ticks[0] > 10


def test_bad_input_raises_the_cli_message(tmp_path):
    scene = scene_with(tmp_path, {"render.samples": 3})
    cli = subprocess.run([RENDER, str(scene), "--out", str(tmp_path / "out")], capture_output=True, text=True)
    assert cli.returncode == 1
    message = cli.stderr.strip().removeprefix("sward-render: error: ")
    with pytest.raises(sward.Error) as error:
        sward.Simulator(scene)
    assert str(error.value) == message
    with pytest.raises(sward.Error, match="not an object"):
        sward.Simulator(scene_with(tmp_path, SMALL), overrides={"render.samples.x": 1})
    with pytest.raises(sward.Error, match="centre"):
        sward.Simulator(scene_with(tmp_path, SMALL)).set_colliders([{"radius": 1}])
    with pytest.raises(sward.Error, match="not a sward dataset"):
        sward.Dataset(tmp_path)


def test_a_million_colliders_are_parsed_in_linear_time_then_refused_by_count(tmp_path):
    # Python's set_colliders goes through the same JSON reader as a scene file: 10^6 colliders gave no answer in 120 s
    # (a quadratic step of the parser's callback); now parsed in about 1.5 s, then refused by their count. CPU time,
    # with a wide margin: a shared machine's load must not fail it, a quadratic parser still would.
    sim = sward.Simulator(scene_with(tmp_path, SMALL))
    colliders = [{"shape": "sphere", "centre": [float(i % 100), 0.0, 0.0], "radius": 0.5} for i in range(10**6)]
    start = time.process_time()
    with pytest.raises(sward.Error, match=r"at most 10000 colliders \(got 1000000\)"):
        sim.set_colliders(colliders)
    assert time.process_time() - start < 30


@pytest.mark.parametrize("name, text, message", [
    ("frames.jsonl", '{"frame": 0}\n{"frame": 1', r"frames.jsonl line 2: not valid JSON"),
    ("frames.jsonl", '{"frame": 0}\n{"time": 1}\n', r"frames.jsonl line 2: not a frame record"),
    ("frames.jsonl", '[0]\n', r"frames.jsonl line 1: not a frame record"),
    ("frames.jsonl", b"\xff\xfe", r"frames.jsonl: not UTF-8 text"),
    ("dataset.json", "{", r"dataset.json: not valid JSON \(Expecting property name"),
    ("dataset.json", "[]", r"dataset.json: must hold a JSON object"),
    ("manifest.json", '{"files": ', r"manifest.json: not valid JSON"),
])
def test_a_broken_dataset_file_raises_sward_error_naming_it(tmp_path, name, text, message):
    """Not the JSON decoder's JSONDecodeError, a KeyError or a UnicodeDecodeError (ValueError) of the file's text."""
    (tmp_path / "left").mkdir()
    (tmp_path / name).write_bytes(text if isinstance(text, bytes) else text.encode())
    with pytest.raises(sward.Error, match=message) as error:
        sward.Dataset(tmp_path)
    assert str(tmp_path / name) in str(error.value)


def test_a_broken_range_file_raises_sward_error_naming_it(tmp_path):
    (tmp_path / "left").mkdir()
    (tmp_path / "left" / "000000.exr").write_bytes(b"")
    sensor = tmp_path / "range" / "lidar"
    sensor.mkdir(parents=True)
    data = sward.Dataset(tmp_path)
    for name, text, message in [("000000.ply", b"ply\nformat binary_little_endian 1.0\n", r"not a PLY file"),
                                ("000000.ply", b"ply\nproperty quad x\nend_header\n", r"header is not one sward"),
                                ("000000.json", b"{ranges", r"000000.json: not valid JSON"),
                                ("000000.json", b'{"ranges": 3}', r"'ranges' must be a list")]:
        for old in sensor.iterdir():
            old.unlink()
        (sensor / name).write_bytes(text)
        with pytest.raises(sward.Error, match=message):
            sward._read_range(tmp_path, "lidar", 0)
    with pytest.raises(TypeError, match="not str"):
        data["0"]


@pytest.mark.parametrize("call, message", [
    (lambda scene: sward.Simulator(scene, seed="5"), r"^seed must be an integer, not str$"),
    (lambda scene: sward.Simulator(scene, validation="yes"), r"^validation must be True or False, not str$"),
    (lambda scene: sward.Simulator(scene, device=0), r"^device must be a device name or index as a str, not int$"),
    (lambda scene: sward.Simulator(scene, time="later"), r"^time must be a number, not str$"),
    (lambda scene: sward.Simulator(scene, allow_assets="assets"), r"^allow_assets must be a list of folders"),
    (lambda scene: sward.write_dataset(scene, "out", frames=5), r'^frames must be a str "A:B", not int$'),
    (lambda scene: sward.write_dataset(scene, 7), r"^out must be a file or folder path"),
    (lambda scene: sward.write_dataset(scene, "out", progress=1), r"^progress must be None, True or a callable"),
    (lambda scene: sward.Dataset(None), r"^path must be a file or folder path"),
])
def test_a_wrong_argument_type_raises_a_type_error_naming_the_argument(tmp_path, call, message):
    """Not pybind11's "incompatible function arguments" with the C++ signatures of the binding."""
    with pytest.raises(TypeError, match=message) as error:
        call(scene_with(tmp_path, SMALL))
    assert "arg0" not in str(error.value) and "->" not in str(error.value)


def test_an_argument_out_of_range_raises_sward_error_naming_it(tmp_path):
    """A sward.ArgumentError: a sward.Error and Python's ValueError. The core's messages name the arguments, not the
    command-line options."""
    with pytest.raises(ValueError, match=r"^seed must be an integer in \[0, 18446744073709551615\] \(got -1\)$"):
        sward.Simulator(scene_with(tmp_path, SMALL), seed=-1)
    with pytest.raises(sward.Error, match=r"^time must be a finite number \(got nan\)$"):
        sward.write_dataset(scene_with(tmp_path, SMALL), tmp_path / "out", time=float("nan"))
    with pytest.raises(sward.Error, match=r"^frames 0:9 goes past the scene's sequence of 3 frame\(s\)") as error:
        sward.write_dataset(scene_with(tmp_path, SMALL), tmp_path / "out", frames="0:9")
    (tmp_path / "other" / "left").mkdir(parents=True)
    (tmp_path / "other" / "left" / "000000.exr").write_bytes(b"")  # files of a dataset, no dataset.json
    with pytest.raises(sward.Error, match=r"overwrite=True to start over or choose another out\b") as error:
        sward.write_dataset(scene_with(tmp_path, SMALL), tmp_path / "other")
    assert "--" not in str(error.value)


def test_numpy_values_pass_and_nan_is_named(tmp_path):
    """numpy numbers in a scene dict or overrides are numbers (json.dumps alone refuses them); NaN names its argument."""
    document = json.loads(scene_with(tmp_path, SMALL).read_text())
    document["render"]["resolution"] = np.array([40, 30])
    sim = sward.Simulator(document, overrides={"render.samples": np.int64(1)})
    assert (sim.width, sim.height) == (40, 30)
    with pytest.raises(sward.Error, match=r"^overrides holds a number that is not finite \(NaN or infinity\)"):
        sward.Simulator(document, overrides={"camera.fov_y_deg": float("nan")})
    with pytest.raises(TypeError, match=r"^scene: a set is not a JSON value$"):
        sward.Simulator({"render": {1, 2}})
    with pytest.raises(TypeError, match=r"^colliders must be a list of dicts, not dict$"):
        sim.set_colliders({"centre": [0, 0, 0]})


def test_a_wrong_argument_of_a_simulator_method_names_the_argument(tmp_path):
    sim = sward.Simulator(scene_with(tmp_path, SMALL))
    with pytest.raises(ValueError, match=r"^ticks must be an integer in \[0, 4294967295\] \(got -1\)$"):
        sim.step(-1)
    with pytest.raises(TypeError, match=r"^ticks must be an integer, not float$"):
        sim.step(2.5)  # never truncated to 2
    with pytest.raises(sward.Error, match=r"^index must be an integer in"):
        sim.set_object_pose(-1, [0, 0], 0)
    with pytest.raises(TypeError, match=r"^position\[1\] must be a number, not str$"):
        sim.set_camera(position=[1, "2", 3])
    with pytest.raises(sward.Error, match=r"^look_at must be 3 numbers \(got 2\)$"):
        sim.set_camera(look_at=[1, 2])
    with pytest.raises(TypeError, match=r"^path must be a file or folder path"):
        sim.save_state(None)


def test_range_sensors_equal_the_cli_files_bitwise(tmp_path):
    """A LiDAR, a laser scanner and a ToF camera: the arrays render() returns are the files sward-render writes."""
    sensors = [{"name": "lidar", "preset": "VLP-16", "angle_step_deg": 2.0,
                "mount": {"position": [53.5, 46.0, 0.0], "height_above_ground": 2.2, "yaw_deg": 120.0}},
               {"name": "scan", "preset": "LMS111", "mount": {"position": [52.0, 47.0, 0.0], "height_above_ground": 0.3}},
               {"name": "tof", "preset": "AzureKinect-NFOV", "resolution": [32, 24],
                "mount": {"position": [53.5, 46.0, 0.0], "height_above_ground": 1.5, "pitch_deg": 30.0}}]
    scene = scene_with(tmp_path, {**SMALL, "range_sensors": sensors})
    out = tmp_path / "out"
    subprocess.run([RENDER, str(scene), "--out", str(out), "--quiet"], check=True, capture_output=True)
    sim = sward.Simulator(scene)
    data_set = sward.Dataset(out)
    ply = np.dtype([("x", "<f4"), ("y", "<f4"), ("z", "<f4"), ("wx", "<f8"), ("wy", "<f8"), ("wz", "<f8"),
                    ("intensity", "<f4"), ("time", "<f4"), ("ring", "<u2"), ("column", "<u2"), ("class", "u1"),
                    ("instance", "<u4")])
    for index in range(3):
        frame = sim.render()["range"]
        name = f"{index:06d}"
        data = (out / "range" / "lidar" / f"{name}.ply").read_bytes()
        points = np.frombuffer(data[data.index(b"end_header\n") + 11:], dtype=ply)
        lidar = frame["lidar"]
        assert len(points) > 1000
        assert bitwise_equal(lidar["xyz"], np.stack([points["x"], points["y"], points["z"]], axis=1))
        assert bitwise_equal(lidar["world"], np.stack([points["wx"], points["wy"], points["wz"]], axis=1))
        for key in ("intensity", "time", "ring", "column", "class", "instance"):
            assert bitwise_equal(lidar[key], points[key]), key
        kitti = np.fromfile(out / "range" / "lidar" / f"{name}.bin", dtype="<f4").reshape(-1, 4)
        assert bitwise_equal(kitti[:, :3], lidar["xyz"]) and bitwise_equal(kitti[:, 3], lidar["intensity"])
        labels = np.fromfile(out / "range" / "lidar" / f"{name}.label", dtype="<u4")
        assert np.array_equal(labels & 0xFFFF, lidar["class"].astype(np.uint32))
        scan = json.loads((out / "range" / "scan" / f"{name}.json").read_text())
        ranges = np.array([np.nan if r is None else r for r in scan["ranges"]], dtype=np.float32)
        assert np.array_equal(np.isnan(ranges), np.isnan(frame["scan"]["ranges"]))
        assert np.array_equal(ranges[~np.isnan(ranges)], frame["scan"]["ranges"][~np.isnan(ranges)])
        depth = sward._sward.read_image(str(out / "range" / "tof" / f"{name}.exr"), "Y")
        assert bitwise_equal(depth, frame["tof"]["depth"])
        # sward.Dataset reads them back to the same arrays.
        read = data_set[index]["range"]
        assert sorted(read) == sorted(frame)
        for sensor in frame:
            assert sorted(read[sensor]) == sorted(frame[sensor]), sensor
            for key in frame[sensor]:
                same = bitwise_equal(read[sensor][key], frame[sensor][key])
                if key == "ranges":  # NaN for no return: compare where there is one
                    got, want = read[sensor][key], frame[sensor][key]
                    same = np.array_equal(np.isnan(got), np.isnan(want)) and np.array_equal(got[~np.isnan(got)], want[~np.isnan(want)])
                assert same, f"{sensor}.{key}"
    assert sim.validation_messages == 0
