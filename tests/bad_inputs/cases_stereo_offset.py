"""Unsynchronised stereo rigs (issue 48; camera.sensor.stereo_offset_s, render/sequence_frame.h): each bad value of
the key is refused before anything is written, with one line naming it."""

import json

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


def mono_with_offset(scene, env):
    """A single camera (baseline 0) given an offset: it has no right view."""
    scene["camera"]["baseline"] = 0
    scene["camera"]["sensor"] = {"stereo_offset_s": 0.01}


def flow_with_vehicle(scene, env):
    """The test scene with its vehicle back (base_scene drops it), flow and an unsynchronised rig."""
    with open(f"{env.source}/tests/data/dataset_scene.json") as f:
        scene["vehicles"] = json.load(f)["vehicles"]
    scene["render"]["flow"] = True
    scene["camera"]["sensor"] = {"stereo_offset_s": 0.01}


RANGE = r"'camera\.sensor\.stereo_offset_s' must be between -1 and 1 \(got "

CASES = [
    Case("camera.sensor stereo_offset_s 1.5 s", "sward-render", sensor({"stereo_offset_s": 1.5}), 1, RANGE + r"1\.5\)"),
    Case("camera.sensor stereo_offset_s -2 s", "sward-render", sensor({"stereo_offset_s": -2}), 1, RANGE + r"-2\)"),
    Case("camera.sensor stereo_offset_s as text", "sward-render", sensor({"stereo_offset_s": "late"}), 1,
         r"'camera\.sensor\.stereo_offset_s' must be a number"),
    Case("camera.sensor stereo_offset_s on a single camera", "sward-render", scene_with(mono_with_offset), 1,
         r"'camera\.sensor\.stereo_offset_s' needs a stereo rig \('camera\.baseline' > 0\): a single camera has no "
         r"right view to offset"),
    Case("camera.sensor stereo_offset_s with render.flow and a vehicle", "sward-render", scene_with(flow_with_vehicle),
         1, r"'camera\.sensor\.stereo_offset_s' with 'render\.flow' in a scene whose colliders press the plants is not "
         r"supported yet"),
]
