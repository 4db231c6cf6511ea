#!/usr/bin/env python3
"""sward-render opens nothing outside the scene's folder, its output folder and the system's own files.

Renders the example scenes (examples/*.json and the generated build/examples/{hills,gis,tracks}) at 32x24, one
frame, under strace (open, openat, openat2, creat), and fails naming each file opened outside the allowed places:
the scene file's folder, the --out folder, and the system paths of ALLOWED_SYSTEM (libraries, drivers, fonts,
GDAL's and PROJ's data, /proc, /sys, /dev), listed in docs/testing.md. Scenes that name the same asset files and
the same kinds of input (objects, range sensors, a world, ...) open the same files: --one-per-group (CTest) traces
one of each such group (9 of 16, about 45 s on two busy cores), without it every scene is traced (about 100 s). A control run first: a grass map
outside the scene's folder, allowed with --allow-assets, must be reported, so the harness is seen to catch an
outside open. Exits 77 (skipped) without strace.

usage: open_trace_test.py BIN_DIR SOURCE_DIR BUILD_DIR [--one-per-group]
"""
import concurrent.futures
import glob
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The system's own files a render may open: the dynamic loader's cache and libraries, the Vulkan loader's ICD and
# layer manifests and the drivers, Mesa's drirc, fonts, GDAL's and PROJ's data, the process's own /proc and the
# devices and sysfs nodes a driver probes.
ALLOWED_SYSTEM = ("/lib/", "/lib64/", "/usr/lib/", "/usr/lib64/", "/usr/share/", "/usr/local/lib/",
                  "/usr/local/share/", "/etc/ld.so.cache", "/etc/vulkan/", "/etc/fonts/", "/etc/gdal/",
                  "/etc/localtime", "/proc/", "/sys/", "/dev/")

OPEN = re.compile(r'^\d+\s+(open|openat|openat2|creat)\((?:(AT_FDCWD|\d+), )?"((?:[^"\\]|\\.)*)".*\)\s+=\s+(-?\d+)')


def inside(path, folder):
    return path == folder or path.startswith(folder.rstrip("/") + "/")


def outside_opens(trace, allowed_folders, cwd):
    """The files the trace opened (successfully) outside the allowed folders and system paths."""
    bad = set()
    with open(trace, encoding="utf-8", errors="replace") as f:
        for line in f:
            m = OPEN.match(line)
            if not m or int(m.group(4)) < 0:
                continue
            dirfd, path = m.group(2), m.group(3)
            if not path.startswith("/"):
                if dirfd not in (None, "AT_FDCWD") and "/" not in path:
                    continue  # a name inside a folder opened by handle (the output tree's openat), itself checked
                path = os.path.join(cwd, path)
            real = os.path.realpath(path)
            if any(inside(real, folder) for folder in allowed_folders):
                continue
            if real.startswith(ALLOWED_SYSTEM) or path.startswith(ALLOWED_SYSTEM):
                continue
            bad.add(real)
    return sorted(bad)


# Top-level scene keys that make sward-render open other files or take other reading paths.
INPUT_KEYS = ("grass_map", "land_cover", "atlas", "terrain", "objects", "vehicles", "range_sensors", "world")


def signature(scene):
    """The asset files a scene names and its kinds of input: scenes of one signature open the same files."""
    with open(scene) as f:
        doc = json.load(f)

    def strings(node):
        if isinstance(node, dict):
            for v in node.values():
                yield from strings(v)
        elif isinstance(node, list):
            for v in node:
                yield from strings(v)
        elif isinstance(node, str):
            yield node
    folder = os.path.dirname(scene)
    files = sorted(os.path.realpath(os.path.join(folder, s)) for s in set(strings(doc))
                   if os.path.isfile(os.path.join(folder, s)))
    return tuple(files), tuple(sorted(k for k in doc if k in INPUT_KEYS))


def control_scene(source, work):
    """A scene whose grass map lies outside its folder (allowed by --allow-assets): the trace must report it."""
    folder = tempfile.mkdtemp(prefix="control-", dir=work)
    outside = tempfile.mkdtemp(prefix="outside-", dir=work)
    shutil.copy(os.path.join(source, "examples", "assets", "uniform-grass.png"), os.path.join(outside, "g.png"))
    with open(os.path.join(source, "examples", "bench-patch.json")) as f:
        doc = json.load(f)
    doc["grass_map"] = os.path.join(outside, "g.png")
    scene = os.path.join(folder, "control.json")
    with open(scene, "w") as f:
        json.dump(doc, f)
    return scene, outside


def trace_one(render, scene, work, *extra):
    name = os.path.splitext(os.path.basename(scene))[0]
    folder = tempfile.mkdtemp(prefix=name + "-", dir=work)
    out, trace = os.path.join(folder, "out"), os.path.join(folder, "trace.txt")
    # The driver stack's caches (the Vulkan validation layer's shader cache, which tests turn on) go to a cache
    # folder of the run's own (XDG_CACHE_HOME), allowed like the system's files; ~/.cache itself is not.
    cache = os.path.join(folder, "cache")
    env = dict(os.environ, MESA_SHADER_CACHE_DISABLE="true", XDG_CACHE_HOME=cache)
    env.pop("DISPLAY", None)
    result = subprocess.run(["strace", "-f", "-qq", "-s", "4096", "-o", trace,
                             "-e", "trace=open,openat,openat2,creat", render, scene, "--out", out,
                             "--resolution", "32x24", "--frames", "0:1", "--samples", "1", "--quiet", *extra],
                            cwd=folder, env=env, capture_output=True, text=True, timeout=300)
    if result.returncode != 0:
        return name, [f"sward-render failed: {result.stderr.strip()}"]
    allowed = [os.path.realpath(os.path.dirname(scene)), os.path.realpath(out), os.path.realpath(cache)]
    return name, outside_opens(trace, allowed, folder)


def main():
    every = "--one-per-group" not in sys.argv
    args = [a for a in sys.argv[1:] if a != "--one-per-group"]
    if len(args) != 3:
        sys.exit(__doc__.strip().splitlines()[-1])
    bin_dir, source, build = (os.path.abspath(a) for a in args)
    if not shutil.which("strace"):
        print("open_trace_test: strace not installed (tools/setup-deps.sh); skipped")
        sys.exit(77)
    scenes = sorted(glob.glob(os.path.join(source, "examples", "*.json")))
    scenes += sorted(glob.glob(os.path.join(build, "examples", "*", "*.json")))
    if not every:
        groups = {}
        for scene in scenes:
            groups.setdefault(signature(scene), scene)
        scenes = list(groups.values())
    render = os.path.join(bin_dir, "sward-render")
    work = tempfile.mkdtemp(prefix="sward-open-trace-")
    failures = 0
    try:
        scene, outside = control_scene(source, work)
        _, bad = trace_one(render, scene, work, "--allow-assets", outside)
        if bad != [os.path.join(os.path.realpath(outside), "g.png")]:
            sys.exit(f"open_trace_test: the control run's outside grass map was not reported alone: {bad}")
        with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
            for name, bad in pool.map(lambda s: trace_one(render, s, work), scenes):
                failures += bool(bad)
                print(f"{'FAIL' if bad else 'ok':5} {name}" + "".join(f"\n      {b}" for b in bad))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    print(f"{len(scenes)} scenes: {len(scenes) - failures} opened nothing outside, {failures} did")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
