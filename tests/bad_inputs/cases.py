"""The bad inputs of bad_inputs.py: one Case per row of the table. A case's setup(env) writes its inputs into
env.folder and returns the tool's arguments; env.out (default FOLDER/out, absent) or env.watched is the path that
must be left exactly as found."""

import base64
import json
import os
import shutil
import struct
from dataclasses import dataclass
from typing import Callable



class Env:
    def __init__(self, bin_dir, source, folder, base_dataset):
        self.bin, self.source, self.folder, self.base_dataset = bin_dir, source, folder, base_dataset
        self.out = os.path.join(folder, "out")
        self.watched = None

    def path(self, name):
        return os.path.join(self.folder, name)

    def write(self, name, data):
        path = self.path(name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "wb" if isinstance(data, bytes) else "w") as f:
            f.write(data)
        return path


@dataclass
class Case:
    name: str                      # the input, as the table shows it
    tool: str
    setup: Callable                # env -> argument list
    exit: int
    error: str                     # regex the one error line must match
    needs_dataset: bool = False
    limit_s: float = 10.0          # the run must end within this many seconds (wall clock)...
    limit_mb: int = 1024           # ...and its process must peak below this resident size (MiB)

    @property
    def slug(self):
        return "".join(c if c.isalnum() else "-" for c in self.name.lower())[:60]


def base_scene(source):
    """The test data scene made tiny: 32x24 pixels, 2 frames, no vehicle (each case is fast)."""
    with open(os.path.join(source, "tests", "data", "dataset_scene.json")) as f:
        scene = json.load(f)
    scene["render"]["resolution"] = [32, 24]
    scene["sequence"]["frames"] = 2
    scene.pop("vehicles", None)
    return scene


def write_scene(folder, scene, name="scene.json"):
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, name)
    with open(path, "w") as f:
        f.write(scene if isinstance(scene, str) else json.dumps(scene, indent=1))
    return path


def render(*extra):
    """sward-render on the tiny scene with a fresh --out and `extra` arguments."""
    def setup(env):
        return [write_scene(env.folder, base_scene(env.source)), "--out", env.out, *extra]
    return setup


def scene_with(edit, files=None):
    """sward-render on the tiny scene changed by edit(scene, env) (which may write files) with a fresh --out."""
    def setup(env):
        scene = base_scene(env.source)
        result = edit(scene, env)
        return [write_scene(env.folder, result if result is not None else scene), "--out", env.out]
    return setup


def scene_text(text):
    def setup(env):
        return [write_scene(env.folder, text), "--out", env.out]
    return setup


def set_key(path, value):
    def edit(scene, env):
        node = scene
        for key in path[:-1]:
            node = node.setdefault(key, {})
        node[path[-1]] = value
    return edit


# --- glTF: a one-triangle model, valid, and bad variants of it -------------------------------------------------

def triangle_gltf(**changes):
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0)
    indices = struct.pack("<3H", 0, 1, 2) + b"\0\0"
    data = positions + indices
    gltf = {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"name": "body", "mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "buffers": [{"byteLength": len(data),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36},
                        {"buffer": 0, "byteOffset": 36, "byteLength": 6}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                       "min": [0, 0, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"}],
    }
    for change in changes.values():
        change(gltf)
    return gltf


def with_object(model_name, model_data):
    """The tiny scene with one object whose model is `model_data` (dict: glTF JSON; str/bytes: as is)."""
    def edit(scene, env):
        if model_data is not None:
            env.write(model_name, json.dumps(model_data) if isinstance(model_data, dict) else model_data)
        scene["objects"] = [{"name": "thing", "model": model_name,
                             "path": {"points": [[50, 46], [50, 60]], "speed": 1.0}}]
    return edit


def ground_mesh(model_data, terrain_keys=None, **mesh_keys):
    """The tiny scene on a glTF ground `model_data` (dict: glTF JSON; None: no file) with terrain.mesh keys and
    other terrain keys."""
    def edit(scene, env):
        if model_data is not None:
            env.write("ground.gltf", json.dumps(model_data))
        scene["terrain"] = {"mesh": {"file": "ground.gltf", **mesh_keys}, **(terrain_keys or {})}
    return edit


def tilted(gltf):
    """The one triangle lying 45 degrees steep (glTF y is up)."""
    positions = struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, -1)
    data = positions + struct.pack("<3H", 0, 1, 2) + b"\0\0"
    gltf["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
    gltf["accessors"][0]["min"], gltf["accessors"][0]["max"] = [0, 0, -1], [1, 1, 0]


def gltf_case(name, exit, error, **changes):
    return Case(name, "sward-render", scene_with(with_object("model.gltf", triangle_gltf(**changes))), exit, error)


# --- sward-eval: copies of one rendered dataset with one file broken --------------------------------------------

def dataset_with(break_it, *extra):
    def setup(env):
        dataset = env.path("dataset")
        shutil.copytree(env.base_dataset, dataset)
        break_it(dataset, env)
        env.out = env.path("report")
        return [dataset, "--out", env.out, *(a.replace("{dataset}", dataset) for a in extra)]
    return setup


def overwrite(relative, data):
    def break_it(dataset, env):
        with open(os.path.join(dataset, relative), "wb") as f:
            f.write(data)
    return break_it


def truncate(relative, keep):
    def break_it(dataset, env):
        path = os.path.join(dataset, relative)
        with open(path, "rb") as f:
            head = f.read(keep)
        with open(path, "wb") as f:
            f.write(head)
    return break_it


def remove(relative):
    return lambda dataset, env: os.remove(os.path.join(dataset, relative))


def eval_case(name, break_it, error, *extra, exit=1):
    return Case(name, "sward-eval", dataset_with(break_it, *extra), exit, error, needs_dataset=True)


def export_case(name, break_it, error, *extra, exit=1):
    return Case(name, "sward-export", dataset_with(break_it, *extra), exit, error, needs_dataset=True)


def export_out_under_a_file(env):
    blocker = env.write("a-file", "not a folder\n")
    env.out = os.path.join(blocker, "out")
    env.watched = blocker
    return [env.base_dataset, "--layout", "ply", "--out", env.out]


def with_lens_distortion(dataset, env):
    """frames.jsonl as a render with the sensor model's lens distortion writes it."""
    path = os.path.join(dataset, "frames.jsonl")
    records = [json.loads(line) for line in open(path)]
    for record in records:
        record["sensor"] = {"enabled": True, "k1": -0.1, "k2": 0.0, "k3": 0.0, "p1": 0.0, "p2": 0.0}
    with open(path, "w") as f:
        f.writelines(json.dumps(r) + "\n" for r in records)


def pfm_of(width, height, value):
    return b"Pf\n%d %d\n-1\n" % (width, height) + struct.pack("<f", value) * (width * height)


# --- cases whose output folder already holds something -----------------------------------------------------------

def out_under_a_file(env):
    blocker = env.write("a-file", "not a folder\n")
    env.out = os.path.join(blocker, "out")
    env.watched = blocker
    return [write_scene(env.folder, base_scene(env.source)), "--out", env.out]


def out_is_a_file(env):
    env.out = env.write("out-file", "user data\n")
    return [write_scene(env.folder, base_scene(env.source)), "--out", env.out]


def resume_with(*changed):
    """A finished run in --out, then the same --out with other options: must refuse, not mix datasets."""
    def setup(env):
        shutil.copytree(env.base_dataset, env.out)
        scene = write_scene(env.path("scene"), base_scene(env.source))
        return [scene, "--out", env.out, *changed]
    return setup


def tool_out(*args, under_file=False):
    def setup(env):
        if under_file:
            blocker = env.write("a-file", "not a folder\n")
            env.out = os.path.join(blocker, "out")
            env.watched = blocker
        return [a.replace("{out}", env.out) for a in args]
    return setup


def corrupt_shard(env):
    env.watched = env.path("dataset")
    env.write("dataset/manifest.shard-0-of-2.json", "{ not json")
    return [env.watched]


def png_row(colour_type, samples):
    """A valid one-row 8-bit PNG (colour type 0 grey, 2 RGB) of the given sample bytes."""
    import zlib

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xffffffff)
    width = len(samples) // (3 if colour_type == 2 else 1)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, 1, 8, colour_type, 0, 0, 0)) + \
        chunk(b"IDAT", zlib.compress(b"\0" + bytes(samples))) + chunk(b"IEND", b"")


def png_bytes():
    """A valid 1x1 8-bit RGB PNG, for grass maps and atlases."""
    return png_row(2, [0x10, 0x80, 0x10])


def grass_map(data):
    def edit(scene, env):
        env.write("map.png", data)
        scene["grass_map"] = "map.png"
    return edit


def grey_png(values):
    """A one-row 8-bit grey PNG holding `values` (land-cover class codes)."""
    return png_row(0, values)


def land_cover(data):
    def edit(scene, env):
        if data is not None:
            env.write("cover.png", data)
        scene["land_cover"] = {"file": "cover.png", "preset": "esa_worldcover"}
    return edit


def utm_cover(env, width, height):
    """A grassland land cover (ESRI ASCII grid) of width x height pixels of 10 m in UTM zone 32N, as the scene's."""
    rows = "\n".join(" ".join(["30"] * width) for _ in range(height))
    env.write("cover.asc", f"ncols {width}\nnrows {height}\nxllcorner 500000\nyllcorner 4100000\ncellsize 10\n{rows}\n")
    env.write("cover.prj", 'PROJCS["WGS_1984_UTM_Zone_32N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID['
              '"WGS_1984",6378137.0,298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],'
              'PROJECTION["Transverse_Mercator"],PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],'
              'PARAMETER["Central_Meridian",9.0],PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],'
              'UNIT["Meter",1.0]]')
    return {"file": "cover.asc", "preset": "esa_worldcover"}


def atlas(png, json_text):
    def edit(scene, env):
        entry = {}
        if png is not None:
            env.write("atlas.png", png)
            entry["png"] = "atlas.png"
        if json_text is not None:
            env.write("atlas.json", json_text)
            entry["json"] = "atlas.json"
        scene["atlas"] = entry
    return edit


def duplicate_seed(env):
    text = json.dumps(base_scene(env.source), indent=1)
    text = text.replace('"seed": 5', '"seed": 5,\n "seed": 6', 1)
    return [write_scene(env.folder, text), "--out", env.out]


CASES = [
    # Command-line values of sward-render (exit 2, before anything is read or written).
    Case("--resolution wider than 2^32", "sward-render", render("--resolution", "4294967616x240"), 2,
         r"width must be a whole number from 1 to 16384, got '4294967616'"),
    Case("--resolution 0x240", "sward-render", render("--resolution", "0x240"), 2, r"width must be"),
    Case("--resolution over the pixel cap", "sward-render", render("--resolution", "16384x16384"), 2,
         r"268435456 pixels, more than"),
    Case("--resolution with a sign", "sward-render", render("--resolution", "+32x24"), 2, r"bad resolution"),
    Case("--frames past 2^32", "sward-render", render("--frames", "4294967296:4294967297"), 2,
         r"bad frame range .*start must be a whole number"),
    Case("--frames reversed", "sward-render", render("--frames", "5:3"), 2, r"start must be less than end"),
    Case("--frames past the scene's sequence", "sward-render", render("--frames", "0:100"), 1,
         r"goes past the scene's sequence"),
    Case("--shard index past 2^32", "sward-render", render("--shard", "4294967296/2"), 2,
         r"shard index I must be a whole number from 0 to 1"),
    Case("--shard 2/2", "sward-render", render("--shard", "2/2"), 2, r"shard index I"),
    Case("--shard 0/0", "sward-render", render("--shard", "0/0"), 2, r"shard count N"),
    Case("--samples 3", "sward-render", render("--samples", "3"), 2, r"--samples must be 1 or 4"),
    Case("--samples huge", "sward-render", render("--samples", "99999999999999999999"), 2,
         r"--samples must be a whole number"),
    Case("--seed negative", "sward-render", render("--seed", "-5"), 2, r"--seed must be a whole number"),
    Case("--fov 0", "sward-render", render("--fov", "0"), 2, r"--fov must be a number from 1 to 170"),
    Case("--time nan", "sward-render", render("--time", "nan"), 2, r"--time must be a number"),
    Case("--camera with two numbers", "sward-render", render("--camera", "1,2"), 2, r"--camera '1,2'"),
    Case("unknown option", "sward-render", render("--bogus"), 2, r"unknown option '--bogus'"),
    Case("--device bogus", "sward-render", render("--device", "no-such-gpu"), 1, r"no-such-gpu"),
    Case("--device index past the last", "sward-render", render("--device", "#99"), 1,
         r"no Vulkan device matches '#99' \(available: #0 '"),
    Case("--device # without an index", "sward-render", render("--device", "#gpu"), 1,
         r"'#' must be followed by a device index"),
    Case("--device unknown UUID", "sward-render", render("--device", "00000000-0000-0000-0000-000000000000"), 1,
         r"no Vulkan device matches '00000000-0000-0000-0000-000000000000'"),
    Case("--out under a regular file", "sward-render", out_under_a_file, 1, r"a-file"),
    Case("--out is a regular file", "sward-render", out_is_a_file, 1, r"out-file"),
    # Scene files.
    Case("missing scene file", "sward-render", lambda env: [env.path("none.json"), "--out", env.out], 1,
         r"none\.json"),
    Case("scene JSON syntax error", "sward-render", scene_text('{"seed": 5,, }'), 1, r"scene\.json"),
    Case("empty scene file", "sward-render", scene_text(""), 1, r"scene\.json"),
    Case("scene is a JSON array", "sward-render", scene_text("[1, 2]"), 1, r"scene\.json"),
    Case("unknown scene key", "sward-render", scene_with(set_key(["colour"], 1)), 1, r"colour"),
    Case("seed of the wrong type", "sward-render", scene_with(set_key(["seed"], "five")), 1, r"seed"),
    Case("negative terrain size", "sward-render", scene_with(set_key(["terrain", "size"], -5)), 1, r"size"),
    Case("resolution 0 in the scene", "sward-render", scene_with(set_key(["render", "resolution"], [0, 10])), 1,
         r"resolution"),
    Case("sequence.frames 0", "sward-render", scene_with(set_key(["sequence", "frames"], 0)), 1, r"frames"),
    Case("render.shadow_cascades 5", "sward-render", scene_with(set_key(["render", "shadow_cascades"], 5)), 1,
         r"'render\.shadow_cascades' must be"),
    Case("shadow image wider than the device's largest", "sward-render",
         scene_with(lambda s, env: (set_key(["render", "shadow_map_size"], 8192)(s, env),
                                    set_key(["render", "shadow_cascades"], 4)(s, env),
                                    set_key(["render", "shadow_distance"], 2)(s, env))[0]), 1,
         r"'render\.shadow_map_size' 8192 with 4 'render\.shadow_cascades' needs a 32768 texel wide shadow image"),
    Case("sequence.frames 2,000,000", "sward-render", scene_with(set_key(["sequence", "frames"], 2000000)), 1,
         r"frames"),
    Case("fov_y_deg 1e400", "sward-render", scene_with(lambda s, env: (
        set_key(["camera", "fov_y_deg"], "HUGE")(s, env), json.dumps(s).replace('"HUGE"', "1e400"))[1]), 1,
        r"'camera\.fov_y_deg' is outside the range"),
    Case("duplicate scene key", "sward-render", duplicate_seed, 1, r"seed"),
    # Ground: heightmaps and glTF meshes.
    Case("missing ground mesh file", "sward-render", scene_with(ground_mesh(None)), 1, r"ground\.gltf"),
    Case("ground mesh seen only edge-on", "sward-render", scene_with(ground_mesh(triangle_gltf())), 1,
         r"terrain\.mesh.*visible from above"),
    Case("ground mesh material not in the file", "sward-render",
         scene_with(ground_mesh(triangle_gltf(t=tilted), vegetation_materials=["grass"])), 1,
         r"terrain\.mesh.*material 'grass' is not in the ground mesh"),
    Case("ground mesh with no surface for plants", "sward-render",
         scene_with(ground_mesh(triangle_gltf(t=tilted), {"max_slope_deg": 30})), 1,
         r"terrain\.mesh.*no surface of it may carry vegetation"),
    Case("terrain with both heightmap and mesh", "sward-render",
         scene_with(set_key(["terrain"], {"mesh": {"file": "a.gltf"}, "heightmap": {"file": "b.png"}})), 1,
         r"either 'heightmap' or 'mesh'"),
    Case("procedural key beside a ground mesh", "sward-render",
         scene_with(ground_mesh(triangle_gltf(t=tilted), {"amplitude": 3})), 1,
         r"'terrain\.amplitude' applies to the procedural terrain only"),
    Case("missing heightmap file", "sward-render",
         scene_with(set_key(["terrain"], {"heightmap": {"file": "none.png", "metres_per_pixel": 1}})), 1,
         r"terrain\.heightmap.*none\.png"),
    Case("heightmap 8-bit PNG", "sward-render",
         scene_with(lambda s, env: (env.write("dem.png", png_bytes()),
                                    s.update(terrain={"heightmap": {"file": "dem.png", "metres_per_pixel": 1}}), s)[-1]),
         1, r"dem\.png.*8-bit"),
    # Grass maps.
    Case("missing grass_map file", "sward-render", scene_with(set_key(["grass_map"], "none.png")), 1,
         r"none\.png"),
    Case("grass_map not an image", "sward-render", scene_with(grass_map("hello\n")), 1, r"map\.png"),
    Case("grass_map truncated PNG", "sward-render", scene_with(grass_map(png_bytes()[:40])), 1, r"map\.png"),
    Case("grass_map outside the scene folder", "sward-render",
         scene_with(lambda s, env: (env.write("../outside.png", png_bytes()), s.update(grass_map="../outside.png"), s)[-1]),
         1, r"grass_map"),
    # Land cover (a grass map made from a raster of class codes).
    Case("missing land_cover file", "sward-render", scene_with(land_cover(None)), 1,
         r"'land_cover': cannot open raster '.*cover\.png': file missing"),
    Case("land_cover file not a raster", "sward-render", scene_with(land_cover("hello\n")), 1,
         r"'land_cover': raster '.*cover\.png' is not a raster file"),
    Case("land_cover code not in the table", "sward-render", scene_with(land_cover(grey_png([30, 7, 30]))), 1,
         r"'land_cover': class code 7 of raster .*cover\.png' \(first at pixel \(1, 0\)\) is not in the table"),
    Case("both grass_map and land_cover", "sward-render",
         scene_with(lambda s, env: (grass_map(png_bytes())(s, env), land_cover(grey_png([30]))(s, env), s)[-1]), 1,
         r"'grass_map' and 'land_cover' both give the grass map"),
    # Ruts.
    Case("rut_depth on a mower", "sward-render",
         scene_with(set_key(["colliders"], [{"kind": "mower", "rut_depth": 0.05,
                                             "path": {"points": [[40, 40], [60, 60]]}}])), 1,
         r"'colliders\[0\]\.rut_depth' applies to push colliders only"),
    Case("tread deeper than the rut", "sward-render",
         scene_with(set_key(["vehicles"], [{"path": {"points": [[40, 40], [60, 60]]}, "rut_depth": 0.02,
                                            "tread_pitch": 0.1, "tread_depth": 0.05}])), 1,
         r"'vehicles\[0\]\.tread_depth' must not exceed 'rut_depth'"),
    # Range sensors.
    Case("range sensor preset unknown", "sward-render",
         scene_with(set_key(["range_sensors"], [{"preset": "VLP-17", "mount": {"position": [50, 50, 0]}}])), 1,
         r"'range_sensors\[0\]' names no preset: 'VLP-17' \(presets: VLP-16, "),
    Case("range sensor type against its preset", "sward-render",
         scene_with(set_key(["range_sensors"], [{"preset": "LMS111", "type": "lidar",
                                                 "mount": {"position": [50, 50, 0]}}])), 1,
         r"'range_sensors\[0\]\.type' contradicts preset 'LMS111'"),
    Case("range sensor sub-rays without divergence", "sward-render",
         scene_with(set_key(["range_sensors"], [{"type": "lidar", "sub_rays": 7, "mount": {"position": [50, 50, 0]}}])),
         1, r"'range_sensors\[0\]\.sub_rays' > 1 needs a beam divergence"),
    Case("range sensor names twice", "sward-render",
         scene_with(set_key(["range_sensors"], [{"name": "a", "mount": {"position": [50, 50, 0]}},
                                                {"name": "a", "mount": {"position": [50, 50, 0]}}])), 1,
         r"'range_sensors' names 'a' twice"),
    Case("range sensor name with a slash", "sward-render",
         scene_with(set_key(["range_sensors"], [{"name": "../a", "mount": {"position": [50, 50, 0]}}])), 1,
         r"range sensor name '\.\./a' may hold only letters"),
    Case("range sensor without a mount", "sward-render",
         scene_with(set_key(["range_sensors"], [{"preset": "VLP-16"}])), 1,
         r"'range_sensors\[0\]\.mount' needs 'position', 'path' or 'object'"),
    Case("range sensor on a missing object", "sward-render",
         scene_with(set_key(["range_sensors"], [{"preset": "VLP-16", "mount": {"object": "rover", "node": "mast"}}])),
         1, r"range sensor 'sensor0': 'mount\.object' names no scene object: 'rover'"),
    Case("range sensor range reversed", "sward-render",
         scene_with(set_key(["range_sensors"], [{"range": [5, 1], "mount": {"position": [50, 50, 0]}}])), 1,
         r"'range_sensors\[0\]\.range' must be \[min, max\] metres with min < max"),
    Case("world budget over the GPU's memory", "sward-render",
         scene_with(lambda s, env: s.update(world={"tiles": [2, 2], "memory_budget_mib": 4096})), 1,
         r"'world\.memory_budget_mib' \(4096 MiB\) is more than the GPU '.+' has \(\d+ MiB of device-local memory\)"),
    Case("range sensor reaching beyond a world's load_radius", "sward-render",
         scene_with(lambda s, env: s.update(range_sensors=[{"range": [0.5, 250], "mount": {"position": [50, 50, 0]}}],
                                            world={"tiles": [2, 2], "load_radius": 200})),
         1, r"'range_sensors\[0\]' \('sensor0'\): its 'range' \(250 m\) plus 2 m must not exceed "
            r"'world\.load_radius' \(200 m\)"),
    Case("range sensor on a missing object in a world", "sward-render",
         scene_with(lambda s, env: s.update(range_sensors=[{"mount": {"object": "rover", "node": "mast"}}],
                                            world={"tiles": [2, 2]})),
         1, r"range sensor 'sensor0': 'mount\.object' names no scene object: 'rover'"),
    # Motion ground truth.
    Case("flow not a boolean", "sward-render", scene_with(set_key(["render", "flow"], "yes")), 1, r"'render\.flow'"),
    # Worlds of many tiles.
    Case("world budget too small for the tiles around one camera", "sward-render",
         scene_with(set_key(["world"], {"tiles": [16, 16], "load_radius": 300, "memory_budget_mib": 1})), 1,
         r"'world\.memory_budget_mib' \(1 MiB\) cannot hold the tiles around one camera.*'world\.load_radius'"),
    Case("world evict_radius not beyond load_radius", "sward-render",
         scene_with(set_key(["world"], {"load_radius": 200, "evict_radius": 150})), 1,
         r"'world\.evict_radius' \(150 m\) must be larger than 'world\.load_radius' \(200 m\)"),
    Case("world of 0 tiles", "sward-render", scene_with(set_key(["world"], {"tiles": [0, 4]})), 1, r"'world\.tiles'"),
    Case("world on a PNG heightmap", "sward-render",
         scene_with(lambda s, env: (env.write("dem.png", png_bytes()),
                                    s.update(terrain={"heightmap": {"file": "dem.png", "metres_per_pixel": 1}},
                                             world={"tiles": [4, 4]}), s)[-1]),
         1, r"'terrain\.heightmap' \('.*dem\.png'\): a world reads its DEM window by window through GDAL"),
    Case("world whose plants reach beyond its view distance", "sward-render",
         scene_with(lambda s, env: s.update(world={"tiles": [2, 2], "view_distance": 100},
                                            lod={"near": 10, "mid": 40, "far": 150, "band": 4})), 1,
         r"'lod\.far' \+ half 'lod\.band' \(152 m\) must not exceed 'world\.view_distance' \(100 m"),
    Case("world view_distance beyond load_radius", "sward-render",
         scene_with(set_key(["world"], {"tiles": [2, 2], "load_radius": 200, "view_distance": 250})), 1,
         r"'world\.view_distance' \(250 m\) must not exceed 'world\.load_radius' \(200 m\)"),
    Case("world horizon spacing off the terrain's lattice", "sward-render",
         scene_with(set_key(["world"], {"tiles": [2, 2], "horizon": {"spacing": 3.3}})), 1,
         r"'world\.horizon\.spacing' \(3\.3 m\) must be a whole multiple of 'terrain\.spacing'"),
    Case("world horizon neither false nor an object", "sward-render",
         scene_with(set_key(["world"], {"tiles": [2, 2], "horizon": "far"})), 1,
         r"'world\.horizon' must be false, true or an object with 'spacing'"),
    Case("world grass_map without whole pixels per tile", "sward-render",
         scene_with(lambda s, env: (grass_map(png_bytes())(s, env), s.update(world={"tiles": [4, 4]}), s)[-1]), 1,
         r"'grass_map': raster '.*map\.png' has 1 x 1 pixels, not a whole number of pixels per tile of the world's "
         r"400 x 400 m \(4 x 4 tiles of 100 m\)"),
    Case("mismatched land-cover extent", "sward-render",
         scene_with(lambda s, env: s.update(land_cover=utm_cover(env, 20, 15), world={"tiles": [2, 2]})), 1,
         r"'land_cover': raster '.*cover\.asc' covers 200 x 150 m \(20 x 15 pixels of 10 x 10 m\), but the world "
         r"covers 200 x 200 m \(2 x 2 tiles of 100 m\): in a world the land cover must cover the world's extent"),
    Case("world collider wider than the load radius", "sward-render",
         scene_with(lambda s, env: s.update(world={"tiles": [2, 2], "load_radius": 2, "view_distance": 2},
                                            lod={"near": 0.5, "mid": 1, "far": 1.5, "band": 0.5},
                                            colliders=[{"shape": "sphere", "radius": 4, "force": 1,
                                                        "path": {"points": [[96.5, 50], [96.5, 60]], "speed": 1}}])),
         1, r"collider 100000 reaches tile \(\d, \d\), which is not resident: raise 'world\.load_radius'"),
    # Atlases.
    Case("atlas with png only", "sward-render", scene_with(atlas(png_bytes(), None)), 1, r"needs both"),
    Case("atlas json not JSON", "sward-render", scene_with(atlas(png_bytes(), "{ nope")), 1, r"atlas\.json"),
    Case("atlas png missing", "sward-render",
         scene_with(lambda s, env: (env.write("atlas.json", "{}"), s.update(atlas={"png": "none.png",
                                                                                    "json": "atlas.json"}))),
         1, r"none\.png|atlas"),
    Case("atlas png garbage", "sward-render", scene_with(atlas(b"garbage", '{"rows": []}')), 1, r"atlas"),
    # Object models (glTF).
    Case("missing model file", "sward-render", scene_with(with_object("none.gltf", None)), 1, r"none\.gltf"),
    Case("model not glTF", "sward-render", scene_with(with_object("model.gltf", "this is not json")), 1,
         r"model\.gltf"),
    Case("glTF buffer file missing", "sward-render", scene_with(with_object("model.gltf", triangle_gltf(
        uri=lambda g: g["buffers"][0].update(uri="mesh.bin")))), 1, r"mesh\.bin"),
    gltf_case("glTF accessor count near 2^62", 1, r"accessor",
              count=lambda g: g["accessors"][0].update(count=2**62)),
    gltf_case("glTF node scale 1e308", 1, r"scale|finite",
              scale=lambda g: g["nodes"][0].update(scale=[1e308, 1e308, 1e308])),
    gltf_case("glTF Draco-compressed", 1, r"(?i)draco",
              draco=lambda g: g.update(extensionsRequired=["KHR_draco_mesh_compression"],
                                       extensionsUsed=["KHR_draco_mesh_compression"])),
    gltf_case("glTF buffer uri naming a system file", 1, r"buffer",
              uri=lambda g: g["buffers"][0].update(uri="/etc/passwd")),
    # Resume into a folder made with other options.
    Case("resume with another resolution", "sward-render", resume_with("--resolution", "40x30"), 1,
         r"(?i)fingerprint|different|another", needs_dataset=True),
    Case("resume with --no-vegetation", "sward-render", resume_with("--no-vegetation"), 1,
         r"(?i)fingerprint|different|another", needs_dataset=True),
    # sward-eval inputs.
    Case("missing dataset folder", "sward-eval", lambda env: [env.path("none"), "--out", env.out], 1, r"none"),
    eval_case("dataset without calib.txt", remove("calib.txt"), r"calib\.txt"),
    eval_case("garbage calib.txt", overwrite("calib.txt", b"cam0=[\n"), r"calib\.txt"),
    eval_case("truncated ground-truth PFM", truncate("disparity/000000.pfm", 20), r"000000\.pfm"),
    eval_case("PFM with a huge width", overwrite("disparity/000000.pfm", b"Pf\n99999999 99999999\n-1.0\n"),
              r"000000\.pfm"),
    eval_case("estimate PFM truncated", truncate("disparity/000000.pfm", 20), r"000000\.pfm", "--disparities",
              "{dataset}/disparity"),
    eval_case("corrupt ground-truth EXR", lambda d, e: (os.remove(os.path.join(d, "disparity/000000.pfm")),
                                                        overwrite("disparity/000000.exr", b"v/1\x01garbage")(d, e)),
              r"000000\.exr"),
    eval_case("corrupt preview PNG", overwrite("preview/000000.png", b"\x89PNG garbage"), r"preview/000000\.png"),
    eval_case("sward-eval --frames past 2^32", lambda d, e: None, r"--frames", "--frames", "4294967296:4294967297",
              exit=2),
    eval_case("sward-eval --block-size 99", lambda d, e: None, r"--block-size", "--block-size", "99", exit=2),
    # sward-export inputs.
    Case("sward-export missing dataset folder", "sward-export",
         lambda env: [env.path("none"), "--layout", "ply", "--out", env.out], 1, r"none"),
    export_case("sward-export folder without dataset.json", remove("dataset.json"), r"dataset\.json",
                "--layout", "middlebury"),
    export_case("sward-export broken frames.jsonl", overwrite("frames.jsonl", b'{"frame": 0,\n'),
                r"frames\.jsonl line 1", "--layout", "colmap"),
    export_case("sward-export truncated disparity PFM", truncate("disparity/000000.pfm", 20), r"000000\.pfm",
                "--layout", "middlebury"),
    export_case("sward-export corrupt depth EXR", overwrite("depth/000001.exr", b"v/1\x01garbage"),
                r"depth/000001\.exr", "--layout", "ply"),
    export_case("sward-export corrupt preview PNG", overwrite("preview_right/000001.png", b"\x89PNG garbage"),
                r"preview_right/000001\.png", "--layout", "colmap"),
    export_case("sward-export dataset without occlusion masks",
                lambda d, e: shutil.rmtree(os.path.join(d, "occlusion")), r"no occlusion/ masks", "--layout", "kitti"),
    export_case("sward-export KITTI disparity of 300 px", overwrite("disparity/000001.pfm", pfm_of(32, 24, 300.0)),
                r"frame 1: disparity 300\.000 px .* KITTI", "--layout", "kitti"),
    export_case("sward-export --frames without rendered frames", lambda d, e: None, r"no rendered frame",
                "--layout", "nerfstudio", "--frames", "5:6"),
    export_case("sward-export KITTI of a lens-distorted dataset", with_lens_distortion, r"lens distortion",
                "--layout", "kitti"),
    export_case("sward-export --layout unknown", lambda d, e: None, r"--layout", "--layout", "blender", exit=2),
    Case("sward-export --out under a file", "sward-export", export_out_under_a_file, 1, r"a-file",
         needs_dataset=True),
    # The other tools.
    Case("sward-view missing scene", "sward-view", lambda env: [env.path("none.json"), "--frames", "1",
                                                                 "--screenshot-dir", env.out], 1, r"none\.json"),
    Case("sward-view --size 0x0", "sward-view", lambda env: ["--size", "0x0", "--screenshot-dir", env.out], 2,
         r"resolution"),
    Case("sward-atlas --cell 33", "sward-atlas", tool_out("--out", "{out}", "--cell", "33"), 2, r"power of two"),
    Case("sward-atlas --out under a file", "sward-atlas", tool_out("--out", "{out}", under_file=True), 1,
         r"a-file"),
    Case("sward-rover --out in a missing folder", "sward-rover", tool_out("--out", "{out}/rover.gltf"), 1,
         r"rover\.gltf"),
    Case("sward-rover --wheel-radius inf", "sward-rover", tool_out("--out", "{out}", "--wheel-radius", "inf"), 2,
         r"--wheel-radius"),
    Case("sward-bench --fields 0", "sward-bench", lambda env: ["collide", "--fields", "0", "--json",
                                                                os.path.join(env.out, "b.json")], 2, r"--fields"),
    Case("corrupt shard manifest", "merge-manifests.py", corrupt_shard, 1, r"manifest\.shard-0-of-2\.json"),
]
