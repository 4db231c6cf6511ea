"""The Simulator and the recorder in a world of several tiles (issue 51; docs/python.md, "Worlds"): a world of 2 x 2
tiles of 40 m whose camera crosses the border x = 40 m while the tiles behind it are evicted. render() returns the
arrays sward-render writes for the same scene (the instance's `tile` channel and a LiDAR's points too) and the
recorder writes its files bytewise; colliders of the program's own and a driven rover press the same plants whether the world is streamed or
wholly resident; reset() drops every tile's touched state. Run by CTest (Python.Module) with PYTHONPATH=build/python
and SWARD_RENDER."""
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import sward

ROOT = pathlib.Path(__file__).resolve().parents[2]
RENDER = os.environ["SWARD_RENDER"]
ASSETS = str(ROOT / "examples/assets")
KINDS = ["left", "right", "depth", "disparity", "semantic", "instance", "tile", "normal", "preview"]
FRAMES = 8  # 0.5 s apart at 8 m/s: the camera goes from x 28 m to 56 m, over the border at x 40 m


def world_scene(tmp, load_radius=12.0, **extra):
    """The world at 64x48 stereo. load_radius 12 m keeps only the tiles near the camera (tile (0, 0) is evicted once
    it is 14 m behind); 400 m keeps all four resident. Both draw out to 12 m."""
    document = {
        "seed": 7,
        "terrain": {"size": 40, "spacing": 1, "amplitude": 3, "feature_size": 30, "octaves": 3},
        "vegetation": {"tile_size": 40, "field_size": 20},
        "world": {"tiles": [2, 2], "view_distance": 12, "load_radius": load_radius,
                  "evict_radius": load_radius + 2, "memory_budget_mib": 256},
        "camera": {"path": {"points": [[28, 20], [90, 20]], "speed": 8, "height_above_ground": 1.5},
                   "look_ahead": 6, "look_at_height_above_ground": 0, "fov_y_deg": 70, "baseline": 0.12},
        "render": {"resolution": [64, 48], "samples": 1, "shadow_map_size": 256, "shadow_distance": 10},
        "lod": {"near": 3, "mid": 5, "far": 8, "band": 2},
        "sequence": {"frames": FRAMES, "time_step": 0.5},
    }
    document.update(extra)
    path = tmp / f"world-{int(load_radius)}.json"
    path.write_text(json.dumps(document))
    return path


def assert_frames_equal(a, b, what):
    assert a["record"] == b["record"], what
    for kind in KINDS:
        assert a[kind].tobytes() == b[kind].tobytes(), f"{what}: {kind}"


def test_world_frames_and_episode_are_what_sward_render_writes(tmp_path):
    # A free collider crossing the border with the camera: the world's interaction ticks in both. A LiDAR rides along
    # (its 7 m range within load_radius): render()'s range arrays are its files' values.
    lidar = {"name": "lidar", "preset": "VLP-16", "range": [0.3, 7],
             "mount": {"path": {"points": [[28, 20.5], [90, 20.5]], "speed": 8, "height_above_ground": 1.0}}}
    scene = world_scene(tmp_path, colliders=[{"path": {"points": [[31, 19], [90, 19]], "speed": 8,
                                                       "height_above_ground": 0.2}, "radius": 0.6}],
                        range_sensors=[lidar])
    cli = tmp_path / "cli"
    subprocess.run([RENDER, str(scene), "--out", str(cli), "--quiet"], check=True, capture_output=True)
    out = tmp_path / "episode"
    with sward.Simulator(scene) as sim, sim.record(out):
        frames = [sim.render() for _ in range(FRAMES)]
    assert {int(t) for f in frames for t in np.unique(f["tile"])} >= {1, 2}  # plants of tiles (0, 0) and (1, 0)
    data = sward.Dataset(cli)
    for f, frame in enumerate(frames):
        item = data[f]
        assert item["record"] == frame["record"]
        assert any(c["id"] == 100000 for c in frame["record"]["colliders"])
        for kind in KINDS:
            assert item[kind].tobytes() == frame[kind].tobytes(), f"frame {f}: {kind}"
        points = frame["range"]["lidar"]
        assert len(points["xyz"]) > 1000
        for key, values in points.items():
            assert item["range"]["lidar"][key].tobytes() == values.tobytes(), f"frame {f}: lidar {key}"
    assert (out / "frames.jsonl").read_text() == (cli / "frames.jsonl").read_text()
    manifest = json.loads((cli / "manifest.json").read_text())
    names = [name for name in manifest["files"] if "/" in name] + ["calib.txt", "classes.json"]
    assert len(names) > 10 * FRAMES
    for name in names:
        assert (out / name).read_bytes() == (cli / name).read_bytes(), name


def colliders_episode(scene, frames=FRAMES):
    """Frames of an episode whose program pushes a sphere 3 m ahead of the camera, across the border."""
    with sward.Simulator(scene) as sim:
        rendered = []
        for f in range(frames):
            x = 31.0 + 4.0 * f
            sim.set_colliders([{"centre": [x, 20.0, 0.0], "radius": 0.7, "force": 2.0}])
            rendered.append(sim.render())
        return rendered


def test_program_colliders_press_the_same_plants_streamed_or_resident(tmp_path):
    streamed = colliders_episode(world_scene(tmp_path))
    resident = colliders_episode(world_scene(tmp_path, load_radius=400.0))
    for f, (a, b) in enumerate(zip(streamed, resident)):
        assert_frames_equal(a, b, f"frame {f}")
    assert all(any(c["id"] == 0x40000000 for c in f["record"]["colliders"]) for f in streamed)
    # The pressed plants show: frame 2 of the same scene without the collider differs.
    with sward.Simulator(world_scene(tmp_path)) as sim:
        sim.step(2)
        untouched = sim.render()
    assert untouched["left"].tobytes() != streamed[2]["left"].tobytes()
    with sward.Simulator(world_scene(tmp_path), vegetation=False) as bare:  # tiles of bare ground: no plant to press
        with pytest.raises(sward.Error, match="set_colliders: the scene has no vegetation to interact with"):
            bare.set_colliders([{"centre": [31.0, 20.0, 0.0]}])
        assert bare.render()["record"]["colliders"] == []


def rover_world(tmp, load_radius=12.0):
    """The world with examples/assets/rover.gltf standing at x 24 m facing +x, its wheels pressing plants and the
    stereo rig on its mast, one tick a second (the rover's 3 m/s top speed: 3 m a tick)."""
    wheel = {"shape": "capsule", "axis": "x", "radius": 0.16, "length": 0.12, "force": 2.0}
    rover = {"name": "rover", "model": str(ROOT / "examples/assets/rover.gltf"),
             "path": {"points": [[24, 20], [30, 20]], "speed": 1.0},
             "colliders": [dict(wheel, node=node) for node in ("wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr")]}
    camera = {"mount": {"object": "rover", "node": "camera_mount", "pitch_deg": 12, "offset": [0, 0, 0.55]},
              "fov_y_deg": 60, "baseline": 0.12, "min_depth": 0.8}
    return world_scene(tmp, load_radius, objects=[rover], camera=camera, sequence={"frames": 20, "time_step": 1.0})


def drive_then_record(scene, out):
    """Drives the rover 9 ticks at full throttle without rendering (over the border at x 40 m), then records 3
    frames driving on. Returns the states and the rendered frames."""
    with sward.Simulator(scene, allow_assets=[ASSETS]) as sim:
        for _ in range(9):
            sim.drive(0, throttle=1.0)
            sim.step(1)
        driven = []
        with sim.record(out):
            for _ in range(3):
                driven.append((sim.drive(0, throttle=1.0, steer=0.2), sim.render()))
        return driven


def test_a_rover_driven_across_a_border_is_recorded_as_if_the_world_were_resident(tmp_path):
    streamed = drive_then_record(rover_world(tmp_path), tmp_path / "streamed")
    resident = drive_then_record(rover_world(tmp_path, load_radius=400.0), tmp_path / "resident")
    states = [state for state, _ in streamed]
    assert states[0]["position"][0] > 45 and states[-1]["position"][0] > 50  # over the border, 26 m from x 24
    assert all(state["speed"] == 3.0 for state in states)
    data = sward.Dataset(tmp_path / "streamed")
    assert data.frames == [9, 10, 11] and data.manifest["fingerprint"]["episode"] is True
    for index, ((state, frame), (other_state, other)) in enumerate(zip(streamed, resident)):
        assert state == other_state
        assert_frames_equal(frame, other, f"frame {9 + index}, streamed and resident")
        pose = np.array(frame["record"]["objects"][0]["pose"])
        assert np.abs(pose[:2, 3] - state["position"]).max() < 1e-9
        wheels = [c for c in frame["record"]["colliders"] if 200000 <= c["id"] < 200004]
        assert len(wheels) == 4
        item = data[index]
        assert item["record"] == frame["record"]
        for kind in KINDS:
            assert item[kind].tobytes() == frame[kind].tobytes(), f"frame {9 + index}: {kind}"
        assert 2 in np.unique(frame["tile"])  # plants of tile (1, 0): y * 2 + x + 1


def test_reset_in_a_world_drops_every_tiles_touched_state(tmp_path):
    scene = rover_world(tmp_path)
    with sward.Simulator(scene, allow_assets=[ASSETS]) as fresh:
        first = [fresh.render() for _ in range(3)]
    with sward.Simulator(scene, allow_assets=[ASSETS]) as sim:
        # The rover presses a track from x 24 m over the border (tile (0, 0) is evicted with it kept), a collider of
        # ours presses plants where the camera looks first, the wind changes.
        for tick in range(12):
            sim.drive(0, throttle=1.0)
            sim.set_colliders([{"centre": [27.0 + 0.5 * tick, 20.5, 0.0], "radius": 0.5, "force": 2.0}])
            sim.step(1)
        sim.set_wind(strength=0.6)
        assert sim.render()["record"]["objects"][0]["pose"][0][3] > 54
        sim.reset()
        assert sim.frame == 0
        for f, expected in enumerate(first):
            assert_frames_equal(sim.render(), expected, f"frame {f} after reset")
