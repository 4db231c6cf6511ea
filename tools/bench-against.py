#!/usr/bin/env python3
"""A frame of this build against an older revision's, back to back on this machine (docs/benchmarks.md, issue 17).

Builds REV's sward-bench from a clean export of the revision (`git archive`, Release, cached under
build/against/REV) unless --old-bench names one, then runs `sward-bench frame` of the old and the new binary in turn,
`--pairs` times, in ABBA order (old-new, new-old, ...) so that a machine's drift over the series weighs on both
alike. Every run draws whole quads only (`--cutout-corners 0`; the new binary also `--no-floor` when it knows it), so
both time the same frame. Prints each run's passes, the medians, and new / old of the medians: only ratios taken
within one series mean anything on a shared machine.

usage: tools/bench-against.py REV [--pairs 3] [--frames 3] [--json F] [--old-scene OLD.json] [-- sward-bench frame arguments]
example: tools/bench-against.py 073f531 -- examples/meadow.json --resolution 1024x768
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
PASSES = ("expansion", "shadow", "main", "resolve", "truth")


def run(command: list[str], **kwargs) -> subprocess.CompletedProcess:
    return subprocess.run(command, check=True, text=True, **kwargs)


def build_old(rev: str) -> str:
    """REV's sward-bench, built once into build/against/<commit>/ from the revision's own files."""
    found = subprocess.run(["git", "-C", ROOT, "rev-parse", "--verify", "--quiet", rev + "^{commit}"],
                           capture_output=True, text=True)
    if found.returncode != 0:
        sys.exit(f"bench-against: '{rev}' names no commit of this repository")
    commit = found.stdout.strip()
    home = os.path.join(ROOT, "build", "against", commit[:12])
    bench = os.path.join(home, "build", "bin", "sward-bench")
    if os.path.exists(bench):
        return bench
    source = os.path.join(home, "source")
    os.makedirs(source, exist_ok=True)
    print(f"bench-against: building {commit[:12]}'s sward-bench in {home} (once; minutes)", file=sys.stderr)
    archive = subprocess.Popen(["git", "-C", ROOT, "archive", commit], stdout=subprocess.PIPE)
    run(["tar", "-x", "-C", source], stdin=archive.stdout)
    if archive.wait() != 0:
        sys.exit(f"bench-against: git archive {commit} failed")
    run(["cmake", "-S", source, "-B", os.path.join(home, "build"), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release"],
        stdout=subprocess.DEVNULL)
    run(["ninja", "-C", os.path.join(home, "build"), "sward-bench"], stdout=subprocess.DEVNULL)
    return bench


def knows(bench: str, option: str) -> bool:
    return option in run([bench, "frame", "--help"], capture_output=True).stdout


def frame(bench: list[str], arguments: list[str], frames: int, scratch: str) -> dict:
    """One `sward-bench frame` run (bench: the binary and its own options): its pass medians in ms, and their sum."""
    out = os.path.join(scratch, "frame.json")
    run([bench[0], "--json", out, "frame", *arguments, "--frames", str(frames), *bench[1:]],
        stdout=subprocess.DEVNULL, cwd=ROOT)
    with open(out) as f:
        passes = json.load(f)["pass_ms"]
    figures = {name: float(passes.get(name, 0.0)) for name in PASSES}
    figures["all"] = sum(figures[name] for name in PASSES)
    return figures


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("rev", help="the older revision (anything git rev-parse takes)")
    parser.add_argument("--old-bench", help="REV's sward-bench, already built (skips the build)")
    parser.add_argument("--new-bench", default=os.path.join(ROOT, "build", "bin", "sward-bench"))
    parser.add_argument("--pairs", type=int, default=3, help="old / new pairs (default 3)")
    parser.add_argument("--frames", type=int, default=3, help="measured frames per run (default 3)")
    parser.add_argument("--json", help="also write every run and the ratios here")
    parser.add_argument("--old-scene", help="the scene REV's binary reads instead of the one after --: the same "
                        "example as of REV (git show REV:examples/meadow.json > old.json) when the example changed "
                        "since, so that the old tree with its scene is timed against the new tree with its scene")
    argv = sys.argv[1:]
    split = argv.index("--") if "--" in argv else len(argv)
    args = parser.parse_args(argv[:split])
    args.frame_args = argv[split + 1:]  # after --: the scene and options for sward-bench frame
    if args.pairs < 1 or args.frames < 1:
        sys.exit("bench-against: --pairs and --frames must be at least 1")
    if not os.path.exists(args.new_bench):
        sys.exit(f"bench-against: '{args.new_bench}' does not exist: build this tree first (./sward.sh build)")
    # Each binary with the options that make it draw whole quads only, asked of it once.
    benches = {}
    for build, path in (("old", args.old_bench or build_old(args.rev)), ("new", args.new_bench)):
        benches[build] = [path, "--cutout-corners", "0", *(["--no-floor"] if knows(path, "--no-floor") else [])]

    scene_args = {"old": args.frame_args, "new": args.frame_args}
    if args.old_scene:
        scenes = [i for i, a in enumerate(args.frame_args) if a.endswith(".json")]
        if not scenes:
            sys.exit("bench-against: --old-scene needs a scene (a .json file) after --")
        scene_args["old"] = [args.old_scene if i == scenes[0] else a for i, a in enumerate(args.frame_args)]
    runs = {"old": [], "new": []}
    with tempfile.TemporaryDirectory() as scratch:
        for pair in range(args.pairs):
            for build in ("old", "new") if pair % 2 == 0 else ("new", "old"):
                figures = frame(benches[build], scene_args[build], args.frames, scratch)
                runs[build].append(figures)
                print(f"pair {pair + 1} {build}: " + "  ".join(f"{k} {v:.0f}" for k, v in figures.items()) + " ms",
                      flush=True)

    medians = {build: {k: statistics.median(r[k] for r in runs[build]) for k in (*PASSES, "all")} for build in runs}
    ratios = {k: medians["new"][k] / medians["old"][k] for k in (*PASSES, "all") if medians["old"][k] > 0}
    print(f"medians, ms: old {medians['old']['all']:.0f}, new {medians['new']['all']:.0f} (all passes)")
    print("new / old: " + "  ".join(f"{k} {v:.3f}" for k, v in ratios.items()))
    print(f"new is {1.0 / ratios['all']:.2f}x as fast as {args.rev} over all passes")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"rev": args.rev, "frame_args": args.frame_args, "frames": args.frames, "runs": runs,
                       "medians": medians, "new_over_old": ratios, "speedup": 1.0 / ratios["all"]}, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
