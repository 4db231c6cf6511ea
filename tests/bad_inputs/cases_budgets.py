"""Budgets before work (issue 45): small inputs within the old limits that cost gigabytes or hours. Each is now
priced from its header or its counts and refused with one line naming the key, the estimate and the limit.

The big-but-small inputs are made here in microseconds: an all-zero PNG's deflate stream is one compressed block
repeated (full flushes make the blocks independent) and its Adler-32 is known in closed form; a TIFF states its
size in a header of 150 bytes."""

import base64
import json
import struct
import zlib

from cases import Case, scene_with, set_key, triangle_gltf


def zero_png(width, height, colour_type, bits=8):
    """An all-zero PNG (colour type 0 grey, 2 RGB, 6 RGBA; 8 or 16 bits) of any size: about 1 KB of deflate per 1 MB
    of pixels."""
    channels = {0: 1, 2: 3, 6: 4}[colour_type]
    row = b"\0" * (1 + width * channels * bits // 8)  # filter byte 0, zero samples
    rows_per_block = max(1, (1 << 22) // len(row))
    blocks, rest = divmod(height, rows_per_block)
    first = zlib.compressobj(9, zlib.DEFLATED, -15)
    block = first.compress(row * rows_per_block) + first.flush(zlib.Z_FULL_FLUSH)
    last = zlib.compressobj(9, zlib.DEFLATED, -15)
    tail = last.compress(row * rest) + last.flush()
    length = len(row) * height
    adler = ((length % 65521) << 16) | 1  # every byte 0: a stays 1, b sums it once a byte
    idat = b"\x78\xda" + block * blocks + tail + struct.pack(">I", adler)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
    header = struct.pack(">IIBBBBB", width, height, bits, colour_type, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", idat) + chunk(b"IEND", b"")


def claimed_tiff(width, height):
    """A 132-byte deflate GeoTIFF whose header states width x height 8-bit pixels in one strip of 10 bytes."""
    entries = [(256, 4, width), (257, 4, height), (258, 3, 8), (259, 3, 8), (262, 3, 1), (273, 4, 0),
               (277, 3, 1), (278, 4, height), (279, 4, 10)]
    data_at = 8 + 2 + 12 * len(entries) + 4
    ifd = struct.pack("<H", len(entries))
    for tag, kind, value in entries:
        value = data_at if tag == 273 else value
        ifd += struct.pack("<HHI", tag, kind, 1) + (struct.pack("<HH", value, 0) if kind == 3 else struct.pack("<I", value))
    return b"II*\0" + struct.pack("<I", 8) + ifd + struct.pack("<I", 0) + zlib.compress(b"\0" * 64)[:10]


def with_file(name, make, edit):
    """edit, after writing make() (made only when the case runs) to `name`."""
    def both(scene, env):
        env.write(name, make())
        edit(scene, env)
    return both


def textured_ground(make_png, materials):
    """The tiny scene on the one-triangle ground whose `materials` materials each use their own texture of one
    image, tex.png (make_png())."""
    def edit(scene, env):
        env.write("tex.png", make_png())
        gltf = triangle_gltf()
        gltf["images"] = [{"uri": "tex.png"}]
        gltf["textures"] = [{"source": 0} for _ in range(materials)]
        gltf["materials"] = [{"name": f"m{i}", "pbrMetallicRoughness": {"baseColorTexture": {"index": i}}}
                             for i in range(materials)]
        primitive = gltf["meshes"][0]["primitives"][0]
        gltf["meshes"][0]["primitives"] = [dict(primitive, material=i) for i in range(materials)]
        env.write("ground.gltf", json.dumps(gltf))
        scene["terrain"] = {"mesh": {"file": "ground.gltf"}}
    return edit


def instanced_ground(nodes, triangles):
    """The tiny scene on a ground whose one mesh of `triangles` (degenerate) triangles is used by `nodes` nodes."""
    def edit(scene, env):
        gltf = triangle_gltf()
        positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
        data = positions + b"\0\0" * (3 * triangles)
        gltf["buffers"] = [{"byteLength": len(data),
                            "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}]
        gltf["bufferViews"][1]["byteLength"] = 6 * triangles
        gltf["accessors"][1]["count"] = 3 * triangles
        gltf["nodes"] = [{"mesh": 0} for _ in range(nodes)]
        gltf["scenes"] = [{"nodes": list(range(nodes))}]
        env.write("ground.gltf", json.dumps(gltf))
        scene["terrain"] = {"mesh": {"file": "ground.gltf"}}
    return edit


def many_colliders(count):
    """The scene's text with `count` colliders, joined as text (json.dumps of 10^6 objects takes seconds)."""
    def edit(scene, env):
        scene["colliders"] = []
        text = json.dumps(scene)
        items = ",".join(['{"centre": [50, 50, 0]}'] * count)
        return text.replace('"colliders": []', '"colliders": [' + items + "]", 1)
    return edit


TOF_4096 = {"type": "tof", "resolution": [4096, 4096], "mount": {"position": [50, 50, 0]}}

CASES = [
    Case("grass_map 1 MB PNG of 16384x16384", "sward-render",
         scene_with(with_file("map.png", lambda: zero_png(16384, 16384, 2), set_key(["grass_map"], "map.png"))), 1,
         r"map\.png' \(16384x16384, 3 channels\) would take 3840 MiB decoded, over the limit of 2048 MiB"),
    Case("heightmap TIFF of 150 bytes claiming 16384x16384", "sward-render",
         scene_with(with_file("dem.tif", lambda: claimed_tiff(16384, 16384),
                              set_key(["terrain"], {"heightmap": {"file": "dem.tif", "metres_per_pixel": 1}}))), 1,
         r"'terrain\.heightmap'.*dem\.tif' has size 16384x16384: 268435456 pixels, over the limit of 67108864"),
    Case("heightmap 16-bit PNG of 8192x8192", "sward-render",
         scene_with(with_file("dem.png", lambda: zero_png(8192, 8192, 0, 16),
                              set_key(["terrain"], {"heightmap": {"file": "dem.png", "metres_per_pixel": 0.05}}))), 1,
         r"'terrain\.heightmap'.*dem\.png' has 8192x8192 = 67108864 samples: its ground would take about 6144 MiB, "
         r"over the limit of 16785409 samples \(4097x4097\)"),
    Case("land_cover TIFF of 150 bytes claiming 16384x16384", "sward-render",
         scene_with(with_file("cover.tif", lambda: claimed_tiff(16384, 16384),
                              set_key(["land_cover"], {"file": "cover.tif", "preset": "esa_worldcover"}))), 1,
         r"'land_cover'.*cover\.tif' has size 16384x16384: 268435456 pixels, over the limit of 67108864"),
    Case("ground texture of 16384x16384", "sward-render", scene_with(textured_ground(lambda: zero_png(16384, 16384, 6), 1)),
         1, r"tex\.png' has size 16384x16384; each edge must be 1\.\.8192 pixels"),
    # Decoded once for all 20 straight to 8-bit RGBA (20 copies took 5.9 GB); the one-triangle ground is then
    # refused as before.
    Case("ground texture of 8192x8192 used by 20 materials", "sward-render",
         scene_with(textured_ground(lambda: zero_png(8192, 8192, 6), 20)), 1, r"ground\.gltf"),
    Case("ground mesh used by 100,000 nodes", "sward-render", scene_with(instanced_ground(100000, 1000)), 1,
         r"ground\.gltf': 100000 mesh instances \(nodes\) would flatten into 100000000 triangles and 300000 "
         r"vertices, over the limit of 16777216 of each"),
    Case("world budget of 1 TiB", "sward-render",
         scene_with(set_key(["world"], {"tiles": [16, 16], "memory_budget_mib": 1048576})), 1,
         r"'world\.memory_budget_mib' \(1048576 MiB\) is more than this machine's memory \(\d+ MiB\)"),
    Case("range sensors of 5 x 10^7 rays a frame", "sward-render",
         scene_with(set_key(["range_sensors"], [dict(TOF_4096, name=f"tof{i}") for i in range(3)])), 1,
         r"'range_sensors' cast 50331648 rays a frame \(beams x 'sub_rays', all sensors\), over the limit of 33554432"),
    Case("render.resolution 16384x16384", "sward-render",
         scene_with(set_key(["render", "resolution"], [16384, 16384])), 1,
         r"'render\.resolution' 16384x16384 is 268435456 pixels \(about \d+ MiB of render images\), over the limit "
         r"of 67108864"),
    # 22 MB of JSON: parsed in linear time (200,000 took 20.7 s), then refused by its count.
    Case("10^6 colliders", "sward-render", scene_with(many_colliders(1000000)), 1,
         r"'colliders' has 1000000 entries, over the limit of 100000"),
]
