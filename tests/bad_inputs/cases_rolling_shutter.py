"""Rolling shutter (issue 48, part 2; render/rolling_shutter.h): each bad `camera.sensor` readout key is refused
before anything is written, with one line naming the key."""

import json

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


def flow_with_vehicle(scene, env):
    """The test scene with its vehicle back (base_scene drops it), flow and a rolling shutter."""
    with open(f"{env.source}/tests/data/dataset_scene.json") as f:
        scene["vehicles"] = json.load(f)["vehicles"]
    scene["render"]["flow"] = True
    scene["camera"]["sensor"] = {"readout_s": 0.03}


BANDS = r"'camera\.sensor\.readout_bands' must be an integer in \[1, 16384\] \(got "

CASES = [
    Case("camera.sensor readout_s negative", "sward-render", sensor({"readout_s": -0.01}), 1,
         r"'camera\.sensor\.readout_s' must be between 0 and 1 \(got -0\.01\)"),
    Case("camera.sensor readout_s 2 s", "sward-render", sensor({"readout_s": 2}), 1,
         r"'camera\.sensor\.readout_s' must be between 0 and 1 \(got 2\)"),
    Case("camera.sensor readout_s as text", "sward-render", sensor({"readout_s": "fast"}), 1,
         r"'camera\.sensor\.readout_s' must be a number"),
    Case("camera.sensor readout_bands 0", "sward-render", sensor({"readout_s": 0.03, "readout_bands": 0}), 1,
         BANDS + r"0\)"),
    Case("camera.sensor readout_bands 16385", "sward-render", sensor({"readout_s": 0.03, "readout_bands": 16385}),
         1, BANDS + r"16385\)"),
    Case("camera.sensor readout_bands fractional", "sward-render", sensor({"readout_s": 0.03, "readout_bands": 2.5}),
         1, BANDS + r"2\.5\)"),
    Case("camera.sensor readout_s with render.flow and a vehicle", "sward-render", scene_with(flow_with_vehicle), 1,
         r"'camera\.sensor\.readout_s' with 'render\.flow' in a scene whose colliders press the plants is not "
         r"supported yet"),
]
