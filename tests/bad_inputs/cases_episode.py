"""A driven episode (issue 50, part 2; render/episode_recorder.h): sward-render never continues a dataset that
Simulator.record wrote (its frames came from a program, not the scene), even with the very scene and options."""

import json
import os
import shutil

from cases import Case, base_scene, write_scene


def episode_folder(env):
    """The base dataset as an episode: its dataset.json's fingerprint with the recorder's "episode" key."""
    shutil.copytree(env.base_dataset, env.out)
    path = os.path.join(env.out, "dataset.json")
    with open(path) as f:
        description = json.load(f)
    description["fingerprint"]["episode"] = True
    with open(path, "w") as f:
        f.write(json.dumps(description, indent=2) + "\n")
    return [write_scene(env.path("scene"), base_scene(env.source)), "--out", env.out]


CASES = [
    Case("sward-render into a recorded episode", "sward-render", episode_folder, 1,
         r"was rendered with frames a program drove \(an episode Simulator\.record wrote\), this run asks for the "
         r"scene's own sequence", needs_dataset=True),
]
