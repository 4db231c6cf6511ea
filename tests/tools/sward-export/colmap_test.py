#!/usr/bin/env python3
"""sward-export's COLMAP model run through Debian's COLMAP as a user runs it, and its points checked against the truth.

Renders a short stereo drive (colmap_scene.json: 4 frames, 160x120, the rig moving 1 m per frame), exports it with
--layout colmap, and runs COLMAP's own feature_extractor, exhaustive_matcher and point_triangulator on the model
(CPU SIFT). They must run to the end: point_triangulator aborts when the database's image ids are not the model's,
which the export's database.db prevents. Then every triangulated point is compared with the ground truth: its
depth in each left view that observed it against the truth depth of the pixel it projects to (Middlebury
disp0.pfm and calib.txt of the same dataset: Z = f * B / d). Prints the median distance; the median must be
below 5 % of the depth (measured 2.5 %: SIFT on 160x120 grass).

    colmap_test.py --render sward-render --export sward-export --colmap colmap --scene colmap_scene.json
Exit 77 (skipped) where COLMAP or numpy is missing.
"""

import argparse
import os
import shutil
import sqlite3
import struct
import sys
import tempfile

try:
    import numpy as np
except ImportError as error:
    print(f"skipped: {error} (Debian: apt-get install python3-numpy)")
    sys.exit(77)

from dataset_reading import read_pfm, run  # shared with the other export tests, numpy present



def read_calib(path):
    calib = dict(line.strip().split("=", 1) for line in open(path) if "=" in line)
    cam0 = [float(v) for v in calib["cam0"].strip("[]").replace(";", " ").split()]
    return cam0[0], cam0[2], cam0[5], float(calib["baseline"]) * 1e-3  # f, cx, cy (OpenCV centres), B in metres


def quaternion_matrix(qw, qx, qy, qz):
    return np.array([[1 - 2 * (qy * qy + qz * qz), 2 * (qx * qy - qz * qw), 2 * (qx * qz + qy * qw)],
                     [2 * (qx * qy + qz * qw), 1 - 2 * (qx * qx + qz * qz), 2 * (qy * qz - qx * qw)],
                     [2 * (qx * qz - qy * qw), 2 * (qy * qz + qx * qw), 1 - 2 * (qx * qx + qy * qy)]])


def read_images_txt(path):
    """images.txt: id -> (name, world-to-camera R, t)."""
    lines = [line for line in open(path) if not line.startswith("#")]
    images = {}
    for line in lines[0::2]:
        fields = line.split()
        q, t = [float(v) for v in fields[1:5]], np.array([float(v) for v in fields[5:8]])
        images[int(fields[0])] = (fields[9], quaternion_matrix(*q), t)
    return images


def read_points3d_bin(path):
    """COLMAP's points3D.bin: xyz and the image ids of each point's track."""
    points = []
    with open(path, "rb") as file:
        (count,) = struct.unpack("<Q", file.read(8))
        for _ in range(count):
            fields = struct.unpack("<Q3d3BdQ", file.read(8 + 24 + 3 + 8 + 8))
            track = struct.unpack("<" + "II" * fields[8], file.read(8 * fields[8]))
            points.append((np.array(fields[1:4]), sorted(set(track[0::2]))))
    return points



def triangulate(colmap, model_dir):
    database = os.path.join(model_dir, "database.db")
    images = os.path.join(model_dir, "images")
    run(colmap, "feature_extractor", "--database_path", database, "--image_path", images,
        "--SiftExtraction.use_gpu", "0")
    run(colmap, "exhaustive_matcher", "--database_path", database, "--SiftMatching.use_gpu", "0")
    output = os.path.join(model_dir, "triangulated")
    os.makedirs(output)
    run(colmap, "point_triangulator", "--database_path", database, "--image_path", images,
        "--input_path", os.path.join(model_dir, "sparse", "0"), "--output_path", output)
    return read_points3d_bin(os.path.join(output, "points3D.bin"))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--render", required=True)
    parser.add_argument("--export", required=True)
    parser.add_argument("--colmap", default="colmap")
    parser.add_argument("--scene", required=True)
    args = parser.parse_args()
    colmap = shutil.which(args.colmap)
    if colmap is None:
        print(f"skipped: no {args.colmap} (Debian: apt-get install colmap)")
        sys.exit(77)
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")  # COLMAP links Qt, also for its command-line tools
    with tempfile.TemporaryDirectory(prefix="sward-colmap-") as tmp:
        dataset, model = os.path.join(tmp, "dataset"), os.path.join(tmp, "colmap")
        run(args.render, args.scene, "--out", dataset)
        run(args.export, dataset, "--layout", "colmap", "--out", model)
        run(args.export, dataset, "--layout", "middlebury", "--out", os.path.join(tmp, "middlebury"))

        # The database's ids are the model's, before and after COLMAP's feature extraction.
        images = read_images_txt(os.path.join(model, "sparse", "0", "images.txt"))
        expected = sorted((image_id, name) for image_id, (name, _, _) in images.items())
        ids = lambda: sorted(sqlite3.connect(os.path.join(model, "database.db")).execute(
            "SELECT image_id, name FROM images").fetchall())
        assert ids() == expected, (ids(), expected)
        points = triangulate(colmap, model)
        assert ids() == expected, (ids(), expected)

        distances = []
        for xyz, track in points:
            per_view = []
            for image_id in track:
                name, rotation, translation = images[image_id]
                if not name.startswith("left/"):
                    continue  # the truth depth is the left view's
                frame = name[len("left/"):-len(".png")]
                disparity = read_pfm(os.path.join(tmp, "middlebury", frame, "disp0.pfm"))
                f, cx, cy, baseline = read_calib(os.path.join(tmp, "middlebury", frame, "calib.txt"))
                x, y, z = rotation @ xyz + translation
                u, v = int(round(f * x / z + cx)), int(round(f * y / z + cy))
                if z > 0 and 0 <= u < disparity.shape[1] and 0 <= v < disparity.shape[0] and np.isfinite(disparity[v, u]):
                    truth = f * baseline / float(disparity[v, u])
                    per_view.append((abs(z - truth), abs(z - truth) / truth))
            if per_view:
                distances.append(np.median(per_view, axis=0))
        distances, relative = np.array(distances).T
        assert len(distances) >= 40, f"only {len(distances)} triangulated points seen by a left view"
        median, p90 = np.median(distances), np.percentile(distances, 90)
        print(f"{len(points)} points triangulated; depth against the truth over {len(distances)} points seen by a "
              f"left view: median {median:.4f} m ({np.median(relative) * 100:.2f} % of the depth), 90th "
              f"percentile {p90:.4f} m ({np.percentile(relative, 90) * 100:.2f} %)")
        # Measured: 63 points, median 0.125 m = 2.5 % of the depth (SIFT on 160x120 grass, the rig 1 m per frame).
        assert np.median(relative) < 0.05, np.median(relative)


if __name__ == "__main__":
    main()
