#include "render/world_simulation.h"

#include "common/error.h"
#include "common/parallel_for.h"
#include "render/scene_gpu.h"
#include "render/sequence_frame.h"
#include "render/vegetation_renderer.h"
#include "scene/world_objects.h"

#include <algorithm>

namespace sward {

WorldSimulation::TileSimulation::TileSimulation(Context& ctx, const Scene& scene, const VegetationTile& tile,
                                                VegetationBuffers& buffers, uint32_t threads)
    : world(tile, scene.vegetation, scene.interaction, threads), gpu(ctx, buffers) {}

WorldSimulation::WorldSimulation(Context& ctx, SceneResources& resources, SceneRenderer& renderer, uint32_t threads)
    : ctx_(ctx), resources_(resources), renderer_(renderer), threads_(resolveThreadCount(threads)) {
    require(resources.world != nullptr && (renderer.vegetation() != nullptr || sceneMakesRuts(resources.scene)),
            "WorldSimulation: needs a world whose vegetation is drawn or whose colliders press ruts");
    if (sceneMakesRuts(resources.scene)) renderer.setWorldGroundTracks(&tracks_);
    resources.world->setBeforeEvict([this](WorldTile& tile) {
        readBack(tile);
        tiles_.erase(Key(tile.coord.y, tile.coord.x));
        renderer_.removeTile(tile.coord); // uploaded again, from the kept state, if it comes back
    });
}

WorldSimulation::~WorldSimulation() {
    resources_.world->setBeforeEvict({});
}

// The tile's dynamic records live on the GPU while it is simulated: the CPU copy (what WorldTiles keeps and saves)
// takes them, with the field activity, field by field (the buffer packs the fields in field order).
void WorldSimulation::readBack(WorldTile& tile, bool kept) {
    const auto it = tiles_.find(Key(tile.coord.y, tile.coord.x));
    if (it == tiles_.end()) return; // never simulated: the CPU copy is the GPU's
    const std::vector<gpu::PlantDynamic> dynamics =
        kept ? renderer_.vegetation()->readKeptState(tile.coord) : it->second->gpu.readDynamics();
    for (FieldVegetation& field : tile.vegetation.fields)
        std::copy_n(dynamics.begin() + field.firstPlant, field.plantCount(), field.dynamicRecords.begin());
    it->second->world.writeActivity(tile.vegetation);
}

std::vector<glm::dvec2> WorldSimulation::interestPoints(uint64_t tick) const {
    // The left camera, as a world without actors loads around (renderSequenceFrame); its position does not depend on
    // the image size.
    std::vector<glm::dvec2> points{glm::dvec2(sequenceRig(resources_, 16, 16, uint32_t(tick)).left.position)};
    const std::vector<glm::dvec2> actors =
        actorPoints(resources_.scene, double(tick) * resources_.scene.sequence.timeStep);
    points.insert(points.end(), actors.begin(), actors.end());
    for (const Collider& collider : external_) points.push_back(glm::dvec2(collider.centre));
    return points;
}

void WorldSimulation::prepare(std::span<const glm::dvec2> around) {
    const Scene& scene = resources_.scene;
    WorldTiles& world = *resources_.world;
    std::vector<glm::dvec2> points = interestPoints(tick_);
    points.insert(points.end(), around.begin(), around.end());
    if (waitForTiles_) world.waitFor(points);
    syncWorldTiles(renderer_, world);
    // Each tile collides only the colliders that reach it, in the scene's order: its contacts do not depend on which
    // other tiles are resident.
    lastColliders_ = worldColliders(scene, resources_.models, tick_);
    lastColliders_.insert(lastColliders_.end(), external_.begin(), external_.end());
    reaching_.clear();
    if (!renderer_.vegetation()) { // bare ground: the colliders press ruts only
        prepared_ = tick_;
        return;
    }
    for (const Collider& collider : lastColliders_)
        for (TileCoord coord : tilesReached(scene, collider)) {
            if (!waitForTiles_ && world.find(coord) == nullptr) continue; // sward-view: no pass on a missing tile
            require(world.find(coord) != nullptr,
                    scene.source + ": at tick " + std::to_string(tick_) + " collider " + std::to_string(collider.id) +
                        " reaches tile (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) +
                        "), which is not resident: raise 'world.load_radius'");
            reaching_[Key(coord.y, coord.x)].push_back(collider);
        }
    // Simulations are made here, not while a tick is recorded: making one reads the GPU.
    for (const auto& [key, colliders] : reaching_) simulationOf(TileCoord{key.second, key.first});
    // A tile restored with plants still springing back (restoreState) recovers from this tick on.
    for (TileCoord coord : world.residentTiles())
        if (!tiles_.contains(Key(coord.y, coord.x)) && recovering(*world.find(coord))) simulationOf(coord);
    prepared_ = tick_;
}

WorldSimulation::TileSimulation& WorldSimulation::simulationOf(TileCoord coord) {
    std::unique_ptr<TileSimulation>& sim = tiles_[Key(coord.y, coord.x)];
    if (!sim) {
        const WorldTile* tile = resources_.world->find(coord);
        require(tile != nullptr, "WorldSimulation: tile (" + std::to_string(coord.x) + ", " + std::to_string(coord.y) +
                                     ") is not resident");
        sim = std::make_unique<TileSimulation>(ctx_, resources_.scene, tile->vegetation,
                                               renderer_.vegetation()->buffers(coord), threads_);
        sim->world.resumeAt(tick_);
    }
    return *sim;
}

void WorldSimulation::runTicksBefore(uint64_t tick) {
    while (tick_ < tick) {
        prepare();
        const uint32_t slot = uint32_t(tick_);
        ctx_.submitter.immediate([&](VkCommandBuffer cmd) { recordNextTick(cmd, slot); });
    }
}

void WorldSimulation::runNextTick(std::span<const glm::dvec2> around,
                                  const std::function<void(VkCommandBuffer)>& before) {
    prepare(around);
    const uint32_t slot = uint32_t(tick_);
    ctx_.submitter.immediate([&](VkCommandBuffer cmd) {
        if (before) before(cmd);
        recordNextTick(cmd, slot);
    });
}

void WorldSimulation::recordNextTick(VkCommandBuffer cmd, uint32_t slot) {
    require(prepared_ == tick_, "WorldSimulation: tick " + std::to_string(tick_) + " was not prepared");
    WorldTiles& world = *resources_.world;
    for (auto& [key, sim] : tiles_) {
        const auto it = reaching_.find(key);
        const TickResult result =
            sim->world.step(it == reaching_.end() ? std::span<const Collider>() : std::span<const Collider>(it->second));
        sim->world.writeActivity(world.find(TileCoord{key.second, key.first})->vegetation);
        contacts_ += result.contacts.size();
        sim->gpu.record(cmd, result.contacts, result.activeFields, resources_.scene.interaction.recovery, slot);
    }
    pressRuts();
    prepared_.reset();
    ++tick_;
}

// Each collider pressing ruts is swept from its previous pose (recomputed after a restore) over the lattice ground
// around both (latticeGround: the tiles' heights bitwise, whichever tiles are resident). GroundTracks keeps the
// deepest press of each vertex, so pressing the colliders one by one equals pressing them together.
void WorldSimulation::pressRuts() {
    const Scene& scene = resources_.scene;
    std::vector<Collider> recomputed;
    if (tick_ > 0 && pressedColliders_.empty()) {
        recomputed = worldColliders(scene, resources_.models, tick_ - 1);
        recomputed.insert(recomputed.end(), external_.begin(), external_.end());
    }
    const std::vector<Collider>& previous = pressedColliders_.empty() ? recomputed : pressedColliders_;
    for (const Collider& collider : lastColliders_) {
        if (collider.kind != ColliderKind::Push || !(collider.rut.depth > 0.0f)) continue;
        const Aabb bounds = worldBounds(collider);
        const double reach = double(GroundTracks::kMaxSweep) + collider.rut.depth + gpu::kTrackCell;
        const Ground ground = latticeGround(scene, glm::dvec2(bounds.min), glm::dvec2(bounds.max), reach);
        tracks_.press(previous, {&collider, 1}, ground);
    }
    pressedColliders_ = lastColliders_;
}

void WorldSimulation::readBackTiles() {
    for (auto& [key, sim] : tiles_) readBack(*resources_.world->find(TileCoord{key.second, key.first}));
}

void WorldSimulation::readBackKeptStates() {
    for (auto& [key, sim] : tiles_) readBack(*resources_.world->find(TileCoord{key.second, key.first}), true);
}

void WorldSimulation::saveState(const std::string& path) {
    WorldTiles& world = *resources_.world;
    for (auto& [key, sim] : tiles_) readBack(*world.find(TileCoord{key.second, key.first}));
    world.saveState(path, tick_, tracks_.blocks());
}

uint64_t WorldSimulation::restoreState(const std::string& path) {
    TrackBlocks tracks;
    const uint64_t tick = resources_.world->restoreState(path, &tracks);
    tracks_.restore(std::move(tracks));
    pressedColliders_.clear(); // recomputed for the next tick's sweep
    // The resident tiles' CPU copies now hold the restored state: the GPU copies and simulations are dropped and made
    // again from them by the next prepare().
    tiles_.clear();
    const std::vector<TileCoord> uploaded = renderer_.tiles();
    for (TileCoord coord : uploaded) renderer_.removeTile(coord);
    prepared_.reset();
    tick_ = tick;
    return tick;
}

} // namespace sward
