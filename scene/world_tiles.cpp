#include "scene/world_tiles.h"

#include "common/error.h"
#include "common/json_reader.h"
#include "common/stopwatch.h"
#include "interaction/state_file.h"
#include "scene/world_ground.h"
#include "vegetation/placement.h"

#include <algorithm>
#include <cmath>

namespace sward {

namespace {

std::string tileName(int32_t x, int32_t y) {
    return "tile (" + std::to_string(x) + ", " + std::to_string(y) + ")";
}

// South-west corner of tile (x, y), in double as placement computes it.
glm::dvec2 tileOrigin(const Scene& scene, int32_t x, int32_t y) {
    const VegetationParams& v = scene.vegetation;
    return {double(v.worldOrigin.x) + double(x) * v.tileSize, double(v.worldOrigin.y) + double(y) * v.tileSize};
}

double distanceToTile(const Scene& scene, int32_t x, int32_t y, glm::dvec2 point) {
    const glm::dvec2 lo = tileOrigin(scene, x, y), hi = lo + double(scene.vegetation.tileSize);
    const double dx = std::max({0.0, lo.x - point.x, point.x - hi.x});
    const double dy = std::max({0.0, lo.y - point.y, point.y - hi.y});
    return std::sqrt(dx * dx + dy * dy);
}

// The same parts predictedTileBytes bounds.
uint64_t tileBytes(const WorldTile& tile) {
    return tile.ground.heightfield()->heights().size() * sizeof(float) + countVegetation(tile.vegetation).totalBytes() +
           tile.vegetation.fields.size() * sizeof(FieldVegetation) + tile.cover.texels.size() * sizeof(glm::vec4);
}

std::string mib(uint64_t bytes) {
    return formatNumber(std::ceil(double(bytes) / 1048576.0)) + " MiB";
}

} // namespace

// A tile with an active field stays resident until its plants have sprung back: recovery runs only on resident tiles,
// so evicting it earlier would freeze a half-recovered track and make a streamed world differ from a resident one.
bool recovering(const WorldTile& tile) {
    return std::any_of(tile.vegetation.fields.begin(), tile.vegetation.fields.end(),
                       [](const FieldVegetation& f) { return f.active; });
}

WorldTile generateWorldTile(const Scene& scene, TileCoord coord, uint32_t threads,
                            std::span<const CategoryLook> looks) {
    const WorldParams& w = scene.world;
    require(w.enabled && coord.x >= 0 && coord.y >= 0 && uint32_t(coord.x) < w.tilesX && uint32_t(coord.y) < w.tilesY,
            "generateWorldTile: " + tileName(coord.x, coord.y) + " is not a tile of the scene's world");
    const glm::dvec2 origin = tileOrigin(scene, coord.x, coord.y);
    // The world's ground over the tile's square, its edge samples shared with its neighbours (a DEM's nodata sample:
    // an error naming the tile).
    WorldTile tile{.coord = coord,
                   .ground = Ground(worldTileHeights(scene, origin, origin + double(scene.vegetation.tileSize)),
                                    scene.terrain.selection)};
    tile.vegetation.coord = coord;
    if (scene.vegetationEnabled) {
        const GrassMap map = buildGrassMap(scene, scene.vegetation.tileSize, origin);
        tile.vegetation = generateTile(tile.ground, map, scene.vegetation, coord, threads);
        if (!looks.empty()) {
            VegetationParams params = scene.vegetation;
            params.worldOrigin = glm::vec2(origin);
            tile.cover = makeCoverMap(map, looks, params);
        }
    }
    tile.bytes = tileBytes(tile);
    return tile;
}

Ground latticeGround(const Scene& scene, glm::dvec2 a, glm::dvec2 b, double margin) {
    const WorldLattice lattice = worldLattice(scene);
    const double step = lattice.spacing;
    const glm::dvec2 o = lattice.origin;
    glm::dvec2 lo = glm::floor((glm::min(a, b) - margin - o) / step) * step + o - 2.0 * step;
    glm::dvec2 hi = glm::ceil((glm::max(a, b) + margin - o) / step) * step + o + 2.0 * step;
    if (!lattice.bounded()) {
        // The procedural terrain's window is square (as it always was: the same heightfield, bitwise).
        hi = lo + std::max(hi.x - lo.x, hi.y - lo.y);
    } else {
        // A DEM ends: the window is clamped to it (height() clamps to the grid's edge beyond).
        const glm::dvec2 last = lattice.last();
        lo = glm::clamp(lo, o, last - step);
        hi = glm::clamp(hi, lo + step, last);
    }
    return Ground(worldHeights(scene, lo, hi), scene.terrain.selection);
}

Ground cameraGround(const Scene& scene, double time) {
    const CameraParams& c = scene.camera;
    const glm::dvec2 a = c.hasPath ? pathPoseXY(c.path, time) : glm::dvec2(c.position);
    const glm::dvec2 b = c.hasPath ? pathPointAheadXY(c.path, time, c.lookAhead) : glm::dvec2(c.lookAt);
    return latticeGround(scene, a, b, 0.0);
}

std::vector<glm::dvec2> actorPoints(const Scene& scene, double time) {
    std::vector<glm::dvec2> points;
    for (const VehicleParams& v : scene.actors.vehicles) points.push_back(pathPoseXY(v.path, time));
    for (const MovingColliderParams& m : scene.actors.colliders) points.push_back(pathPoseXY(m.path, time));
    for (const ObjectParams& object : scene.objects) points.push_back(pathPoseXY(object.path, time));
    return points;
}

std::vector<Collider> worldActorColliders(const Scene& scene, double time) {
    const ActorParams& actors = scene.actors;
    std::vector<Collider> colliders;
    for (size_t v = 0; v < actors.vehicles.size(); ++v) {
        const VehicleParams& vehicle = actors.vehicles[v];
        const glm::dvec2 centre = pathPoseXY(vehicle.path, time);
        const Ground ground = latticeGround(scene, centre, centre, double(vehicle.wheelBase + vehicle.trackWidth));
        const auto wheels = wheelColliders(vehicle, vehicleWheels(vehicle, ground, time), uint32_t(v));
        colliders.insert(colliders.end(), wheels.begin(), wheels.end());
    }
    for (size_t i = 0; i < actors.colliders.size(); ++i) {
        const glm::dvec2 centre = pathPoseXY(actors.colliders[i].path, time);
        colliders.push_back(
            movingCollider(actors.colliders[i], uint32_t(i), latticeGround(scene, centre, centre, 0.0), time));
    }
    return colliders;
}

std::vector<TileCoord> tilesReached(const Scene& scene, const Collider& collider) {
    const Aabb box = worldBounds(collider);
    const WorldParams& w = scene.world;
    const double s = scene.vegetation.tileSize;
    const glm::dvec2 origin = tileOrigin(scene, 0, 0);
    const glm::dvec2 lo = glm::floor((glm::dvec2(box.min) - 1.0 - origin) / s);
    const glm::dvec2 hi = glm::floor((glm::dvec2(box.max) + 1.0 - origin) / s);
    std::vector<TileCoord> tiles;
    for (double y = std::max(lo.y, 0.0); y <= std::min(hi.y, double(w.tilesY) - 1.0); ++y)
        for (double x = std::max(lo.x, 0.0); x <= std::min(hi.x, double(w.tilesX) - 1.0); ++x)
            tiles.push_back(TileCoord{int32_t(x), int32_t(y)});
    return tiles;
}

std::vector<TileCoord> tilesWithin(const Scene& scene, glm::dvec2 point, double radius) {
    const WorldParams& w = scene.world;
    std::vector<TileCoord> tiles;
    for (uint32_t y = 0; y < w.tilesY; ++y)
        for (uint32_t x = 0; x < w.tilesX; ++x)
            if (distanceToTile(scene, int32_t(x), int32_t(y), point) <= radius)
                tiles.push_back(TileCoord{int32_t(x), int32_t(y)});
    return tiles;
}

WorldTiles::WorldTiles(Scene scene, uint32_t threads, std::vector<CategoryLook> looks)
    : scene_(std::move(scene)), threads_(threads), looks_(std::move(looks)) {
    require(scene_.world.enabled, scene_.source + ": the scene has no 'world'");
    checkWorldScene(scene_);
    if (!looks_.empty()) checkWorldBudget(scene_, true); // drawn tiles carry their far cover too
    predictedTileBytes_ = predictedTileBytes(scene_, !looks_.empty());
}

WorldTiles::~WorldTiles() {
    stopWorker();
}

WorldTiles::Plan WorldTiles::plan(std::span<const glm::dvec2> points) const {
    const WorldParams& w = scene_.world;
    const double s = scene_.vegetation.tileSize;
    const glm::dvec2 origin = tileOrigin(scene_, 0, 0);
    std::map<Key, double> wanted; // tile -> distance to the nearest point
    for (const glm::dvec2& p : points) {
        require(std::isfinite(p.x) && std::isfinite(p.y), "world: an interest point is not finite");
        const glm::dvec2 lo = glm::floor((p - w.loadRadius - origin) / s),
                         hi = glm::floor((p + w.loadRadius - origin) / s);
        // Clamped in double first: a point far outside the world must not overflow the conversion.
        const int64_t x0 = int64_t(std::clamp(lo.x, 0.0, double(w.tilesX)));
        const int64_t y0 = int64_t(std::clamp(lo.y, 0.0, double(w.tilesY)));
        const int64_t x1 = int64_t(std::clamp(hi.x, -1.0, double(w.tilesX) - 1.0));
        const int64_t y1 = int64_t(std::clamp(hi.y, -1.0, double(w.tilesY) - 1.0));
        for (int64_t y = y0; y <= y1; ++y)
            for (int64_t x = x0; x <= x1; ++x)
                if (const double d = distanceToTile(scene_, int32_t(x), int32_t(y), p); d <= w.loadRadius) {
                    auto [it, added] = wanted.emplace(Key(int32_t(y), int32_t(x)), d);
                    if (!added) it->second = std::min(it->second, d);
                }
    }
    Plan result;
    std::vector<std::pair<double, Key>> missing;
    for (const auto& [key, distance] : wanted)
        if (!resident_.contains(key)) missing.emplace_back(distance, key);
    std::sort(missing.begin(), missing.end());
    for (const auto& [distance, key] : missing) result.load.push_back(key);
    for (const auto& [key, tile] : resident_)
        if (recovering(tile) || wantedNear(key, points)) result.keep.push_back(key);
    return result;
}

// Several points far apart may want more than the budget holds: first the tiles only the hysteresis band keeps go,
// farthest first; if the tiles within load_radius still do not fit, nothing changes and the error says so.
void WorldTiles::fitBudget(Plan& p, std::span<const glm::dvec2> points, uint64_t pendingBytes) {
    const WorldParams& w = scene_.world;
    uint64_t bytes = pendingBytes + p.load.size() * predictedTileBytes_;
    std::vector<std::pair<double, Key>> band; // (distance to the nearest point, tile) beyond load_radius
    for (const Key& key : p.keep) {
        bytes += resident_.at(key).bytes;
        double nearest = INFINITY;
        for (const glm::dvec2& point : points)
            nearest = std::min(nearest, distanceToTile(scene_, key.second, key.first, point));
        if (nearest > w.loadRadius && !recovering(resident_.at(key))) band.emplace_back(nearest, key);
    }
    std::sort(band.begin(), band.end());
    while (bytes > w.memoryBudgetBytes && !band.empty()) {
        const Key key = band.back().second;
        band.pop_back();
        bytes -= resident_.at(key).bytes;
        p.keep.erase(std::find(p.keep.begin(), p.keep.end(), key));
    }
    require(bytes <= w.memoryBudgetBytes, scene_.source + ": the tiles within 'world.load_radius' (" +
                                              formatNumber(w.loadRadius) + " m) of " + std::to_string(points.size()) +
                                              " interest points need " + mib(bytes) +
                                              ", over 'world.memory_budget_mib' (" + mib(w.memoryBudgetBytes) +
                                              "); raise the budget or keep the cameras and colliders closer together");
}

void WorldTiles::evictAllBut(const std::vector<Key>& keep) {
    for (auto it = resident_.begin(); it != resident_.end();) {
        if (std::find(keep.begin(), keep.end(), it->first) != keep.end()) {
            ++it;
            continue;
        }
        if (beforeEvict_) beforeEvict_(it->second);
        TileInteractionState state = captureTouchedFields(it->second.vegetation);
        if (state.fields.empty())
            kept_.erase(it->first);
        else
            kept_[it->first] = std::move(state);
        ++stats_.evicted;
        it = resident_.erase(it);
    }
}

void WorldTiles::makeResident(WorldTile tile) {
    const Key key(tile.coord.y, tile.coord.x);
    if (auto kept = kept_.find(key); kept != kept_.end()) {
        restoreTouchedFields(tile.vegetation, kept->second,
                             scene_.source + ": the kept interaction state of " + tileName(key.second, key.first));
        kept_.erase(kept);
        ++stats_.restored;
    }
    ++stats_.generated;
    for (const FieldVegetation& f : tile.vegetation.fields) stats_.plantsGenerated += f.plantCount();
    resident_.insert_or_assign(key, std::move(tile));
}

bool WorldTiles::wantedNear(const Key& key, std::span<const glm::dvec2> points) const {
    for (const glm::dvec2& p : points)
        if (distanceToTile(scene_, key.second, key.first, p) <= scene_.world.evictRadius) return true;
    return false;
}

// Finished tiles near the points become resident, the others (requests overtaken by a move) are dropped.
uint32_t WorldTiles::absorbFinished(std::span<const glm::dvec2> points) {
    std::vector<WorldTile> finished;
    {
        std::lock_guard lock(mutex_);
        if (error_) std::rethrow_exception(std::exchange(error_, nullptr));
        finished.swap(finished_);
        stats_.generationSeconds += std::exchange(workerSeconds_, 0.0);
    }
    uint32_t count = 0;
    for (WorldTile& tile : finished) {
        const Key key(tile.coord.y, tile.coord.x);
        if (resident_.contains(key) || !wantedNear(key, points)) continue;
        makeResident(std::move(tile));
        ++count;
    }
    return count;
}

void WorldTiles::waitFor(std::span<const glm::dvec2> points) {
    {
        // Whatever the viewer asked for before: drop the queue and let the tile in progress finish.
        std::unique_lock lock(mutex_);
        queue_.clear();
        wake_.wait(lock, [&] { return !inFlight_; });
    }
    absorbFinished(points);
    Plan p = plan(points);
    fitBudget(p, points, 0);
    evictAllBut(p.keep);
    // (y, x) order: the offline renderer's log and timings are the same on every run (the tiles are anyway).
    std::sort(p.load.begin(), p.load.end());
    for (const Key& key : p.load) {
        const Stopwatch generation;
        WorldTile tile = generateWorldTile(scene_, TileCoord{key.second, key.first}, threads_, looks_);
        stats_.generationSeconds += generation.seconds();
        makeResident(std::move(tile));
    }
    lastPoints_.assign(points.begin(), points.end());
}

// Under mutex_: drops from `load` the tiles the worker holds (in progress or finished), so none is made twice.
void WorldTiles::dropHeld(std::vector<Key>& load) const {
    std::erase_if(load, [&](const Key& key) {
        return key == inFlight_ || std::any_of(finished_.begin(), finished_.end(),
                                               [&](const WorldTile& t) { return Key(t.coord.y, t.coord.x) == key; });
    });
}

void WorldTiles::request(std::span<const glm::dvec2> points) {
    absorbFinished(points);
    Plan p = plan(points);
    uint64_t pendingBytes = 0;
    {
        std::lock_guard lock(mutex_);
        dropHeld(p.load);
        pendingBytes = (finished_.size() + (inFlight_ ? 1 : 0)) * predictedTileBytes_;
    }
    // Not under the lock: the eviction hook may read back GPU buffers or ask this object about its tiles.
    fitBudget(p, points, pendingBytes);
    evictAllBut(p.keep);
    lastPoints_.assign(points.begin(), points.end());
    {
        std::lock_guard lock(mutex_);
        dropHeld(p.load);                              // the worker may have finished one meanwhile
        queue_.assign(p.load.rbegin(), p.load.rend()); // nearest at the back
        if (!worker_.joinable() && !queue_.empty()) worker_ = std::thread([this] { workerLoop(); });
    }
    wake_.notify_all();
}

uint32_t WorldTiles::poll() {
    return absorbFinished(lastPoints_);
}

void WorldTiles::workerLoop() {
    std::unique_lock lock(mutex_);
    for (;;) {
        wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
        if (stop_) return;
        const Key key = queue_.back();
        queue_.pop_back();
        inFlight_ = key;
        lock.unlock();
        const Stopwatch generation;
        std::optional<WorldTile> tile;
        std::exception_ptr error;
        try {
            tile = generateWorldTile(scene_, TileCoord{key.second, key.first}, threads_, looks_);
        } catch (...) {
            error = std::current_exception();
        }
        lock.lock();
        workerSeconds_ += generation.seconds();
        inFlight_.reset();
        if (tile) finished_.push_back(std::move(*tile));
        if (error && !error_) error_ = error;
        wake_.notify_all();
    }
}

void WorldTiles::clear() {
    {
        std::unique_lock lock(mutex_);
        queue_.clear();
        wake_.wait(lock, [&] { return !inFlight_; });
        finished_.clear();
    }
    resident_.clear();
    kept_.clear();
}

void WorldTiles::stopWorker() {
    {
        std::lock_guard lock(mutex_);
        stop_ = true;
    }
    wake_.notify_all();
    if (worker_.joinable()) worker_.join();
}

std::optional<float> WorldTiles::height(glm::dvec2 xy) const {
    const glm::dvec2 t = glm::floor((xy - tileOrigin(scene_, 0, 0)) / double(scene_.vegetation.tileSize));
    if (!(t.x >= 0.0 && t.y >= 0.0 && t.x < scene_.world.tilesX && t.y < scene_.world.tilesY)) return std::nullopt;
    const WorldTile* tile = find(TileCoord{int32_t(t.x), int32_t(t.y)});
    if (!tile) return std::nullopt;
    return tile->ground.height(glm::vec2(xy));
}

const WorldTile* WorldTiles::find(TileCoord coord) const {
    const auto it = resident_.find(Key(coord.y, coord.x));
    return it == resident_.end() ? nullptr : &it->second;
}

WorldTile* WorldTiles::find(TileCoord coord) {
    const auto it = resident_.find(Key(coord.y, coord.x));
    return it == resident_.end() ? nullptr : &it->second;
}

std::vector<TileCoord> WorldTiles::residentTiles() const {
    std::vector<TileCoord> tiles;
    for (const auto& [key, tile] : resident_) tiles.push_back(tile.coord);
    return tiles;
}

uint64_t WorldTiles::residentBytes() const {
    uint64_t bytes = 0;
    for (const auto& [key, tile] : resident_) bytes += tile.bytes;
    return bytes;
}

uint64_t WorldTiles::keptStateBytes() const {
    uint64_t bytes = 0;
    for (const auto& [key, state] : kept_) bytes += state.bytes();
    return bytes;
}

uint32_t WorldTiles::pendingTiles() const {
    std::lock_guard lock(mutex_);
    return uint32_t(queue_.size() + finished_.size() + (inFlight_ ? 1 : 0));
}

void WorldTiles::saveState(const std::string& path, uint64_t tick, const TrackBlocks& tracks) const {
    std::map<Key, TileInteractionState> tiles(kept_.begin(), kept_.end());
    for (const auto& [key, tile] : resident_)
        if (TileInteractionState state = captureTouchedFields(tile.vegetation); !state.fields.empty())
            tiles.emplace(key, std::move(state));
    WorldInteractionState world{.tick = tick,
                                .tilesX = scene_.world.tilesX,
                                .tilesY = scene_.world.tilesY,
                                .seed = scene_.seed,
                                .tracks = tracks};
    for (auto& [key, state] : tiles) world.tiles.push_back(std::move(state));
    saveWorldState(path, world);
}

uint64_t WorldTiles::restoreState(const std::string& path, TrackBlocks* tracks) {
    WorldInteractionState world = loadWorldState(path, scene_.seed);
    const WorldParams& w = scene_.world;
    require(world.tilesX == w.tilesX && world.tilesY == w.tilesY,
            path + ": the world state belongs to a world of " + std::to_string(world.tilesX) + " x " +
                std::to_string(world.tilesY) + " tiles; this one has " + std::to_string(w.tilesX) + " x " +
                std::to_string(w.tilesY));
    std::map<Key, TileInteractionState> tiles;
    for (TileInteractionState& state : world.tiles) tiles.emplace(Key(state.coord.y, state.coord.x), std::move(state));
    // Check every resident tile before changing any, so a foreign file leaves the world as it was.
    const TileInteractionState untouched;
    auto stateOf = [&](const Key& key) -> const TileInteractionState& {
        const auto it = tiles.find(key);
        return it == tiles.end() ? untouched : it->second;
    };
    for (const auto& [key, tile] : resident_)
        checkTouchedFields(tile.vegetation, stateOf(key), path + ": " + tileName(key.second, key.first));
    for (auto& [key, tile] : resident_) restoreTouchedFields(tile.vegetation, stateOf(key), path);
    kept_.clear();
    for (auto& [key, state] : tiles)
        if (!resident_.contains(key)) kept_.emplace(key, std::move(state));
    if (tracks) *tracks = std::move(world.tracks);
    return world.tick;
}

} // namespace sward
