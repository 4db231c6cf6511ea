"""The camera's digital output (issue 48, part 4; scene/sensor_raw.h): a bad `camera.sensor.bit_depth` is refused
before anything is written, with one line naming the key; so is a bit depth on a sensor that is switched off."""

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


BAD = r"'camera\.sensor\.bit_depth' must be 0 \(no digital output\), 8, 10, 12, 14 or 16 \(got "

CASES = [
    Case("camera.sensor bit_depth 7", "sward-render", sensor({"bit_depth": 7}), 1, BAD + r"7\)"),
    Case("camera.sensor bit_depth 17", "sward-render", sensor({"bit_depth": 17}), 1, BAD + r"17\)"),
    Case("camera.sensor bit_depth -1", "sward-render", sensor({"bit_depth": -1}), 1, BAD + r"-1\)"),
    Case("camera.sensor bit_depth as text", "sward-render", sensor({"bit_depth": "12"}), 1, BAD + r"\"12\"\)"),
    Case("camera.sensor bit_depth 12.5", "sward-render", sensor({"bit_depth": 12.5}), 1, BAD + r"12\.5\)"),
    Case("camera.sensor bit_depth on a disabled sensor", "sward-render", sensor({"enabled": False, "bit_depth": 12}),
         1, r"'camera\.sensor\.bit_depth' needs an enabled sensor \(the sensor has 'enabled': false\)"),
]
