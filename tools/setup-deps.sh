#!/usr/bin/env bash
# Installs every Debian package sward's build, tests and tools need. Idempotent and fast when everything is
# already there: it asks dpkg first and only runs apt-get for what is missing.
set -euo pipefail

packages=(
  # toolchain
  g++ cmake ninja-build pkg-config git python3
  # the sanitizer + fuzzing build (tools/sanitize-and-fuzz.sh): clang, its ASan/UBSan/libFuzzer runtimes (only
  # recommended by clang, so named here) and llvm-symbolizer (package llvm) for source lines in reports
  clang libclang-rt-14-dev llvm
  # Vulkan: loader + headers, lavapipe (Mesa's CPU driver), validation layers, shader compiler, vulkaninfo
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers glslang-tools vulkan-tools
  # maths, windowing, assets, image formats
  libglm-dev libglfw3-dev libtinygltf-dev libstb-dev libopenexr-dev libpng-dev
  # SQLite: sward-export's COLMAP database.db; COLMAP itself runs the export's test (tests/tools/sward-export)
  libsqlite3-dev colmap
  # GIS rasters: GDAL reads land-cover maps and heightmaps (io/raster_file); the build writes the example worlds'
  # GeoTIFFs with gdal-bin's gdal_translate (tools/make-example-data.py)
  libgdal-dev gdal-bin
  # ray casting of the range sensors (range/ray_scene): Intel's Embree 3
  libembree-dev
  # OpenCV modules used by tests and sward-eval (the per-module packages avoid 40+ unrelated ones); features2d: the
  # detectors of sward-eval odometry (ORB, AKAZE, SIFT); video: the optical-flow baselines of sward-eval flow (DIS,
  # Farneback)
  libopencv-core-dev libopencv-imgproc-dev libopencv-imgcodecs-dev libopencv-features2d-dev libopencv-calib3d-dev
  libopencv-video-dev
  # configuration, command line, UI
  nlohmann-json3-dev libcli11-dev libimgui-dev
  # the Python module (python/): pybind11 and numpy; its tests run under pytest
  pybind11-dev python3-dev python3-numpy python3-pytest
  # `pip install .` of the checkout (pyproject.toml, setup.py: offline, --no-build-isolation) and its check under
  # Debian's mypy --strict (tests/python/pip_install.py)
  python3-setuptools python3-wheel python3-pip python3-venv mypy
  # a compiler cache (sward.sh and the sanitizer build use it when present)
  ccache
  # tests and benchmarks; a virtual X server for the viewer test; strace for the open-tracing test
  # (tests/tools/sward-render/open_trace_test.py: no file outside the scene's folder is opened)
  libgtest-dev libgmock-dev libbenchmark-dev xvfb xauth strace
  # sward-export's point clouds read back by Open3D (tests/tools/sward-export/open3d_test.py; brings numpy)
  python3-open3d
  # scale-out tests (tests/scale-out): a private single-node Slurm, and the Kubernetes manifest check (YAML in
  # Python, TypeScript run by Node.js)
  slurm-wlm munge python3-yaml nodejs
  # the release archive's check (tools/release-check.sh): a minimal Debian 12 root file system to run it in
  debootstrap
  # sward-bench suite's test: suite.json validated against docs/suite.schema.json (tests/tools/sward-bench)
  python3-jsonschema
)
# A Node.js from another source (e.g. NodeSource) brings its own npm; Debian's npm would conflict with it.
command -v npm >/dev/null || packages+=(npm)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${db:Status-Status}' "$p" 2>/dev/null || true)
  [ "$status" = "installed" ] || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  echo "setup: all ${#packages[@]} packages present"
else
  sudo=""
  [ "$(id -u)" -eq 0 ] || sudo="sudo"
  echo "setup: installing ${missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi

# npm packages of the Kubernetes manifest check, exactly as its package-lock.json pins them (versions and
# hashes); the test then runs offline. Skipped when node_modules was installed from the same lock file.
k8s="$(cd "$(dirname "$0")/.." && pwd)/tests/scale-out/k8s"
if ! cmp -s "$k8s/package-lock.json" "$k8s/node_modules/.sward-installed-lock.json"; then
  echo "setup: npm ci in $k8s"
  npm ci --prefix "$k8s" --no-audit --no-fund --loglevel=error
  cp "$k8s/package-lock.json" "$k8s/node_modules/.sward-installed-lock.json"
fi

# npm packages of the ROS 2 bag check (tests/tools/sward-export/ros2_bag_test.cpp: Foxglove's MCAP reader and ROS 2
# message decoders read sward-export --layout ros2), pinned and installed the same way.
mcap="$(cd "$(dirname "$0")/.." && pwd)/tests/tools/sward-export/mcap"
if ! cmp -s "$mcap/package-lock.json" "$mcap/node_modules/.sward-installed-lock.json"; then
  echo "setup: npm ci in $mcap"
  npm ci --prefix "$mcap" --no-audit --no-fund --loglevel=error
  cp "$mcap/package-lock.json" "$mcap/node_modules/.sward-installed-lock.json"
fi
