// WorldSimulation: the fixed-tick interaction loop of a world of several tiles (issue 15, part 3) — what Simulation
// is for one tile. Tick t happens at time t * timeStep, as there.
//
// Before each tick, the tiles within load_radius of the left camera and of every vehicle, free collider and object are
// made resident (WorldTiles::waitFor; deterministic) and uploaded. Each actor and object stands on the world's lattice
// ground around itself and gusts blow within view_distance of the left camera (scene/world_objects.h), so the
// colliders (worldColliders) do not depend on residency. A tile a collider reaches gets its own collision pass and GPU
// recovery (an InteractionWorld + InteractionGpu on the renderer's buffers of that tile), resumed at the current tick;
// it keeps them while resident. Before a tile is evicted its dynamic records are read back into the CPU tile, whose
// touched fields WorldTiles keeps; WorldTiles keeps a tile resident while its plants recover. So the state of every
// plant at tick t is the same whether the world is streamed or wholly resident.
//
// Ruts (colliders with rut_depth): one GroundTracks for the whole world (its lattice is world-wide), pressed each tick
// on the world's lattice ground around each collider, so they do not depend on residency either; they are drawn on
// every tile (SceneRenderer::setWorldGroundTracks) and saved with the world's state. Nothing of them is evicted.
#pragma once

#include "interaction/ground_tracks.h"
#include "interaction/interaction.h"
#include "render/interaction_gpu.h"
#include "render/scene_renderer.h"
#include "scene/scene_resources.h"

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace sward {

class WorldSimulation {
public:
    // `resources` (a world) and `renderer` (drawing its tiles) must outlive the simulation. threads: collision
    // threads (0 = all cores).
    WorldSimulation(Context& ctx, SceneResources& resources, SceneRenderer& renderer, uint32_t threads = 0);
    ~WorldSimulation();
    WorldSimulation(const WorldSimulation&) = delete;
    WorldSimulation& operator=(const WorldSimulation&) = delete;

    uint64_t nextTick() const { return tick_; }
    // Readies the next tick, outside any command buffer: makes resident and uploads the tiles it needs (around the left
    // camera, every actor at its time and the points `around`: a frame's sub-frame cameras; waits for their generation)
    // and the collision pass of every tile its colliders reach. Throws sward::Error naming 'world.memory_budget_mib'
    // when the tiles cannot fit, or when a collider reaches a tile that is not resident then (a load_radius smaller
    // than the collider).
    void prepare(std::span<const glm::dvec2> around = {});
    // Simulates every tick before `tick` that has not run yet, each prepared and in its own submission (waits).
    void runTicksBefore(uint64_t tick);
    // Prepares the next tick with the points `around` (as prepare) and runs it in its own submission, `before` recorded
    // first (the motion ground truth keeps the plants' states there: render/sequence_frame.cpp). Waits.
    void runNextTick(std::span<const glm::dvec2> around, const std::function<void(VkCommandBuffer)>& before);
    // Runs the collision pass of the next tick (prepared) on every tile a collider reaches and records the GPU update
    // of every simulated tile into `cmd`.
    void recordNextTick(VkCommandBuffer cmd, uint32_t slot);

    // Reads every simulated tile's dynamic records back into its CPU tile, as before an eviction: the resident tiles
    // then hold the plants' state after the latest tick (what the range sensors cast against).
    void readBackTiles();
    // The same with the state VegetationRenderer::recordKeepState kept last instead of the live records: after a frame
    // with flow, whose next tick has run, the plants' state its cameras drew (render/sequence_frame.h). A simulated
    // tile's CPU copy is never its live state (the GPU's ticks move on), and every eviction and save reads the live
    // records back again first.
    void readBackKeptStates();
    // The whole world's interaction state (WorldTiles::saveState after reading every simulated tile back).
    void saveState(const std::string& path);
    // Restores a state saved by saveState; returns its tick. The renderer's tiles are uploaded again.
    uint64_t restoreState(const std::string& path);

    // Colliders of a program's own (render/session.h setColliders): from the next tick they act after the scene's
    // (as Simulation's do) and are interest points like them, until replaced.
    void setExternalColliders(std::vector<Collider> colliders) { external_ = std::move(colliders); }
    // false (sward-view, which never waits for a tile's generation): prepare() takes the tiles resident as they are,
    // and a collider reaching a tile that is not resident has no pass there (its plants stand as generated). Ruts are
    // pressed wherever colliders go: they need no tile.
    void setWaitForTiles(bool wait) { waitForTiles_ = wait; }
    const std::vector<Collider>& lastColliders() const { return lastColliders_; } // of the latest tick
    const GroundTracks& tracks() const { return tracks_; }                        // the world's ruts
    uint32_t simulatedTiles() const { return uint32_t(tiles_.size()); }
    uint64_t contacts() const { return contacts_; } // summed over all ticks and tiles

private:
    using Key = std::pair<int32_t, int32_t>; // (y, x)
    struct TileSimulation {
        TileSimulation(Context& ctx, const Scene& scene, const VegetationTile& tile, VegetationBuffers& buffers,
                       uint32_t threads);
        InteractionWorld world;
        InteractionGpu gpu;
    };
    TileSimulation& simulationOf(TileCoord coord);
    void readBack(WorldTile& tile, bool kept = false);
    std::vector<glm::dvec2> interestPoints(uint64_t tick) const;
    void pressRuts();

    Context& ctx_;
    SceneResources& resources_;
    SceneRenderer& renderer_;
    uint32_t threads_;
    uint64_t tick_ = 0;
    std::map<Key, std::unique_ptr<TileSimulation>> tiles_;
    std::vector<Collider> external_, lastColliders_;
    std::optional<uint64_t> prepared_;              // the tick prepare() readied
    std::map<Key, std::vector<Collider>> reaching_; // its colliders by the tiles they reach, in the scene's order
    uint64_t contacts_ = 0;
    GroundTracks tracks_;
    std::vector<Collider> pressedColliders_; // of the last tick whose ruts were pressed; empty after a restore
    bool waitForTiles_ = true;
};

} // namespace sward
