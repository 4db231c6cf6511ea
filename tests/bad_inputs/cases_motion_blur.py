"""Exposure time and motion blur (issue 48, part 1; render/motion_blur.h): each bad `camera.sensor` shutter key is
refused before anything is written, with one line naming the key."""

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


SAMPLES = r"'camera\.sensor\.motion_samples' must be \"auto\", 0 \(auto\) or an integer in \[2, 64\] \(got "

CASES = [
    Case("camera.sensor shutter_s negative", "sward-render", sensor({"shutter_s": -0.01}), 1,
         r"'camera\.sensor\.shutter_s' must be between 0 and 1 \(got -0\.01\)"),
    Case("camera.sensor shutter_s 2 s", "sward-render", sensor({"shutter_s": 2}), 1,
         r"'camera\.sensor\.shutter_s' must be between 0 and 1 \(got 2\)"),
    Case("camera.sensor motion_samples 1", "sward-render", sensor({"shutter_s": 0.01, "motion_samples": 1}), 1,
         SAMPLES + r"1\)"),
    Case("camera.sensor motion_samples 65", "sward-render", sensor({"shutter_s": 0.01, "motion_samples": 65}), 1,
         SAMPLES + r"65\)"),
    Case("camera.sensor motion_samples as other text", "sward-render", sensor({"motion_samples": "many"}), 1,
         SAMPLES + r"\"many\"\)"),
]
