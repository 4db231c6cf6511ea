#!/usr/bin/env python3
"""Tests of tools/merge-manifests.py on hand-made two-shard datasets. Usage: merge_manifests_test.py SCRIPT"""

import hashlib
import json
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = None  # set from argv


def sha(data):
    return hashlib.sha256(data).hexdigest()


class Dataset:
    """A fake 4-frame dataset rendered as shards 0/2 (frames 0, 1) and 1/2 (frames 2, 3)."""

    def __init__(self, root):
        self.root = root
        self.manifests = {}
        base = {"format": "sward-dataset-1", "scene": "examples/rover-track.json", "scene_sha256": sha(b"scene"),
                "seed": 7, "options": {"resolution": [64, 48], "samples": 4, "no_vegetation": False},
                "sward_revision": "0123abc", "device": "llvmpipe", "driver": "Mesa 22.3.6",
                "fingerprint": {"scene_sha256": sha(b"scene"), "seed": 7, "resolution": "64x48", "samples": 4,
                                "no_vegetation": False, "sward_revision": "0123abc", "device": "llvmpipe",
                                "driver": "Mesa 22.3.6"}}
        for shard, (a, b) in enumerate([(0, 2), (2, 4)]):
            files = {"calib.txt": self.write("calib.txt", b"cam0=[50 0 32; 0 50 24; 0 0 1]\n")}
            lines = b"".join(b'{"frame": %d, "tick": %d}\n' % (f, 2 * f) for f in range(a, b))
            files[f"frames.shard-{shard}-of-2.jsonl"] = self.write(f"frames.shard-{shard}-of-2.jsonl", lines)
            for f in range(a, b):
                for name in (f"left/{f:06d}.exr", f"depth/{f:06d}.exr", f"disparity/{f:06d}.png"):
                    files[name] = self.write(name, f"{name} content".encode())
            self.manifests[shard] = dict(base, frames=[a, b], shard=f"{shard}/2", files=files,
                                         fingerprint=dict(base["fingerprint"]))
        self.save()

    def write(self, name, data):
        path = os.path.join(self.root, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb") as f:
            f.write(data)
        return sha(data)

    def save(self):
        for shard, manifest in self.manifests.items():
            with open(os.path.join(self.root, f"manifest.shard-{shard}-of-2.json"), "w") as f:
                json.dump(manifest, f, indent=2)

    def merge(self, *extra):
        run = subprocess.run([sys.executable, SCRIPT, self.root, *extra], capture_output=True, text=True)
        return run.returncode, run.stdout + run.stderr

    def merged(self):
        with open(os.path.join(self.root, "manifest.json")) as f:
            return json.load(f)


class MergeManifestsTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.data = Dataset(self.tmp.name)

    def tearDown(self):
        self.tmp.cleanup()

    def assertFails(self, expected_message, *extra):
        code, output = self.data.merge(*extra)
        self.assertEqual(code, 1, output)
        self.assertIn(expected_message, output)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "manifest.json")), "wrote a manifest anyway")

    def test_merges_two_shards_into_the_full_run_manifest(self):
        code, output = self.data.merge("--verify")
        self.assertEqual(code, 0, output)
        merged = self.data.merged()
        self.assertIsNone(merged["shard"])
        self.assertEqual(merged["frames"], [0, 4])
        with open(os.path.join(self.tmp.name, "frames.jsonl"), "rb") as f:
            self.assertEqual(f.read(), b"".join(b'{"frame": %d, "tick": %d}\n' % (n, 2 * n) for n in range(4)))
        # What a single full run would have written: every frame file, calib.txt once, one frames.jsonl.
        expected = {name: digest for m in self.data.manifests.values() for name, digest in m["files"].items()
                    if ".shard-" not in name}
        expected["frames.jsonl"] = sha(b"".join(b'{"frame": %d, "tick": %d}\n' % (n, 2 * n) for n in range(4)))
        self.assertEqual(merged["files"], expected)
        for key in ("format", "scene", "scene_sha256", "seed", "options", "sward_revision", "device", "driver",
                    "fingerprint"):
            self.assertEqual(merged[key], self.data.manifests[0][key], key)
        # The merged manifest verifies on its own (no shard manifests left).
        for shard in (0, 1):
            os.remove(os.path.join(self.tmp.name, f"manifest.shard-{shard}-of-2.json"))
        code, output = self.data.merge("--verify")
        self.assertEqual(code, 0, output)

    def test_verify_detects_a_changed_file(self):
        self.data.write("depth/000003.exr", b"bit rot")
        code, output = self.data.merge()  # existence only: passes
        self.assertEqual(code, 0, output)
        os.remove(os.path.join(self.tmp.name, "manifest.json"))
        self.assertFails("depth/000003.exr: SHA-256", "--verify")

    def test_missing_file_on_disk(self):
        os.remove(os.path.join(self.tmp.name, "left", "000001.exr"))
        self.assertFails("left/000001.exr is listed but missing on disk")

    def test_frame_file_listed_by_two_shards(self):
        self.data.manifests[1]["files"]["left/000001.exr"] = self.data.manifests[0]["files"]["left/000001.exr"]
        self.data.save()
        self.assertFails("left/000001.exr is listed by both")

    def test_frame_file_missing_from_every_manifest(self):
        del self.data.manifests[1]["files"]["disparity/000002.png"]
        self.data.save()
        self.assertFails("disparity/000002.png is missing")

    def test_missing_shard(self):
        os.remove(os.path.join(self.tmp.name, "manifest.shard-1-of-2.json"))
        self.assertFails("missing shard(s) 1 of 2")

    def test_frame_gap(self):
        self.data.manifests[1]["frames"] = [3, 4]
        for name in [n for n in self.data.manifests[1]["files"] if "000002" in n]:
            del self.data.manifests[1]["files"][name]
        self.data.save()
        self.assertFails("frames [2, 3) are in no shard")

    def test_shards_of_different_runs(self):
        self.data.manifests[1]["seed"] = 8
        self.data.save()
        self.assertFails("'seed' differs")

    def test_shards_with_different_fingerprints(self):
        self.data.manifests[1]["fingerprint"]["resolution"] = "200x150"
        self.data.save()
        self.assertFails("fingerprint 'resolution' differs")

    def test_shard_without_a_fingerprint(self):
        del self.data.manifests[1]["fingerprint"]
        self.data.save()
        self.assertFails("manifest lacks fingerprint")

    def test_dataset_description_with_another_fingerprint(self):
        other = dict(self.data.manifests[0]["fingerprint"], no_vegetation=True)
        self.data.write("dataset.json", json.dumps({"format": "sward-dataset-1", "fingerprint": other}).encode())
        self.assertFails("fingerprint 'no_vegetation' differs from")

    def test_shards_from_machines_with_other_devices_merge_with_a_warning(self):
        self.data.manifests[1]["device"] = self.data.manifests[1]["fingerprint"]["device"] = "RTX"
        self.data.save()
        code, output = self.data.merge()
        self.assertEqual(code, 0, output)
        self.assertIn("warning: shards ran with different devices", output)
        self.assertEqual(self.data.merged()["fingerprint"]["device"], ["RTX", "llvmpipe"])
        self.assertEqual([n for n in os.listdir(self.tmp.name) if n.endswith(".tmp")], [])

    def test_shared_file_with_different_content(self):
        self.data.manifests[1]["files"]["calib.txt"] = sha(b"another rig")
        self.data.save()
        self.assertFails("calib.txt differs between")

    def add_backward_flow(self, frames):
        for shard, manifest in self.data.manifests.items():
            a, b = manifest["frames"]
            for f in range(a, b):
                if f in frames:
                    name = f"flow_backward/{f:06d}.flo"
                    manifest["files"][name] = self.data.write(name, f"{name} content".encode())
        self.data.save()

    def test_sharded_flow_dataset_without_backward_flow_at_frame_0_merges(self):
        self.add_backward_flow({1, 2, 3})  # frame 0 has no previous frame: no backward flow by design
        code, output = self.data.merge("--verify")
        self.assertEqual(code, 0, output)
        self.assertIn("flow_backward/000003.flo", self.data.merged()["files"])

    def test_lost_backward_flow_of_a_later_frame_is_still_missing(self):
        self.add_backward_flow({1, 3})
        self.assertFails("flow_backward/000002.flo is missing")

    def test_malformed_manifest(self):
        with open(os.path.join(self.tmp.name, "manifest.shard-1-of-2.json"), "w") as f:
            f.write("{ not json")
        self.assertFails("manifest.shard-1-of-2.json: cannot read manifest")


if __name__ == "__main__":
    SCRIPT = sys.argv.pop(1)
    unittest.main()
