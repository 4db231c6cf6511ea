#!/usr/bin/env python3
"""The GIS world example end to end (issue 51): examples/gis-world's DEM, land cover, rover, stereo, LiDAR and flow,
streamed against wholly resident.

    gis_world_example_test.py SWARD_RENDER BUILT_EXAMPLES_DIR

The example's scene, cut down to a test's size: the south-west 12 x 3 tiles of 40 m of its 4 x 4 km DEM (10 samples a
tile), 48x32 pixels, lod.far 30 m, and its rover on an out-and-back path that crosses 22 tile borders (counted here
from the path) and drives back over its own track. Rendered twice with sward-render, frames taken along the drive:
- streamed: load_radius 40 m, evict_radius 60 m, so the tiles behind the rover are evicted and generated again on
  the way back (the summary line's counts are checked: tiles evicted, and tiles restored with their kept state,
  i.e. the outbound track);
- resident: load_radius 1000 m, so every tile of the window is resident from the first tick and never evicted.
Every file of every frame — colour, depth, disparity, labels, instances, normals, flow, the LiDAR's points — must be
bitwise the same in both. The frames after the turn see the track pressed before its tiles were evicted: a track
lost or changed on eviction would change them. Python 3 standard library only.
"""

import json
import math
import os
import re
import subprocess
import sys
import tempfile

TILE = 40.0
ORIGIN = (0.0, 0.0)        # the window's south-west corner: the DEM's and the land cover's
TILES = (12, 3)
PATH = [[10.0, 90.0], [450.0, 100.0], [12.0, 104.0]]  # out east, back west 4 m beside the outbound track
SPEED = 20.0               # m/s
TIME_STEP = 0.2            # s: a tick every 4 m
FRAMES = [0, 60, 130, 215]


def scene(example, load_radius, evict_radius):
    s = json.loads(json.dumps(example))
    s["vegetation"]["tile_size"] = TILE
    s["vegetation"]["field_size"] = 20.0
    s["vegetation"]["world_origin"] = list(ORIGIN)
    s["world"] = {"tiles": list(TILES), "load_radius": load_radius, "evict_radius": evict_radius,
                  "view_distance": 34, "memory_budget_mib": 1024}
    s["lod"] = {"near": 4, "mid": 10, "far": 30, "band": 4}
    s["render"].update({"resolution": [48, 32], "samples": 1, "shadow_distance": 20})
    rover = s["objects"][0]
    rover["path"] = {"points": PATH, "speed": SPEED}
    s["range_sensors"][0]["range"] = [0.3, 30.0]  # within load_radius, as a world's sensors must be
    s["sequence"] = {"frames": 220, "time_step": TIME_STEP}
    return s


def borders_crossed():
    """Tile borders the rover's path crosses, counted from the path's polyline (x and y borders)."""
    crossings = 0
    for (x0, y0), (x1, y1) in zip(PATH, PATH[1:]):
        for a, b, o in ((x0, x1, ORIGIN[0]), (y0, y1, ORIGIN[1])):
            crossings += abs(math.floor((b - o) / TILE) - math.floor((a - o) / TILE))
    return crossings


def render(exe, scene_path, out):
    summaries = []
    for frame in FRAMES:  # each run simulates every tick before its frame, then renders that one
        result = subprocess.run([exe, scene_path, "--out", out, "--frames", f"{frame}:{frame + 1}"],
                                capture_output=True, text=True)
        if result.returncode != 0:
            sys.exit(f"sward-render failed on frame {frame}:\n{result.stderr}")
        summaries.append(result.stdout + result.stderr)
    return summaries


def frame_files(root):
    """{relative path: bytes} of every per-frame file (the folders; not the manifests and logs, which name the
    scene's radii)."""
    files = {}
    for folder, _, names in os.walk(root):
        if os.path.samefile(folder, root):
            continue
        for n in names:
            path = os.path.join(folder, n)
            with open(path, "rb") as f:
                files[os.path.relpath(path, root)] = f.read()
    return files


def world_counts(summary):
    m = re.search(r"world tiles: (\d+) generated \((\d+) restored with kept state\), (\d+) evicted", summary)
    if not m:
        sys.exit("no world tiles summary in:\n" + summary)
    return tuple(int(g) for g in m.groups())


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    exe, examples = sys.argv[1], sys.argv[2]
    folder = os.path.join(examples, "gis-world")
    with open(os.path.join(folder, "gis-world.json")) as f:
        example = json.load(f)
    crossings = borders_crossed()
    assert crossings >= 6, crossings
    with tempfile.TemporaryDirectory() as tmp:
        runs = {}
        for name, load, evict in (("streamed", 40.0, 60.0), ("resident", 1000.0, 1100.0)):
            # The scene sits in the example's folder (its DEM, land cover and rover are assets there) under a
            # temporary name, removed afterwards.
            scene_path = os.path.join(folder, f".test-{name}-{os.getpid()}.json")
            with open(scene_path, "w") as f:
                json.dump(scene(example, load, evict), f)
            try:
                summaries = render(exe, scene_path, os.path.join(tmp, name))
            finally:
                os.remove(scene_path)
            runs[name] = (frame_files(os.path.join(tmp, name)), summaries)
        streamed, resident = runs["streamed"][0], runs["resident"][0]
        kinds = sorted({path.split(os.sep)[0] for path in streamed})
        for needed in ("left", "right", "depth", "disparity", "semantic", "instance", "normal", "flow", "range"):
            assert any(k.startswith(needed) for k in kinds), f"no {needed} files: {kinds}"
        assert sorted(streamed) == sorted(resident), "the two runs wrote different files"
        differing = [p for p in sorted(streamed) if streamed[p] != resident[p]]
        assert not differing, f"{len(differing)} of {len(streamed)} files differ streamed vs resident: {differing[:8]}"
        generated, restored, evicted = world_counts(runs["streamed"][1][-1])
        r_generated, _, r_evicted = world_counts(runs["resident"][1][-1])
        assert evicted > 0 and restored > 0, (generated, restored, evicted)
        assert r_evicted == 0, r_evicted
        print(f"gis-world: {len(FRAMES)} frames, {len(streamed)} files bitwise equal streamed vs resident ({kinds}); "
              f"the rover crosses {crossings} tile borders; the last streamed run generated {generated} tiles, "
              f"evicted {evicted}, restored {restored} with their kept state (resident: {r_generated} generated, "
              f"none evicted)")


if __name__ == "__main__":
    main()
