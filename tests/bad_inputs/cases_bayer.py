"""A Bayer sensor (issue 48's ISP; scene/sensor_bayer.h): a bad `camera.sensor.bayer` or `camera.sensor.demosaic` is
refused before anything is written, with one line naming the key; so is a demosaic without a pattern and a pattern on
a sensor that is switched off."""

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


BAD = r"'camera\.sensor\.bayer' must be null \(a three-channel sensor\), \"RGGB\", \"BGGR\", \"GRBG\" or \"GBRG\" \(got "

CASES = [
    Case("camera.sensor bayer RGBG", "sward-render", sensor({"bayer": "RGBG"}), 1, BAD + r"\"RGBG\"\)"),
    Case("camera.sensor bayer lower case", "sward-render", sensor({"bayer": "rggb"}), 1, BAD + r"\"rggb\"\)"),
    Case("camera.sensor bayer as a number", "sward-render", sensor({"bayer": 1}), 1, BAD + r"1\)"),
    Case("camera.sensor demosaic unknown", "sward-render", sensor({"bayer": "RGGB", "demosaic": "ahd"}), 1,
         r"'camera\.sensor\.demosaic' must be bilinear or malvar"),
    Case("camera.sensor demosaic without bayer", "sward-render", sensor({"demosaic": "malvar"}), 1,
         r"'camera\.sensor\.demosaic' needs a colour filter array \('bayer'\)"),
    Case("camera.sensor bayer on a disabled sensor", "sward-render", sensor({"enabled": False, "bayer": "RGGB"}), 1,
         r"'camera\.sensor\.bayer' needs an enabled sensor \(the sensor has 'enabled': false\)"),
]
