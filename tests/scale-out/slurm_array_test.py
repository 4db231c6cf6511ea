#!/usr/bin/env python3
"""Scale-out on a real Slurm: docs/scale-out.md's job array script and merge job give a single run's dataset.

Starts a private single-node Slurm (slurm_cluster.py), takes the sbatch script out of docs/scale-out.md (so the
doc and the test cannot drift), submits it as an array of N shards of a small stereo scene, submits the merge
(tools/merge-manifests.py --verify) as a job that depends on the array, exactly as the doc does, then checks that
every file equals the one of an uninterrupted sward-render run (manifest.json byte-identical) and that every shard
rendered only its own block of frames. The cluster is torn down on every exit path; a daemon that does not start
fails the test with its log, never skips it.

Usage: slurm_array_test.py --render SWARD_RENDER --merge MERGE_MANIFESTS_PY --doc SCALE_OUT_MD --scene SCENE
"""

import argparse
import json
import os
import re
import signal
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from slurm_cluster import ClusterError, SlurmCluster  # noqa: E402

SCRIPT_NAME = "render-shards.sbatch"
JOB_TIMEOUT_S = 150


class TestFailure(Exception):
    pass


def extract_sbatch_script(doc_path):
    """The ```bash block of the doc whose second line names render-shards.sbatch."""
    with open(doc_path, encoding="utf-8") as f:
        doc = f.read()
    blocks = [b for b in re.findall(r"```bash\n(.*?)```", doc, re.S) if b.startswith("#!/bin/bash\n# " + SCRIPT_NAME)]
    if len(blocks) != 1:
        raise TestFailure(f"{doc_path}: expected one bash block starting '#!/bin/bash' + '# {SCRIPT_NAME}', "
                          f"found {len(blocks)}")
    return blocks[0]


def list_files(root):
    found = {}
    for folder, _, names in os.walk(root):
        for name in names:
            path = os.path.join(folder, name)
            found[os.path.relpath(path, root)] = path
    return found


def read_bytes(path):
    with open(path, "rb") as f:
        return f.read()


def compare_with_single_run(single, sharded, shards):
    """Every file of the single run is in the merged folder with the same bytes; the only extras are the shards'
    own manifests and frame lists. Returns the number of files compared."""
    expected = list_files(single)
    got = list_files(sharded)
    shard_files = {f"manifest.shard-{i}-of-{shards}.json" for i in range(shards)}
    shard_files |= {f"frames.shard-{i}-of-{shards}.jsonl" for i in range(shards)}
    problems = [f"missing in the merged dataset: {p}" for p in sorted(set(expected) - set(got))]
    problems += [f"not in the single run: {p}" for p in sorted(set(got) - set(expected) - shard_files)]
    problems += [f"differs from the single run: {p}" for p in sorted(set(expected) & set(got))
                 if read_bytes(expected[p]) != read_bytes(got[p])]
    if "manifest.json" not in expected:
        problems.append("the single run wrote no manifest.json")
    if problems:
        raise TestFailure("\n".join(problems))
    return len(expected)


def check_shard_blocks(sharded, shards, frames):
    """Shard I's manifest covers exactly block I of the frames and lists no other frame's files: without this a
    job whose tasks each rendered everything would pass the comparison."""
    for i in range(shards):
        path = os.path.join(sharded, f"manifest.shard-{i}-of-{shards}.json")
        if not os.path.exists(path):
            raise TestFailure(f"shard {i} wrote no {path}")
        with open(path, encoding="utf-8") as f:
            manifest = json.load(f)
        block = [i * frames // shards, (i + 1) * frames // shards]
        if manifest["frames"] != block or manifest["shard"] != f"{i}/{shards}":
            raise TestFailure(f"shard {i}: manifest says frames {manifest['frames']} shard {manifest['shard']}, "
                              f"expected {block} and {i}/{shards}")
        numbers = {int(m.group(1)) for m in (re.search(r"/(\d{6})\.", p) for p in manifest["files"]) if m}
        if not numbers or min(numbers) < block[0] or max(numbers) >= block[1]:
            raise TestFailure(f"shard {i}: lists frame files {sorted(numbers)} outside its block {block}")


def task_logs(logs_dir):
    text = []
    for name in sorted(os.listdir(logs_dir)) if os.path.isdir(logs_dir) else []:
        with open(os.path.join(logs_dir, name), errors="replace") as f:
            text.append(f"--- {name} ---\n{f.read()[-4000:]}")
    return "\n".join(text)


def run_on_slurm(cluster, args, script, out):
    """Submits the array and the dependent merge job as docs/scale-out.md does; waits for the merge."""
    work = cluster.path("work")
    os.makedirs(os.path.join(work, "logs"))
    with open(os.path.join(work, SCRIPT_NAME), "w") as f:
        f.write(script)
    extra = ["--resolution", args.resolution]
    array = cluster.run(["sbatch", "--parsable", f"--array=0-{args.shards - 1}", SCRIPT_NAME, args.scene, out,
                         str(args.shards)] + extra, timeout=30, cwd=work)
    if array.returncode != 0:
        raise TestFailure(f"sbatch of the array failed: {array.stderr.strip()}\n" + cluster.log_text())
    job_id = array.stdout.strip().split(";")[0]
    merge = cluster.run(["sbatch", "--parsable", "--wait", f"--dependency=afterok:{job_id}",
                         "--output=logs/merge-%j.out", "--wrap",
                         f"python3 {args.merge} {out} --verify"], timeout=JOB_TIMEOUT_S, cwd=work)
    merge_id = merge.stdout.strip().split(";")[0]
    # sbatch --wait exits 0 for a job cancelled before it ran (a failed dependency), so ask for the states.
    states = {job: job_states(cluster, job) for job in (job_id, merge_id) if job}
    if merge.returncode != 0 or len(states.get(job_id, [])) != args.shards or states.get(merge_id) != ["COMPLETED"] \
            or any(s != "COMPLETED" for s in states[job_id]):
        raise TestFailure(f"array {job_id} / merge job {merge_id}: states {states}, sbatch --wait status "
                          f"{merge.returncode} {merge.stderr.strip()}\n" + task_logs(os.path.join(work, "logs"))
                          + "\n" + cluster.log_text())
    print(f"slurm: array job {job_id} ({args.shards} tasks) and merge job {merge_id} completed")


def job_states(cluster, job_id):
    """JobState of every task of a job (one for a plain job), from slurmctld's records."""
    result = cluster.run(["scontrol", "--oneliner", "show", "job", job_id], timeout=30)
    return re.findall(r"\bJobState=(\S+)", result.stdout)


def render_single(args, out):
    result = subprocess.run([args.render, args.scene, "--out", out, "--resolution", args.resolution, "--quiet"],
                            capture_output=True, text=True)
    if result.returncode != 0:
        raise TestFailure(f"single run failed ({result.returncode}): {result.stderr.strip()}")
    with open(os.path.join(out, "manifest.json"), encoding="utf-8") as f:
        first, end = json.load(f)["frames"]
    return end - first


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--render", required=True, help="sward-render executable")
    parser.add_argument("--merge", required=True, help="tools/merge-manifests.py")
    parser.add_argument("--doc", required=True, help="docs/scale-out.md")
    parser.add_argument("--scene", required=True, help="scene JSON (small, stereo)")
    parser.add_argument("--shards", type=int, default=3)
    parser.add_argument("--resolution", default="96x72")
    args = parser.parse_args()
    args.render, args.merge, args.scene = map(os.path.abspath, (args.render, args.merge, args.scene))

    # ctest and Ctrl-C stop us with a signal: turn it into an exception so the finally below tears down.
    for sig in (signal.SIGTERM, signal.SIGINT, signal.SIGHUP):
        signal.signal(sig, lambda s, _: sys.exit(128 + s))

    script = extract_sbatch_script(args.doc)
    cluster = SlurmCluster()
    # Array tasks find sward-render on PATH, as the doc asks of every node.
    cluster.env["PATH"] = os.path.dirname(args.render) + os.pathsep + cluster.env.get("PATH", "")
    leftover, root = [], cluster.root
    try:
        single = cluster.path("single")
        frames = render_single(args, single)
        cluster.start()
        sharded = cluster.path("sharded")
        run_on_slurm(cluster, args, script, sharded)
        check_shard_blocks(sharded, args.shards, frames)
        count = compare_with_single_run(single, sharded, args.shards)
        print(f"slurm: {args.shards} shards of {frames} frames merged = single run, {count} files bitwise equal "
              "(manifest.json included)")
    finally:
        leftover = cluster.stop()
    if leftover or os.path.exists(root):
        raise TestFailure(f"teardown left processes {leftover} or the folder {root}")


if __name__ == "__main__":
    try:
        main()
    except (TestFailure, ClusterError) as e:
        print(f"FAIL: {e}", file=sys.stderr)
        sys.exit(1)
