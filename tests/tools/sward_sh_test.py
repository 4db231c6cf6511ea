#!/usr/bin/env python3
"""./sward.sh: --help / -h / help answer at once without setup or build, an unknown command exits 2 before setup,
`render ARGS` passes ARGS to sward-render with the default scene and --out added only where ARGS give none, and
`package [--lean]` configures build (every optional component) or build-lean (none) and runs cpack there.

    sward_sh_test.py SWARD_SH

The script runs from a copy in a temporary folder whose tools/setup-deps.sh, cmake and build/bin/sward-render
are stubs that record what they were asked to do, so nothing is installed or built. Python 3 standard library.
"""

import os
import shutil
import stat
import subprocess
import sys
import tempfile
import time
import unittest

SCRIPT = None


def write_executable(path, text):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(text)
    os.chmod(path, os.stat(path).st_mode | stat.S_IXUSR)


class SwardSh(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="sward-sh-test-")
        self.log = os.path.join(self.root, "stub.log")
        self.render_args = os.path.join(self.root, "render.args")
        shutil.copy(SCRIPT, os.path.join(self.root, "sward.sh"))
        write_executable(os.path.join(self.root, "tools", "setup-deps.sh"), f'#!/bin/sh\necho setup >> "{self.log}"\n')
        write_executable(os.path.join(self.root, "stubs", "cmake"), f'#!/bin/sh\necho "cmake $*" >> "{self.log}"\n')
        write_executable(os.path.join(self.root, "build", "bin", "sward-render"),
                         f'#!/bin/sh\nfor a in "$@"; do printf "%s\\0" "$a"; done > "{self.render_args}"\n')

    def tearDown(self):
        shutil.rmtree(self.root)

    def sward(self, *args):
        env = dict(os.environ, PATH=os.path.join(self.root, "stubs") + os.pathsep + os.environ["PATH"])
        start = time.monotonic()
        result = subprocess.run([os.path.join(self.root, "sward.sh"), *args], capture_output=True, text=True,
                                env=env, timeout=60)
        return result, time.monotonic() - start

    def stub_log(self):
        if not os.path.exists(self.log):
            return ""
        with open(self.log) as f:
            return f.read()

    def render(self, *args):
        result, _ = self.sward("render", *args)
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("setup", self.stub_log())
        self.assertIn("cmake --build", self.stub_log())
        with open(self.render_args) as f:
            return f.read().split("\0")[:-1]

    def test_help_answers_at_once_without_setup_or_build(self):
        for flag in ("--help", "-h", "help"):
            with self.subTest(flag=flag):
                result, seconds = self.sward(flag)
                self.assertEqual(result.returncode, 0, result.stderr)
                self.assertIn("usage: ./sward.sh", result.stdout)
                self.assertEqual(result.stderr, "")
                self.assertLess(seconds, 1.0)
                self.assertEqual(self.stub_log(), "", "help must not run the setup or the build")

    def test_unknown_command_exits_2_before_setup(self):
        result, _ = self.sward("rendr", "--out", "x")
        self.assertEqual(result.returncode, 2)
        self.assertEqual(result.stderr.splitlines(), ["sward.sh: error: unknown command 'rendr' (see ./sward.sh --help)"])
        self.assertEqual(self.stub_log(), "")

    def test_render_defaults_scene_and_out(self):
        self.assertEqual(self.render(), ["examples/meadow.json", "--out", "out"])

    def test_render_takes_the_users_out(self):
        self.assertEqual(self.render("--out", "my data"), ["examples/meadow.json", "--out", "my data"])
        self.assertEqual(self.render("-o", "d", "-q"), ["examples/meadow.json", "-o", "d", "-q"])
        self.assertEqual(self.render("--out=d"), ["examples/meadow.json", "--out=d"])

    def test_render_takes_the_users_scene(self):
        self.assertEqual(self.render("my.json", "--frames", "0:2"), ["--out", "out", "my.json", "--frames", "0:2"])
        self.assertEqual(self.render("--quiet", "my.json", "--out", "o"), ["--quiet", "my.json", "--out", "o"])

    def test_option_values_are_not_mistaken_for_a_scene(self):
        self.assertEqual(self.render("--resolution", "64x48", "--device", "llvmpipe"),
                         ["examples/meadow.json", "--out", "out", "--resolution", "64x48", "--device", "llvmpipe"])

    def package(self, *args):
        # cpack runs in the build folder and leaves the archive in its package/ folder.
        write_executable(os.path.join(self.root, "stubs", "cpack"),
                         f'#!/bin/sh\necho "cpack in $(basename "$PWD")" >> "{self.log}"\n'
                         'mkdir -p package && touch package/sward-0.1.0-linux-x86_64.tar.gz\n')
        return self.sward("package", *args)[0]

    def test_package_builds_every_component(self):
        result = self.package()
        self.assertEqual(result.returncode, 0, result.stderr)
        log = self.stub_log()
        self.assertIn("-B build -G Ninja", log)
        for option in ("SWARD_WITH_GDAL", "SWARD_WITH_EMBREE", "SWARD_WITH_OPENCV"):
            self.assertIn(f"-D{option}=ON", log)
        self.assertIn("cpack in build\n", log)

    def test_package_lean_leaves_out_the_optional_components_in_build_lean(self):
        os.makedirs(os.path.join(self.root, "build-lean")) # as the (stubbed) configure would make it
        result = self.package("--lean")
        self.assertEqual(result.returncode, 0, result.stderr)
        log = self.stub_log()
        self.assertIn("-B build-lean -G Ninja", log)
        for option in ("SWARD_WITH_GDAL", "SWARD_WITH_EMBREE", "SWARD_WITH_OPENCV"):
            self.assertIn(f"-D{option}=OFF", log)
        self.assertIn("cmake --build build-lean", log)
        self.assertIn("cpack in build-lean\n", log)

    def test_package_refuses_other_arguments_before_setup(self):
        result = self.package("--small")
        self.assertEqual(result.returncode, 2)
        self.assertEqual(result.stderr.splitlines(),
                         ["sward.sh: error: package takes only --lean, not '--small' (see ./sward.sh --help)"])
        self.assertEqual(self.stub_log(), "")


if __name__ == "__main__":
    SCRIPT = os.path.abspath(sys.argv[1])
    unittest.main(argv=sys.argv[:1], verbosity=1)
