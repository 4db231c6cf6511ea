#!/usr/bin/env python3
"""Crash consistency of sward-render: SIGKILL at seeded random instants, then resume, gives the files of one
uninterrupted run, bitwise, and no temporary or partial file is ever visible.

    crash_consistency_test.py SWARD_RENDER SCENE [--kills N] [--seed S]

Renders an 8-frame 64x48 stereo dataset once as the reference (timing it), then, in fresh folders, starts
sward-render again and again and kills it with SIGKILL after a pseudo-random delay within the reference run's
duration (fixed seed), until at least N (default 20) runs were killed while running. After every kill, every
file under a final name must equal the reference's file of that name, and no temporary may be visible (where
the file system has O_TMPFILE; elsewhere only temporaries of the killed process may remain, removed by the next
run). Whenever a run completes, and at the end after a resume, the whole folder must equal the reference,
manifest included, with no lock file (a killed run's .sward.lock may stay until the next run takes it over). Python 3 standard library only.
"""

import argparse
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time

TEMPORARY = re.compile(r"^\..+\.sward-\d+\.tmp$")
LOCK_FILE = ".sward.lock"  # common/output_lock.h


def files_under(root):
    found = {}
    for folder, _, names in os.walk(root):
        for name in names:
            path = os.path.join(folder, name)
            found[os.path.relpath(path, root)] = path
    return found


def has_tmpfile(folder):
    try:
        os.close(os.open(folder, os.O_TMPFILE | os.O_WRONLY, 0o600))
        return True
    except (AttributeError, OSError):
        return False


def read(path):
    with open(path, "rb") as f:
        return f.read()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("exe")
    parser.add_argument("scene")
    parser.add_argument("--kills", type=int, default=20)
    parser.add_argument("--seed", type=int, default=14)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    work = tempfile.mkdtemp(prefix="sward_crash_")
    problems = []
    try:
        with open(args.scene, encoding="utf-8") as f:
            scene = json.load(f)
        scene["sequence"]["frames"] = 8
        scene_path = os.path.join(work, "scene.json")
        with open(scene_path, "w", encoding="utf-8") as f:
            json.dump(scene, f)

        def command(out):
            return [args.exe, scene_path, "--resolution", "64x48", "--samples", "1", "--quiet", "--out", out]

        reference = os.path.join(work, "reference")
        start = time.monotonic()
        subprocess.run(command(reference), check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        duration = time.monotonic() - start
        expected = {name: read(path) for name, path in files_under(reference).items()}
        tmpfile = has_tmpfile(work)

        def check(out, when, complete):
            for name, path in files_under(out).items():
                if name == LOCK_FILE:
                    # A killed run's lock file (its flock died with it) is taken over by the next run, whose
                    # clean exit removes it.
                    if complete:
                        problems.append(f"{when}: the lock file {name} was left behind")
                elif TEMPORARY.match(os.path.basename(name)) or name.endswith(".tmp"):
                    if tmpfile or not TEMPORARY.match(os.path.basename(name)):
                        problems.append(f"{when}: temporary {name} visible")
                elif name not in expected:
                    problems.append(f"{when}: unexpected file {name}")
                elif read(path) != expected[name]:
                    problems.append(f"{when}: {name} differs from the uninterrupted run")
            if complete and set(n for n in files_under(out)
                                if not TEMPORARY.match(os.path.basename(n)) and n != LOCK_FILE) != set(expected):
                problems.append(f"{when}: the finished folder lacks {sorted(set(expected) - set(files_under(out)))}")

        kills, runs, rounds = 0, 0, 0
        out = os.path.join(work, f"run{rounds}")
        while kills < args.kills and runs < 10 * args.kills:
            delay = rng.uniform(0.0, duration)
            process = subprocess.Popen(command(out), stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            runs += 1
            try:
                process.wait(timeout=delay)
            except subprocess.TimeoutExpired:
                process.send_signal(signal.SIGKILL)
                process.wait()
                kills += 1
                check(out, f"kill {kills} after {delay:.2f} s", complete=False)
                continue
            if process.returncode != 0:
                problems.append(f"run {runs} exited {process.returncode}")
                break
            check(out, f"run {runs} (completed)", complete=True)
            rounds += 1  # a complete folder: go on killing in a fresh one
            out = os.path.join(work, f"run{rounds}")
        subprocess.run(command(out), check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        check(out, "final resume", complete=True)
        if kills < args.kills:
            problems.append(f"only {kills} of {runs} runs were killed while running")
        for message in problems[:20]:
            print(message, file=sys.stderr)
        print(f"crash consistency: {kills} kills in {runs} runs over {rounds + 1} folder(s), reference run "
              f"{duration:.2f} s, O_TMPFILE {'yes' if tmpfile else 'no'}: {'FAILED' if problems else 'ok'}")
        return 1 if problems else 0
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
