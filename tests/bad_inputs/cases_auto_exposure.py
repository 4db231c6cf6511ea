"""Auto-exposure (issue 48, part 4; render/auto_exposure.h, scene/sensor_exposure.h): each bad
`camera.sensor.auto_exposure` key is refused before anything is written, with one line naming the key."""

from cases import Case, scene_with, set_key


def auto_exposure(keys):
    return scene_with(set_key(["camera", "sensor"], {"auto_exposure": keys}))


KEY = r"'camera\.sensor\.auto_exposure"

CASES = [
    Case("camera.sensor auto_exposure not an object", "sward-render",
         scene_with(set_key(["camera", "sensor"], {"auto_exposure": 0.5})), 1, KEY + r"' must be an object"),
    Case("camera.sensor auto_exposure target_grey 0", "sward-render", auto_exposure({"target_grey": 0}), 1,
         KEY + r"\.target_grey' must be between 0\.0001 and 100 \(got 0\)"),
    Case("camera.sensor auto_exposure time_constant_s negative", "sward-render",
         auto_exposure({"time_constant_s": -1}), 1, KEY + r"\.time_constant_s' must be between 0 and 60 \(got -1\)"),
    Case("camera.sensor auto_exposure min_ev above max_ev", "sward-render", auto_exposure({"min_ev": 2, "max_ev": 1}),
         1, KEY + r"\.min_ev' must not be above 'max_ev'"),
    Case("camera.sensor auto_exposure max_ev 31", "sward-render", auto_exposure({"max_ev": 31}), 1,
         KEY + r"\.max_ev' must be between -30 and 30 \(got 31\)"),
    Case("camera.sensor auto_exposure unknown key", "sward-render", auto_exposure({"speed": 1}), 1,
         r"unknown key " + KEY + r"\.speed'"),
]

CASES.append(Case("camera.sensor auto_exposure max_window_frames 0", "sward-render",
                  auto_exposure({"max_window_frames": 0}), 1,
                  KEY + r"\.max_window_frames' must be an integer in \[1, 100000\] \(got 0\)"))
