#!/usr/bin/env python3
"""Renders the look views of issues 46-47 and measures them with `sward-eval look`.

    tools/look-views.py OUT [--bin build/bin] [--reference DIR] [--views meadow,rover,meadow2,top]

Views (640x480, 4x MSAA, frame 0), each a dataset under OUT/<view>:
  meadow   examples/meadow.json from its own camera (1.8 m up, looking 33 m ahead)
  rover    examples/rover-track.json from the rover's stereo camera
  meadow2  the meadow from 1.6 m, looking 11 m ahead, elsewhere in the tile
  top      the meadow straight down from 8 m
Prints, per view, the statistics the issues bound (vegetation and far regions) and OUT/summary.json. The scene
variants are written into OUT (the meadow reads no asset files, so they render from there).
"""
import argparse
import json
import pathlib
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent

# Issue 47's acceptance bounds: (region, statistic, low, high).
BOUNDS = [
    ("vegetation", "saturation_mean", 0.12, 0.40),
    ("vegetation", "value_std", None, 0.14),
    ("vegetation", "gradient_mean", None, 0.045),
    ("vegetation", "laplacian_rms_0", None, 0.14),
    ("vegetation", "laplacian_rms_2", None, 0.085),
    ("vegetation", "fast_per_mp", None, 30000),
    ("vegetation", "dx_excess_kurtosis", 2.8, None),
    ("vegetation", "sharp_fraction", None, 0.90),
    ("vegetation", "spectrum_slope_high", -2.8, -1.7),
    ("far", "sharp_fraction", None, 0.90),
    ("far", "saturation_mean", None, 0.35),
]


def meadow_variant(out, name, camera):
    scene = json.loads((ROOT / "examples/meadow.json").read_text())
    scene["camera"].update(camera)
    path = out / f"{name}.json"
    path.write_text(json.dumps(scene, indent=1))
    return path


def views(out):
    return {
        "meadow": ROOT / "examples/meadow.json",
        "rover": ROOT / "examples/rover-track.json",
        "meadow2": meadow_variant(out, "meadow2", {"position": [300, 200, 0], "look_at": [306, 209, 0],
                                                   "height_above_ground": 1.6}),
        "top": meadow_variant(out, "top", {"position": [240, 170, 0], "look_at": [240, 170.05, 0],
                                           "height_above_ground": 8}),
    }


def run(command):
    result = subprocess.run([str(c) for c in command], capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"look-views: error: {' '.join(map(str, command))} failed:\n{result.stderr.strip()}")


def check(value, low, high):
    if value is None:
        return "n/a"
    return "ok" if (low is None or value >= low) and (high is None or value <= high) else "OUT"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("out", type=pathlib.Path)
    parser.add_argument("--bin", type=pathlib.Path, default=ROOT / "build/bin")
    parser.add_argument("--reference", type=pathlib.Path)
    parser.add_argument("--views", default="meadow,rover,meadow2,top")
    args = parser.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    summary = {}
    for name, scene in views(args.out).items():
        if name not in args.views.split(","):
            continue
        dataset = args.out / name
        run([args.bin / "sward-render", scene, "--out", dataset, "--frames", "0:1", "--resolution", "640x480",
             "--samples", "4", "--quiet", "--overwrite"])
        look = [args.bin / "sward-eval", "look", dataset, "--no-pictures"]
        run(look + (["--reference", args.reference] if args.reference else []))
        measured = json.loads((dataset / "eval-look/look.json").read_text())["summary"]
        summary[name] = {region: measured.get(region) for region in ("vegetation", "far", "turf", "soil")}
    (args.out / "summary.json").write_text(json.dumps(summary, indent=1))
    names = list(summary)
    print(f"{'region':<11}{'statistic':<21}{'bound':>15}" + "".join(f"{n:>16}" for n in names))
    for region, stat, low, high in BOUNDS:
        bound = f"{'' if low is None else low}..{'' if high is None else high}"
        cells = []
        for n in names:
            value = (summary[n].get(region) or {}).get(stat)
            cells.append(f"{'n/a' if value is None else f'{value:.4g}'} {check(value, low, high):>3}")
        print(f"{region:<11}{stat:<21}{bound:>15}" + "".join(f"{c:>16}" for c in cells))


if __name__ == "__main__":
    main()
