"""sward-bench suite (issue 49, render/bench_suite.h): a bad option or a used output folder is refused before any
figure runs, with one line naming the option, and the folder is left as found."""

import os

from cases import Case


def used_out(*extra):
    def setup(env):
        env.write("out/notes.txt", "an earlier run's file\n")
        return ["suite", "--quick", "--out", env.out, *extra]
    return setup


def used_reference_folder(env):
    env.write("out/notes.txt", "an earlier run's file\n")
    return ["suite", "--write-reference", env.out]


def no_examples(env):
    os.makedirs(env.path("data"), exist_ok=True)
    return ["suite", "--quick", "--data", env.path("data"), "--out", env.out]


CASES = [
    Case("sward-bench suite --only unknown", "sward-bench",
         lambda env: ["suite", "--quick", "--only", "crosscheck,nosuch", "--out", env.out], 2, r"--only.*nosuch"),
    Case("sward-bench suite without --out", "sward-bench", lambda env: ["suite", "--quick"], 1,
         r"--out: a folder is required"),
    Case("sward-bench suite --out not empty", "sward-bench", used_out(), 1,
         r"--out: '.*out' exists and is not an empty folder; use --overwrite"),
    Case("sward-bench suite --device unknown", "sward-bench",
         lambda env: ["suite", "--quick", "--device", "nosuchgpu", "--out", env.out], 1,
         r"no Vulkan device matches 'nosuchgpu'"),
    Case("sward-bench suite --data without examples", "sward-bench", no_examples, 1,
         r"--data: '.*data' holds no examples/meadow\.json"),
    Case("sward-bench suite --write-reference not empty", "sward-bench",
         used_reference_folder, 1,
         r"--write-reference: '.*out' is not empty; use --overwrite"),
]
