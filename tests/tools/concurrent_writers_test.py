#!/usr/bin/env python3
"""One writer per folder (common/output_lock.h): two writers of one folder in every combination of sward-render,
sward-render --overwrite, sward-export and sward-eval. One wins, the other exits 1 at once with one error line
naming the winner's pid and leaves the folder as it was; the winner's output verifies.

    concurrent_writers_test.py --bin BIN_DIR --merge MERGE_MANIFESTS_PY --scene SCENE [--trials 20] [--seed S]

Each trial starts writer A on a folder holding a copy of a tiny rendered dataset (32x24, one frame), waits until
A holds the folder's lock (its pid in .sward.lock), lets it run a random moment longer and stops it (SIGSTOP), so
that the second writer B certainly meets it mid-run; B must fail, A is continued and must finish. The first 16
trials are the 16 ordered pairs in a random order, the rest random pairs. Verified: a render's manifest with
merge-manifests.py --verify and its files bitwise equal to a reference render; an export bitwise equal to a
reference export; a report with its metrics; no lock file or staging folder left. Python 3 standard library only.
"""

import argparse
import fcntl
import itertools
import json
import os
import random
import shutil
import signal
import subprocess
import sys
import tempfile
import time

LOCK_FILE = ".sward.lock"
KINDS = ("render", "render --overwrite", "export", "eval")


class TestFailure(Exception):
    pass


def tiny_scene(source, folder):
    with open(source) as f:
        scene = json.load(f)
    scene["render"]["resolution"] = [32, 24]
    scene["sequence"]["frames"] = 1
    scene.pop("vehicles", None)
    path = os.path.join(folder, "scene.json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    return path


def files_under(root):
    found = {}
    for folder, _, names in os.walk(root):
        for name in names:
            path = os.path.join(folder, name)
            with open(path, "rb") as f:
                found[os.path.relpath(path, root)] = f.read()
    return found


class Writers:
    def __init__(self, bin_dir, scene, source_dataset):
        self.bin, self.scene, self.source = bin_dir, scene, source_dataset

    def command(self, kind, out):
        if kind.startswith("render"):
            extra = ["--overwrite"] if kind.endswith("--overwrite") else []
            return [os.path.join(self.bin, "sward-render"), self.scene, "--out", out, "--quiet", *extra]
        if kind == "export":
            return [os.path.join(self.bin, "sward-export"), self.source, "--out", out, "--layout", "middlebury"]
        return [os.path.join(self.bin, "sward-eval"), self.source, "--out", out, "--no-pictures"]


def run(command):
    result = subprocess.run(command, capture_output=True, text=True, timeout=120)
    if result.returncode != 0:
        raise TestFailure(f"{' '.join(command)} exited {result.returncode}: {result.stderr.strip()}")


def wait_for_lock(process, folder):
    """True once `process` holds `folder`'s lock, False when it ended first."""
    path = os.path.join(folder, LOCK_FILE)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            with open(path) as f:
                if f.read().strip() == str(process.pid):
                    return True
        except FileNotFoundError:
            pass
        if process.poll() is not None:
            return False
        time.sleep(0.001)
    raise TestFailure(f"pid {process.pid} took no lock on {folder} within 60 s")


def still_held(folder, pid):
    """Whether `pid` (stopped) holds `folder`'s lock: its pid in the file, and the file locked by someone."""
    try:
        fd = os.open(os.path.join(folder, LOCK_FILE), os.O_RDONLY)
    except FileNotFoundError:
        return False
    try:
        if os.read(fd, 32).strip() != str(pid).encode():
            return False
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
        return False  # nobody holds it exclusively
    except BlockingIOError:
        return True
    finally:
        os.close(fd)


def verify(kind, out, references, merge):
    """The winner's output: what a writer alone would have written, and nothing of the lock or staging."""
    left = [n for n in os.listdir(os.path.dirname(out)) if n.startswith("." + os.path.basename(out) + ".sward-")]
    if os.path.lexists(os.path.join(out, LOCK_FILE)) or left:
        raise TestFailure(f"{kind} left its lock file or staging folder: {left}")
    got = files_under(out)
    if kind.startswith("render"):
        run([sys.executable, merge, out, "--verify"])
        expected = files_under(references["render"])
    elif kind == "export":
        expected = files_under(references["export"])
    else:
        expected = {name: None for name in ("report.md", "metrics.json", "metrics.csv")}
        json.loads(got.get("metrics.json", b"null"))
    for name, data in expected.items():
        if name not in got or (data is not None and got[name] != data):
            raise TestFailure(f"{kind}: {name} is {'missing' if name not in got else 'not what a lone run writes'}")


def trial(writers, references, merge, a, b, folder, rng):
    """A holds `folder`, B tries it; returns False when A finished before it could be caught holding the lock."""
    shutil.rmtree(folder, ignore_errors=True)
    shutil.copytree(references["render"], folder)
    first = subprocess.Popen(writers.command(a, folder), stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                             text=True)
    try:
        if not wait_for_lock(first, folder):
            first.wait()
            return False
        time.sleep(rng.uniform(0.0, 0.3 if a.startswith("render") else 0.002))
        first.send_signal(signal.SIGSTOP)
        if first.poll() is not None or not still_held(folder, first.pid):
            first.send_signal(signal.SIGCONT)
            first.communicate(timeout=120)
            return False  # it let go (or ended) before it was stopped: B would not meet it
        before = files_under(folder)
        second = subprocess.run(writers.command(b, folder), capture_output=True, text=True, timeout=120)
        lines = [line for line in second.stderr.splitlines() if not line.startswith("sward: device: ")]
        expected = f"is being written by another sward process (pid {first.pid})"
        if second.returncode != 1 or len(lines) != 1 or expected not in lines[0]:
            raise TestFailure(f"{b} beside {a}: exit {second.returncode}, expected 1 and one line '... {expected}': "
                              f"{second.stderr.strip()}")
        if files_under(folder) != before:
            raise TestFailure(f"{b} beside {a}: the losing writer changed the folder")
    finally:
        first.send_signal(signal.SIGCONT)
    _, errors = first.communicate(timeout=120)
    if first.returncode != 0:
        raise TestFailure(f"{a} (the winner) exited {first.returncode}: {errors.strip()}")
    verify(a, folder, references, merge)
    return True


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--bin", required=True)
    parser.add_argument("--merge", required=True)
    parser.add_argument("--scene", required=True)
    parser.add_argument("--trials", type=int, default=20)
    parser.add_argument("--seed", type=int, default=45)
    args = parser.parse_args()
    rng = random.Random(args.seed)
    start = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="sward-writers-") as work:
        scene = tiny_scene(args.scene, work)
        references = {"render": os.path.join(work, "reference"), "export": os.path.join(work, "reference-export")}
        writers = Writers(os.path.abspath(args.bin), scene, references["render"])
        run(writers.command("render", references["render"]))
        run(writers.command("export", references["export"]))
        pairs = list(itertools.product(KINDS, KINDS))
        rng.shuffle(pairs)
        pairs += [rng.choice(pairs) for _ in range(max(0, args.trials - len(pairs)))]
        problems, caught = [], 0
        for index, (a, b) in enumerate(pairs[:args.trials]):
            folder = os.path.join(work, f"out{index}")
            try:
                for _ in range(20):  # a fast writer may finish before it is seen holding the lock: try again
                    if trial(writers, references, args.merge, a, b, folder, rng):
                        caught += 1
                        break
                else:
                    problems.append(f"trial {index}: {a} was never caught holding the folder")
            except TestFailure as failure:
                problems.append(f"trial {index}: {failure}")
    for message in problems:
        print(message, file=sys.stderr)
    print(f"concurrent writers: {caught} of {args.trials} trials, {time.monotonic() - start:.1f} s: "
          f"{'FAILED' if problems else 'ok'}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
