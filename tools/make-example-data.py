#!/usr/bin/env python3
"""Generates the data files of sward's example worlds (docs/scene-format.md, "terrain"):

  hills/hills.gltf    a hilly ground mesh as a glTF exporter writes it: Y up, two nested nodes with rotation,
                      non-uniform scale and translation, NORMAL and TEXCOORD_0 per vertex, two materials ("meadow"
                      and "rock", the rock being a knoll kept bare of plants by the scene, with a base-colour
                      texture hills/rock.png repeated every 8 m)
  gis/dem.tif         a GeoTIFF heightmap (UTM 33N, 2 m pixels, float32 metres) of a known analytic surface
  gis/landcover.tif   a GeoTIFF of ESA WorldCover class codes over the scene's 500 m vegetation tile, whose
                      south-west corner is the DEM's south-west sample (4 m pixels, byte)
  gis-world/dem.tif   a 4 x 4 km GeoTIFF DEM (UTM 33N, 4 m pixels, float32 metres) of a valley landscape: a winding
                      river valley with a tributary, ridges between them, hillside undulation
  gis-world/landcover.tif  ESA WorldCover codes over the same 4 x 4 km at 10 m pixels (as WorldCover's own):
                      meadow (grassland), cropland fields, bare ground, the river (water) and tree cover
  tracks/grass.png    the grass map of examples/tracks: meadow west of a wandering edge near x = 40 m, bare soil east

The surfaces are closed-form functions below; tests compare what sward builds from these files with them. The
GeoTIFFs are written by GDAL's own gdal_translate from ASCII grids. Usage: make-example-data.py OUT_DIR
"""
import base64
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import zlib

# --- hills.gltf ------------------------------------------------------------------------------------------------
HILLS_CELLS = 48        # grid cells per side
HILLS_SIZE = 160.0      # metres per side in the mesh's own frame
ROCK_CENTRE = (30.0, -20.0)  # glTF (x, z) of the rock knoll's centre, mesh frame
ROCK_RADIUS = 22.0


def hills_height(x, z):
    """Mesh-frame height (glTF y) at mesh-frame (x, z)."""
    knoll = 9.0 * math.exp(-((x - ROCK_CENTRE[0]) ** 2 + (z - ROCK_CENTRE[1]) ** 2) / (2 * 14.0 ** 2))
    return 5.0 * math.sin(x / 23.0) * math.cos(z / 31.0) + 0.03 * x + knoll


def hills_normal(x, z):
    e = 0.01
    dx = (hills_height(x + e, z) - hills_height(x - e, z)) / (2 * e)
    dz = (hills_height(x, z + e) - hills_height(x, z - e)) / (2 * e)
    n = (-dx, 1.0, -dz)
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


def write_png_rgb(path, width, height, pixel):
    """An 8-bit RGB PNG; pixel(x, y) -> (r, g, b) bytes."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in pixel(x, y)) for y in range(height))

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def rock_pixel(x, y):
    """Grey granite: a hashed speckle on two scales (deterministic, no random module)."""
    def hashed(i, j, salt):
        h = (i * 73856093 ^ j * 19349663 ^ salt * 83492791) & 0xffffffff
        h = (h ^ (h >> 13)) * 0x5bd1e995 & 0xffffffff
        return ((h ^ (h >> 15)) & 0xff) / 255.0
    v = 0.55 * hashed(x // 8, y // 8, 1) + 0.45 * hashed(x, y, 2)
    grey = 150 + int(90 * (v - 0.5))
    return (grey, grey - 6, grey - 12)


def write_hills(path):
    n = HILLS_CELLS + 1
    step = HILLS_SIZE / HILLS_CELLS
    coords = [-HILLS_SIZE / 2 + i * step for i in range(n)]
    positions, normals = [], []
    for z in coords:
        for x in coords:
            positions.append((x, hills_height(x, z), z))
            normals.append(hills_normal(x, z))
    meadow, rock = [], []
    for j in range(HILLS_CELLS):
        for i in range(HILLS_CELLS):
            a, b, c, d = j * n + i, j * n + i + 1, (j + 1) * n + i + 1, (j + 1) * n + i
            cx, cz = coords[i] + step / 2, coords[j] + step / 2
            on_rock = math.hypot(cx - ROCK_CENTRE[0], cz - ROCK_CENTRE[1]) < ROCK_RADIUS
            # Counter-clockwise seen from +y (glTF up), as exporters write outward faces.
            (rock if on_rock else meadow).extend([a, d, c, a, c, b])
    blob = bytearray()
    views, accessors = [], []

    def add(data, fmt, count, kind, component, extra=None):
        offset = len(blob)
        blob.extend(struct.pack("<" + fmt * count, *data))
        while len(blob) % 4:
            blob.append(0)
        views.append({"buffer": 0, "byteOffset": offset, "byteLength": struct.calcsize("<" + fmt * count)})
        per = {"VEC3": 3, "VEC2": 2, "SCALAR": 1}[kind]
        accessor = {"bufferView": len(views) - 1, "componentType": component, "count": count // per, "type": kind}
        accessor.update(extra or {})
        accessors.append(accessor)
        return len(accessors) - 1

    uvs = [(p[0] / 8.0, p[2] / 8.0) for p in positions]  # repeats every 8 m of the mesh frame
    flat_p = [c for p in positions for c in p]
    lo = [min(p[k] for p in positions) for k in range(3)]
    hi = [max(p[k] for p in positions) for k in range(3)]
    pos = add(flat_p, "f", len(flat_p), "VEC3", 5126, {"min": lo, "max": hi})
    nor = add([c for v in normals for c in v], "f", len(normals) * 3, "VEC3", 5126)
    tex = add([c for v in uvs for c in v], "f", len(uvs) * 2, "VEC2", 5126)
    idx_meadow = add(meadow, "I", len(meadow), "SCALAR", 5125)
    idx_rock = add(rock, "I", len(rock), "SCALAR", 5125)
    gltf = {
        "asset": {"version": "2.0", "generator": "sward tools/make-example-data.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        # Parent: 20 degrees about the vertical (glTF y), stretched 1.5x along glTF x, moved to world (120, 110).
        # Child: another 15 degrees and 2 m up. sward's world is Z up: glTF (x, y, z) -> (x, -z, y).
        "nodes": [
            {"name": "terrain_root", "children": [1], "translation": [120.0, 0.0, -110.0],
             "rotation": [0.0, math.sin(math.radians(10)), 0.0, math.cos(math.radians(10))], "scale": [1.5, 1.0, 1.0]},
            {"name": "hills", "mesh": 0, "translation": [0.0, 2.0, 0.0],
             "rotation": [0.0, math.sin(math.radians(7.5)), 0.0, math.cos(math.radians(7.5))]},
        ],
        "meshes": [{"name": "hills", "primitives": [
            {"attributes": {"POSITION": pos, "NORMAL": nor, "TEXCOORD_0": tex}, "indices": idx_meadow, "material": 0},
            {"attributes": {"POSITION": pos, "NORMAL": nor, "TEXCOORD_0": tex}, "indices": idx_rock, "material": 1}]}],
        "materials": [
            {"name": "meadow", "pbrMetallicRoughness": {"baseColorFactor": [0.16, 0.2, 0.07, 1.0], "roughnessFactor": 1.0}},
            {"name": "rock", "pbrMetallicRoughness": {"baseColorFactor": [0.45, 0.42, 0.4, 1.0], "roughnessFactor": 0.9,
                                                      "baseColorTexture": {"index": 0}}},
        ],
        "textures": [{"source": 0}],
        "images": [{"uri": "rock.png"}],
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(blob)).decode()}],
    }
    with open(path, "w") as f:
        json.dump(gltf, f, separators=(",", ":"))
    write_png_rgb(os.path.join(os.path.dirname(path), "rock.png"), 64, 64, rock_pixel)


# --- gis/dem.tif and gis/landcover.tif --------------------------------------------------------------------------
DEM_SAMPLES = 257      # per side
DEM_SPACING = 2.0      # metres
UTM_WEST, UTM_SOUTH = 500000.0, 5200000.0  # projected corner of the rasters (EPSG:32633)


def dem_height(x, y):
    """Height in metres at (x, y) metres east / north of the DEM's south-west sample."""
    return 40.0 + 6.0 * math.sin(2 * math.pi * x / 256.0) * math.cos(2 * math.pi * y / 192.0) + 0.02 * x - 0.01 * y


LANDCOVER_PIXELS = 125  # per side, 4 m each: the 500 m vegetation tile from the DEM's south-west sample
LANDCOVER_PIXEL = 4.0


def landcover_code(x, y):
    """ESA WorldCover class at (x, y) metres east / north of the south-west corner."""
    if math.hypot(x - 380.0, y - 140.0) < 45.0:
        return 80   # permanent water: a pond
    if x < 128.0:
        return 10   # tree cover along the west edge
    if y > 384.0:
        return 20   # shrubland to the north
    if math.hypot(x - 260.0, y - 300.0) < 40.0:
        return 60   # bare / sparse vegetation
    return 30       # grassland


def write_ascii_grid(path, rows, cellsize, xll, yll, nodata=None):
    with open(path, "w") as f:
        f.write(f"ncols {len(rows[0])}\nnrows {len(rows)}\nxllcorner {xll}\nyllcorner {yll}\ncellsize {cellsize}\n")
        if nodata is not None:
            f.write(f"NODATA_value {nodata}\n")
        for row in rows:
            f.write(" ".join(row) + "\n")


def translate(src, dst, output_type):
    subprocess.run(["gdal_translate", "-q", "-of", "GTiff", "-ot", output_type, "-a_srs", "EPSG:32633",
                    "-co", "COMPRESS=DEFLATE", src, dst], check=True)


def write_gis(folder):
    with tempfile.TemporaryDirectory() as tmp:
        # Pixel-is-area: the sample of column i, row r (top row first) sits at the pixel centre.
        rows = [[f"{dem_height(i * DEM_SPACING, (DEM_SAMPLES - 1 - r) * DEM_SPACING):.6f}" for i in range(DEM_SAMPLES)]
                for r in range(DEM_SAMPLES)]
        write_ascii_grid(os.path.join(tmp, "dem.asc"), rows, DEM_SPACING, UTM_WEST - DEM_SPACING / 2,
                         UTM_SOUTH - DEM_SPACING / 2)
        translate(os.path.join(tmp, "dem.asc"), os.path.join(folder, "dem.tif"), "Float32")
        n = LANDCOVER_PIXELS
        rows = [[str(landcover_code((i + 0.5) * LANDCOVER_PIXEL, (n - 1 - r + 0.5) * LANDCOVER_PIXEL)) for i in range(n)]
                for r in range(n)]
        write_ascii_grid(os.path.join(tmp, "landcover.asc"), rows, LANDCOVER_PIXEL, UTM_WEST, UTM_SOUTH)
        translate(os.path.join(tmp, "landcover.asc"), os.path.join(folder, "landcover.tif"), "Byte")


# --- gis-world/dem.tif and gis-world/landcover.tif: the GIS world example (examples/gis-world) ------------------
# Synthetic, made here (no third-party data): a 4 x 4 km landscape the rover of examples/gis-world crosses.
GISW_SIZE = 4000.0        # metres per side
GISW_DEM_SPACING = 4.0    # metres between DEM samples (1001 x 1001 samples: the sample grid covers [0, 4000]^2)
GISW_LC_PIXEL = 10.0      # metres per land-cover pixel (400 x 400 pixels, each an area)
GISW_WEST, GISW_SOUTH = 620000.0, 5180000.0  # projected south-west corner (EPSG:32633)


def gisw_river_y(x):
    """North coordinate of the main river's centre line at x (metres from the south-west corner)."""
    return 1900.0 + 520.0 * math.sin(2 * math.pi * x / 3100.0) + 140.0 * math.sin(2 * math.pi * x / 900.0 + 1.0)


def gisw_tributary_x(y):
    """East coordinate of the tributary's centre line at y; it joins the main valley from the north."""
    return 2700.0 + 260.0 * math.sin(2 * math.pi * y / 1700.0 + 0.4)


def gisw_valley_distance(x, y):
    main = abs(y - gisw_river_y(x))
    tributary = abs(x - gisw_tributary_x(y)) if y > gisw_river_y(x) else 1e9
    return min(main, tributary)


def gisw_height(x, y):
    """Height in metres at (x, y) metres east / north of the DEM's south-west sample."""
    d = gisw_valley_distance(x, y)
    valley = 55.0 * (1.0 - math.exp(-(d / 420.0) ** 2))          # a trough 55 m deep, 400 m wide shoulders
    ridges = 18.0 * math.sin(2 * math.pi * x / 1300.0) * math.cos(2 * math.pi * y / 1700.0)
    undulation = 3.0 * math.sin(x / 61.0 + 0.7 * math.sin(y / 97.0)) * math.cos(y / 73.0)
    return 210.0 + 0.012 * (x + y) + valley + ridges + undulation


def gisw_hash(i, j, salt):
    h = (i * 73856093 ^ j * 19349663 ^ salt * 83492791) & 0xffffffff
    h = (h ^ (h >> 13)) * 0x5bd1e995 & 0xffffffff
    return ((h ^ (h >> 15)) & 0xffff) / 65535.0


def gisw_landcover(x, y):
    """ESA WorldCover class at (x, y) metres east / north of the south-west corner."""
    d = gisw_valley_distance(x, y)
    if d < 18.0:
        return 80   # permanent water: the river and its tributary
    field_i, field_j = int(x // 320.0), int(y // 240.0)
    if d < 60.0 and gisw_hash(int(x // 50.0), int(y // 50.0), 3) < 0.5:
        return 60   # bare / sparse vegetation: gravel banks along the water
    if gisw_height(x, y) > 330.0 and gisw_hash(int(x // 150.0), int(y // 150.0), 1) < 0.7:
        return 10   # tree cover on the high ridges
    if d > 250.0 and gisw_hash(field_i, field_j, 2) < 0.35:
        return 40   # cropland: rectangular fields on the valley shoulders
    if gisw_hash(int(x // 90.0), int(y // 90.0), 4) < 0.04:
        return 60   # bare patches
    return 30       # grassland: the meadow


def write_gis_world(folder):
    with tempfile.TemporaryDirectory() as tmp:
        n = int(GISW_SIZE / GISW_DEM_SPACING) + 1
        rows = [[f"{gisw_height(i * GISW_DEM_SPACING, (n - 1 - r) * GISW_DEM_SPACING):.4f}" for i in range(n)]
                for r in range(n)]
        write_ascii_grid(os.path.join(tmp, "dem.asc"), rows, GISW_DEM_SPACING, GISW_WEST - GISW_DEM_SPACING / 2,
                         GISW_SOUTH - GISW_DEM_SPACING / 2)
        translate(os.path.join(tmp, "dem.asc"), os.path.join(folder, "dem.tif"), "Float32")
        m = int(GISW_SIZE / GISW_LC_PIXEL)
        rows = [[str(gisw_landcover((i + 0.5) * GISW_LC_PIXEL, (m - 1 - r + 0.5) * GISW_LC_PIXEL)) for i in range(m)]
                for r in range(m)]
        write_ascii_grid(os.path.join(tmp, "landcover.asc"), rows, GISW_LC_PIXEL, GISW_WEST, GISW_SOUTH)
        translate(os.path.join(tmp, "landcover.asc"), os.path.join(folder, "landcover.tif"), "Byte")


# tracks: a 75 m meadow whose eastern part is bare soil, 0.5 m per texel; channels ferns, grass, flowers.
TRACKS_SIZE, TRACKS_TEXELS, TRACKS_BARE_FROM = 75.0, 150, 40.0


def tracks_pixel(i, r):
    x = (i + 0.5) * TRACKS_SIZE / TRACKS_TEXELS
    y = (TRACKS_TEXELS - r - 0.5) * TRACKS_SIZE / TRACKS_TEXELS  # row 0 is north
    # A 2 m wide edge that wanders by up to 1.9 m either side of x = 40 m, as a field's edge does (not a straight step).
    edge = TRACKS_BARE_FROM + 1.2 * math.sin(0.29 * y) + 0.7 * math.sin(0.71 * y + 2.0)
    meadow = min(max((edge - x) / 2.0, 0.0), 1.0)
    flowers = 0.5 + 0.5 * math.sin(0.9 * x) * math.sin(0.7 * y)
    return (0, round(235 * meadow), round(200 * meadow * flowers))


def main():
    if len(sys.argv) != 2:
        sys.exit("usage: make-example-data.py OUT_DIR")
    out = sys.argv[1]
    for sub in ("hills", "gis", "gis-world", "tracks"):
        os.makedirs(os.path.join(out, sub), exist_ok=True)
    write_hills(os.path.join(out, "hills", "hills.gltf"))
    write_gis(os.path.join(out, "gis"))
    write_gis_world(os.path.join(out, "gis-world"))
    write_png_rgb(os.path.join(out, "tracks", "grass.png"), TRACKS_TEXELS, TRACKS_TEXELS, tracks_pixel)


if __name__ == "__main__":
    main()
