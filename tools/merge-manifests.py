#!/usr/bin/env python3
"""Merge the shard manifests of a sharded `sward-render --shard I/N` run into one manifest.json, and verify it.

    tools/merge-manifests.py DIR [SHARD_MANIFEST ...] [--verify] [--jobs N]

DIR is the dataset folder holding every shard's files (shards rendered into one shared folder, or per-shard
folders copied together). Shard manifests are DIR/manifest.shard-I-of-N.json unless given explicitly.

Checks, each reported on one line (exit status 1 if any fails):
  - every shard 0..N-1 of one N is present exactly once, and all agree on format, scene, scene hash, seed,
    options, sward revision, assets, units, conventions and the dataset fingerprint (everything that determines the bytes, see
    dataset/fingerprint.h; its device and driver may differ between machines, with a warning), which must also
    be the one in DIR/dataset.json when that file is there;
  - the shards' frame ranges [A, B) tile one range without gap or overlap;
  - no frame file (e.g. left/000012.exr) is listed by two shards or lies outside its shard's range, every
    frame of the range has every kind of frame file the dataset has (so a lost depth/000012.exr is found; frame 0
    has no backward flow by design),
    and per-dataset files (calib.txt) listed by several shards have the same hash;
  - every listed file exists; with --verify its SHA-256 is recomputed and compared.
Per-shard line files NAME.shard-I-of-N.jsonl (e.g. frames.shard-0-of-4.jsonl) are concatenated in frame order
into NAME.jsonl, which replaces them in the merged manifest, so the result matches a full run's dataset.

The merged manifest has the shard manifests' keys with "shard": null, "frames" covering the union and "files"
the union; it is written atomically (temporary file + rename) as sorted-key, 2-space-indented UTF-8 JSON.
Without shard manifests, DIR/manifest.json itself is checked (files present; hashes with --verify).
Python 3 standard library only.
"""

import argparse
import concurrent.futures
import glob
import hashlib
import json
import os
import re
import subprocess
import sys

FORMAT = "sward-dataset-1"
SHARD_NAME = re.compile(r"^manifest\.shard-(\d+)-of-(\d+)\.json$")
FRAME_FILE = re.compile(r"^(.+)/(\d{6})\.([A-Za-z0-9]+)$")
SHARD_JSONL = re.compile(r"^(.+)\.shard-(\d+)-of-(\d+)\.jsonl$")
# Folders of motion truth towards the previous frame (dataset/naming.h): frame 0 has none by design.
BACKWARD_FOLDERS = {"flow_backward", "flow_backward_mask", "flow_backward_right", "flow_backward_mask_right",
                    "disparity_change_backward"}
# Keys every shard must agree on; device and driver may differ between machines (reported, kept as lists).
SHARED_KEYS = ("format", "scene", "scene_sha256", "seed", "options", "sward_revision")
# Written by newer sward-renders only (asset paths and hashes, units, conventions); shards must still agree.
OPTIONAL_SHARED_KEYS = ("assets", "units", "conventions")
REQUIRED_KEYS = SHARED_KEYS + ("frames", "shard", "device", "driver", "fingerprint", "files")
MACHINE_KEYS = ("device", "driver")  # fingerprint entries that may differ between the machines of shards


class Problems:
    def __init__(self):
        self.messages = []

    def add(self, message):
        self.messages.append(message)


def sha256_file(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def load_manifest(path, problems):
    try:
        with open(path, encoding="utf-8") as f:
            manifest = json.load(f)
    except (OSError, ValueError) as e:
        problems.add(f"{path}: cannot read manifest: {e}")
        return None
    if not isinstance(manifest, dict):
        problems.add(f"{path}: manifest must be a JSON object")
        return None
    missing = [k for k in REQUIRED_KEYS if k not in manifest]
    if missing:
        problems.add(f"{path}: manifest lacks {', '.join(missing)}")
        return None
    if manifest["format"] != FORMAT:
        problems.add(f"{path}: format is {manifest['format']!r}, expected {FORMAT!r}")
        return None
    frames = manifest["frames"]
    if not (isinstance(frames, list) and len(frames) == 2 and all(isinstance(x, int) for x in frames)
            and 0 <= frames[0] <= frames[1]):
        problems.add(f"{path}: 'frames' must be [A, B] with 0 <= A <= B")
        return None
    if not isinstance(manifest["fingerprint"], dict):
        problems.add(f"{path}: 'fingerprint' must be an object")
        return None
    if not isinstance(manifest["files"], dict):
        problems.add(f"{path}: 'files' must be an object of path: sha256")
        return None
    return manifest


def parse_shard(manifest, path, problems):
    shard = manifest["shard"]
    match = re.fullmatch(r"(\d+)/(\d+)", shard) if isinstance(shard, str) else None
    if not match or not int(match.group(1)) < int(match.group(2)):
        problems.add(f"{path}: 'shard' must be \"I/N\" with 0 <= I < N (got {shard!r})")
        return None
    return int(match.group(1)), int(match.group(2))


def fingerprint_difference(a, b):
    """The first fingerprint key (device and driver aside) on which a and b differ, or None."""
    for key in sorted(set(a) | set(b)):
        if key not in MACHINE_KEYS and a.get(key) != b.get(key):
            return key
    return None


def check_fingerprints(dataset, shards, problems):
    first_path, first = shards[0][1], shards[0][2]["fingerprint"]
    for _, path, manifest in shards[1:]:
        key = fingerprint_difference(first, manifest["fingerprint"])
        if key is not None:
            problems.add(f"{path}: fingerprint '{key}' differs from {first_path} "
                         f"({manifest['fingerprint'].get(key)!r} vs {first.get(key)!r}): shards of different renders")
    description = os.path.join(dataset, "dataset.json")
    if os.path.exists(description):
        try:
            with open(description, encoding="utf-8") as f:
                recorded = json.load(f)["fingerprint"]
        except (OSError, ValueError, KeyError, TypeError):
            problems.add(f"{description}: not a sward dataset description")
            return
        key = fingerprint_difference(recorded, first)
        if key is not None:
            problems.add(f"{first_path}: fingerprint '{key}' differs from {description}'s")


def merge_jsonl(dataset, name, parts, problems):
    """Concatenates per-shard line files (already sorted by shard, i.e. by frame) into NAME.jsonl."""
    lines, last_frame = [], None
    for shard_path in parts:
        try:
            with open(os.path.join(dataset, shard_path), "rb") as f:
                shard_lines = f.read().splitlines(keepends=True)
        except OSError as e:
            problems.add(f"{shard_path}: cannot read: {e}")
            return None
        for number, line in enumerate(shard_lines, 1):
            try:
                frame = json.loads(line)["frame"]
            except (ValueError, KeyError, TypeError):
                problems.add(f"{shard_path}:{number}: not a JSON object with a 'frame'")
                return None
            if last_frame is not None and frame <= last_frame:
                problems.add(f"{shard_path}:{number}: frame {frame} out of order or duplicated")
                return None
            last_frame = frame
            lines.append(line if line.endswith(b"\n") else line + b"\n")
    merged = name + ".jsonl"
    write_atomically(os.path.join(dataset, merged), b"".join(lines))
    return merged


def write_atomically(path, data):
    # sward's temporary name (common/atomic_file.h), which sward-render cleans up and no user file has
    folder, name = os.path.split(path)
    tmp = os.path.join(folder, f".{name}.sward-{os.getpid()}.tmp")
    with open(tmp, "wb") as f:
        f.write(data)
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def merge(dataset, manifest_paths, problems):
    shards = []
    for path in manifest_paths:
        manifest = load_manifest(path, problems)
        if manifest is None:
            continue
        index = parse_shard(manifest, path, problems)
        if index is not None:
            shards.append((index, path, manifest))
    if problems.messages:
        return None

    counts = {n for (_, n), _, _ in shards}
    if len(counts) != 1:
        problems.add(f"shard manifests disagree on N: {sorted(counts)}")
        return None
    n = counts.pop()
    seen = {}
    for (i, _), path, _ in shards:
        if i in seen:
            problems.add(f"shard {i}/{n} appears twice: {seen[i]} and {path}")
        seen[i] = path
    absent = [str(i) for i in range(n) if i not in seen]
    if absent:
        problems.add(f"missing shard(s) {', '.join(absent)} of {n}")
    if problems.messages:
        return None
    shards.sort(key=lambda s: s[0][0])

    first_path, first = shards[0][1], shards[0][2]
    for _, path, manifest in shards[1:]:
        for key in SHARED_KEYS + OPTIONAL_SHARED_KEYS:
            if manifest.get(key) != first.get(key):
                problems.add(f"{path}: '{key}' differs from {first_path}")
    check_fingerprints(dataset, shards, problems)

    ordered = sorted(shards, key=lambda s: (s[2]["frames"][0], s[2]["frames"][1]))
    start, end = ordered[0][2]["frames"][0], ordered[0][2]["frames"][0]
    for _, path, manifest in ordered:
        a, b = manifest["frames"]
        if a == b:
            continue  # an empty shard (more shards than frames)
        if a < end:
            problems.add(f"{path}: frames [{a}, {b}) overlap frames before {end}")
        elif a > end:
            problems.add(f"frames [{end}, {a}) are in no shard")
        end = max(end, b)

    files, owner, jsonl_parts = {}, {}, {}
    for _, path, manifest in ordered:
        a, b = manifest["frames"]
        for name, digest in manifest["files"].items():
            frame_match = FRAME_FILE.match(name)
            jsonl_match = SHARD_JSONL.match(name)
            if jsonl_match:
                jsonl_parts.setdefault(jsonl_match.group(1), []).append(name)
                continue
            if frame_match and not a <= int(frame_match.group(2)) < b:
                problems.add(f"{path}: lists {name}, outside its frames [{a}, {b})")
            if name in files:
                if frame_match:
                    problems.add(f"{name} is listed by both {owner[name]} and {path}")
                elif files[name] != digest:
                    problems.add(f"{name} differs between {owner[name]} and {path}")
                continue
            files[name] = digest
            owner[name] = path

    kinds = {(m.group(1), m.group(3)) for m in map(FRAME_FILE.match, files) if m}
    for frame in range(start, end):
        for folder, extension in sorted(kinds):
            if frame == 0 and folder in BACKWARD_FOLDERS:
                continue
            name = f"{folder}/{frame:06d}.{extension}"
            if name not in files:
                problems.add(f"{name} is missing (no shard lists it)")
    if problems.messages:
        return None

    result = {key: first[key] for key in first}
    result["shard"] = None
    result["frames"] = [start, end]
    result["files"] = files
    for key in ("device", "driver"):
        values = sorted({json.dumps(m[key], sort_keys=True) for _, _, m in shards})
        if len(values) > 1:
            print(f"warning: shards ran with different {key}s; images may not be bitwise identical to a "
                  f"single-machine run", file=sys.stderr)
            result[key] = [json.loads(v) for v in values]
            result["fingerprint"] = dict(result["fingerprint"], **{key: result[key]})
    parts = {part: digest for _, _, m in ordered for part, digest in m["files"].items() if SHARD_JSONL.match(part)}
    return result, jsonl_parts, parts


def check_files(dataset, files, verify, jobs, problems):
    def check(item):
        name, digest = item
        path = os.path.join(dataset, name)
        if not os.path.isfile(path):
            return f"{name} is listed but missing on disk"
        if verify:
            actual = sha256_file(path)
            if actual != digest:
                return f"{name}: SHA-256 {actual} does not match the manifest's {digest}"
        return None

    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        for message in pool.map(check, sorted(files.items())):
            if message:
                problems.add(message)


TOOL = "merge-manifests.py"
VERSION = "0.1.0"  # the sward version (CMakeLists.txt project())


class Parser(argparse.ArgumentParser):
    """argparse with sward's command-line convention (tools/tool_main.h): a usage error is one line on stderr,
    "merge-manifests.py: error: ... (see --help)", and exit status 2."""

    def parse_args(self, args=None, namespace=None):
        # argparse reports missing positionals before unknown options; the unknown option is the real mistake.
        known = {o for action in self._actions for o in action.option_strings}
        for arg in sys.argv[1:] if args is None else args:
            if arg == "--":
                break
            negative_number = re.fullmatch(r"-[0-9.]+", arg)
            if arg.startswith("-") and len(arg) > 1 and not negative_number and arg.split("=", 1)[0] not in known:
                self.error(f"unknown option '{arg}'")
        return super().parse_args(args, namespace)

    def error(self, message):
        print(f"{TOOL}: error: {message} (see --help)", file=sys.stderr)
        sys.exit(2)


def jobs_count(text):
    """--jobs: a whole number from 1 to 1024, digits only."""
    if not text.isascii() or not text.isdigit() or not 1 <= int(text) <= 1024:
        raise argparse.ArgumentTypeError(f"must be a whole number from 1 to 1024, got '{text}'")
    return int(text)


def revision():
    """The source revision as `git describe` gives it for this file's checkout, or "unknown"."""
    try:
        run = subprocess.run(["git", "describe", "--always", "--dirty", "--abbrev=12"], capture_output=True,
                             text=True, cwd=os.path.dirname(os.path.abspath(__file__)), timeout=10)
        return run.stdout.strip() or "unknown"
    except (OSError, subprocess.SubprocessError):
        return "unknown"


def main(argv=None):
    parser = Parser(prog=TOOL, description=__doc__.split("\n\n")[0])
    parser.add_argument("dataset", help="dataset folder (sward-render --out)")
    parser.add_argument("manifests", nargs="*", help="shard manifests (default: DIR/manifest.shard-*-of-*.json)")
    parser.add_argument("--verify", action="store_true", help="re-hash every file and compare with the manifest")
    parser.add_argument("--jobs", type=jobs_count, default=min(os.cpu_count() or 1, 1024),
                        help="files hashed in parallel (1..1024)")
    parser.add_argument("--version", action="version", version=f"{TOOL} {VERSION} ({revision()})")
    args = parser.parse_args(argv)

    problems = Problems()
    paths = args.manifests or sorted(p for p in glob.glob(os.path.join(args.dataset, "manifest.shard-*-of-*.json"))
                                     if SHARD_NAME.match(os.path.basename(p)))
    output = os.path.join(args.dataset, "manifest.json")
    jobs = args.jobs
    if not os.path.isdir(args.dataset):
        print(f"{TOOL}: error: dataset folder '{args.dataset}' does not exist", file=sys.stderr)
        return 1
    if paths:
        merged, jsonl_parts, part_files = merge(args.dataset, paths, problems) or (None, {}, {})
        if merged is not None:
            check_files(args.dataset, {**merged["files"], **part_files}, args.verify, jobs, problems)
        if not problems.messages:
            for name, parts in sorted(jsonl_parts.items()):
                combined = merge_jsonl(args.dataset, name, parts, problems)
                if combined is not None:
                    merged["files"][combined] = sha256_file(os.path.join(args.dataset, combined))
    else:
        merged = load_manifest(output, problems)
        if merged is not None:
            print(f"no shard manifests in {args.dataset}: checking manifest.json", file=sys.stderr)
            check_files(args.dataset, merged["files"], args.verify, jobs, problems)
    if problems.messages:
        for message in problems.messages:
            print(f"{TOOL}: error: {message}", file=sys.stderr)
        return 1
    if paths:
        text = json.dumps(merged, indent=2, sort_keys=True, ensure_ascii=False) + "\n"
        write_atomically(output, text.encode("utf-8"))
    what = "verified" if args.verify else "present"
    print(f"{output}: {len(merged['files'])} files {what}, frames [{merged['frames'][0]}, {merged['frames'][1]})"
          + (f", merged from {len(paths)} shard manifests" if paths else ""))
    return 0


if __name__ == "__main__":
    sys.exit(main())
