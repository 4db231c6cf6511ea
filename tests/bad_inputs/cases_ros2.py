"""sward-export --layout ros2 (issue 50, part 5; export/ros2_bag.h): a frame record, LiDAR point cloud or laser scan
that a ROS 2 bag cannot carry is one error naming the file, and no bag is left behind."""

import json
import os

from cases import export_case

IDENTITY = [[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0]]


def with_records(change):
    """frames.jsonl with `change(record)` applied to every record."""
    def break_it(dataset, env):
        path = os.path.join(dataset, "frames.jsonl")
        records = [json.loads(line) for line in open(path)]
        for record in records:
            change(record)
        with open(path, "w") as f:
            f.writelines(json.dumps(r) + "\n" for r in records)
    return break_it


def with_range_sensor(kind, name, data):
    """A range sensor in every frame record, and its frame 0 file range/<name>/000000.<ext> holding `data`."""
    def add(record):
        record["range_sensors"] = [{"name": name, "type": kind, "sweep_start": record["time"], "sweep_duration": 0.1,
                                    "start_pose": IDENTITY, "end_pose": IDENTITY}]

    def break_it(dataset, env):
        with_records(add)(dataset, env)
        os.makedirs(os.path.join(dataset, "range", name))
        ext = ".ply" if kind == "lidar" else ".json"
        with open(os.path.join(dataset, "range", name, "000000" + ext), "wb") as f:
            f.write(data)
    return break_it


def set_time(record):
    record["time"] = -1.0


SHORT_PLY = b"ply\nformat binary_little_endian 1.0\nelement vertex 10\nproperty float x\nend_header\n" + b"\0" * 12

CASES = [
    export_case("sward-export ros2 truncated LiDAR PLY", with_range_sensor("lidar", "lidar", SHORT_PLY),
                r"000000\.ply: 12 bytes of vertices, expected 10 x 4", "--layout", "ros2"),
    export_case("sward-export ros2 laser scan not JSON", with_range_sensor("scanner", "scanner", b"{\"ranges\": ["),
                r"000000\.json: not a sward laser scan", "--layout", "ros2"),
    export_case("sward-export ros2 negative frame time", with_records(set_time),
                r"frames\.jsonl line 1: time -1\.000000 s does not fit a ROS 2 stamp", "--layout", "ros2"),
]


def object_named_like_the_sensor(record):
    record["objects"] = [{"name": "lidar", "instance": 16000000, "pose": IDENTITY}]


CASES.append(export_case("sward-export ros2 object and range sensor of one name",
                         lambda d, e: (with_range_sensor("lidar", "lidar", SHORT_PLY)(d, e),
                                       with_records(object_named_like_the_sensor)(d, e)),
                         r"frames\.jsonl frame 0: two frames of the ROS 2 bag would be called 'lidar'",
                         "--layout", "ros2"))
