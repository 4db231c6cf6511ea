"""`pip install .` of the checkout as a user does it (docs/python.md, "Installing with pip"), offline: a fresh venv of
Debian's Python with its site packages (numpy, pip, setuptools, mypy), `pip install --no-build-isolation --no-index
.` (and `pip wheel .`: one wheel of the version, the stubs in it), then from another folder `import sward` has the
project's version as __version__ and as its package metadata, the stubs and py.typed are installed, and Debian's
mypy --strict accepts a user script typed against them while refusing one with a type error; the accepted script
then runs on the installed package (a 64x48 frame).

The extension is not compiled again: SWARD_BUILD_DIR (setup.py) points pip at the CMake build folder that built it,
so the test takes seconds; the default path of setup.py (its own CMake build) compiles the same target.

A SWARD_BUILD_DIR that is no CMake build folder is refused first, naming it.

usage: pip_install.py SOURCE_DIR BUILD_DIR VERSION   (run by CTest as Python.PipInstall, with /usr/bin/python3)
"""
import os
import pathlib
import subprocess
import sys
import tempfile
import time
import zipfile

GOOD = """\
import numpy as np
import numpy.typing as npt
import sward

def felled_pixels(sim: sward.Simulator) -> int:
    frame = sim.render()
    semantic: npt.NDArray[np.uint8] = frame["semantic"]
    return int((semantic == sward.SEMANTIC_CLASSES["felled"]).sum())

def first_depth(path: str) -> float:
    data = sward.Dataset(path, int_dtype="int64")
    part: sward.Dataset = data[1:3]
    item = part[np.int64(0)]
    return float(item["depth"].mean()) + len(data.classes)

with sward.Simulator(None, overrides={"render.resolution": [64, 48]}, seed=7) as sim:
    sim.step(2)
    sim.set_camera(position=[0.0, 0.0, 2.0], look_at=[1.0, 0.0, 0.0], fov=60)
    print(felled_pixels(sim), sim.classes["grass"], repr(sim))
try:
    sward.write_dataset("scene.json", "out", frames="0:2", overwrite=True, progress=lambda done, total: None)
except sward.Error as e:
    print(e)
version: str = sward.__version__
"""
BAD = 'import sward\nsward.Simulator().step("2")\n'


def run(command, **kwargs):
    started = time.monotonic()
    result = subprocess.run(command, capture_output=True, text=True, **kwargs)
    print(f"{time.monotonic() - started:5.1f} s  {' '.join(map(str, command))}", flush=True)
    return result


def check(result, what):
    if result.returncode != 0:
        sys.exit(f"FAIL: {what} (exit {result.returncode})\n{result.stdout}\n{result.stderr}")


def main():
    source, build, version = sys.argv[1], sys.argv[2], sys.argv[3]
    env = {k: v for k, v in os.environ.items() if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV")}
    env["SWARD_BUILD_DIR"] = build
    with tempfile.TemporaryDirectory(prefix="sward-pip-") as tmp:
        tmp = pathlib.Path(tmp)
        check(run([sys.executable, "-m", "venv", "--system-site-packages", "--without-pip", tmp / "venv"]), "venv")
        python = str(tmp / "venv" / "bin" / "python")
        nowhere = run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--quiet", source],
                      env={**env, "SWARD_BUILD_DIR": str(tmp / "nowhere")}, cwd=tmp)
        said = nowhere.stdout + nowhere.stderr
        if nowhere.returncode == 0 or "is not a CMake build folder (no CMakeCache.txt)" not in said:
            sys.exit(f"FAIL: SWARD_BUILD_DIR of no build was not refused by name:\n{nowhere.stdout}{nowhere.stderr}")
        check(run([python, "-m", "pip", "install", "--no-build-isolation", "--no-index", "--quiet",
                   source], env=env, cwd=tmp), "pip install --no-build-isolation .")
        check(run([python, "-m", "pip", "wheel", "--no-build-isolation", "--no-index", "--no-deps", "--quiet",
                   "--wheel-dir", tmp / "wheels", source], env=env, cwd=tmp), "pip wheel --no-build-isolation .")
        wheels = list((tmp / "wheels").glob(f"sward-{version}-*.whl"))
        stubs = {"sward/__init__.pyi", "sward/py.typed"}
        if len(wheels) != 1 or not stubs <= set(zipfile.ZipFile(wheels[0]).namelist()):
            sys.exit(f"FAIL: pip wheel made {[w.name for w in wheels]}, not one sward-{version} wheel with the stubs")
        shown = run([python, "-c", "import importlib.metadata as m, sward, sys; "
                     "print(sward.__version__, m.version('sward'), sward.__file__.startswith(sys.prefix))"],
                    env=env, cwd=tmp)
        check(shown, "import sward from another folder")
        if shown.stdout.split() != [version, version, "True"]:
            sys.exit(f"FAIL: version / metadata / location: {shown.stdout!r}, expected {version} twice from the venv")
        files = run([python, "-c", "import importlib.metadata as m; "
                     "print(' '.join(sorted(str(f) for f in m.files('sward'))))"], env=env, cwd=tmp)
        check(files, "importlib.metadata.files")
        for name in ("sward/__init__.py", "sward/__init__.pyi", "sward/py.typed"):
            if name not in files.stdout.split():
                sys.exit(f"FAIL: the installed package lacks {name}: {files.stdout}")
        (tmp / "good.py").write_text(GOOD)
        (tmp / "bad.py").write_text(BAD)
        mypy = [python, "-m", "mypy", "--strict", "--cache-dir", str(tmp / "mypy-cache")]
        check(run([*mypy, "good.py"], env=env, cwd=tmp), "mypy --strict on a script using the stubs")
        bad = run([*mypy, "bad.py"], env=env, cwd=tmp)
        if bad.returncode == 0 or 'incompatible type "str"' not in bad.stdout:
            sys.exit(f"FAIL: mypy --strict accepted step('2'):\n{bad.stdout}\n{bad.stderr}")
        # and the script runs on the installed package: a 64x48 frame of the built-in scene, its classes by name
        ran = run([python, "good.py"], env=env, cwd=tmp)
        check(ran, "the typed script on the installed package")
        if "<sward.Simulator of the built-in scene, 64x48" not in ran.stdout or "scene.json" not in ran.stdout:
            sys.exit(f"FAIL: the script's output: {ran.stdout!r}")
    print(f"ok: pip install of sward {version}, metadata, stubs under mypy --strict")


if __name__ == "__main__":
    main()
