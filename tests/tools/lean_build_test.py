#!/usr/bin/env python3
"""A lean build (SWARD_WITH_GDAL, SWARD_WITH_EMBREE and SWARD_WITH_OPENCV OFF; docs/release.md, "A lean build")
refuses what needs a left-out component with exit 1 and one stderr line naming the input, the component and its
option, and writes nothing: a GeoTIFF heightmap and a land-cover raster (GDAL), range sensors (Embree), sward-eval
(OpenCV). Registered only in lean builds (tests/CMakeLists.txt).

    lean_build_test.py BIN_DIR EXAMPLES_BUILD_DIR

Python 3 standard library only; no GPU: every case fails while the scene is read, before a device is opened.
"""

import json
import os
import shutil
import subprocess
import sys
import tempfile
import unittest

BIN = BUILT_EXAMPLES = None


class LeanBuild(unittest.TestCase):
    def setUp(self):
        self.dir = tempfile.mkdtemp(prefix="sward-lean-test-")
        self.out = os.path.join(self.dir, "out")

    def tearDown(self):
        shutil.rmtree(self.dir)

    def refused(self, tool, args, line):
        result = subprocess.run([os.path.join(BIN, tool), *args], capture_output=True, text=True, timeout=60)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertEqual(result.stderr.splitlines(), [line])
        self.assertFalse(os.path.exists(self.out), "a refused run must write nothing")

    def scene_in_dir(self, scene, files):
        """The scene written into the temporary folder with the example files it names."""
        for source in files:
            shutil.copy(source, self.dir)
        path = os.path.join(self.dir, "scene.json")
        with open(path, "w") as f:
            json.dump(scene, f)
        return path

    def test_a_geotiff_heightmap_needs_gdal(self):
        scene = os.path.join(BUILT_EXAMPLES, "gis", "gis.json")
        self.refused("sward-render", [scene, "--out", self.out],
                     f"sward-render: error: {scene}: 'terrain.heightmap.file' needs GDAL, which this build of sward "
                     "leaves out (SWARD_WITH_GDAL=OFF)")

    def test_a_land_cover_raster_needs_gdal(self):
        path = self.scene_in_dir({"land_cover": {"file": "landcover.tif", "preset": "esa_worldcover"},
                                  "render": {"resolution": [64, 48]}},
                                 [os.path.join(BUILT_EXAMPLES, "gis", "landcover.tif")])
        self.refused("sward-render", [path, "--out", self.out],
                     f"sward-render: error: {path}: 'land_cover.file' needs GDAL, which this build of sward leaves "
                     "out (SWARD_WITH_GDAL=OFF)")

    def test_range_sensors_need_embree(self):
        path = self.scene_in_dir({"range_sensors": [{"name": "lidar", "preset": "VLP-16"}],
                                  "render": {"resolution": [64, 48]}}, [])
        self.refused("sward-render", [path, "--out", self.out],
                     f"sward-render: error: {path}: 'range_sensors' needs Embree, which this build of sward leaves "
                     "out (SWARD_WITH_EMBREE=OFF)")

    def test_sward_eval_needs_opencv(self):
        self.refused("sward-eval", [self.dir, "--out", self.out],
                     "sward-eval: error: sward-eval needs OpenCV, which this build of sward leaves out "
                     "(SWARD_WITH_OPENCV=OFF)")

    def test_a_png_heightmap_needs_no_gdal(self):
        # A PNG heightmap is read without GDAL: this 8-bit one gets the heightfield reader's own refusal.
        path = self.scene_in_dir({"terrain": {"heightmap": {"file": "rock.png", "metres_per_pixel": 1.0}},
                                  "render": {"resolution": [64, 48]}},
                                 [os.path.join(BUILT_EXAMPLES, "hills", "rock.png")])
        result = subprocess.run([os.path.join(BIN, "sward-render"), path, "--out", self.out],
                                capture_output=True, text=True, timeout=120)
        self.assertEqual(result.returncode, 1, result.stderr)
        self.assertNotIn("GDAL", result.stderr)
        self.assertIn("is an 8-bit PNG", result.stderr)


if __name__ == "__main__":
    BIN, BUILT_EXAMPLES = (os.path.abspath(a) for a in sys.argv[1:3])
    unittest.main(argv=sys.argv[:1], verbosity=1)
