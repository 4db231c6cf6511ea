#include "vegetation/placement.h"

#include "common/error.h"
#include "common/hash.h"
#include "common/parallel_for.h"
#include "vegetation/meadow_pattern.h"
#include "vegetation/records.h"

#include "shared/gpu_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <unistd.h>

namespace sward {

namespace {

constexpr uint32_t kCells = kDensityGrid * kDensityGrid;
constexpr uint64_t kBytesPerPlant = sizeof(gpu::PlantStatic) + sizeof(gpu::PlantDynamic);
// Key component that separates the count-rounding threshold from the per-sample streams.
constexpr uint64_t kRoundingSample = ~uint64_t(0);

std::string mib(double bytes) {
    return std::to_string(uint64_t(std::ceil(bytes / 1048576.0))) + " MiB";
}

// Density of every category at one cluster, on the kDensityGrid^2 sub-cell centres (row-major, x fastest).
struct ClusterDensity {
    std::array<std::array<double, kCells>, gpu::kMaxPlantCategories> cells{};
    std::array<uint32_t, gpu::kMaxPlantCategories> counts{};
};

// World and tile-relative frame of a field, shared by the planning and the placement passes.
struct FieldFrame {
    double tileOriginX, tileOriginY; // world
    double localX, localY;           // field min corner relative to the tile
    glm::vec2 origin;                // world, as stored and decoded (float)
    float step;                      // metres per position step
    double stepsPerMetre;
};

FieldFrame fieldFrame(const VegetationParams& p, TileCoord tile, FieldCoord coord) {
    FieldFrame f{};
    f.tileOriginX = double(p.worldOrigin.x) + double(tile.x) * p.tileSize;
    f.tileOriginY = double(p.worldOrigin.y) + double(tile.y) * p.tileSize;
    f.localX = double(coord.x) * p.fieldSize;
    f.localY = double(coord.y) * p.fieldSize;
    f.origin = glm::vec2(float(f.tileOriginX + f.localX), float(f.tileOriginY + f.localY));
    f.step = p.fieldSize / float(gpu::kPlantPositionSteps);
    f.stepsPerMetre = double(gpu::kPlantPositionSteps) / p.fieldSize;
    return f;
}

uint64_t clusterKey(const VegetationParams& p, TileCoord tile, uint32_t field, uint32_t cluster, uint32_t category) {
    return hashKey({p.seed, uint32_t(tile.x), uint32_t(tile.y), field, cluster, category});
}

ClusterDensity planCluster(const GrassMap& map, const VegetationParams& p, const FieldFrame& frame, TileCoord tile,
                           uint32_t fieldIndex, uint32_t cx, uint32_t cy, uint32_t clusterIndex) {
    ClusterDensity plan;
    const double cell = double(p.clusterSize) / kDensityGrid;
    const double x0 = frame.localX + cx * double(p.clusterSize), y0 = frame.localY + cy * double(p.clusterSize);
    std::array<double, gpu::kMaxPlantCategories> scale{};
    for (uint32_t c = 0; c < p.categoryCount; ++c) scale[c] = double(p.categories[c].density) * p.densityMultiplier;
    for (uint32_t j = 0; j < kDensityGrid; ++j) {
        for (uint32_t i = 0; i < kDensityGrid; ++i) {
            const double x = x0 + (i + 0.5) * cell, y = y0 + (j + 0.5) * cell; // tile-relative
            const glm::vec4 intensity = map.sample(glm::vec2(float(x / p.tileSize), float(y / p.tileSize)));
            for (uint32_t ch = 0; ch < 4; ++ch) {
                const int32_t c = p.channelCategory[ch];
                if (c == kUnusedChannel) continue;
                const double patches =
                    patchDensityFactor(p.pattern, p.seed, uint32_t(c), frame.tileOriginX + x, frame.tileOriginY + y);
                plan.cells[c][j * kDensityGrid + i] += double(intensity[int(ch)]) * scale[c] * patches;
            }
        }
    }
    for (uint32_t c = 0; c < p.categoryCount; ++c) {
        double sum = 0.0;
        for (double d : plan.cells[c]) sum += d;
        const double expected = sum * cell * cell;
        // Hashed threshold: floor(expected + u) is expected on average and never off by more than one.
        const double u = unitDouble(hashKey({clusterKey(p, tile, fieldIndex, clusterIndex, c), kRoundingSample}));
        plan.counts[c] = uint32_t(std::min(std::floor(expected + u), double(std::numeric_limits<uint32_t>::max())));
    }
    return plan;
}

// Inverse CDF of a piecewise-constant 1D density: maps t in [0, total) to (bin, fraction in bin).
// `weight(k)` is bin k's mass; the last bin with mass absorbs rounding at the top end.
template <class Weight> std::pair<uint32_t, double> invertCdf(double t, uint32_t bins, Weight weight) {
    uint32_t last = bins - 1;
    while (last > 0 && weight(last) <= 0.0) --last;
    uint32_t k = 0;
    while (k < last && t >= weight(k)) {
        t -= weight(k);
        ++k;
    }
    const double w = weight(k);
    return {k, w > 0.0 ? std::clamp(t / w, 0.0, 1.0) : 0.5};
}

struct Bounds {
    glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
    bool empty() const { return lo.x > hi.x; }
    void add(glm::vec3 p, float radius) {
        lo = glm::min(lo, p - radius);
        hi = glm::max(hi, p + radius);
    }
};

// Places the n plants of category c in cluster (cx, cy), whose sub-cell densities are d: a stratified point set
// warped through the density. Appends their records and grows bounds by each plant's extent.
void placeCategory(const Ground& ground, const VegetationParams& p, const FieldFrame& frame, uint64_t key, uint32_t cx,
                   uint32_t cy, uint32_t c, uint32_t n, const std::array<double, kCells>& d,
                   std::vector<gpu::PlantStatic>& records, Bounds& bounds) {
    const double cell = double(p.clusterSize) / kDensityGrid;
    const glm::vec3 worldUp(0.0f, 0.0f, 1.0f);
    std::array<double, kDensityGrid> columns{};
    for (uint32_t j = 0; j < kDensityGrid; ++j)
        for (uint32_t i = 0; i < kDensityGrid; ++i) columns[i] += d[j * kDensityGrid + i];
    double total = 0.0;
    for (double col : columns) total += col;
    const VegetationCategory& category = p.categories[c];
    // Strata: R rows, row r split into n_r equal cells, so every one of the n strata is ~1/n of the area. The rows run
    // from low y to high y and each row from low x to high x, which the expansion's draw order inside a cluster relies
    // on (gpu::walkPlantsBackwards).
    const uint32_t rows = std::max(1u, uint32_t(std::floor(std::sqrt(double(n)) + 0.5)));
    for (uint32_t r = 0, sample = 0; r < rows; ++r) {
        const uint32_t inRow = uint32_t(uint64_t(r + 1) * n / rows - uint64_t(r) * n / rows);
        for (uint32_t s = 0; s < inRow; ++s, ++sample) {
            const uint64_t h = hashKey({key, sample});
            const uint64_t g = mix64(h ^ 0xa0761d6478bd642full);
            const double u = (s + unitDouble(h)) / inRow;
            const double v = (r + double(uint32_t(h) >> 8) * (1.0 / 16777216.0)) / rows;
            // Warp the stratified point through the density: column from the x marginal, row from the column's
            // conditional.
            auto [i, fx] = invertCdf(u * total, kDensityGrid, [&](uint32_t b) { return columns[b]; });
            // i = i: clang 14 cannot capture a structured binding by reference (C++20 allows it; clang 16 does).
            auto [j, fy] =
                invertCdf(v * columns[i], kDensityGrid, [&, i = i](uint32_t b) { return d[b * kDensityGrid + i]; });
            double lx = double(cx) * p.clusterSize + (i + fx) * cell; // field-relative
            double ly = double(cy) * p.clusterSize + (j + fy) * cell;
            const double wx = frame.tileOriginX + frame.localX + lx, wy = frame.tileOriginY + frame.localY + ly;
            if (p.pattern.clumping > 0.0f) {
                // Pulled toward its tussock (meadow_pattern.h), and kept inside the cluster whose records and
                // bounds it belongs to.
                const glm::dvec2 moved = clumpPosition(p.pattern, p.seed, c, wx, wy);
                lx = std::clamp(lx + (moved.x - wx), double(cx) * p.clusterSize, double(cx + 1) * p.clusterSize);
                ly = std::clamp(ly + (moved.y - wy), double(cy) * p.clusterSize, double(cy + 1) * p.clusterSize);
            }
            // Truncation is floor here (non-negative), without a libm call.
            const uint32_t qx = std::min(uint32_t(lx * frame.stepsPerMetre), 65535u);
            const uint32_t qy = std::min(uint32_t(ly * frame.stepsPerMetre), 65535u);
            const glm::vec2 xy = decodePlanarPosition(qx, qy, frame.origin, frame.step);
            const std::optional<SurfacePoint> ground_ = ground.surface(xy);
            // No ground here, or ground the scene keeps bare (material, slope): the plant does not exist.
            if (!ground_ || !ground_->plantable) continue;
            const glm::vec3 blended = worldUp + (ground_->normal - worldUp) * p.upNormalBlend;
            const double sizeScale = (1.0 + category.heightVariation * (2.0 * unitDouble(g) - 1.0)) *
                                     patchHeightFactor(p.pattern, p.seed, c, wx, wy);
            const uint32_t size = std::clamp(uint32_t(sizeScale * gpu::kPlantSizeDivisor + 0.5), 1u, 255u);
            const PlantInstance plant{
                .positionX = qx,
                .positionY = qy,
                .height = ground_->height,
                .up = blended / std::sqrt(glm::dot(blended, blended)),
                .category = c,
                .variant = uint32_t(g & 0xffffu) % category.variants,
                .orientation = uint32_t(g >> 16) & 255u,
                .random = uint32_t(g >> 24) & 255u,
                .size = size,
            };
            records.push_back(encodePlantStatic(plant));
            bounds.add(glm::vec3(xy, ground_->height), category.height * float(size) / gpu::kPlantSizeDivisor);
        }
    }
}

} // namespace

double predictPlantCount(const GrassMap& map, const VegetationParams& p) {
    double perSquareMetre = 0.0;
    for (uint32_t ch = 0; ch < 4; ++ch) {
        const int32_t c = p.channelCategory[ch];
        if (c != kUnusedChannel)
            perSquareMetre += map.meanIntensity(ch) * p.categories[c].density * double(p.densityMultiplier);
    }
    return perSquareMetre * double(p.tileSize) * p.tileSize;
}

namespace {

// Physical memory of the machine (0 when unknown): a budget above it would end in std::bad_alloc instead of an error.
uint64_t physicalMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

} // namespace

void checkPlantIdSpace(uint64_t plants, const std::string& what) {
    require(plants <= gpu::kMaxPlantInstances,
            what + " " + std::to_string(plants) + " plants per tile, over the limit of " +
                std::to_string(gpu::kMaxPlantInstances) +
                " (the plant instance ids of the ground-truth labels); lower "
                "'vegetation.density_multiplier', the categories' 'density' or 'vegetation.tile_size'");
}

void checkMemoryBudget(const GrassMap& map, const VegetationParams& p) {
    const double plants = predictPlantCount(map, p);
    // The id space first: no budget can lift it, so its error must not suggest raising one.
    checkPlantIdSpace(uint64_t(std::min(plants, 1e18)), "grass map '" + map.source() + "': its densities predict");
    // Cluster records are allocated whatever the densities (tiny cluster sizes over a big tile add up too).
    const double clusters = double(p.fieldsPerTile()) * p.fieldsPerTile() * p.clustersPerField() * p.clustersPerField();
    const double bytes = plants * double(kBytesPerPlant) + clusters * double(sizeof(gpu::PlantCluster));
    const std::string what = "grass map '" + map.source() + "': its densities predict " +
                             std::to_string(uint64_t(std::min(plants, 1e18))) + " plants per tile in " +
                             std::to_string(uint64_t(clusters)) + " clusters (" + mib(bytes) + " of records)";
    require(bytes <= double(p.memoryBudgetBytes),
            what + ", over the vegetation memory budget of " + mib(double(p.memoryBudgetBytes)) +
                "; lower the map or 'density' values or raise 'memory_budget_mib'");
    const uint64_t physical = physicalMemoryBytes();
    require(physical == 0 || bytes <= double(physical),
            what + ", over this machine's physical memory of " + mib(double(physical)) +
                "; lower the map or 'density' values, 'vegetation.tile_size' or raise 'vegetation.cluster_size'");
}

FieldVegetation generateField(const Ground& ground, const GrassMap& map, const VegetationParams& p, TileCoord tile,
                              FieldCoord coord) {
    const uint32_t fieldsPerTile = p.fieldsPerTile(), clustersPerField = p.clustersPerField();
    require(fieldsPerTile != 0 && clustersPerField != 0, "generateField: invalid vegetation params");
    require(coord.x < fieldsPerTile && coord.y < fieldsPerTile, "generateField: field coordinate outside the tile");
    const uint32_t fieldIndex = coord.y * fieldsPerTile + coord.x;
    const FieldFrame frame = fieldFrame(p, tile, coord);

    // Pass 1: densities and counts of every cluster, so the field's size is known before allocating.
    const uint32_t clusterCount = clustersPerField * clustersPerField;
    std::vector<ClusterDensity> plans(clusterCount);
    uint64_t planned = 0;
    for (uint32_t cy = 0, k = 0; cy < clustersPerField; ++cy)
        for (uint32_t cx = 0; cx < clustersPerField; ++cx, ++k) {
            plans[k] = planCluster(map, p, frame, tile, fieldIndex, cx, cy, k);
            for (uint32_t c = 0; c < p.categoryCount; ++c) planned += plans[k].counts[c];
        }
    require(planned * kBytesPerPlant <= p.memoryBudgetBytes,
            "grass map '" + map.source() + "': field (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) +
                ") alone needs " + mib(double(planned * kBytesPerPlant)) +
                " of plant records, over the vegetation memory budget of " + mib(double(p.memoryBudgetBytes)));

    FieldVegetation field;
    field.coord = coord;
    field.origin = frame.origin;
    field.positionStep = frame.step;
    field.staticRecords.reserve(planned);
    field.clusters.resize(clusterCount);

    Bounds fieldBounds;
    for (uint32_t cy = 0, k = 0; cy < clustersPerField; ++cy) {
        for (uint32_t cx = 0; cx < clustersPerField; ++cx, ++k) {
            const ClusterDensity& plan = plans[k];
            const uint32_t first = field.plantCount();
            Bounds bounds;
            for (uint32_t c = 0; c < p.categoryCount; ++c) {
                const uint32_t n = plan.counts[c];
                if (n == 0) continue;
                placeCategory(ground, p, frame, clusterKey(p, tile, fieldIndex, k, c), cx, cy, c, n, plan.cells[c],
                              field.staticRecords, bounds);
            }
            gpu::PlantCluster& cluster = field.clusters[k];
            const uint32_t count = field.plantCount() - first;
            if (bounds.empty()) {
                const glm::vec3 centre(
                    frame.origin + glm::vec2((cx + 0.5f) * p.clusterSize, (cy + 0.5f) * p.clusterSize), 0.0f);
                bounds.lo = bounds.hi = centre;
            } else {
                fieldBounds.lo = glm::min(fieldBounds.lo, bounds.lo);
                fieldBounds.hi = glm::max(fieldBounds.hi, bounds.hi);
            }
            cluster.boundsMin = glm::vec4(bounds.lo, 0.0f);
            cluster.boundsMax = glm::vec4(bounds.hi, 0.0f);
            cluster.range = glm::uvec4(first, count, 0u, 0u);
        }
    }
    if (fieldBounds.empty()) {
        fieldBounds.lo = fieldBounds.hi = glm::vec3(frame.origin + glm::vec2(0.5f * p.fieldSize), 0.0f);
    }
    field.boundsMin = fieldBounds.lo;
    field.boundsMax = fieldBounds.hi;
    field.dynamicRecords.assign(field.staticRecords.size(), restingPlantDynamic());
    return field;
}

VegetationTile generateTile(const Ground& ground, const GrassMap& map, const VegetationParams& p, TileCoord coord,
                            uint32_t threads) {
    validateVegetationParams(p, "vegetation parameters");
    checkMemoryBudget(map, p);
    VegetationTile tile;
    tile.coord = coord;
    tile.size = p.tileSize;
    tile.fieldSize = p.fieldSize;
    tile.clusterSize = p.clusterSize;
    tile.fieldsPerSide = p.fieldsPerTile();
    tile.clustersPerField = p.clustersPerField();
    tile.origin = glm::vec2(float(double(p.worldOrigin.x) + double(coord.x) * p.tileSize),
                            float(double(p.worldOrigin.y) + double(coord.y) * p.tileSize));
    const uint32_t fieldCount = tile.fieldsPerSide * tile.fieldsPerSide;
    tile.fields.resize(fieldCount);

    // Each field writes only its own slot, so the result is the same for any thread count and scheduling; the
    // first error in field order is rethrown.
    parallelFor(fieldCount, threads, [&](uint32_t f, uint32_t) {
        const FieldCoord field{f % tile.fieldsPerSide, f / tile.fieldsPerSide};
        tile.fields[f] = generateField(ground, map, p, coord, field);
    });

    uint64_t plants = 0, clusters = 0;
    for (const FieldVegetation& f : tile.fields) plants += f.plantCount();
    checkPlantIdSpace(plants, "grass map '" + map.source() + "': the vegetation tile holds");
    plants = 0;
    for (FieldVegetation& f : tile.fields) {
        f.firstPlant = uint32_t(plants);
        f.firstCluster = uint32_t(clusters);
        f.staticRange = {plants * sizeof(gpu::PlantStatic), f.staticRecords.size() * sizeof(gpu::PlantStatic)};
        f.dynamicRange = {plants * sizeof(gpu::PlantDynamic), f.dynamicRecords.size() * sizeof(gpu::PlantDynamic)};
        plants += f.plantCount();
        clusters += f.clusters.size();
    }
    return tile;
}

} // namespace sward
