"""Bad inputs of issue 45's weak points: error lines that quoted a whole base64 data URI, and pose files of numbers
that are no poses accepted by sward-eval odometry."""

import base64
import os
import shutil

from cases import Case, scene_with, triangle_gltf, with_object

# Kilobytes of base64: an error line that quotes the URI whole is that long; a shortened one keeps its media type
# and 8 characters of data, then "... (N characters)".
PAYLOAD = "data:application/octet-stream;base64," + base64.b64encode(bytes(range(256)) * 24).decode()
SHORTENED = r"data:application/octet-stream;base64,AAECAwQF\.\.\. \(\d+ characters\)"


def data_uri_case(name, error, uri, byte_length=None):
    def change(gltf):
        gltf["buffers"][0]["uri"] = uri
        if byte_length is not None:
            gltf["buffers"][0]["byteLength"] = byte_length
    # The regex ends at the line's end: nothing of the base64 after the kept bytes.
    return Case(name, "sward-render", scene_with(with_object("model.gltf", triangle_gltf(uri=change))), 1,
                error + r"( in Buffer)?$")


def poses(*lines):
    """sward-eval odometry on a copy of the base dataset (2 frames) scoring a pose file of `lines`."""
    def setup(env):
        dataset = env.path("dataset")
        shutil.copytree(env.base_dataset, dataset)
        pose_file = env.write("poses.txt", "".join(line + "\n" for line in lines))
        env.out = env.path("report")
        return ["odometry", dataset, "--poses", pose_file, "--out", env.out]
    return setup


IDENTITY = "1 0 0 0 0 1 0 0 0 0 1 0"

CASES = [
    # glTF: a data URI in tinygltf's error text, or refused by the asset policy, is shortened on the error line.
    data_uri_case("glTF data URI buffer of the wrong byteLength", r"Failed to decode 'uri' : " + SHORTENED,
                  PAYLOAD, byte_length=7),
    data_uri_case("glTF data URI of an unknown media type",
                  r"data:text/plain;base64,AAECAwQF\.\.\. \(\d+ characters\)",
                  PAYLOAD.replace("application/octet-stream", "text/plain")),
    # sward-eval odometry --poses: numbers that are finite but no camera pose.
    Case("pose file with a scaled rotation", "sward-eval", poses(IDENTITY, "2 0 0 0 0 2 0 0 0 0 2 0"), 1,
         r"poses\.txt line 2: the 3x3 part is not a rotation \(max \|R\^T R - I\| = 3, over 0\.001\)",
         needs_dataset=True),
    Case("pose file with a mirror", "sward-eval", poses(IDENTITY, "1 0 0 0 0 1 0 0 0 0 -1 0"), 1,
         r"poses\.txt line 2: the 3x3 part is a reflection, not a rotation \(determinant -1, not 1\)",
         needs_dataset=True),
    Case("pose file with a position of 1e308", "sward-eval", poses("1 0 0 1e308 0 1 0 0 0 0 1 0", IDENTITY), 1,
         r"poses\.txt line 1: the position \(1e\+308, 0, 0\) lies beyond 1e\+06 m of the origin",
         needs_dataset=True),
]
