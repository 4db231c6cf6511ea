"""pip's build of the package (pyproject.toml holds the metadata): the extension sward._sward is built by CMake with
the project's own build (python/CMakeLists.txt), for the Python that runs pip; python/sward/ is the package.

- By default CMake configures a private Release build in build/pip/cmake (tests off) and builds only the target
  sward_python there: the first install compiles the libraries (minutes), later ones only what changed.
- SWARD_BUILD_DIR=DIR takes the extension already built in the CMake build folder DIR (`cmake --build DIR --target
  sward_python` first) and builds nothing: `SWARD_BUILD_DIR=build pip install --no-build-isolation .` after
  `./sward.sh build` takes seconds. DIR must have been configured for the same Python version as pip's.
"""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

ROOT = pathlib.Path(__file__).resolve().parent
# setuptools' own build folders under build/pip (not build/lib, which is CMake's in the usual build folder).
PIP_BUILD = ROOT / "build" / "pip"


def cmake_version():
    """The one source of the version: CMakeLists.txt's `project(sward VERSION X.Y.Z ...)`."""
    found = re.search(r"project\(\s*sward\s+VERSION\s+([0-9]+(?:\.[0-9]+)*)", (ROOT / "CMakeLists.txt").read_text())
    if not found:
        sys.exit("setup.py: CMakeLists.txt has no 'project(sward VERSION X.Y.Z ...)'")
    return found.group(1)


def run(command):
    print("setup.py:", " ".join(command), flush=True)
    subprocess.run(command, check=True)


class CMakeBuild(build_ext):
    """Builds sward._sward with CMake (or takes it from SWARD_BUILD_DIR) and copies it where setuptools wants it."""

    def build_extension(self, ext):
        built = self.cmake_extension()
        target = pathlib.Path(self.get_ext_fullpath(ext.name))
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(built, target)

    def cmake_extension(self):
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        given = os.environ.get("SWARD_BUILD_DIR")
        if given:
            folder = pathlib.Path(given).resolve()
            if not (folder / "CMakeCache.txt").is_file():
                sys.exit(f"setup.py: SWARD_BUILD_DIR={given} is not a CMake build folder (no CMakeCache.txt)")
        else:
            folder = PIP_BUILD / "cmake"
            generator = ["-G", "Ninja"] if shutil.which("ninja") else []
            run(["cmake", "-S", str(ROOT), "-B", str(folder), *generator, "-DCMAKE_BUILD_TYPE=Release",
                 "-DSWARD_BUILD_TESTS=OFF", "-DSWARD_PYTHON=ON", f"-DPython3_EXECUTABLE={sys.executable}"])
            run(["cmake", "--build", str(folder), "--target", "sward_python"])
        built = folder / "python" / "sward" / f"_sward{suffix}"
        if not built.is_file():
            others = sorted(p.name for p in (folder / "python" / "sward").glob("_sward*"))
            sys.exit(f"setup.py: {built} does not exist (this Python needs the suffix {suffix}; the folder has "
                     f"{', '.join(others) or 'no extension'}: build the target sward_python there, configured with "
                     f"-DPython3_EXECUTABLE={sys.executable})")
        return built


PIP_BUILD.mkdir(parents=True, exist_ok=True)
setup(
    version=cmake_version(),
    ext_modules=[Extension("sward._sward", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    options={"build": {"build_base": str(PIP_BUILD.relative_to(ROOT))},
             "egg_info": {"egg_base": str(PIP_BUILD.relative_to(ROOT))}},
)
