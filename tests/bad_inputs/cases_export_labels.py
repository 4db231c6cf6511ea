"""sward-export --labels and --layout semantickitti (issue 50, part 4; export/label_maps.h, export/semantic_kitti.h):
an unknown ontology, an ontology for a layout without class ids, a dataset without a LiDAR, a label file that does
not match its scan and a LiDAR that moves against the camera are each one error, and nothing is written."""

import json
import os

from cases import export_case

IDENTITY = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]


def with_lidar(bin_bytes, label_bytes, moving=False):
    """A LiDAR 'lidar' in every frame record (fixed to the world, or moving 1 m a frame), with frame 0's files."""
    def break_it(dataset, env):
        path = os.path.join(dataset, "frames.jsonl")
        records = [json.loads(line) for line in open(path)]
        for record in records:
            pose = [row[:] for row in IDENTITY]
            pose[0][3] = float(record["frame"]) if moving else 0.0
            record["range_sensors"] = [{"name": "lidar", "type": "lidar", "sweep_start": record["time"],
                                        "sweep_duration": 0.1, "start_pose": pose, "end_pose": pose}]
        with open(path, "w") as f:
            f.writelines(json.dumps(r) + "\n" for r in records)
        os.makedirs(os.path.join(dataset, "range", "lidar"))
        for frame in range(len(records)):
            for ext, data in ((".bin", bin_bytes), (".label", label_bytes)):
                with open(os.path.join(dataset, "range", "lidar", f"{frame:06d}{ext}"), "wb") as f:
                    f.write(data)
    return break_it


CASES = [
    export_case("sward-export --labels unknown", lambda d, e: None, r"--labels 'cityscapes' is not a label ontology",
                "--layout", "ply", "--labels", "cityscapes", exit=2),
    export_case("sward-export --labels for a layout without classes", lambda d, e: None,
                r"--labels rellis applies to the ply and semantickitti layouts", "--layout", "kitti", "--labels",
                "rellis"),
    export_case("sward-export semantickitti without a LiDAR", lambda d, e: None, r"has no LiDAR",
                "--layout", "semantickitti"),
    export_case("sward-export semantickitti label file shorter than its scan",
                with_lidar(b"\0" * 32, b"\0" * 4), r"000000\.label: 4 bytes for 2 points",
                "--layout", "semantickitti"),
    export_case("sward-export semantickitti LiDAR moving against the camera",
                with_lidar(b"\0" * 32, b"\0" * 8, moving=True), r"LiDAR 'lidar' moves relative to the left camera",
                "--layout", "semantickitti"),
]
