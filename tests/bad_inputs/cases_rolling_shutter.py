"""Rolling shutter (issue 48, part 2; render/rolling_shutter.h): each bad `camera.sensor` readout key is refused
before anything is written, with one line naming the key."""

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


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
]
