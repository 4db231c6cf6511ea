"""The camera's lens (issue 48, part 3; scene/sensor_optics.h): each bad `camera.sensor` optics key is refused before
anything is written, with one line naming the key. The focus distance against the focal length needs the camera
(fx of the scene's 32x24 test image, 20.8 px, times the default 3.45 um pitch: 72 um) and is checked with the rig."""

from cases import Case, scene_with, set_key


def sensor(keys):
    return scene_with(set_key(["camera", "sensor"], keys))


CASES = [
    Case("camera.sensor aperture_f without focus_distance_m", "sward-render", sensor({"aperture_f": 2.8}), 1,
         r"'camera\.sensor\.focus_distance_m' is required when 'aperture_f' is greater than 0"),
    Case("camera.sensor aperture_f 0.5", "sward-render", sensor({"aperture_f": 0.5, "focus_distance_m": 2}), 1,
         r"'camera\.sensor\.aperture_f' must be 0 \(a pinhole\) or between 0\.7 and 64 \(got 0\.5\)"),
    Case("camera.sensor focus_distance_m 0", "sward-render", sensor({"aperture_f": 2, "focus_distance_m": 0}), 1,
         r"'camera\.sensor\.focus_distance_m' must be greater than 0"),
    Case("camera.sensor focused inside the focal length", "sward-render",
         sensor({"aperture_f": 2, "focus_distance_m": 5e-5}), 1,
         r"'camera\.sensor': 'focus_distance_m' \(5e-05 m\) must exceed the focal length fx \* 'pixel_size_um' "
         r"\(7\.17\d*e-05 m\)"),
    Case("camera.sensor pixel_size_um 0", "sward-render", sensor({"pixel_size_um": 0}), 1,
         r"'camera\.sensor\.pixel_size_um' must be between 0\.5 and 100 \(got 0\)"),
    Case("camera.sensor mtf_sigma_px 6", "sward-render", sensor({"mtf_sigma_px": 6}), 1,
         r"'camera\.sensor\.mtf_sigma_px' must be between 0 and 5 \(got 6\)"),
    Case("camera.sensor chromatic_aberration_px as text", "sward-render", sensor({"chromatic_aberration_px": "red"}),
         1, r"'camera\.sensor\.chromatic_aberration_px' must be a number"),
]
