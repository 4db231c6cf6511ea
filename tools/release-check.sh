#!/usr/bin/env bash
# The release archive's acceptance check (issue 49, docs/release.md): does sward-<version>-linux-x86_64.tar.gz run
# on a machine that has nothing but Debian 12's base system, a Vulkan loader, a driver, python3 and numpy?
#
#   tools/release-check.sh ARCHIVE
#
# 1. A minimal Debian 12 root file system: `debootstrap --variant=minbase bookworm` from Debian's archive, plus only
#    libvulkan1 mesa-vulkan-drivers python3 python3-numpy (no recommends). Made once and cached in ROOT_CACHE; every
#    run works on a fresh copy of it, so nothing one run leaves behind reaches the next.
# 2. The archive is unpacked in the copy at /opt, and inside the chroot (only /proc and /dev bound in; unmounted on
#    exit, whatever happens) run: the loader check (every library each binary and the Python module load resolves,
#    and only the C library family, libstdc++ / libgcc_s and the Vulkan loader come from outside the archive),
#    sward-render of examples/meadow.json at 320x240 (one frame, lavapipe), of the GIS example (GDAL) and of the
#    LiDAR example (Embree) at 160x120, sward-eval (SGBM stereo) and sward-export (KITTI) on the meadow's output,
#    `import sward` and a 64x48 Simulator render with the chroot's python3, and `sward-bench suite --quick` where
#    the archive's sward-bench has that command. The archive of a lean build (./sward.sh package --lean) must
#    instead refuse the GIS and LiDAR renders and sward-eval, each with its one error, writing nothing.
# Each step prints its command, PASS or FAIL and its time; the exit status is 1 when any step failed, 2 on a usage
# error. Needs root (debootstrap, chroot, mount).
#
# Environment: SUITE (default bookworm; e.g. trixie checks a newer distribution: its glibc, libstdc++ and Mesa
# against the bundled libraries; the Python module then has no CPython 3.11 to load into), ROOT_CACHE (default
# /var/cache/sward-release-check/SUITE-minbase), MIRROR (default: the first Debian mirror of this machine's apt
# sources, else http://deb.debian.org/debian), WORK (the copy, default a temporary folder; removed on exit unless
# KEEP=1).
set -euo pipefail

usage() { echo "usage: tools/release-check.sh ARCHIVE (see the comment at the top of the script)" >&2; exit 2; }
[ $# = 1 ] || usage
case "$1" in -h|--help) usage ;; esac
archive=$(realpath "$1")
[ -f "$archive" ] || { echo "release-check: error: no archive '$1'" >&2; exit 2; }
[ "$(id -u)" = 0 ] || { echo "release-check: error: needs root (debootstrap, chroot, mount)" >&2; exit 2; }
for tool in debootstrap chroot mount; do
  command -v $tool >/dev/null || { echo "release-check: error: $tool missing (tools/setup-deps.sh installs it)" >&2; exit 2; }
done

suite=${SUITE:-bookworm}
cache=${ROOT_CACHE:-/var/cache/sward-release-check/$suite-minbase}
packages="libvulkan1 mesa-vulkan-drivers python3 python3-numpy"
if [ -z "${MIRROR:-}" ]; then
  MIRROR=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/* 2>/dev/null | grep -v '^ *#' \
             | grep -oE 'https?://[^ ]+/debian/?( |$)' | head -1 | tr -d ' ' || true)
  MIRROR=${MIRROR:-http://deb.debian.org/debian}
fi

start=$(date +%s)
# The cached root: debootstrap into a temporary folder, add the four packages, and only then name it the cache, so
# an interrupted run never leaves a half-made cache behind. The package list is recorded; another list remakes it.
if [ "$(cat "$cache/.sward-packages" 2>/dev/null || true)" != "$packages" ]; then
  echo "release-check: making the Debian $suite minbase root in $cache (once; from $MIRROR)"
  rm -rf "$cache.partial"
  mkdir -p "$(dirname "$cache")"
  debootstrap --variant=minbase "$suite" "$cache.partial" "$MIRROR" > "$cache.partial.log" 2>&1 \
    || { tail -20 "$cache.partial.log"; echo "release-check: error: debootstrap failed" >&2; exit 1; }
  mount -t proc proc "$cache.partial/proc"
  chroot "$cache.partial" /usr/bin/env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin DEBIAN_FRONTEND=noninteractive \
    sh -c "apt-get install -y --no-install-recommends $packages && apt-get clean" >> "$cache.partial.log" 2>&1 \
    || { umount "$cache.partial/proc"; tail -20 "$cache.partial.log"; echo "release-check: error: apt-get in the root failed" >&2; exit 1; }
  umount "$cache.partial/proc"
  echo "$packages" > "$cache.partial/.sward-packages"
  rm -rf "$cache"
  mv "$cache.partial" "$cache"
  mv "$cache.partial.log" "$cache.log"
  echo "release-check: root made in $(( $(date +%s) - start )) s, $(du -sh "$cache" | cut -f1)"
fi

work=${WORK:-$(mktemp -d /tmp/sward-release-check.XXXXXX)}
root="$work/root"
mounted=()
cleanup() {
  local m
  for m in "${mounted[@]}"; do umount -l "$m" 2>/dev/null || true; done
  [ "${KEEP:-0}" = 1 ] && { echo "release-check: kept $work"; return; }
  # Never remove a folder that still has something mounted in it (the host's /dev).
  if ! grep -q " $root/" /proc/mounts; then rm -rf "$work"; fi
}
trap cleanup EXIT
trap 'exit 130' INT TERM

rm -rf "$root"
cp -a --reflink=auto "$cache" "$root"
tar -xzf "$archive" -C "$root/opt"
release=$(cd "$root/opt" && ls -d sward-*/ | head -1)
release=/opt/${release%/}
echo "release-check: $(basename "$archive") ($(du -h "$archive" | cut -f1)) unpacked at $release in a Debian $(cat "$root/etc/debian_version") minbase root"
for m in proc dev; do
  if [ $m = proc ]; then mount -t proc proc "$root/proc"; else mount --bind /dev "$root/dev"; fi
  mounted=("$root/$m" "${mounted[@]}")
done

failures=0
# run NAME COMMAND [SHOWN]: COMMAND runs in the chroot by bash, in the release's folder, with a clean environment
# (the archive must need no LD_LIBRARY_PATH: its binaries find lib/ by their rpath); SHOWN is printed in its place.
run() {
  local name=$1 command=$2 t0 rc
  echo "\$ ${3:-$command}"
  t0=$(date +%s.%N)
  set +e
  chroot "$root" /usr/bin/env -i PATH="$release/bin:/usr/bin:/bin" HOME=/root LC_ALL=C.UTF-8 \
    bash -c "cd $release && $command" > "$work/$name.log" 2>&1
  rc=$?
  set -e
  local secs
  secs=$(awk "BEGIN { printf \"%.1f\", $(date +%s.%N) - $t0 }")
  if [ $rc = 0 ]; then
    echo "PASS $name (${secs} s)"
    tail -3 "$work/$name.log" | sed 's/^/    /'
  else
    echo "FAIL $name (exit $rc, ${secs} s); its last lines:"
    tail -15 "$work/$name.log" | sed 's/^/    /'
    failures=$((failures + 1))
  fi
}

# Every ELF file of the archive (the tools, the Python module): no library missing, and none but the allowed ones from the system.
run loader 'status=0; for f in bin/* $(find lib -name "_sward*.so"); do
  [ "$(head -c 4 "$f" | tail -c 3)" = ELF ] || continue # bin/merge-manifests.py is a Python script
  out=$(ldd "$f") || { echo "$f: ldd failed"; status=1; continue; }
  if echo "$out" | grep -q "not found"; then echo "$f:"; echo "$out" | grep "not found"; status=1; fi
  echo "$out" | awk "/=> \\// {print \$3}" | grep -v "^$PWD/" \
    | grep -vE "/(libc|libm|libpthread|libdl|librt|libresolv|libstdc\\+\\+|libgcc_s|libvulkan)\\.so" \
    | sed "s|^|$f: from the system: |" | grep . && status=1
done; exit $status' 'ldd bin/* lib/python3/dist-packages/sward/_sward*.so: nothing missing, nothing from the system but glibc, libstdc++, libgcc_s, libvulkan'
run render 'sward-render share/sward/examples/meadow.json --resolution 320x240 --frames 0:1 --out /tmp/meadow -q && ls /tmp/meadow | tr "\n" " "; echo'
# The optional parts' libraries at work: GDAL (the GIS example's GeoTIFF land cover and heightmap) and Embree (the
# LiDAR's rays). An archive of a lean build (docs/release.md, "A lean build": its bundled-libraries.txt has no GDAL,
# Embree or OpenCV) must instead refuse each with its one error, writing nothing.
bundled="$root$release/share/doc/sward/bundled-libraries.txt"
# optional NAME LIBRARY COMPONENT OPTION OUT COMMAND [THEN]: "COMMAND && THEN" as a step, or where LIBRARY is not
# bundled the step NAME-refused: COMMAND fails with the one error naming COMPONENT and OPTION, and OUT is not made.
optional() {
  if grep -q "^$2" "$bundled"; then
    run "$1" "$6${7:+ && $7}"
  else
    run "$1-refused" "! $6 2> /tmp/$1.err; cat /tmp/$1.err; grep -q 'needs $3, which this build of sward leaves out ($4=OFF)' /tmp/$1.err && [ ! -e $5 ]"
  fi
}
optional render-gis libgdal GDAL SWARD_WITH_GDAL /tmp/gis \
  'sward-render share/sward/examples/gis/gis.json --resolution 160x120 --frames 0:1 --out /tmp/gis -q'
optional render-lidar libembree Embree SWARD_WITH_EMBREE /tmp/lidar \
  'sward-render share/sward/examples/rover-lidar.json --resolution 160x120 --frames 0:1 --out /tmp/lidar -q' \
  'ls /tmp/lidar | tr "\n" " "; echo'
optional eval libopencv_core OpenCV SWARD_WITH_OPENCV /tmp/meadow-eval \
  'sward-eval /tmp/meadow --out /tmp/meadow-eval --no-pictures' 'ls /tmp/meadow-eval | tr "\n" " "; echo'
run export 'sward-export /tmp/meadow --layout kitti --out /tmp/meadow-kitti && find /tmp/meadow-kitti -type f | sort | tr "\n" " "; echo'
run python 'PYTHONPATH=$PWD/lib/python3/dist-packages python3 -c "import sward; print(sward.__version__ if hasattr(sward, \"__version__\") else \"ok\")"'
run python-render 'PYTHONPATH=$PWD/lib/python3/dist-packages python3 -c "import sward; f = sward.Simulator(\"share/sward/examples/meadow.json\", overrides={\"render.resolution\": [64, 48]}).render(); print({k: v.shape for k, v in sorted(f.items()) if hasattr(v, \"shape\")})"'
if chroot "$root" "$release/bin/sward-bench" --help 2>/dev/null | grep -qE '^ +suite '; then
  run bench-suite 'sward-bench suite --quick --out /tmp/suite'
else
  echo "(sward-bench has no 'suite' command in this archive: not run)"
fi

echo "release-check: $failures step(s) failed; $(( $(date +%s) - start )) s in all"
[ $failures = 0 ]
