"""Bad inputs of GIS worlds (issue 51, part A: a `world` whose ground is a DEM, scene/world_ground.h): a DEM in
degrees, a nodata sample inside the world's tiles, and tiles reaching beyond the DEM, each one line naming the file
or the keys. The DEMs are Esri ASCII grids written here, with a .prj naming their coordinate system."""

from cases import Case, scene_with

UTM_32N = ('PROJCS["WGS_1984_UTM_Zone_32N",GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,'
           '298.257223563]],PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]],PROJECTION["Transverse_Mercator"],'
           'PARAMETER["False_Easting",500000.0],PARAMETER["False_Northing",0.0],PARAMETER["Central_Meridian",9.0],'
           'PARAMETER["Scale_Factor",0.9996],PARAMETER["Latitude_Of_Origin",0.0],UNIT["Meter",1.0]]')
WGS_84 = ('GEOGCS["GCS_WGS_1984",DATUM["D_WGS_1984",SPHEROID["WGS_1984",6378137.0,298.257223563]],'
          'PRIMEM["Greenwich",0.0],UNIT["Degree",0.0174532925199433]]')


def gis_world(prj=UTM_32N, cellsize=1, hole=None, world=None):
    """The tiny scene on a 41 x 21 DEM (2 x 1 tiles of 20 m at 1 m), `hole`: the (column, row) of a nodata sample."""
    def edit(scene, env):
        rows = []
        for r in range(21):
            rows.append(" ".join("-9999" if (c, r) == hole else f"{30 + 0.1 * c - 0.05 * r:.2f}" for c in range(41)))
        env.write("dem.asc", f"ncols 41\nnrows 21\nxllcorner 500000\nyllcorner 4100000\ncellsize {cellsize}\n"
                             "NODATA_value -9999\n" + "\n".join(rows) + "\n")
        env.write("dem.prj", prj)
        scene["terrain"] = {"heightmap": {"file": "dem.asc"}}
        scene["vegetation"].update(tile_size=20, field_size=10)
        scene["lod"] = {"near": 3, "mid": 6, "far": 14, "band": 2}
        scene["camera"].update(position=[8, 6, 0], look_at=[14, 10, 0])
        scene["world"] = dict({"load_radius": 30, "view_distance": 18, "memory_budget_mib": 256}, **(world or {}))
    return edit


CASES = [
    Case("world on a DEM in degrees", "sward-render", scene_with(gis_world(prj=WGS_84, cellsize=0.0001)), 1,
         r"'terrain\.heightmap'.*dem\.asc' is not in a projected coordinate system \(metres\)"),
    Case("world DEM with nodata inside the world", "sward-render", scene_with(gis_world(hole=(30, 5))), 1,
         r"'terrain\.heightmap' \('.*dem\.asc'\) has a nodata or non-finite sample at world \(30, 15\) \(pixel 30, 5\) "
         r"in tile \(1, 0\): a world's DEM is not filled"),
    Case("world tiles beyond the DEM", "sward-render", scene_with(gis_world(world={"tiles": [3, 1]})), 1,
         r"'world\.tiles' \(3 x 1\) of 'vegetation\.tile_size' \(20 m\) from 'vegetation\.world_origin' \(0, 0\) "
         r"reach \(60, 20\), beyond the DEM 'terrain\.heightmap'"),
]
