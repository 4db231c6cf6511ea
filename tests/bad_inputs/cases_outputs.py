"""Bad inputs of the output folders (issue 45, causes 6-8): links in an output tree are refused, never followed;
a folder another writer holds is refused at once, naming its pid; sward-export refuses a damaged frames.jsonl and
a move-in that cannot complete, leaving --out as found. Each case watches a folder holding both the output and
the place a link points to, so a write through the link shows as a change."""

import json
import os
import shutil
import subprocess
import sys
import time

from cases import Case, base_scene, write_scene

LINK_ERROR = r"is a symbolic link: sward never writes through links in an output folder"
LOCK_ERROR = r"is being written by another sward process \(pid \d+\): one writer per folder"

# A process that holds the folder's lock as a sward writer would (flock, its pid in the file) for 30 s.
HOLDER = """
import fcntl, os, sys, time
fd = os.open(os.path.join(sys.argv[1], ".sward.lock"), os.O_RDWR | os.O_CREAT, 0o666)
fcntl.flock(fd, fcntl.LOCK_EX)
os.write(fd, b"%-10d\\n" % os.getpid())
time.sleep(30)
"""


def watched_tree(env):
    """env.folder/w: the output and every link target go under it, and it is the path that must stay as found."""
    tree = env.path("w")
    os.makedirs(os.path.join(tree, "elsewhere"), exist_ok=True)
    with open(os.path.join(tree, "elsewhere", "keep.txt"), "w") as f:
        f.write("not sward's\n")
    env.watched = tree
    return tree


def tiny_scene(env):
    return write_scene(env.folder, base_scene(env.source))


def link_in_dataset(relative, *extra):
    """sward-render on a copy of the base dataset whose `relative` (a folder or file) is a link to a copy of it
    outside --out."""
    def setup(env):
        tree = watched_tree(env)
        env.out = os.path.join(tree, "out")
        shutil.copytree(env.base_dataset, env.out)
        target = os.path.join(tree, "elsewhere", os.path.basename(relative))
        shutil.move(os.path.join(env.out, relative), target)
        os.symlink(target, os.path.join(env.out, relative))
        return [tiny_scene(env), "--out", env.out, "--quiet", *extra]
    return setup


def export_over_link(env):
    tree = watched_tree(env)
    env.out = os.path.join(tree, "exp")
    os.makedirs(env.out)
    os.symlink(os.path.join(tree, "elsewhere"), os.path.join(env.out, "000000"))
    return [env.base_dataset, "--layout", "middlebury", "--out", env.out]


def export_with_linked_lock_file(env):
    tree = watched_tree(env)
    env.out = os.path.join(tree, "exp")
    os.makedirs(env.out)
    os.symlink(os.path.join(tree, "elsewhere", "keep.txt"), os.path.join(env.out, ".sward.lock"))
    return [env.base_dataset, "--layout", "ply", "--out", env.out]


def eval_into_linked_default_report(env):
    tree = watched_tree(env)
    dataset = os.path.join(tree, "dataset")
    shutil.copytree(env.base_dataset, dataset)
    os.symlink(os.path.join(tree, "elsewhere"), os.path.join(dataset, "eval"))
    env.out = dataset
    return [dataset, "--no-pictures"]


def eval_report_with_linked_frames(env):
    tree = watched_tree(env)
    env.out = os.path.join(tree, "report")
    os.makedirs(env.out)
    os.symlink(os.path.join(tree, "elsewhere"), os.path.join(env.out, "frames"))
    return [env.base_dataset, "--out", env.out]


def held_folder(env, folder):
    """Starts a process holding `folder`'s lock and waits until its pid is in the lock file."""
    os.makedirs(folder, exist_ok=True)
    holder = subprocess.Popen([sys.executable, "-c", HOLDER, folder])
    path = os.path.join(folder, ".sward.lock")
    for _ in range(1000):
        try:
            with open(path) as f:
                if f.read().strip() == str(holder.pid):
                    return holder
        except FileNotFoundError:
            pass
        time.sleep(0.01)
    holder.kill()
    raise RuntimeError("the lock holder did not start")


def while_held(arguments):
    """The tool on an --out that another writer holds; `arguments(env)` gives its arguments."""
    def setup(env):
        held_folder(env, env.out)
        return arguments(env)
    return setup


def frames_jsonl_with(edit):
    """sward-export of a copy of the base dataset whose frames.jsonl records are changed by edit(records)."""
    def setup(env):
        dataset = env.path("dataset")
        shutil.copytree(env.base_dataset, dataset)
        path = os.path.join(dataset, "frames.jsonl")
        with open(path) as f:
            records = [json.loads(line) for line in f]
        edit(records)
        with open(path, "w") as f:
            f.write("".join(json.dumps(r) + "\n" for r in records))
        return [dataset, "--layout", "middlebury", "--out", env.out]
    return setup


def set_frame(index, value):
    def edit(records):
        records[index]["frame"] = value
    return edit


def export_over_a_file_where_a_frame_folder_goes(env):
    """An earlier export's 000000/ and a file named 000001: the move-in must not replace 000000's files and then
    fail at 000001 (a half-replaced --out)."""
    tree = watched_tree(env)
    env.out = os.path.join(tree, "exp")
    os.makedirs(os.path.join(env.out, "000000"))
    for name in ("im0.png", "im1.png", "disp0GT.pfm", "calib.txt"):
        with open(os.path.join(env.out, "000000", name), "w") as f:
            f.write("an earlier export\n")
    with open(os.path.join(env.out, "000001"), "w") as f:
        f.write("in the way\n")
    return [env.base_dataset, "--layout", "middlebury", "--out", env.out]


CASES = [
    # Cause 6: links in output folders.
    Case("sward-export --out whose frame folder is a link elsewhere", "sward-export", export_over_link, 1,
         r"exp/000000' " + LINK_ERROR, needs_dataset=True),
    Case("sward-export --out whose lock file is a link elsewhere", "sward-export", export_with_linked_lock_file, 1,
         r"\.sward\.lock.*symbolic link", needs_dataset=True),
    Case("sward-render --overwrite of a dataset whose left/ is a link elsewhere", "sward-render",
         link_in_dataset("left", "--overwrite"), 1, r"out/left' " + LINK_ERROR, needs_dataset=True),
    Case("sward-render resume of a dataset whose depth/ is a link elsewhere", "sward-render",
         link_in_dataset("depth"), 1, r"out/depth' " + LINK_ERROR, needs_dataset=True),
    Case("sward-render resume of a dataset whose frame file is a link elsewhere", "sward-render",
         link_in_dataset("disparity/000000.pfm"), 1, r"out/disparity/000000\.pfm' " + LINK_ERROR,
         needs_dataset=True),
    Case("sward-render --overwrite of a dataset whose manifest.json is a link elsewhere", "sward-render",
         link_in_dataset("manifest.json", "--overwrite"), 1, r"out/manifest\.json' " + LINK_ERROR,
         needs_dataset=True),
    Case("sward-eval of a dataset whose eval/ is a link elsewhere", "sward-eval", eval_into_linked_default_report,
         1, r"dataset/eval' " + LINK_ERROR, needs_dataset=True),
    Case("sward-eval --out whose frames/ is a link elsewhere", "sward-eval", eval_report_with_linked_frames, 1,
         r"report/frames' " + LINK_ERROR, needs_dataset=True),
    # Cause 7: one writer per folder.
    Case("sward-render into an --out another writer holds", "sward-render",
         while_held(lambda env: [tiny_scene(env), "--out", env.out, "--quiet"]), 1, LOCK_ERROR),
    Case("sward-render --overwrite of an --out another writer holds", "sward-render",
         while_held(lambda env: [tiny_scene(env), "--out", env.out, "--quiet", "--overwrite"]), 1, LOCK_ERROR),
    Case("sward-render --shard into an --out a whole-range writer holds", "sward-render",
         while_held(lambda env: [tiny_scene(env), "--out", env.out, "--quiet", "--shard", "0/2"]), 1, LOCK_ERROR),
    Case("sward-export into an --out another writer holds", "sward-export",
         while_held(lambda env: [env.base_dataset, "--layout", "ply", "--out", env.out]), 1, LOCK_ERROR,
         needs_dataset=True),
    Case("sward-eval into an --out another writer holds", "sward-eval",
         while_held(lambda env: [env.base_dataset, "--out", env.out, "--no-pictures"]), 1, LOCK_ERROR,
         needs_dataset=True),
    # Cause 8: sward-export whole or not at all, frames.jsonl checked first.
    Case("sward-export frames.jsonl with a duplicate frame", "sward-export", frames_jsonl_with(set_frame(1, 0)), 1,
         r"frames\.jsonl line 2: frame 0, expected 1", needs_dataset=True),
    Case("sward-export frames.jsonl with a negative frame", "sward-export", frames_jsonl_with(set_frame(1, -1)), 1,
         r"frames\.jsonl line 2: frame -1, expected 1", needs_dataset=True),
    Case("sward-export frames.jsonl with a skipped frame", "sward-export", frames_jsonl_with(set_frame(1, 2)), 1,
         r"frames\.jsonl line 2: frame 2, expected 1", needs_dataset=True),
    Case("sward-export frames.jsonl starting at frame 1", "sward-export", frames_jsonl_with(set_frame(0, 1)), 1,
         r"frames\.jsonl line 1: frame 1, expected 0", needs_dataset=True),
    Case("sward-export --out with a file where a frame folder goes", "sward-export",
         export_over_a_file_where_a_frame_folder_goes, 1, r"exp/000001' is a file where the output has a folder",
         needs_dataset=True),
]
