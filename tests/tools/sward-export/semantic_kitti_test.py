#!/usr/bin/env python3
"""sward-export --layout semantickitti read back as SemanticKITTI's tools read it, by a reader of this test's own.

Renders semantic_kitti_scene.json (64x48 stereo, 3 frames, a VLP-16 LiDAR and the camera both on fixed mounts),
exports it with --labels sward and --labels rellis, and reads the sequences following the documented format
(semantic-kitti-api's laserscan.py and config/semantic-kitti.yaml): .bin float32 x y z intensity, .label uint32
with the class in the low 16 bits and the instance in the high 16, the YAML's learning_map applied through a
lookup table, poses.txt 12 numbers per scan, calib.txt P0..P3 and Tr. Checks against the dataset's own files (the
LiDAR PLY's class property, .label instances, and Middlebury depth of the scene without vegetation: LiDAR points
through Tr and P0 land where the camera sees their depth) and a class table written out here by name.

    semantic_kitti_test.py --render sward-render --export sward-export --scene semantic_kitti_scene.json
Exit 77 (skipped) where numpy or PyYAML is missing.
"""

import argparse
import os
import sys
import tempfile

try:
    import numpy as np
    import yaml
except ImportError as error:
    print(f"skipped: {error} (Debian: apt-get install python3-numpy python3-yaml)")
    sys.exit(77)

from dataset_reading import read_pfm, run  # shared with the other export tests, numpy present

# SemanticKITTI's training classes (semantic-kitti.yaml's learning_map targets), in their order.
KITTI_TRAINING = ["unlabeled", "car", "bicycle", "motorcycle", "truck", "other-vehicle", "person", "bicyclist",
                  "motorcyclist", "road", "parking", "sidewalk", "other-ground", "building", "fence", "vegetation",
                  "trunk", "terrain", "pole", "traffic-sign"]
# What each sward class must become (docs/dataset-format.md, "Label ontologies").
EXPECTED = {"sky": ("unlabeled", "sky"), "ground": ("terrain", "dirt"), "vegetation category 0": ("vegetation", "bush"),
            "vegetation category 1": ("vegetation", "grass"), "vegetation category 2": ("vegetation", "bush"),
            "vegetation category 3": ("vegetation", "bush"), "object": ("unlabeled", "object"),
            "felled": ("vegetation", "grass"), "cut": ("vegetation", "grass"), "turf": ("terrain", "grass"),
            "track": ("terrain", "dirt")}
SWARD_NAMES = {0: "sky", 1: "ground", 2: "vegetation category 0", 3: "vegetation category 1",
               4: "vegetation category 2", 5: "vegetation category 3", 8: "object", 9: "felled", 10: "cut",
               11: "turf", 12: "track"}



def read_ply_classes(path):
    """The class property of a binary little-endian PLY, by its header."""
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    types = {"float": "<f4", "double": "<f8", "uchar": "u1", "ushort": "<u2", "uint": "<u4", "int": "<i4"}
    fields, count = [], 0
    for line in data[:end].decode().splitlines():
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count = int(words[2])
        elif words[:1] == ["property"]:
            fields.append((words[2], types[words[1]]))
    return np.frombuffer(data, dtype=np.dtype(fields), count=count, offset=end)["class"]



def read_calib(path):
    """calib.txt: key -> 3x4 matrix (KITTI odometry)."""
    calib = {}
    for line in open(path):
        key, values = line.split(":", 1)
        numbers = [float(v) for v in values.split()]
        assert len(numbers) == 12, (key, numbers)
        calib[key] = np.array(numbers).reshape(3, 4)
    return calib


def learning_lut(config):
    """semantic-kitti-api's remap: a lookup table from raw label to training id."""
    lut = np.zeros(max(config["learning_map"]) + 100, dtype=np.int32)
    lut[list(config["learning_map"].keys())] = list(config["learning_map"].values())
    return lut


def check_sequence(root, dataset, ontology, frames):
    config = yaml.safe_load(open(os.path.join(root, "semantic-kitti.yaml")))
    assert set(config) >= {"labels", "color_map", "learning_map", "learning_map_inv", "learning_ignore"}, config.keys()
    assert set(config["labels"]) == set(config["color_map"]) == set(config["learning_map"])
    lut = learning_lut(config)
    sequence = os.path.join(root, "sequences", "00")
    for scan in range(frames):
        name = f"{scan:06d}"
        points = np.fromfile(os.path.join(sequence, "velodyne", name + ".bin"), dtype=np.float32).reshape(-1, 4)
        label = np.fromfile(os.path.join(sequence, "labels", name + ".label"), dtype=np.uint32)
        assert label.shape[0] == points.shape[0] > 100, (label.shape, points.shape)
        assert open(os.path.join(sequence, "velodyne", name + ".bin"), "rb").read() == \
            open(os.path.join(dataset, "range", "lidar", name + ".bin"), "rb").read()
        semantic, instance = label & 0xFFFF, label >> 16
        truth = np.fromfile(os.path.join(dataset, "range", "lidar", name + ".label"), dtype=np.uint32)
        assert np.array_equal(instance, truth >> 16)
        sward = read_ply_classes(os.path.join(dataset, "range", "lidar", name + ".ply"))
        assert np.array_equal(sward, truth & 0xFFFF)
        for sward_id in np.unique(sward):
            expected_kitti, expected_rellis = EXPECTED[SWARD_NAMES[int(sward_id)]]
            raw = np.unique(semantic[sward == sward_id])
            assert len(raw) == 1, (sward_id, raw)
            raw = int(raw[0])
            if ontology == "sward":
                assert raw == sward_id and KITTI_TRAINING[lut[raw]] == expected_kitti, (sward_id, lut[raw])
            else:
                assert config["labels"][raw] == expected_rellis, (sward_id, config["labels"][raw])
        print(f"{ontology} scan {name}: {len(points)} points, classes "
              f"{sorted(config['labels'][int(r)] for r in np.unique(semantic))}")
    poses = np.loadtxt(os.path.join(sequence, "poses.txt")).reshape(-1, 12)
    assert poses.shape[0] == frames and np.allclose(poses[0].reshape(3, 4), np.eye(4)[:3], atol=1e-9), poses
    return sequence


def check_calibration(sequence, middlebury):
    """Tr and P0 take each LiDAR point of scan 0 to the left image's pixel whose truth depth it has."""
    calib = read_calib(os.path.join(sequence, "calib.txt"))
    assert set(calib) == {"P0", "P1", "P2", "P3", "Tr"}, calib.keys()
    points = np.fromfile(os.path.join(sequence, "velodyne", "000000.bin"), dtype=np.float32).reshape(-1, 4)
    camera = calib["Tr"] @ np.c_[points[:, :3].astype(np.float64), np.ones(len(points))].T
    pixels = calib["P0"] @ np.r_[camera, np.ones((1, camera.shape[1]))]
    u, v, z = pixels[0] / pixels[2], pixels[1] / pixels[2], camera[2]
    disparity = read_pfm(os.path.join(middlebury, "000000", "disp0.pfm"))
    f, baseline = calib["P0"][0, 0], -calib["P1"][0, 3] / calib["P0"][0, 0]
    # Disparity is affine in the pixel position on a plane, so bilinear interpolation between the four pixel
    # centres around (u, v) holds the truth of the smooth ground to second order (the nearest pixel would be off by
    # up to half a row: 4 % at 64x48 where the view grazes the ground; measured 1.2e-3 interpolated). The dataset has no vegetation: a blade in
    # front of the ground the LiDAR reaches between blades would be another surface.
    inside = (z > 0) & (u >= 0) & (v >= 0) & (u < disparity.shape[1] - 1) & (v < disparity.shape[0] - 1)
    u0, v0 = np.floor(u[inside]).astype(int), np.floor(v[inside]).astype(int)
    du, dv = u[inside] - u0, v[inside] - v0
    d = disparity.astype(np.float64)
    corners = np.stack([d[v0, u0], d[v0, u0 + 1], d[v0 + 1, u0], d[v0 + 1, u0 + 1]])
    weights = np.stack([(1 - du) * (1 - dv), du * (1 - dv), (1 - du) * dv, du * dv])
    keep = np.all(np.isfinite(corners), axis=0)
    truth = f * baseline / (weights * corners).sum(axis=0)[keep]
    relative = np.abs(z[inside][keep] - truth) / truth
    print(f"Tr, P0: {len(relative)} LiDAR points in the left image, depth within a median {np.median(relative):.2e} "
          f"(largest {relative.max():.2e}) of the truth interpolated at their position")
    assert len(relative) > 50 and np.median(relative) < 5e-3, (len(relative), np.median(relative))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--render", required=True)
    parser.add_argument("--export", required=True)
    parser.add_argument("--scene", required=True)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="sward-semantickitti-") as tmp:
        dataset = os.path.join(tmp, "dataset")
        run(args.render, args.scene, "--out", dataset)
        for ontology in ("sward", "rellis"):
            out = os.path.join(tmp, ontology)
            run(args.export, dataset, "--layout", "semantickitti", "--labels", ontology, "--out", out)
            check_sequence(out, dataset, ontology, 3)
        bare = os.path.join(tmp, "bare")  # the ground alone for the calibration's check
        run(args.render, args.scene, "--out", bare, "--frames", "0:1", "--no-vegetation")
        run(args.export, bare, "--layout", "middlebury", "--out", os.path.join(tmp, "middlebury"))
        run(args.export, bare, "--layout", "semantickitti", "--out", os.path.join(tmp, "bare-kitti"))
        check_calibration(os.path.join(tmp, "bare-kitti", "sequences", "00"), os.path.join(tmp, "middlebury"))


if __name__ == "__main__":
    main()
