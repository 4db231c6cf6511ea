"""Bad inputs of the input door (common/input_file.h, io/raster_door.h): companion files GDAL opens by itself
(.aux.xml, an EHdr .hdr, an HFA .ige named by content) outside the scene's folder, FIFOs and devices where a file
is expected, and a sidecar added between two runs of one dataset."""

import os
import shutil
import subprocess

from cases import (Case, base_scene, write_scene, grey_png, png_bytes, triangle_gltf, with_object, atlas, scene_with,
                   eval_case, export_case, ground_mesh)

OUTSIDE_AUX_XML = "<PAMDataset><Metadata><MDI key=\"k\">v</MDI></Metadata></PAMDataset>\n"


def land_cover_with(companion):
    """The tiny scene on a land-cover PNG whose cover.png.aux.xml companion(env, path) makes."""
    def edit(scene, env):
        env.write("cover.png", grey_png([30, 30, 30]))
        companion(env, env.path("cover.png.aux.xml"))
        scene["land_cover"] = {"file": "cover.png", "preset": "esa_worldcover"}
    return edit


def symlink_outside(env, path):
    outside = env.write("../outside-" + os.path.basename(env.folder) + ".aux.xml", OUTSIDE_AUX_XML)
    os.symlink(outside, path)


def fifo(env, path):
    os.mkfifo(path)


def dev_zero(env, path):
    os.symlink("/dev/zero", path)


def ehdr_header_outside(scene, env):
    env.write("dem.bil", bytes([10, 30]))
    outside = env.write("../dem-" + os.path.basename(env.folder) + ".hdr",
                        "ncols 2\nnrows 1\nnbands 1\nnbits 8\nbyteorder I\nlayout bil\n")
    os.symlink(outside, env.path("dem.hdr"))
    scene["terrain"] = {"heightmap": {"file": "dem.bil", "metres_per_pixel": 1}}


def hfa_spill_outside(env):
    """An HFA heightmap in FOLDER/scene whose content names its spill file "../o.ige" (FOLDER/o.ige: outside)."""
    scene_dir = env.path("scene")
    os.makedirs(scene_dir)
    grid = env.write("a.asc", "ncols 4\nnrows 4\nxllcorner 0\nyllcorner 0\ncellsize 1\n" + "1 2 3 4\n" * 4)
    made = env.path("abcd.img")
    subprocess.run(["gdal_translate", "-q", "-of", "HFA", "-co", "USE_SPILL=YES", grid, made], check=True)
    with open(made, "rb") as f:
        data = f.read().replace(b"abcd.ige", b"../o.ige")  # same length: the name field keeps its size
    with open(os.path.join(scene_dir, "abcd.img"), "wb") as f:
        f.write(data)
    os.rename(env.path("abcd.ige"), env.path("o.ige"))
    scene = base_scene(env.source)
    scene["terrain"] = {"heightmap": {"file": "abcd.img", "metres_per_pixel": 1}}
    return [write_scene(scene_dir, scene), "--out", env.out]


def gltf_buffer_fifo(scene, env):
    gltf = triangle_gltf()
    gltf["buffers"][0]["uri"] = "buffer.bin"
    with_object("model.gltf", gltf)(scene, env)
    os.mkfifo(env.path("buffer.bin"))


def model_fifo(scene, env):
    with_object("model.gltf", None)(scene, env)
    os.mkfifo(env.path("model.gltf"))


def atlas_json_fifo(scene, env):
    atlas(png_bytes(), None)(scene, env)
    os.mkfifo(env.path("atlas.json"))
    scene["atlas"]["json"] = "atlas.json"


def scene_fifo(env):
    path = env.path("scene.json")
    os.mkfifo(path)
    return [path, "--out", env.out]


def sidecar_added_between_runs(env):
    """A first run renders the land-cover scene; a .aux.xml then appears beside the raster; the resume refuses."""
    scene = base_scene(env.source)
    land_cover_with(lambda env, path: None)(scene, env)
    path = write_scene(env.folder, scene)
    first = subprocess.run([os.path.join(env.bin, "sward-render"), path, "--out", env.out, "--quiet"],
                           capture_output=True, text=True, timeout=300)
    if first.returncode != 0:
        raise RuntimeError("the first render failed: " + first.stderr.strip())
    env.write("cover.png.aux.xml", OUTSIDE_AUX_XML)
    return [path, "--out", env.out]


def fifo_instead_of(relative):
    """A dataset whose file `relative` is a FIFO (reading it would wait for a writer forever)."""
    def break_it(dataset, env):
        os.remove(os.path.join(dataset, relative))
        os.mkfifo(os.path.join(dataset, relative))
    return break_it


def pose_file_fifo(env):
    dataset = env.path("dataset")
    shutil.copytree(env.base_dataset, dataset)
    fifo_path = env.path("poses.txt")
    os.mkfifo(fifo_path)
    env.out = env.path("report")
    return ["odometry", dataset, "--poses", fifo_path, "--out", env.out]


def look_reference(make):
    """sward-eval look against a reference folder holding one real image (a copy of the dataset's preview), broken
    by make(reference_folder)."""
    def setup(env):
        reference = env.path("real")
        os.makedirs(reference)
        shutil.copyfile(os.path.join(env.base_dataset, "preview", "000000.png"), os.path.join(reference, "a.png"))
        make(reference, env)
        env.out = env.path("report")
        return ["look", env.base_dataset, "--reference", reference, "--out", env.out]
    return setup


def look_mask_outside(reference, env):
    env.write("outside.png", "not read")
    with open(os.path.join(reference, "regions.json"), "w") as f:
        f.write('{"a.png": {"soil": "../outside.png"}}')


CASES = [
    Case("land_cover .aux.xml symlinked outside the scene folder", "sward-render",
         scene_with(land_cover_with(symlink_outside)), 1, r"cover\.png\.aux\.xml.*outside the scene's folder"),
    Case("land_cover .aux.xml a FIFO", "sward-render", scene_with(land_cover_with(fifo)), 1,
         r"cover\.png\.aux\.xml.*not a regular file"),
    Case("land_cover .aux.xml symlinked to /dev/zero", "sward-render", scene_with(land_cover_with(dev_zero)), 1,
         r"cover\.png\.aux\.xml.*/dev/zero, outside the scene's folder"),
    Case("heightmap EHdr .hdr symlinked outside the scene folder", "sward-render", scene_with(ehdr_header_outside),
         1, r"dem\.hdr.*outside the scene's folder"),
    Case("heightmap HFA .img naming its .ige ../o.ige outside", "sward-render", hfa_spill_outside, 1,
         r"o\.ige.*outside the scene's folder"),
    Case("object model a FIFO", "sward-render", scene_with(model_fifo), 1, r"model\.gltf.*not a regular file"),
    Case("glTF buffer file a FIFO", "sward-render", scene_with(gltf_buffer_fifo), 1,
         r"buffer\.bin.*not a regular file"),
    Case("atlas.json a FIFO", "sward-render", scene_with(atlas_json_fifo), 1, r"atlas\.json.*not a regular file"),
    Case("scene file a FIFO", "sward-render", scene_fifo, 1, r"scene\.json.*not a regular file"),
    Case("land_cover .aux.xml added between two runs (resume)", "sward-render", sidecar_added_between_runs, 1,
         r"land_cover\.file/cover\.png\.aux\.xml"),
    eval_case("dataset calib.txt a FIFO", fifo_instead_of("calib.txt"), r"calib\.txt.*not a regular file"),
    Case("pose file a FIFO (sward-eval odometry --poses)", "sward-eval", pose_file_fifo, 1,
         r"poses\.txt.*not a regular file", needs_dataset=True),
    Case("reference image a FIFO (sward-eval look --reference)", "sward-eval",
         look_reference(lambda reference, env: os.mkfifo(os.path.join(reference, "b.png"))), 1,
         r"b\.png.*not a regular file", needs_dataset=True),
    Case("reference regions.json a FIFO (sward-eval look)", "sward-eval",
         look_reference(lambda reference, env: os.mkfifo(os.path.join(reference, "regions.json"))), 1,
         r"regions\.json.*not a regular file", needs_dataset=True),
    Case("reference region mask leaving the folder (sward-eval look)", "sward-eval", look_reference(look_mask_outside),
         1, r"\.\./outside\.png.*not a file name inside the reference folder", needs_dataset=True),
    export_case("sward-export frames.jsonl a FIFO", fifo_instead_of("frames.jsonl"),
                r"frames\.jsonl.*not a regular file", "--layout", "colmap"),
]


def ground_image(uri):
    """A glTF ground whose material's base-colour texture is the image `uri`."""
    def add(gltf):
        gltf["meshes"][0]["primitives"][0]["material"] = 0
        gltf["materials"] = [{"name": "grass", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]
        gltf["textures"] = [{"source": 0}]
        gltf["images"] = [{"uri": uri}]
    return ground_mesh(triangle_gltf(image=add))


CASES += [
    Case("glTF ground image uri ../../../../../../../../etc/passwd", "sward-render",
         scene_with(ground_image("../" * 8 + "etc/passwd")), 1,
         r"image 0 uri: '(\.\./)+etc/passwd' resolves to /etc/passwd, outside the scene's folder"),
    Case("glTF ground image uri /etc/passwd", "sward-render", scene_with(ground_image("/etc/passwd")), 1,
         r"image 0 uri: '/etc/passwd' resolves to /etc/passwd, outside the scene's folder"),
]
