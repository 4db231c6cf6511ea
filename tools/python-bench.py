#!/usr/bin/env python3
"""Python rendering overhead against sward-render on the same frames (docs/benchmarks.md, issue 16).

Runs, `--repeat` times each, in fresh temporary folders: sward-render SCENE (the whole job, files written),
sward.write_dataset(SCENE) (the same job called from Python) and a sward.Simulator rendering the scene's frames to
numpy arrays (no files). Prints every wall time, the medians and their ratios to the CLI's.

usage: PYTHONPATH=build/python python3 tools/python-bench.py [--scene S] [--render build/bin/sward-render]
"""
import argparse
import statistics
import subprocess
import tempfile
import time

import sward


def timed(work) -> float:
    start = time.perf_counter()
    work()
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default="tests/data/dataset_scene.json")
    parser.add_argument("--render", default="build/bin/sward-render")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()

    def simulator_frames():
        sim = sward.Simulator(args.scene)
        while sim.frame < frames:
            sim.render()


    frames = 0  # the scene's sequence, counted from the first dataset written
    results = {"sward-render": [], "sward.write_dataset": [], "sward.Simulator frames": []}
    for _ in range(args.repeat):
        with tempfile.TemporaryDirectory() as tmp:
            results["sward-render"].append(timed(lambda: subprocess.run(
                [args.render, args.scene, "--out", tmp + "/cli", "-q"], check=True, capture_output=True)))
            results["sward.write_dataset"].append(timed(lambda: sward.write_dataset(args.scene, tmp + "/py")))
            frames = len(sward.Dataset(tmp + "/py"))
            results["sward.Simulator frames"].append(timed(simulator_frames))
    cli = statistics.median(results["sward-render"])
    for name, times in results.items():
        median = statistics.median(times)
        print(f"{name:24s} {' '.join(f'{t:6.2f}' for t in times)} s  median {median:6.2f} s  x{median / cli:.3f}")


if __name__ == "__main__":
    main()
