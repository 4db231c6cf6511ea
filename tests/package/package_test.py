#!/usr/bin/env python3
"""Package.InstallAndBuildAConsumer: `cmake --install` into a temporary prefix, move the prefix elsewhere (the
package must be relocatable and must not reach back into the build tree), then build two programs against it with
find_package(sward) + sward::render and run them on SCENE: tests/package/consumer (one frame rendered headless) and
examples/host-app (the host's own Vulkan device, its object and sward's meadow in one image, validation clean).
Every tool of the build (bin/sward-*) and tools/merge-manifests.py must be installed and answer --version.

usage: package_test.py BUILD_DIR CONSUMER_SOURCE HOST_APP_SOURCE SCENE
"""
import os
import pathlib
import subprocess
import sys
import tempfile


def run(*command: str) -> str:
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"FAIL: {' '.join(command)} exited {result.returncode}\n{result.stdout}\n{result.stderr}")
    return result.stdout


def main() -> int:
    build, consumer, host_app, scene = (pathlib.Path(a).resolve() for a in sys.argv[1:5])
    with tempfile.TemporaryDirectory(prefix="sward-package-") as tmp:
        staged, prefix = pathlib.Path(tmp, "staged"), pathlib.Path(tmp, "prefix")
        run("cmake", "--install", str(build), "--prefix", str(staged))
        staged.rename(prefix)  # relocated: nothing may point at the staging path
        for header in ("engine/context.h", "render/scene_gpu.h", "common/error.h", "shared/config.h"):
            if not (prefix / "include/sward" / header).is_file():
                sys.exit(f"FAIL: include/sward/{header} not installed")
        for text_file in (prefix / "lib/cmake/sward").iterdir():
            text = text_file.read_text()
            for tree in (str(build), str(pathlib.Path(__file__).resolve().parents[2]), str(staged)):
                if tree in text:
                    sys.exit(f"FAIL: {text_file.name} names {tree}")
        for source, program in ((consumer, "consumer"), (host_app, "host-app")):
            out = pathlib.Path(tmp, program + "-build")
            run("cmake", "-S", str(source), "-B", str(out), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                f"-DCMAKE_PREFIX_PATH={prefix}")
            run("cmake", "--build", str(out))
            print(run(str(out / program), str(scene)).strip())
        # Every tool the build makes (bin/sward-*) and the shard merge the docs call is installed and runs.
        tools = sorted(p.name for p in (build / "bin").glob("sward-*") if os.access(p, os.X_OK))
        for tool in tools + ["merge-manifests.py"]:
            if not (prefix / "bin" / tool).is_file():
                sys.exit(f"FAIL: bin/{tool} not installed")
            print(run(str(prefix / "bin" / tool), "--version").strip())
        # The Python module from the prefix (its numpy is Debian's, as for the build tree's).
        site = prefix / "lib/python3/dist-packages"
        print(run("env", f"PYTHONPATH={site}", sys.executable, "-c",
                  "import sward; print('python: sward', sward.__version__, 'from', sward.__file__)").strip())
        for typing_file in ("__init__.pyi", "py.typed"):  # the stubs type checkers read (docs/python.md)
            if not (site / "sward" / typing_file).is_file():
                sys.exit(f"FAIL: lib/python3/dist-packages/sward/{typing_file} not installed")
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
