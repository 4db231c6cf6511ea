#!/usr/bin/env python3
"""Writes the seed corpora of the fuzz targets into fuzz/corpus/<target>/ (standard library only).

The seeds are committed; this script documents how each was made and remakes them: scenes come from examples/ and
the test scenes, the binary formats are written here, tiny and valid (a few invalid-but-close ones too), so that
libFuzzer starts deep in each parser instead of at its magic number. Run from anywhere: fuzz/make-seeds.py
"""
import base64
import json
import pathlib
import shutil
import struct
import zlib

ROOT = pathlib.Path(__file__).resolve().parent.parent
CORPUS = ROOT / "fuzz" / "corpus"


def put(target, name, data):
    folder = CORPUS / target
    folder.mkdir(parents=True, exist_ok=True)
    (folder / name).write_bytes(data if isinstance(data, bytes) else data.encode())


def png(width, height, bit_depth, color_type, rows, palette=None):
    """rows: packed sample bytes per row (no filter byte)."""
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    raw = b"".join(b"\0" + r for r in rows)
    out = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, bit_depth, color_type, 0, 0, 0))
    if palette:
        out += chunk(b"PLTE", palette)
    return out + chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")


def exr(width, height, channels, pixel_type=2):
    """Uncompressed scanline OpenEXR; channels: names; pixel_type 1 half, 2 float."""
    def attr(name, kind, body):
        return name.encode() + b"\0" + kind.encode() + b"\0" + struct.pack("<i", len(body)) + body
    size = 2 if pixel_type == 1 else 4
    chlist = b"".join(c.encode() + b"\0" + struct.pack("<iB3xii", pixel_type, 0, 1, 1) for c in sorted(channels)) + b"\0"
    box = struct.pack("<iiii", 0, 0, width - 1, height - 1)
    header = (b"\x76\x2f\x31\x01" + struct.pack("<i", 2) + attr("channels", "chlist", chlist) +
              attr("compression", "compression", b"\0") + attr("dataWindow", "box2i", box) +
              attr("displayWindow", "box2i", box) + attr("lineOrder", "lineOrder", b"\0") +
              attr("pixelAspectRatio", "float", struct.pack("<f", 1)) +
              attr("screenWindowCenter", "v2f", struct.pack("<ff", 0, 0)) +
              attr("screenWindowWidth", "float", struct.pack("<f", 1)) + b"\0")
    lines, offset = [], len(header) + 8 * height
    table = b""
    for y in range(height):
        data = b""
        for c in sorted(channels):
            for x in range(width):
                v = 0.25 * (x + 1) + y
                data += struct.pack("<e" if pixel_type == 1 else "<f", v)
        line = struct.pack("<ii", y, len(data)) + data
        table += struct.pack("<Q", offset)
        offset += len(line)
        lines.append(line)
    return header + table + b"".join(lines)


def fnv1a64(data):
    h = 0xcbf29ce484222325
    for b in data:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    return h


def state_file(fields, plants, tick=7, tracks=()):
    """tracks: [((x, y), {vertex index: depth}), ...], ascending (y, x); each block holds 32 x 32 depths."""
    out = b"SWARDST1" + struct.pack("<IIQQ", 2, len(fields), tick, len(plants))
    for active, last in fields:
        out += struct.pack("<IQ", active, last)
    for bend, state in plants:
        out += struct.pack("<II", bend, state)
    out += struct.pack("<I", len(tracks))
    for (x, y), depths in tracks:
        out += struct.pack("<ii", x, y) + struct.pack("<1024f", *[depths.get(k, 0.0) for k in range(1024)])
    return out + struct.pack("<Q", fnv1a64(out))


def world_state(tiles, tick=7, size=(4, 4), seed=1):
    """tiles: [((x, y), [(field, active, last, [(bend, state), ...]), ...]), ...]"""
    out = b"SWARDWS1" + struct.pack("<IIQIIQ", 2, len(tiles), tick, *size, seed)
    for (x, y), fields in tiles:
        out += struct.pack("<iiI", x, y, len(fields))
        for field, active, last, plants in fields:
            out += struct.pack("<IIQI", field, active, last, len(plants))
            for bend, state in plants:
                out += struct.pack("<II", bend, state)
    return out + struct.pack("<Q", fnv1a64(out))


def pfm(width, height, values, little=True):
    header = f"Pf\n{width} {height}\n{-1.0 if little else 1.0}\n".encode()
    return header + struct.pack(("<" if little else ">") + f"{len(values)}f", *values)


def gltf_triangle():
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 0, 1)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    buffer = positions + indices
    doc = {
        "asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "root", "mesh": 0, "translation": [1, 0, 0], "children": [1]},
                  {"name": "child", "mesh": 0, "scale": [2, 2, 2], "rotation": [0, 0, 0, 1]}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
        "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.6, 0.7, 1]}}],
        "buffers": [{"byteLength": len(buffer)}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 0, 1]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    return doc, buffer


def glb(doc, buffer):
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    body = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(buffer), b"BIN\0") + buffer
    return struct.pack("<4sII", b"glTF", 2, 12 + len(body)) + body


def main():
    shutil.rmtree(CORPUS, ignore_errors=True)
    for scene in sorted((ROOT / "examples").glob("*.json")):
        put("scene", scene.name, scene.read_bytes())
    put("scene", "dataset_scene.json", (ROOT / "tests/data/dataset_scene.json").read_bytes())
    put("scene", "small_meadow.json", (ROOT / "tests/tools/sward-view/small_meadow.json").read_bytes())
    put("scene", "empty.json", "{}")

    rgb = png(2, 2, 8, 2, [bytes([255, 0, 0, 0, 255, 0]), bytes([0, 0, 255, 9, 9, 9])])
    put("grass_map", "rgb8.png", rgb)
    put("grass_map", "rgba16.png", png(2, 1, 16, 6, [bytes(range(16))]))
    put("grass_map", "palette.png", png(2, 1, 8, 3, [bytes([0, 1])], palette=bytes([0, 255, 0, 255, 0, 0])))
    put("grass_map", "grey.png", png(1, 1, 8, 0, [b"\x80"]))
    put("grass_map", "rgb.exr", exr(2, 2, ["R", "G", "B"]))
    put("grass_map", "rgba_half.exr", exr(2, 1, ["R", "G", "B", "A"], pixel_type=1))

    # 2 columns x 2 rows of 4x4 cells: an 8x8 RGBA image.
    cell = png(8, 8, 8, 6, [bytes(v for x in range(8) for v in (40, 160, 40, (x * 37 + y * 11) % 256))
                            for y in range(8)])
    atlas = {"format": "sward-atlas", "version": 1, "cell_size": [4, 4], "base_u": 0.5, "base_v": 1.0,
             "rows": [{"category": "grass", "columns": 2,
                       "cells": [{"base_u": 0.5, "base_v": 1.0, "aspect": 1.0}, {"aspect": 0.5}]},
                      {"category": "ferns", "columns": 1}]}
    put("atlas", "grass_ferns", json.dumps(atlas).encode() + b"\0" + cell)

    doc, buffer = gltf_triangle()
    embedded = dict(doc, buffers=[{"byteLength": len(buffer),
                                   "uri": "data:application/octet-stream;base64," + base64.b64encode(buffer).decode()}])
    put("gltf", "triangle.gltf", json.dumps(embedded, indent=1))
    put("glb", "triangle.glb", glb(doc, buffer))
    # No rover seed: its 27 KB of geometry made every execution of a mutation of it slow (300 a second as .gltf,
    # 775 as .glb); the triangle's two-node hierarchy with a material reaches the same loader paths.

    put("state_file", "two_fields.bin", state_file([(1, 5), (0, 0)], [(0x3c003c00, 1), (0, 0), (7, 2)]))
    put("state_file", "empty.bin", state_file([], [], tick=0))
    put("state_file", "ruts.bin", state_file([], [], tick=3, tracks=[((-1, 4), {0: 0.04, 33: 0.025}),
                                                                       ((2, 4), {1023: 0.01})]))
    put("state_file", "world.bin", world_state([((1, 0), [(0, 1, 5, [(0x3c003c00, 1), (7, 2)]), (3, 0, 0, [])]),
                                                ((0, 2), [(2, 0, 9, [(0, 0)])])]))

    put("pfm", "little.pfm", pfm(3, 2, [1.5, 2.0, float("inf"), 0.0, 4.25, 8.0]))
    put("pfm", "big.pfm", pfm(2, 1, [3.0, -1.0], little=False))
    # fuzz_flow: the first byte picks the reader (even: .flo, odd: KITTI flow PNG).
    put("flow", "small.flo", b"\x00" + struct.pack("<fii", 202021.25, 2, 1) + struct.pack("<4f", 1.5, -2.0, 1e10, 1e10))
    put("flow", "kitti.png", b"\x01" + png(2, 1, 16, 2, [struct.pack(">HHHHHH", 32832, 32640, 1, 0, 0, 0)]))
    put("kitti_png", "kitti.png", png(2, 2, 16, 0, [struct.pack(">HH", 0, 256), struct.pack(">HH", 1000, 65535)]))
    put("exr", "depth_y.exr", exr(3, 2, ["Y"]))
    put("exr", "rgb_half.exr", exr(2, 2, ["R", "G", "B"], pixel_type=1))
    put("calib", "calib.txt", "cam0=[700 0 320; 0 700 240; 0 0 1]\ncam1=[700 0 320; 0 700 240; 0 0 1]\n"
                              "doffs=0\nbaseline=120\nwidth=640\nheight=480\nndisp=128\nisint=0\nvmin=2\nvmax=96\n"
                              "dyavg=0\ndymax=0\n")
    put("calib", "minimal.txt", "width=4\nheight=3\nndisp=16\nbaseline=1e2\n"
                                "cam0=[1 0 2; 0 1 1.5; 0 0 1]\ncam1=[1 0 2; 0 1 1.5; 0 0 1]\n")

    # fuzz_raster: the first byte picks the file name (0: input.tif, 1: input.asc, 2: input.png, ...).
    grid = "ncols 3\nnrows 2\nxllcorner 0\nyllcorner 0\ncellsize 10\nNODATA_value -9999\n1 2 3\n4 -9999 6\n"
    put("raster", "grid.asc.bin", b"\x01" + grid.encode())
    put("raster", "codes.png.bin", b"\x02" + png(3, 1, 8, 0, [bytes([10, 30, 80])]))
    # The same grid as a GeoTIFF in UTM 33N: gdal_translate -of GTiff -a_srs EPSG:32633 grid.asc utm.tif
    put("raster", "utm.tif.bin", b"\x00" + base64.b64decode(
        "SUkqAAgAAAAQAAABAwABAAAAAwAAAAEBAwABAAAAAgAAAAIBAwABAAAAIAAAAAMBAwABAAAAAQAAAAYBAwABAAAAAQAAABEBBAAB"
        "AAAAegEAABUBAwABAAAAAQAAABYBAwABAAAAAgAAABcBBAABAAAAGAAAABwBAwABAAAAAQAAAFMBAwABAAAAAgAAAA6DDAADAAAA"
        "1AAAAIKEDAAGAAAA7AAAAK+HAwAgAAAAHAEAALGHAgAeAAAAXAEAAIGkAgAGAAAAzgAAAAAAAAAtOTk5OQAAAAAAAAAkQAAAAAAA"
        "ACRAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAADRAAAAAAAAAAAABAAEAAAAHAAAEAAABAAEA"
        "AQQAAAEAAQACBLGHFgAAAAEIsYcHABYABggAAAEAjiMADAAAAQB5fwQMAAABACkjV0dTIDg0IC8gVVRNIHpvbmUgMzNOfFdHUyA4"
        "NHwAAQAAAAIAAAADAAAABAAAAPHY//8GAAAA"
    ))


if __name__ == "__main__":
    main()
