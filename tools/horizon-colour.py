#!/usr/bin/env python3
"""How often sky-labelled pixels just above the horizon carry plant colour (issue 47: colour and labels agree there).

    tools/horizon-colour.py SCENE OUT [--bin build/bin] [--resolution 640x480] [--samples 4] [--rows 2:6]

Renders frame 0 of SCENE twice into OUT (with and with `--no-vegetation`: the same terrain, sky and haze, no plant),
then, in every column, takes the horizon row h (the topmost pixel the semantic image does not label sky) and the
sky-labelled pixels in rows h - 6 .. h - 2 (--rows). A pixel carries plant colour when its 8-bit preview differs from
the render without plants by more than T in some channel; printed for T = 4, 8, 16, 32 as counts and shares of the
pixels examined. Nothing but the plants differs between the two renders, so this counts plant colour alone, whatever
the sky's own gradient. The renderer's own image is measured: a scene with a camera model (`camera.sensor`, whose
optics blur every colour into its neighbours) is rendered from a copy without it written into OUT, so such a scene
must not read files by relative paths. Needs /usr/bin/python3's numpy and cv2 (Debian's python3-opencv).
"""
import argparse
import json
import pathlib
import subprocess
import sys

import cv2
import numpy as np

ROOT = pathlib.Path(__file__).resolve().parent.parent
THRESHOLDS = (4, 8, 16, 32)


def render(bin_dir, scene, out, args, extra):
    command = [str(bin_dir / "sward-render"), str(scene), "--out", str(out), "--frames", "0:1", "--resolution",
               args.resolution, "--samples", str(args.samples), "--quiet", "--overwrite", *extra]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"horizon-colour: error: {' '.join(command)} failed:\n{result.stderr.strip()}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("scene", type=pathlib.Path)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--bin", type=pathlib.Path, default=ROOT / "build/bin")
    parser.add_argument("--resolution", default="640x480")
    parser.add_argument("--samples", type=int, default=4)
    parser.add_argument("--rows", default="2:6", help="rows above the horizon, nearest:farthest (default 2:6)")
    args = parser.parse_args()
    near, far = (int(v) for v in args.rows.split(":"))
    with_plants, without = args.out / "plants", args.out / "no-plants"
    name = args.scene
    scene = json.loads(args.scene.read_text())
    if "sensor" in scene.get("camera", {}):
        del scene["camera"]["sensor"]
        args.out.mkdir(parents=True, exist_ok=True)
        args.scene = args.out / "scene-without-sensor.json"
        args.scene.write_text(json.dumps(scene))
    render(args.bin, args.scene, with_plants, args, [])
    render(args.bin, args.scene, without, args, ["--no-vegetation"])
    semantic = cv2.imread(str(with_plants / "semantic/000000.png"), cv2.IMREAD_UNCHANGED)
    a = cv2.imread(str(with_plants / "preview/000000.png")).astype(np.int32)
    b = cv2.imread(str(without / "preview/000000.png")).astype(np.int32)
    difference = np.abs(a - b).max(axis=2)
    examined, carrying = 0, {t: 0 for t in THRESHOLDS}
    for x in range(semantic.shape[1]):
        ground = np.nonzero(semantic[:, x] != 0)[0]
        if ground.size == 0:
            continue
        rows = [y for y in range(ground[0] - far, ground[0] - near + 1) if y >= 0 and semantic[y, x] == 0]
        examined += len(rows)
        for t in THRESHOLDS:
            carrying[t] += sum(1 for y in rows if difference[y, x] > t)
    print(f"{name}: {examined} sky-labelled pixels {near}-{far} px above the horizon")
    for t in THRESHOLDS:
        share = carrying[t] / examined if examined else 0.0
        print(f"  differing by more than {t:>2} of 255 from the render without plants: {carrying[t]:>5} ({share:.2%})")


if __name__ == "__main__":
    main()
