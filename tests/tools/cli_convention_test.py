#!/usr/bin/env python3
"""Every sward tool follows one command-line convention (tools/tool_main.h):
exit 0 for --help (usage on stdout) and --version ("<tool> <version> (<revision>)" on stdout), 2 for a usage error
(unknown option, bad or out-of-range value: one stderr line "<tool>: error: ... (see --help)"), 1 for a run-time
error such as a missing input file (one stderr line "<tool>: error: ...").

    cli_convention_test.py BIN_DIR MERGE_MANIFESTS_PY

Python 3 standard library only; no GPU: every case fails before a device is opened.
"""

import os
import re
import subprocess
import sys
import tempfile
import unittest

BIN = None
MERGE = None
TOOLS = ("sward-render", "sward-view", "sward-atlas", "sward-rover", "sward-eval", "sward-export", "sward-bench",
         "merge-manifests.py")


def command(tool):
    if tool == "merge-manifests.py":
        return [sys.executable, MERGE]
    return [os.path.join(BIN, tool)]


def run(tool, *args):
    env = dict(os.environ)
    env.pop("DISPLAY", None)  # sward-view must refuse its input before it opens a window
    result = subprocess.run(command(tool) + list(args), capture_output=True, text=True, timeout=60, env=env)
    return result.returncode, result.stdout, result.stderr


class Convention(unittest.TestCase):
    def assertOneErrorLine(self, tool, stderr, pattern, usage):
        lines = stderr.splitlines()
        self.assertEqual(len(lines), 1, f"{tool}: stderr must be one line:\n{stderr}")
        self.assertTrue(lines[0].startswith(f"{tool}: error: "), lines[0])
        self.assertRegex(lines[0], pattern)
        self.assertEqual(lines[0].endswith("(see --help)"), usage, lines[0])
        for raw in ("The following argument", "Run with --help", "Could not convert", "required but received",
                    "Traceback", "usage:"):
            self.assertNotIn(raw, lines[0])

    def test_unknown_option_exits_2_with_one_line(self):
        for tool in TOOLS:
            with self.subTest(tool=tool):
                code, _, err = run(tool, "--bogus")
                self.assertEqual(code, 2, err)
                self.assertOneErrorLine(tool, err, r"unknown option '--bogus'", True)

    def test_help_exits_0_with_usage_on_stdout(self):
        for tool in TOOLS:
            with self.subTest(tool=tool):
                code, out, err = run(tool, "--help")
                self.assertEqual(code, 0, err)
                self.assertRegex(out, r"(?i)usage")
                self.assertEqual(err, "")

    def test_eval_help_lists_every_command_and_each_usage_names_its_command(self):
        code, out, _ = run("sward-eval", "--help")
        self.assertEqual(code, 0)
        for word in ("stereo", "flow", "odometry", "look"):
            self.assertRegex(out, rf"(?m)^  {word} ")
            code, out_word, err = run("sward-eval", word, "--help")
            self.assertEqual(code, 0, err)
            self.assertRegex(out_word, rf"(?m)^Usage: sward-eval \[?{word}\]? ")

    def test_version_exits_0_and_names_tool_version_and_revision(self):
        for tool in TOOLS:
            with self.subTest(tool=tool):
                code, out, err = run(tool, "--version")
                self.assertEqual(code, 0, err)
                self.assertRegex(out.strip(), rf"^{re.escape(tool)} \d+\.\d+\.\d+ \(\S+\)$")

    def test_missing_input_exits_1_with_one_line(self):
        with tempfile.TemporaryDirectory() as tmp:
            blocker = os.path.join(tmp, "a-file")
            open(blocker, "w").close()
            cases = {
                "sward-render": ["/nonexistent/scene.json", "--out", os.path.join(tmp, "render")],
                "sward-view": ["/nonexistent/scene.json", "--frames", "1"],
                "sward-atlas": ["--out", os.path.join(blocker, "atlas")],
                "sward-rover": ["--out", "/nonexistent/folder/rover.gltf"],
                "sward-eval": ["/nonexistent/dataset"],
                "sward-export": ["/nonexistent/dataset", "--layout", "ply", "--out", os.path.join(tmp, "export")],
                "sward-bench": ["frame", "/nonexistent/scene.json"],
                "merge-manifests.py": ["/nonexistent/dataset"],
            }
            self.assertEqual(set(cases), set(TOOLS))
            for tool, args in cases.items():
                with self.subTest(tool=tool):
                    code, _, err = run(tool, *args)
                    self.assertEqual(code, 1, err)
                    self.assertOneErrorLine(tool, err, r"/nonexistent|a-file", False)

    def test_numbers_that_used_to_wrap_are_usage_errors(self):
        cases = [
            ("sward-render", ["--resolution", "4294967616x240"], r"width .* 1 to 16384, got '4294967616'"),
            ("sward-render", ["--resolution", "16384x16384"], r"pixels, more than"),
            ("sward-render", ["--frames", "4294967296:4294967297"], r"start .* got '4294967296'"),
            ("sward-render", ["--frames", "0:1000001"], r"end .* 1 to 1000000"),
            ("sward-render", ["--shard", "4294967296/2"], r"shard index I .* got '4294967296'"),
            ("sward-render", ["--shard", "0/0"], r"shard count N"),
            ("sward-render", ["--samples", "99999999999999999999"], r"--samples must be a whole number"),
            ("sward-render", ["--samples", "3"], r"--samples must be 1 or 4"),
            ("sward-render", ["--seed", "-5"], r"--seed must be a whole number"),
            ("sward-render", ["--seed", "18446744073709551616"], r"--seed must be a whole number"),
            ("sward-render", ["--fov", "nan"], r"--fov must be a number from 1 to 170"),
            ("sward-render", ["--time", "-1"], r"--time must be a number"),
            ("sward-render", ["--camera", "1,2"], r"--camera '1,2': expected X,Y,Z"),
            ("sward-render", ["--out"], r"--out needs a value"),
            ("sward-render", ["a.json", "b.json"], r"unexpected argument 'b.json'"),
            ("sward-view", ["--size", "4294967616x240"], r"width"),
            ("sward-view", ["--frames", "-1"], r"--frames must be a whole number"),
            ("sward-view", ["--press", "99999999999999999999:m"], r"FRAME must be a whole number"),
            ("sward-view", ["--resize-at", "5"], r"--resize-at needs 2 values"),
            ("sward-view", ["--screenshot", "x.png"], r"--screenshot requires --frames"),
            ("sward-atlas", ["--out", "x", "--cell", "4294967328"], r"--cell must be a whole number"),
            ("sward-atlas", ["--out", "x", "--cell", "33"], r"--cell must be a power of two"),
            ("sward-atlas", ["--out", "x", "--seed", "-1"], r"--seed must be a whole number"),
            ("sward-rover", ["--out", "x", "--wheel-radius", "inf"], r"--wheel-radius must be a number"),
            ("sward-eval", ["d", "--frames", "4294967296:4294967297"], r"--frames .* start"),
            ("sward-eval", ["d", "--threads", "-1"], r"--threads must be a whole number"),
            ("sward-eval", ["d", "--bands", "5,x"], r"--bands '5,x'"),
            ("sward-eval", ["d", "--mode", "fast"], r"SGBM mode 'fast'"),
            ("sward-export", ["d", "--out", "o", "--layout", "ply", "--frames", "4294967296:4294967297"],
             r"--frames .* start"),
            ("sward-export", ["d", "--out", "o", "--layout", "blender"], r"--layout 'blender' is not a layout"),
            ("sward-export", ["d", "--out", "o", "--layout", "ply", "--point-frame", "gl"], r"--point-frame 'gl'"),
            ("sward-export", ["d", "--out", "o"], r"--layout is required"),
            ("sward-bench", [], r"a command is required"),
            ("sward-bench", ["frame", "--resolution", "4294967616x240"], r"width"),
            ("sward-bench", ["collide", "--fields", "4294967297"], r"--fields must be a whole number from 1 to 400"),
            ("sward-bench", ["dataset", "--frames", "1"], r"--frames must be a whole number from 2 to 10000"),
            ("sward-bench", ["collide", "--tick-rate", "-1"], r"--tick-rate must be a number from 0 to 1000"),
            ("merge-manifests.py", ["d", "--jobs", "-3"], r"--jobs: must be a whole number"),
        ]
        for tool, args, pattern in cases:
            with self.subTest(tool=tool, args=args):
                code, out, err = run(tool, *args)
                self.assertEqual(code, 2, err)
                self.assertEqual(out, "")
                self.assertOneErrorLine(tool, err, pattern, True)


if __name__ == "__main__":
    BIN, MERGE = sys.argv[1], sys.argv[2]
    unittest.main(argv=sys.argv[:1], verbosity=1)
