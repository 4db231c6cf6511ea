"""Readers shared by the export tests (open3d_test.py, colmap_test.py, semantic_kitti_test.py): a Middlebury PFM and
a command that must succeed. Imported after each test has checked that numpy is there."""
import subprocess
import sys

import numpy as np


def read_pfm(path):
    """Middlebury PFM: 'Pf', width height, negative scale = little endian, bottom row first."""
    with open(path, "rb") as file:
        data = file.read()
    fields, offset = [], 0
    while len(fields) < 4:
        end = offset
        while data[end:end + 1] not in (b" ", b"\n"):
            end += 1
        if end > offset:
            fields.append(data[offset:end].decode())
        offset = end + 1
    assert fields[0] == "Pf" and float(fields[3]) < 0, fields
    width, height = int(fields[1]), int(fields[2])
    values = np.frombuffer(data, dtype="<f4", count=width * height, offset=offset).reshape(height, width)
    return values[::-1]


def run(*command, cwd=None):
    """Runs `command`; exits the test naming it, with the ends of its output, when it fails."""
    result = subprocess.run(command, capture_output=True, text=True, cwd=cwd)
    if result.returncode != 0:
        sys.exit(f"{' '.join(command)} failed ({result.returncode}): {result.stdout[-2000:]} {result.stderr[-2000:]}")
    return result
