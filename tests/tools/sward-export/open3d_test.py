#!/usr/bin/env python3
"""sward-export read by Open3D (Debian python3-open3d) and numpy, as a user's reconstruction script reads it.

Renders one stereo frame, exports it as a world-frame PLY, a Middlebury pair and a nerfstudio transforms.json,
then checks with nothing of sward's: Open3D reads the PLY, every property of it; the nerfstudio pose and intrinsics, applied to the
depth that Middlebury's disp0.pfm and calib.txt give (Z = f * B / d), reproduce every point within 1e-4 m.

    open3d_test.py --render sward-render --export sward-export --scene SCENE
Exit 77 (skipped) where Open3D or numpy is missing.
"""

import argparse
import json
import os
import sys
import tempfile

try:
    import numpy as np
    import open3d as o3d
except ImportError as error:
    print(f"skipped: {error} (Debian: apt-get install python3-open3d)")
    sys.exit(77)

from dataset_reading import read_pfm, run  # shared with the other export tests, numpy present



def read_calib(path):
    calib = dict(line.strip().split("=", 1) for line in open(path) if "=" in line)
    cam0 = calib["cam0"].strip("[]").replace(";", " ").split()
    return float(cam0[0]), float(calib["baseline"]) * 1e-3



def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--render", required=True)
    parser.add_argument("--export", required=True)
    parser.add_argument("--scene", required=True)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="sward-open3d-") as tmp:
        dataset = os.path.join(tmp, "dataset")
        run(args.render, args.scene, "--out", dataset, "--frames", "0:1", "--validation")
        for layout in ("ply", "middlebury", "nerfstudio"):
            run(args.export, dataset, "--layout", layout, "--out", os.path.join(tmp, layout))

        cloud = o3d.io.read_point_cloud(os.path.join(tmp, "ply", "000000.ply"))
        points = np.asarray(cloud.points)
        colours = np.asarray(cloud.colors)
        assert len(points) > 1000 and colours.shape == points.shape, (points.shape, colours.shape)
        # Open3D's tensor reader keeps every property it can type (it skips uint ones with a warning): all of them.
        tensor = o3d.t.io.read_point_cloud(os.path.join(tmp, "ply", "000000.ply")).point
        read = {name: (str(tensor[name].dtype), tuple(tensor[name].shape)) for name in tensor}
        n = len(points)
        assert read == {"positions": ("Float64", (n, 3)), "colors": ("UInt8", (n, 3)), "class": ("UInt8", (n, 1)),
                        "instance": ("Int32", (n, 1)), "normals": ("Float32", (n, 3))}, read
        assert tensor["instance"].numpy().max() > 0, "no plant instance read"

        disparity = read_pfm(os.path.join(tmp, "middlebury", "000000", "disp0.pfm"))
        f, baseline = read_calib(os.path.join(tmp, "middlebury", "000000", "calib.txt"))
        transforms = json.load(open(os.path.join(tmp, "nerfstudio", "transforms.json")))
        view = transforms["frames"][0]
        assert view["file_path"] == "images/left/000000.png", view["file_path"]
        pose = np.array(view["transform_matrix"])  # camera-to-world, OpenGL axes (x right, y up, z back)

        # nerfstudio's rays: through pixel centres (u + 0.5, v + 0.5), y up and z back in the camera.
        v, u = np.nonzero(np.isfinite(disparity))  # row-major order, as the PLY lists its points
        depth = f * baseline / disparity[v, u].astype(np.float64)
        camera = np.stack([(u + 0.5 - transforms["cx"]) / transforms["fl_x"] * depth,
                           -(v + 0.5 - transforms["cy"]) / transforms["fl_y"] * depth,
                           -depth, np.ones_like(depth)])
        world = (pose @ camera)[:3].T
        assert world.shape == points.shape, (world.shape, points.shape)
        error = np.abs(world - points).max()
        print(f"{len(points)} points, largest difference {error:.2e} m")
        assert error < 1e-4, error


if __name__ == "__main__":
    main()
