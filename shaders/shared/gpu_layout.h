// GPU struct layouts and constants shared by C++ and GLSL. One definition, two languages:
// in C++ the structs live in namespace sward::gpu with glm types and their sizes are static_assert'ed;
// in GLSL the same text declares the std140/std430 block members. Use only vec4/mat4/uvec4-aligned members
// (or scalars packed into them) so std140, std430 and C++ agree without padding rules to remember.
#ifndef SWARD_GPU_LAYOUT_H
#define SWARD_GPU_LAYOUT_H

#include "config.h"

#ifdef __cplusplus
#include <glm/glm.hpp>
#include <cstdint>
namespace sward::gpu {
using vec2 = glm::vec2;
using vec4 = glm::vec4;
using uvec4 = glm::uvec4;
using mat4 = glm::mat4;
using uint = uint32_t;
using glm::clamp; // the functions shared with GLSL call these by their GLSL names
using glm::max;
using glm::min;
using glm::sqrt;
#define SWARD_CONST(type, name, value) inline constexpr type name = value
#else
#define SWARD_CONST(type, name, value) const type name = value
#endif

// Ground-truth depth is written as the bit pattern of a float into an R32_UINT attachment, so that the MSAA
// resolve can pick sample 0 (integer formats resolve with SAMPLE_ZERO; float formats could only average,
// which would blend foreground and background into "flying pixels"). Sky keeps the clear value: +inf.
SWARD_CONST(uint, kDepthInfinityBits, 0x7f800000u);

// Ground-truth labels: a second R32_UINT truth attachment holds (semantic class << 24) | instance id, written
// by the same fragments as the depth, so masks and depth always agree. Class ids (docs/dataset-format.md):
SWARD_CONST(uint, kSemanticSky, 0u);        // clear value: nothing hit
SWARD_CONST(uint, kSemanticGround, 1u);     // terrain
SWARD_CONST(uint, kSemanticVegetation, 2u); // + category index (0..3): standing or recovering plants
SWARD_CONST(uint, kSemanticObject, 8u);     // glTF scene objects (the rover, ...)
SWARD_CONST(uint, kSemanticFelled, 9u);     // felled plants: tyre tracks
SWARD_CONST(uint, kSemanticCut, 10u);       // mowed plants
SWARD_CONST(uint, kSemanticTurf, 11u);      // ground under dense vegetation: the turf layer (turfFraction >= 0.5)
SWARD_CONST(uint, kSemanticTrack, 12u);     // ground pressed into a rut by a wheel (rut depth >= kTrackLabelDepth)
SWARD_CONST(uint, kInstanceBits, 24u);      // instance id: 0 sky / ground, plant index + 1, kInstanceObjectBase + object
SWARD_CONST(uint, kInstanceObjectBase, 16000000u);
// The id space's two disjoint ranges: plant ids 1 .. kInstanceObjectBase - 1, object ids kInstanceObjectBase ..
// 2^kInstanceBits - 1. More plants in a tile or more objects in a scene would wrap into the class bits or into
// each other's ids, so scenes above these counts are refused (checkPlantIdSpace, checkObjectIdSpace).
SWARD_CONST(uint, kMaxPlantInstances, kInstanceObjectBase - 1u);
SWARD_CONST(uint, kMaxObjectInstances, (1u << kInstanceBits) - kInstanceObjectBase);

// Sun shadow cascades (world/sun_shadow.h): at most this many, each dithering into the next (the last fading into
// no shadow) over the last kShadowBlend of its distance range, so no cascade edge shows.
SWARD_CONST(uint, kMaxShadowCascades, 4u);
SWARD_CONST(float, kShadowBlend, 0.15);

// Per-frame constants (uniform buffer, set 0 binding 0).
struct FrameConstants {
    mat4 viewProj;       // world -> clip (reversed Z, infinite far plane)
    mat4 view;           // world -> camera, OpenCV axes (x right, y down, z forward)
    mat4 invViewProj;    // clip -> world, for sky rays
    vec4 cameraPosition; // xyz world position, w unused
    vec4 sunDirection;   // xyz unit vector towards the sun, w unused
    vec4 sunRadiance;    // rgb, linear, w unused
    vec4 skyZenith;      // rgb radiance at the zenith
    vec4 skyHorizon;     // rgb radiance at the horizon
    vec4 groundAmbient;  // rgb radiance from below the horizon
    vec4 viewport;       // width, height, 1/width, 1/height
    vec4 timeParams;     // x simulation time in seconds, yzw reserved
    mat4 shadowViewProj; // shadow pass: world -> clip space of the cascade this draw renders (its own frame slot)
    vec4 shadowParams;   // x cascades (0: no sun shadows); shadow pass: yz the distances of the plants that can shade
                         // the drawn cascade (plant.vert culls the others), w the atlas level every plant of the
                         // draw reads its alpha from (VegetationRenderer::shadowAtlasLevel; plantShadowAlpha)
    uvec4 debug;         // x kDebug* flags (sward-view overlays; 0 for renders), yzw unused
    vec4 coverBand;      // x lod.far, y lod.band (the plants' dissolve band around it), z lod.mid, w the ground disc:
                         // a world's tiles are drawn within w of shadowOrigin.xy and its horizon ring beyond
                         // (horizon_ring.glsl); 0: no disc (one-tile scenes, a world without a ring)
    // Cascaded sun shadows (world/sun_shadow.h, shadow.glsl): cascade k is tile k of a row of square maps.
    mat4 shadowCascades[kMaxShadowCascades]; // world -> cascade k's clip space (orthographic, reversed Z)
    vec4 shadowTiles[kMaxShadowCascades];    // cascade k's tile in the shadow image: x u offset, y u scale, z v scale,
                                             // w one texel in the tile's own uv
    vec4 shadowEnds;     // far end of cascade k: distance to shadowOrigin
    vec4 shadowBias;     // cascade k's depth bias (5 cm along the light)
    vec4 shadowOrigin;   // xyz the reference (left) camera, so both views of a stereo pair pick the same cascade
    // Motion ground truth (render.flow; flow_vertex.glsl): where each drawn point is at the previous and the next tick.
    mat4 viewProjPrevious;      // this view's world -> clip at the previous tick
    mat4 viewProjNext;          // ... and at the next tick
    vec4 flowReferencePrevious; // xyz the reference camera at the previous tick (far billboards face it), w unused
    vec4 flowReferenceNext;     // ... at the next tick
    vec4 flowTimes;             // x the wind's time at the previous tick, y at the next, zw unused
    uvec4 flowParams;           // x object transforms per tick (the previous tick's follow this tick's, then the next's)
    // The sky and the atmosphere (render/sky_constants.h; frame.glsl, atmosphere.glsl).
    vec4 skyParams;       // x kSkyGradient / kSkyPhysical, y haze extinction per metre (0: none), z cloud cover, w unused
    vec4 skyPerez[5];     // physical sky: Perez coefficients A..E, xyz for (Y, x, y) (world/sky.h)
    vec4 skyZenithOverF0; // physical sky: the zenith's (Y, x, y) over F(0, sun's zenith angle)
    vec4 skyAmbient;      // rgb the sky's cosine-weighted mean radiance: the ambient light of an up-facing surface
    vec4 hazeToward;      // rgb the horizon's radiance towards the sun's azimuth (the haze's colour), w unused
    vec4 hazeSide;        // ... across it
    vec4 hazeAway;        // ... away from it
    vec4 sunHorizontal;   // xy the unit horizontal direction towards the sun, zw unused
};

// FrameConstants::skyParams.x: the sky model.
SWARD_CONST(float, kSkyGradient, 0.0);
SWARD_CONST(float, kSkyPhysical, 1.0);

// Per-tile constants of the terrain's main pass (push constants of terrain.frag): each tile has its own cover map.
struct TerrainTileConstants {
    vec4 coverRect; // the cover map's tile: xy world south-west corner, z 1 / edge (0: no cover), w unused
    uvec4 material; // x the bare ground's material (kGroundMaterial*, terrain.material); y 1: some category has
                    // a material of its own (vegetation.categories[i].ground_material), blended in by the tile's
                    // ground material weights (kBindingGroundMaterials), 0: they are not read; z the categories'
                    // materials, 8 bits each, category 0 lowest (the terrain's where a category has none); w what
                    // is drawn: kGroundTile or kGroundHorizonRing (render/horizon_ring.h)
};

// TerrainTileConstants::material.w: a tile's ground, or a world's horizon ring (drawn beyond the ground disc).
SWARD_CONST(uint, kGroundTile, 0u);
SWARD_CONST(uint, kGroundHorizonRing, 1u);

// Ground material presets (terrain.material; ground_material.glsl holds their albedos and textures).
SWARD_CONST(uint, kGroundMaterialSoil, 0u);
SWARD_CONST(uint, kGroundMaterialDrySoil, 1u);
SWARD_CONST(uint, kGroundMaterialMud, 2u);
SWARD_CONST(uint, kGroundMaterialGravel, 3u);
SWARD_CONST(uint, kGroundMaterialForestFloor, 4u);
SWARD_CONST(uint, kGroundMaterialCount, 5u);

// FrameConstants::debug.x flags: viewer visualisations drawn by the main-pass shaders.
SWARD_CONST(uint, kDebugLodColors, 1u);      // tint plants by level of detail (near red, mid green, far blue)
SWARD_CONST(uint, kDebugUpdatedPlants, 2u);  // tint plants the interaction moved (recovering, felled, cut)

// Vertex of the viewer's debug lines (field rectangles, cluster boxes, collider wireframes).
struct DebugLineVertex {
    vec4 position; // xyz world, w unused
    vec4 color;    // linear HDR rgb, a unused
};

// Vertex of the terrain mesh (vertex buffer, binding 0).
struct TerrainVertex {
    vec4 positionHeight; // xyz world position, w unused
    vec4 normal;         // xyz smooth normal, w the horizon ring's rim width (horizon_ring.glsl), 0: not the ring
    vec4 albedo;         // rgb: linear base colour of a mesh ground's material; a = 1 draws it, a = 0 the
                         // procedural soil / turf of heightfield grounds
    vec4 uvLayer;        // xy: the material texture's coordinate; z: its layer in the ground textures, -1: none;
                         // w the horizon ring's floor height (its rim sinks to it), 0 elsewhere
};

// Vegetation expansion: the three levels of detail of paper Figure 3.
SWARD_CONST(uint, kLodNear, 0u); // 4 textured quads at different horizontal and vertical angles
SWARD_CONST(uint, kLodMid, 1u);  // 2 crossed vertical quads
SWARD_CONST(uint, kLodFar, 2u);  // 1 camera-facing billboard
SWARD_CONST(uint, kLodCount, 3u);
// Quads per plant in each level of detail; each quad is two triangles (6 vertices unindexed). The draws index the
// quad's 4 corners (plantIndex), so a CPU driver shades 4 vertices a quad instead of 6.
SWARD_CONST(uint, kQuadsNear, 4u);
SWARD_CONST(uint, kQuadsMid, 2u);
SWARD_CONST(uint, kQuadsFar, 1u);
SWARD_CONST(uint, kVerticesPerQuad, 6u);
// Cut-out quads (vegetation/atlas_cutout.h): near and mid quads drawn as their atlas cell's convex polygon of n
// corners (3 <= n <= kMaxCutoutCorners, chosen at run time: VegetationConstants::options.x), a fan of n - 2
// triangles. The polygon holds every texel with alpha > 0 of mip levels 0..kCutoutMaxLevel, grown by
// kCutoutMarginTexels texels of its level. Far billboards stay whole quads: most are smaller than a pixel.
SWARD_CONST(uint, kMaxCutoutCorners, 8u);
SWARD_CONST(uint, kCutoutMaxLevel, 4u);
SWARD_CONST(float, kCutoutMarginTexels, 2.0);

// Vertices drawn per quad in `lod`: two triangles, or with cutoutCorners >= 3 a fan over the cut-out polygon for near
// and mid quads. The same text is a GLSL and a C++ function.
#ifdef __cplusplus
constexpr
#endif
uint quadVertexCount(uint lod, uint cutoutCorners) {
    return cutoutCorners >= 3u && lod != kLodFar ? 3u * (cutoutCorners - 2u) : kVerticesPerQuad;
}

// Vertices drawn per plant in `lod` (the draws' index count per instance).
#ifdef __cplusplus
constexpr
#endif
uint plantVertexCount(uint lod, uint cutoutCorners) {
    uint quads = lod == kLodNear ? kQuadsNear : lod == kLodMid ? kQuadsMid : kQuadsFar;
    return quads * quadVertexCount(lod, cutoutCorners);
}

// Distinct corners per quad in `lod`: the whole quad's 4, or the cut-out polygon's.
#ifdef __cplusplus
constexpr
#endif
uint quadCornerCount(uint lod, uint cutoutCorners) {
    return cutoutCorners >= 3u && lod != kLodFar ? cutoutCorners : 4u;
}

// Corner of fan vertex k of a quad: triangle t = k / 3 of the fan over the quad's corners is (t + 1, t + 2, 0), the
// fan triangle (0, t + 1, t + 2) with its vertices rotated (same winding). So each triangle's first vertex, whose flat
// outputs it takes, is a corner of its own (t + 1), and in the indexed draw that corner writes its triangle's normal
// (plant.vert). The whole quad is (1, 2, 0), (2, 3, 0) over (0, 0), (1, 0), (1, 1), (0, 1).
#ifdef __cplusplus
constexpr
#endif
uint fanCorner(uint k) {
    uint j = k % 3u;
    return j == 2u ? 0u : k / 3u + 1u + j;
}

// Index k of a plant's indexed draw in `lod` (every pass): fan vertex k % perQuad of quad k / perQuad
// is that quad's corner, numbered quad * quadCornerCount + corner (the vertex shader's gl_VertexIndex). The triangles
// and their vertex order are those of the unindexed draw, so the rasterised fragments are the same.
#ifdef __cplusplus
constexpr
#endif
uint plantIndex(uint lod, uint cutoutCorners, uint k) {
    uint perQuad = quadVertexCount(lod, cutoutCorners);
    return k / perQuad * quadCornerCount(lod, cutoutCorners) + fanCorner(k % perQuad);
}

// First index of `lod`'s pattern in the plant index buffers: the LODs' patterns lie one after another.
#ifdef __cplusplus
constexpr
#endif
uint plantFirstIndex(uint lod, uint cutoutCorners) {
    uint first = 0u;
    for (uint l = 0u; l < lod; ++l) first += plantVertexCount(l, cutoutCorners);
    return first;
}

// Largest horizontal tip offset of an expanded plant (interaction bend + wind), in plant heights: a blade
// bends, it does not stretch (1 would lay the tip on the ground).
SWARD_CONST(float, kMaxTipOffset, 0.95);
// A felled plant (PlantDynamic state kPlantStateFelled) lies along its push: its near and mid quads turn across
// the lay direction (fanned by kFelledSpread radians either side) and lean this far from its up axis, so the plant
// is a mat of blades showing their faces from above, as flattened grass in a tyre track does.
SWARD_CONST(float, kFelledLean, 1.35);
SWARD_CONST(float, kFelledSpread, 0.35);

// Turf (issue 18, "dense from above"): under vegetation the ground is drawn as the low, dense base of the sward
// (leaf litter, short shoots), coloured from the cover map, so a view from above sees a closed meadow between the
// plants instead of bare soil. How much of the ground it covers follows the cover map's S (m^2 of plant side area
// per m^2 of ground, vegetation/cover_map.h): none below kTurfAreaBare, all of it from kTurfAreaFull. The colour
// pass blends soil and turf by this fraction; the truth pass labels a ground pixel kSemanticTurf where it is at
// least one half. The same text is a GLSL and a C++ function (smoothstep written out).
SWARD_CONST(float, kTurfAreaBare, 0.05);
SWARD_CONST(float, kTurfAreaFull, 0.25);
#ifdef __cplusplus
constexpr
#endif
float turfFraction(float coverArea) {
    float t = (coverArea - kTurfAreaBare) / (kTurfAreaFull - kTurfAreaBare);
    t = t < 0.0f ? 0.0f : t > 1.0f ? 1.0f : t;
    return t * t * (3.0f - 2.0f * t);
}

// Ground tracks (issue 18, interaction/ground_tracks.h): ruts pressed into the ground live on a world-wide lattice
// of kTrackCell metres, vertex (i, j) at (i, j) * kTrackCell, in blocks of kTrackBlockCells x kTrackBlockCells
// vertices (block (bx, by) owns i in [bx, bx + 1) * kTrackBlockCells). A block holding any rut is drawn as a fine
// patch of the ground (track.vert) of kTrackPatchVertices^2 vertices: its own, the next block's first row and column
// (the shared edge), and a ring of kTrackPatchRing beyond, so neighbouring patches and the coarse ground around them
// overlap and never leave a crack. The coarse ground discards its fragments inside such blocks (ground_tracks.glsl).
// A patch far from the camera is drawn with every 2nd or 4th vertex (level of detail 1 or 2: kTrackLodLevels), so
// its triangles stay about a pixel wide. A ground point whose rut is at least kTrackLabelDepth deep is labelled
// kSemanticTrack.
SWARD_CONST(float, kTrackCell, 0.025);
SWARD_CONST(uint, kTrackBlockCells, 32u);
SWARD_CONST(uint, kTrackPatchRing, 2u);
SWARD_CONST(uint, kTrackPatchVertices, kTrackBlockCells + 1u + 2u * kTrackPatchRing); // 37: 36 cells, 9 at level 2
SWARD_CONST(uint, kTrackLodLevels, 3u);
SWARD_CONST(uint, kTrackLodShift, 28u); // a drawn patch's entry: slot | level << kTrackLodShift
SWARD_CONST(float, kTrackLabelDepth, 0.002);
// Slot of block (x, y) in the GPU's open-addressing table of patched blocks (linear probing from here; the table
// size is a power of two). The same text is a GLSL and a C++ function.
#ifdef __cplusplus
constexpr
#endif
uint trackBlockHash(int x, int y) {
    uint h = uint(x) * 0x9E3779B1u ^ (uint(y) + 0x7F4A7C15u) * 0x85EBCA77u;
    h ^= h >> 15u;
    h *= 0x2C1B3C6Du;
    return h ^ (h >> 12u);
}
// An empty slot of that table holds this key (no block lies there: it would be 10^8 km away).
SWARD_CONST(int, kTrackEmptyKey, -2147483647 - 1);

// Integer hashing for decisions that must be the same on every device and on the CPU (no sin, no float noise):
// PCG's output permutation (Jarzynski and Olano, "Hash Functions for GPU Rendering", 2020). GLSL and C++ functions.
#ifdef __cplusplus
constexpr
#endif
uint pcgHash(uint v) {
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}
// A hash's top 24 bits as a number in [0, 1).
#ifdef __cplusplus
constexpr
#endif
float unitFromHash(uint h) { return float(h >> 8u) * (1.0f / 16777216.0f); }

// A plant's own hashes in [0, 1), from its index in the tile, one per decision that must not follow another: each
// XORs the index with its own word of SHA-256's initial state before hashing. Two decisions keyed alike would pick
// the same plants (the far billboards kept by the width merge would be the ones kept by the depth merge, or those
// that take the next shadow cascade). Salts: width merge 0x6A09E667 (mergeHash), depth merge 0xBB67AE85
// (depthMergeHash), shadow cascade 0x3C6EF372 (plantShadowHash); test `PlantHashes.AreUncorrelated`.
#ifdef __cplusplus
constexpr
#endif
float plantHash(uint index, uint salt) { return unitFromHash(pcgHash(index ^ salt)); }

// Draw order inside a cluster. Placement lays out each category's plants in rows of increasing y, each row by
// increasing x, so walking a cluster's records forwards draws from low y to high y, and from low x to high x along
// each row. Seen from the high-y side, that is back to front, and the early depth test rejects little (the bench
// patch seen from there: colour and truth passes 30 % longer). The expansion walks a cluster's records backwards when
// the camera lies on the high side of the cluster's middle, in y where it is farther off in y than in x (the rows are
// then at different distances), else in x (then the order along each row decides). Clusters themselves are sorted
// front to back on the CPU (frontToBack in vegetation/vegetation_tile.h).
#ifdef __cplusplus
constexpr
#endif
bool walkPlantsBackwards(float cameraX, float cameraY, float minX, float minY, float maxX, float maxY) {
    float dx = cameraX - 0.5f * (minX + maxX), dy = cameraY - 0.5f * (minY + maxY);
    return (dy < 0.0f ? -dy : dy) >= (dx < 0.0f ? -dx : dx) ? dy > 0.0f : dx > 0.0f;
}

// Slicing of far billboards. A grazing ray crosses many far billboards before it reaches the ground, and it meets
// them near their tops: the parts of the plants below some height are hidden behind the plants in front. A far
// billboard is drawn only above that height, so the hidden parts cost nothing, while every ray that reaches a drawn
// part meets the same plants at the same height as without slicing (a ray above the cut height only meets plant parts
// above it, all of which are drawn; the sun's rays to a drawn point likewise, so its shadows are the same too).
// The cut height is where a ray has crossed `layersWanted` layers of opaque card from the canopy top, so it reaches
// the ground through the drawn parts with probability exp(-layersWanted) only (Boolean model).
// `cover2` and `cover1`: the sums over the plant's cluster of categoryCard * height^2 and categoryCard * height per m^2
// of ground; `sinView`: sine of the angle between the ray to the camera and the plant's up. Returns the cut height
// in metres above the plants' bases (0: whole). The expected layers above height z are
// cot(angle) * sum(card * h * (h - z)) / area for z below every plant's height; that linear form undercounts above
// the shortest plant (it subtracts the plants shorter than z), so the cut it gives is never too high.
#ifdef __cplusplus
inline
#endif
float tanOfView(float sinView) { // tan of the angle between the ray and the ground, kept finite
    float s = max(sinView, 1e-3f);
    return s / max(sqrt(max(1.0f - s * s, 0.0f)), 1e-6f);
}
#ifdef __cplusplus
inline
#endif
float sliceHeight(float layersWanted, float cover2, float cover1, float sinView) {
    if (layersWanted <= 0.0f || cover1 <= 0.0f) return 0.0f;
    return max((cover2 - layersWanted * tanOfView(sinView)) / cover1, 0.0f);
}
// ExpandedPlant::attributes bits 24-31: the cut height as a fraction of the plant's height, times this (rounded
// down: a drawn part is never lost). 0: whole; kSliceUnit: not drawn.
SWARD_CONST(float, kSliceUnit, 255.0);

// Merging of far billboards narrower than a few pixels (LodParams::mergeWidth) into fewer, wider ones: a far plant
// `widthPixels` wide on screen is kept with probability widthPixels / mergeWidth (by its hash `u` in [0, 1)) and drawn
// that much wider, up to kMaxMergeWiden times, showing that many copies of its plant side by side (plant_fragment.glsl,
// plantTexel), not one plant stretched. The expected drawn width per plant is its own, so coverage and the height at
// which a grazing ray meets the plants are unchanged (Boolean model: density times width is what blocks a ray), while
// the rasteriser sees a few billboards a block wide instead of many smaller ones, each of which costs at least a 4 x 4
// block of fragment lanes on a CPU driver (a 2 x 2 quad on a GPU) and a vertex stage. The kept plants nearest the
// threshold (the top kMergeFade of the kept range) shrink to nothing as the camera moves away, so none pops.
// mergeScale is that rule for a size on screen (the width here; the height for merging in depth, below): it returns
// the plant's scale (0: not drawn), exactly 1 where nothing is merged.
SWARD_CONST(float, kMergeFade, 0.25);
SWARD_CONST(float, kMaxMergeWiden, 6.0);
#ifdef __cplusplus
inline
#endif
float mergeScale(float mergeSize, float sizePixels, float u, float maxScale) {
    if (mergeSize <= 0.0f) return 1.0f;
    float r = max(sizePixels / mergeSize, 1.0f / maxScale); // the share of plants to draw
    float q = r / (1.0f - 0.5f * kMergeFade); // kept: u < q, shrinking over [q * (1 - kMergeFade), q)
    float zone = q * (1.0f - kMergeFade);
    if (zone >= 1.0f) return 1.0f;
    // The expected drawn share over u: q * (1 - fade / 2) = r, or, where part of the shrinking zone lies beyond
    // u = 1, what is left of it (continuous in q, so the width changes smoothly).
    float share = q <= 1.0f ? r : zone + ((q - zone) * (q - zone) - (q - 1.0f) * (q - 1.0f)) / (2.0f * q * kMergeFade);
    return clamp((q - u) / (q * kMergeFade), 0.0f, 1.0f) / share;
}
#ifdef __cplusplus
inline
#endif
float mergeWidthScale(float mergeWidth, float widthPixels, float u) {
    return mergeScale(mergeWidth, widthPixels, u, kMaxMergeWiden);
}
// ExpandedPlant::fade bits 8-15 hold the width scale times this (32: 1, exactly; 0: not drawn).
SWARD_CONST(float, kWidthScaleUnit, 32.0);
// A plant's width-merging hash (plantHash).
#ifdef __cplusplus
constexpr
#endif
float mergeHash(uint index) { return plantHash(index, 0x6A09E667u); }

// Merging of far billboards in depth (LodParams::depthMerge): at a grazing view a far pixel looks through tens of
// billboards one behind the other, and each costs its own fragment lanes. A far plant `heightPixels` tall on screen
// is kept with mergeScale's rule (threshold depthMerge pixels, by an independent hash, so which plants are widened and
// which are thickened is not correlated), and instead of wider its card is drawn denser: where its alpha is a it shows
// 1 - (1 - a)^(scale^kDepthMergeExponent) (plant_vertex.glsl, plantTexel), one card standing for several at the
// plant's place. Only as far as cards overlap: the scale is at most cot(view angle) / kDepthMergeGrazing (at most
// kMaxDepthMerge), and where that is below 2 the threshold shrinks with it, to no merging at all below 1. Seen from
// higher up, cards overlap less, and one denser card covers less than the cards it stands for (the far band at the
// far limit darkened 8 % seen from 30 m without that bound). The exponent is below the Boolean model's 1 because a
// coarse mip's soft alpha, thresholded by alpha-to-coverage, gains coverage faster than independent cards would (with
// 1 the meadow's far band was 3-10 % brighter, per channel). The constants are measured in docs/benchmarks.md. The
// opacity fades to nothing with the scale for the kept plants nearest the threshold: none pops. The scale is stored
// as the width scale is (scaleBits), in ExpandedPlant::attributes bits 8-15 of a far billboard drawn alone: a
// billboard faces the camera and has no use for the plant's orientation.
SWARD_CONST(float, kDepthMergeExponent, 0.6);
SWARD_CONST(float, kMaxDepthMerge, 6.0);
SWARD_CONST(float, kDepthMergeGrazing, 16.0);
#ifdef __cplusplus
inline
#endif
float depthMergeScale(float depthMerge, float heightPixels, float sinView, float u) {
    float overlap = 1.0f / (tanOfView(sinView) * kDepthMergeGrazing); // cot(view angle) / kDepthMergeGrazing
    // The threshold fades in over overlap 1..2, so that a steeper view merges nothing (a threshold of 0: a scale of
    // exactly 1) and the scale stays continuous in the angle, too.
    float threshold = depthMerge * clamp(overlap - 1.0f, 0.0f, 1.0f);
    return mergeScale(threshold, heightPixels, u, clamp(overlap, 1.0f, kMaxDepthMerge));
}
// A plant's depth-merging hash (plantHash).
#ifdef __cplusplus
constexpr
#endif
float depthMergeHash(uint index) { return plantHash(index, 0xBB67AE85u); }
// A plant's choice in a shadow cascade's blend band (plantShadowCoordinate in shadow.glsl; plantHash).
#ifdef __cplusplus
constexpr
#endif
float plantShadowHash(uint plant) { return plantHash(plant, 0x3C6EF372u); }
// The colour pass's per-plant hue shift (plant_shading.glsl): its own key, so a plant's hue follows none of its
// other decisions.
#ifdef __cplusplus
constexpr
#endif
float plantColourHash(uint plant) { return plantHash(plant, 0x9B05688Cu); }
// The 8-bit field of a merging scale (a unit is kWidthScaleUnit; 0: not drawn).
#ifdef __cplusplus
inline
#endif
uint scaleBits(float scale) { return uint(min(scale * kWidthScaleUnit + 0.5f, 255.0f)); }

// Per-frame constants of the vegetation expansion (uniform buffer).
struct VegetationConstants {
    vec4 frustumPlanes[5]; // world space, xyz inward normal, w offset: inside when dot(n, p) + w >= 0
    vec4 cameraPosition;   // xyz
    vec4 lodDistances;     // x near->mid, y mid->far, z far limit (beyond: not drawn), w cross-fade band width, m
    vec4 wind;             // xy unit direction, z steady bend (tip offset in plant heights), w gust frequency, Hz
    vec4 windGusts;        // x gust bend (plant heights), y gust wavelength (m), z simulation time (s), w flutter
    vec4 categoryHeight;   // base height per category, metres
    uvec4 counts;          // x clusters, y clusters per field, z instance capacity, w atlas max columns
    uvec4 atlasColumns;    // variants (atlas columns) per category
    uvec4 tile;            // x: the tile's ground-truth label in a world of several tiles (y * tilesX + x + 1), else 0
    uvec4 options;         // x: cut-out corners (>= 3: near and mid quads drawn as their cell's polygon; 0: off)
                           // y: blades per near plant of the categories in mask z (plant_blades.h; 0: cards)
    vec4 categoryCard;     // per category: opaque card area per height^2 (cardCover(), vegetation/atlas.h)
    vec4 categoryAspect;   // per category: mean width / height of its atlas cells (meanAspects(), far merging)
    vec4 farLod;           // x: card layers a ray crosses above a far billboard's cut (LodParams::sliceLayers; 0: off),
                           // y: far billboards narrower merge to this width, pixels (LodParams::mergeWidth; 0: off),
                           // z: the camera's vertical focal length, pixels,
                           // w: far billboards shorter merge in depth below this height, pixels (LodParams::depthMerge)
};

// One expanded plant in one level of detail (storage buffer written by vegetation_expand.comp).
struct ExpandedPlant {
    vec4 positionHeight; // xyz world position of the base, w plant height in metres (after size and cut)
    uint up;             // octahedral unit up vector, as PlantStatic::up
    uint attributes;     // as PlantStatic::attributes (category, variant, orientation, random) but bits 24-31: the
                         // far slicing's cut height (sliceHeight) / height * kSliceUnit (the size is in
                         // positionHeight.w), and on a far billboard drawn alone bits 8-15 its depth merging's scale
                         // (scaleBits, depthMergeScale)
    uint tip;            // packHalf2x16: horizontal tip offset (wind + interaction) in plant heights, world xy
    uint fade;           // bits 0-7 cross-fade t (unorm8), bits 8-15 the far merging's width scale times
                         // kWidthScaleUnit, bit 16 set on the upper-LOD copy, bits 17-20 plant state (PlantDynamic
                         // state bits 20-23), bits 24-31 cut height byte
};

// Atlas cell mapping (storage buffer, row * maxColumns + column).
struct AtlasCellGpu {
    vec4 uvRect;         // u0, v0, u1, v1
    vec4 baseAspect;     // x base u, y base v (cell uv of the plant base), z width / height, w unused
    vec4 cutout[kMaxCutoutCorners / 2u]; // the cut-out polygon's corners in cell uv (u right, v down), two per vec4
};

// One pre-expanded plant vertex (plant_bake.comp -> plant_static.vert), for baselines and reference tests.
struct BakedVertex {
    vec4 positionFraction; // xyz world position, w height fraction (0 base, 1 top)
    vec4 uvRandom;         // xy atlas uv, z plant random value, w unused
    uvec4 upFade;          // x octahedral up, y fade bits (as ExpandedPlant::fade), zw unused
};

// Interaction contacts (CPU collision pass -> GPU recovery pass), at most one per plant per tick.
SWARD_CONST(uint, kContactPush, 1u); // hold the plant bent to `push`; it springs back once released
SWARD_CONST(uint, kContactFell, 2u); // flatten the plant for good along `push` (tyre tracks)
SWARD_CONST(uint, kContactCut, 3u);  // cut the plant to the height byte in flags (mower); also pushes
struct PlantContact {
    uint plant; // index into the tile's record buffers
    uint push;  // 2 x snorm16: horizontal tip offset imposed by the collider, plant heights
    uint flags; // bits 0-3 kContact*, bits 8-15 cut height byte (kContactCut)
    uint field; // index of the plant's field (for bookkeeping and checks)
};

// Recovery pass parameters (push constants).
struct RecoveryConstants {
    vec4 spring;  // x time step (s), y stiffness (1/s^2), z damping (1/s), w rest threshold
    vec4 fell;    // x tip offset of felled plants (plant heights), yzw unused
    uvec4 range;  // x first plant, y plant count (one active field), z contact count, w first contact
};

// Scan pass parameters (push constants of vegetation_scan.comp).
struct ScanConstants {
    uint clusterCount;
    uint capacity; // instance capacity of the frame's pool: draws keep instances below it
    uint firstTile; // 1: the frame's first tile, whose instances start at 0 (the cursor is only written)
    uint cutoutCorners; // as VegetationConstants::options.x: the draws' vertex counts follow it
    uint nearBlades;    // as VegetationConstants::options.y: draw kLodCount, the near blades (plant_blades.h), if > 0
};

// Bake pass parameters (push constants of plant_bake.comp): one dispatch per level of detail.
struct BakeConstants {
    uint lod;
    uint firstInstance;
    uint firstVertex; // output offset
    uint vertexCount; // instances * plantVertexCount(lod, cutout corners)
};

// Expansion statistics written by the scan (storage buffer), for benchmarks and the viewer.
struct ExpansionStats {
    uvec4 instances;     // instances per LOD (x near, y mid, z far), w total
    uvec4 info;          // x clusters visible, y instances dropped for lack of capacity, z plants in visible
                         // clusters (the per-plant work done), w the tile's first instance in the frame's pool
};

#ifdef __cplusplus
static_assert(sizeof(FrameConstants) == (6 + kMaxShadowCascades) * 64 + (30 + kMaxShadowCascades) * 16);
static_assert(sizeof(TerrainTileConstants) == 32);
static_assert(sizeof(DebugLineVertex) == 32);
static_assert(sizeof(VegetationConstants) == 17 * 16);
static_assert(sizeof(ExpandedPlant) == 32);
static_assert(sizeof(AtlasCellGpu) == 32 + 8 * kMaxCutoutCorners);
static_assert(sizeof(ExpansionStats) == 32);
static_assert(sizeof(BakedVertex) == 48);
static_assert(sizeof(PlantContact) == 16);
static_assert(sizeof(RecoveryConstants) == 48);
static_assert(sizeof(ScanConstants) == 20);
static_assert(sizeof(BakeConstants) == 16);
static_assert(sizeof(TerrainVertex) == 64);
} // namespace sward::gpu
#endif
#undef SWARD_CONST

#endif
