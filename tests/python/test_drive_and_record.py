"""Drive, then record (docs/python.md, "Drive and record"): a Python controller steers the rover by throttle and steer
while a Recorder writes what render() returned as a dataset: frames.jsonl holds the driven poses and the colliders
that acted, the files hold render()'s arrays bitwise, merge-manifests.py --verify passes, and sward-render refuses to
continue an episode. Run by CTest (Python.Module) with PYTHONPATH=build/python, SWARD_RENDER and SWARD_TEST_SCENE."""
import json
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import sward

ROOT = pathlib.Path(__file__).resolve().parents[2]
RENDER = os.environ["SWARD_RENDER"]
TINY = {"render.resolution": [64, 48], "render.samples": 1}
FILE_KINDS = ["left", "right", "depth", "disparity", "semantic", "instance", "normal", "preview"]
WHEELS = ("wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr")


def rover_scene(tmp):
    """The GPU test scene with examples/assets/rover.gltf instead of its path-driven vehicle, the stereo rig on its
    mast (as examples/rover-track.json mounts it)."""
    document = json.loads(pathlib.Path(os.environ["SWARD_TEST_SCENE"]).read_text())
    document.pop("vehicles")
    wheel = {"shape": "capsule", "axis": "x", "radius": 0.16, "length": 0.12, "force": 2.0, "rut_depth": 0.04}
    document["objects"] = [{"name": "rover", "model": str(ROOT / "examples/assets/rover.gltf"),
                            "path": {"points": [[50, 46], [50, 60]], "speed": 1.0},
                            "colliders": [dict(wheel, node=node) for node in WHEELS]}]
    document["camera"] = {"mount": {"object": "rover", "node": "camera_mount", "pitch_deg": 12, "offset": [0, 0, 0.55]},
                          "fov_y_deg": 60, "baseline": 0.12, "min_depth": 0.8}
    document["sequence"] = {"frames": 40, "time_step": 0.1}
    path = tmp / "rover.json"
    path.write_text(json.dumps(document))
    return path


def steer_towards(state, target):
    """A proportional heading controller: full lock at 30 degrees off."""
    dx, dy = target[0] - state["position"][0], target[1] - state["position"][1]
    error = (np.degrees(np.arctan2(dy, dx)) - state["heading_deg"] + 180) % 360 - 180
    return float(np.clip(error / 30, -1, 1))


def verify_manifest(out):
    run = subprocess.run([sys.executable, str(ROOT / "tools/merge-manifests.py"), str(out), "--verify"],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_closed_loop_drive_is_recorded_as_driven(tmp_path):
    scene = rover_scene(tmp_path)
    out = tmp_path / "episode"
    rendered = []
    with sward.Simulator(scene, overrides=TINY, allow_assets=[str(ROOT / "examples/assets")]) as sim:
        state = {"position": (50.0, 46.0), "heading_deg": 90.0}
        with sim.record(out) as recorder:
            for tick in range(40):
                braking = tick >= 34
                state = sim.drive(0, throttle=0.0 if braking else 0.6, steer=steer_towards(state, (44, 56)),
                                  brake=1.0 if braking else 0.0)
                frame = sim.render()
                assert frame["tick"] == tick and frame["time"] == pytest.approx(tick * 0.1)
                rendered.append((state, frame))
            assert recorder.frames == list(range(40)) and "40 frame(s), recording" in repr(recorder)
        assert recorder.closed
    first, last = rendered[0][0], rendered[-1][0]
    travelled = np.hypot(last["position"][0] - 50, last["position"][1] - 46)
    assert travelled > 4 and last["heading_deg"] > 100 and last["speed"] == 0  # turned left towards x 44, stopped

    data = sward.Dataset(out)
    assert len(data) == 40 and data.manifest["fingerprint"]["episode"] is True
    for index, (state, frame) in enumerate(rendered):
        item = data[index]
        record = item["record"]
        assert record == frame["record"]
        # The driven pose: the rover's model origin where drive() put it, the rig mounted on it.
        pose = np.array(record["objects"][0]["pose"])
        assert np.abs(pose[:2, 3] - state["position"]).max() < 1e-9
        assert np.array_equal(np.array(record["left_pose"]), frame["left_pose"])
        assert np.array_equal(np.array(record["right_pose"]), frame["right_pose"])
        # The wheels' colliders of the tick, ids 200000 + collider, within a wheel base of the driven origin.
        wheels = [c for c in record["colliders"] if 200000 <= c["id"] < 200004]
        assert len(wheels) == 4
        for c in wheels:
            assert np.hypot(c["centre"][0] - state["position"][0], c["centre"][1] - state["position"][1]) < 0.8
        for kind in FILE_KINDS:
            assert item[kind].tobytes() == frame[kind].tobytes(), f"frame {index}: {kind}"
    assert np.abs(rendered[-1][1]["left_pose"][:2, 3] - rendered[0][1]["left_pose"][:2, 3]).max() > 3
    assert "files verified" in verify_manifest(out)

    # An episode is never resumed: sward-render refuses the folder, the recorder wants overwrite=True.
    run = subprocess.run([RENDER, str(scene), "--out", str(out), "--resolution", "64x48", "--samples", "1",
                          "--frames", "0:1", "--allow-assets", str(ROOT / "examples/assets")],
                         capture_output=True, text=True)
    assert run.returncode != 0 and "use --overwrite to start over" in run.stderr


def test_an_undriven_episode_is_what_sward_render_writes(tmp_path):
    scene = pathlib.Path(os.environ["SWARD_TEST_SCENE"])
    cli = tmp_path / "cli"
    subprocess.run([RENDER, str(scene), "--out", str(cli), "--resolution", "64x48", "--samples", "1", "--frames", "0:3",
                    "--quiet"], check=True, capture_output=True)
    out = tmp_path / "episode"
    with sward.Simulator(scene, overrides=TINY) as sim, sim.record(out):
        for _ in range(3):
            sim.render()
    lines = (cli / "frames.jsonl").read_text().splitlines()[:3]
    assert (out / "frames.jsonl").read_text().splitlines() == lines
    manifest = json.loads((cli / "manifest.json").read_text())
    frame_files = [name for name in manifest["files"] if "/" in name]
    assert len(frame_files) > 40
    for name in frame_files:
        assert (out / name).read_bytes() == (cli / name).read_bytes(), name
    for name in ("calib.txt", "classes.json"):
        assert (out / name).read_bytes() == (cli / name).read_bytes(), name
    verify_manifest(out)


def test_drive_and_record_refuse_bad_arguments(tmp_path):
    with sward.Simulator(os.environ["SWARD_TEST_SCENE"], overrides=TINY) as sim:
        with pytest.raises(sward.ArgumentError, match="throttle must be a number from -1 to 1"):
            sim.drive(0, throttle=2)
        with pytest.raises(TypeError, match="steer must be a number"):
            sim.drive(0, steer="left")
        with pytest.raises(sward.Error, match="no object 0 to drive"):
            sim.drive(0, throttle=1)
        with pytest.raises(TypeError, match="out must be a folder path"):
            sim.record(3)
        recorder = sim.record(tmp_path / "a")
        with pytest.raises(sward.Error, match="already recording"):
            sim.record(tmp_path / "b")
        with pytest.raises(sward.Error, match="reset: this simulator is recording; close the recorder first"):
            sim.reset()
        sim.render()
        recorder.close()
        assert recorder.closed and recorder.frames == [0]
        with pytest.raises(sward.Error, match="already holds a dataset; pass overwrite=True"):
            sim.record(tmp_path / "a")
        with sim.record(tmp_path / "a", overwrite=True):  # frame 1 only: the episode replaces the old one
            sim.render()
    assert sward.Dataset(tmp_path / "a").frames == [1]
    assert "files verified, frames [1, 2)" in verify_manifest(tmp_path / "a")


def test_reset_starts_a_new_episode_bitwise_on_the_same_device(tmp_path):
    scene = rover_scene(tmp_path)
    options = {"overrides": TINY, "allow_assets": [str(ROOT / "examples/assets")]}
    with sward.Simulator(scene, **options) as sim, sward.Simulator(scene, **options) as fresh:
        first = [fresh.render() for _ in range(2)]
        for _ in range(4):  # an episode: driven, a collider of our own, other weather
            sim.drive(0, throttle=1, steer=0.5)
            sim.render()
        sim.set_colliders([{"centre": [50, 47, 0.2], "radius": 0.5}])
        sim.set_wind(strength=0.6)
        sim.set_sun(elevation_deg=5)
        sim.set_sky(turbidity=6)
        sim.render()
        sim.reset()  # the scene as built, the interaction at rest
        assert sim.frame == 0
        for expected in first:
            frame = sim.render()
            assert frame["record"] == expected["record"]
            for kind in FILE_KINDS:
                assert frame[kind].tobytes() == expected[kind].tobytes(), kind
        sim.reset(seed=9)  # another scene, built on the device already open
        reseeded = sim.render()
    with sward.Simulator(scene, seed=9, **options) as other:
        expected = other.render()
    assert reseeded["record"] == expected["record"] and reseeded["depth"].tobytes() == expected["depth"].tobytes()
    assert reseeded["left"].tobytes() != first[0]["left"].tobytes()


def test_wind_sun_and_sky_change_between_frames():
    with sward.Simulator(os.environ["SWARD_TEST_SCENE"], overrides=TINY) as sim:
        before = sim.render()
        sim.set_wind(strength=0.5, direction_deg=10)
        windy = sim.render()
        assert windy["record"]["wind"]["strength"] == 0.5 and windy["record"]["wind"]["direction_deg"] == 10
        assert windy["record"]["wind"]["gust_strength"] == before["record"]["wind"]["gust_strength"]  # kept
        sim.set_sun(elevation_deg=10, azimuth_deg=200)
        low_sun = sim.render()
        assert low_sun["left"].tobytes() != windy["left"].tobytes()
        sim.set_sky(turbidity=6)
        hazy = sim.render()
        assert hazy["left"].tobytes() != low_sun["left"].tobytes()
        with pytest.raises(sward.Error, match=r"set_wind: 'wind.strength' must be between 0 and 0.9 \(got 2\)"):
            sim.set_wind(strength=2)
        with pytest.raises(sward.Error, match="unknown key 'sun.colour'"):
            sim.set_sun(colour=[1, 1, 1])
        with pytest.raises(sward.Error, match="not finite"):
            sim.set_sky(turbidity=float("nan"))
        assert sim.render()["record"]["wind"]["strength"] == 0.5  # a refused change changes nothing
