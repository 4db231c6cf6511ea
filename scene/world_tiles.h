// WorldTiles: a world of N x M scene tiles (the scene's "world" key) made resident around interest points — cameras
// and colliders — and evicted behind them, under a memory budget (issue 15, part 3).
//
// Tile (x, y) covers vegetation.world_origin + tile_size * [x, x+1) x [y, y+1). Its procedural terrain (a window on
// one world-wide lattice), its meadow grass map (a function of world xy) and its plants (hashed from (seed, tile,
// field, cluster, category, sample)) depend only on the scene and (x, y): a tile generated alone, after others, in
// any order or on any number of threads is bitwise the same, and neighbouring tiles meet without gap or overlap.
//
// Residency: a tile whose square lies within load_radius of a point is made resident; one beyond evict_radius of every
// point is evicted (the band between them keeps tiles from flickering in and out) once its plants have recovered (no
// active field: recovery runs on resident tiles only, so a tile still springing back stays, at most rest_ticks). An evicted tile leaves behind only
// its touched fields (interaction/tile_state.h), written back when it is generated again, so a track survives.
// Memory grows with the resident tiles: besides them the object holds the kept state of touched tiles and nothing
// per world tile.
#pragma once

#include "interaction/colliders.h"
#include "interaction/ground_tracks.h"
#include "interaction/tile_state.h"
#include "scene/scene.h"
#include "vegetation/cover_map.h"
#include "vegetation/vegetation_tile.h"
#include "world/ground.h"

#include <glm/glm.hpp>

#include <condition_variable>
#include <cstdint>
#include <exception>
#include <functional>
#include <map>
#include <mutex>
#include <optional>
#include <span>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace sward {

struct WorldTile {
    TileCoord coord;
    Ground ground;             // the tile's procedural terrain
    VegetationTile vegetation; // its plants (no fields with vegetation off); dynamic records + field activity are
                               // its interaction state
    CoverMap cover;            // its far cover (empty without category looks)
    uint64_t bytes = 0;        // resident bytes: terrain heights, plant and cluster records, field headers, cover
};

// The tile (x, y) of a world scene, generated on `threads` threads (0 = all cores); a pure function of the scene
// and the coordinate. Requires scene.world.enabled and (x, y) inside the world. With `looks` (one per category,
// categoryLooks), also the tile's far cover.
WorldTile generateWorldTile(const Scene& scene, TileCoord coord, uint32_t threads,
                            std::span<const CategoryLook> looks = {});

// The ground a world scene's camera needs at `time`: the procedural terrain on the world's lattice (bitwise the
// tiles' heights) around the camera's position and its look-at point, without generating any tile.
Ground cameraGround(const Scene& scene, double time);

// The procedural terrain on the world's lattice over the square spanned by a and b, widened by `margin` metres and
// two lattice cells: bitwise the tiles' heights there, without generating any tile.
Ground latticeGround(const Scene& scene, glm::dvec2 a, glm::dvec2 b, double margin);

// The xy of every vehicle, free collider and object (on its path) of a world scene at `time`: interest points, like
// the cameras.
std::vector<glm::dvec2> actorPoints(const Scene& scene, double time);

// actorColliders for a world scene: each actor stands on the lattice ground around itself (latticeGround), so its
// colliders are the same whichever tiles are resident. Same ids. Without the gusts and the objects' colliders:
// worldColliders (scene/world_objects.h) adds them.
std::vector<Collider> worldActorColliders(const Scene& scene, double time);

// The tiles of the world whose plants `collider` may touch, ascending (y, x): those whose square its bounds overlap,
// widened by a metre (the collision pass tests plants by their roots, which lie inside their tile).
std::vector<TileCoord> tilesReached(const Scene& scene, const Collider& collider);

// The tiles of the world whose square lies within `radius` metres of `point` (xy; the distance WorldTiles makes
// tiles resident by), ascending (y, x).
std::vector<TileCoord> tilesWithin(const Scene& scene, glm::dvec2 point, double radius);

// Whether a tile has an active field: its plants are still springing back from a contact.
bool recovering(const WorldTile& tile);

struct WorldTileStats {
    uint64_t generated = 0, evicted = 0, restored = 0; // tiles; restored: generated with kept state written back
    uint64_t plantsGenerated = 0;
    double generationSeconds = 0.0; // wall clock spent generating (waitFor and the worker together)
};

class WorldTiles {
public:
    // Requires scene.world.enabled; checks the memory budget (checkWorldScene). threads: per tile (0 = all cores).
    // looks: the vegetation's far look (categoryLooks), given to every tile's cover; empty: no cover.
    explicit WorldTiles(Scene scene, uint32_t threads = 0, std::vector<CategoryLook> looks = {});
    ~WorldTiles(); // stops the worker once the tile it is generating (discarded) is done
    WorldTiles(const WorldTiles&) = delete;
    WorldTiles& operator=(const WorldTiles&) = delete;

    // Blocking and deterministic (the offline renderer): evicts, then generates every missing tile within load_radius
    // of a point, in (y, x) order, before it returns. Throws sward::Error naming 'world.memory_budget_mib' when the
    // points' tiles cannot fit (several points far apart); nothing is evicted or generated then.
    void waitFor(std::span<const glm::dvec2> points);
    // Non-blocking (the viewer): evicts as waitFor does and hands the missing tiles, nearest first, to the worker
    // thread, replacing what an earlier request queued. They become resident in poll(). Budget error as waitFor.
    void request(std::span<const glm::dvec2> points);
    // Makes resident the tiles the worker has finished that the last request still wants (others are dropped);
    // returns how many. Never waits for a generation. Rethrows an error of the worker.
    uint32_t poll();

    const WorldTile* find(TileCoord coord) const;
    // The ground height at xy from the resident tile under it; nothing where that tile is not resident.
    std::optional<float> height(glm::dvec2 xy) const;
    WorldTile* find(TileCoord coord);             // its vegetation's dynamic records and activity may be written
    std::vector<TileCoord> residentTiles() const; // ascending (y, x)
    uint32_t residentCount() const { return uint32_t(resident_.size()); }
    uint64_t residentBytes() const;
    uint64_t keptStateBytes() const; // touched fields of evicted tiles
    uint32_t pendingTiles() const;   // requested, not yet resident
    const WorldTileStats& stats() const { return stats_; }
    const Scene& scene() const { return scene_; }

    // Called with a resident tile just before it is evicted: a GPU owner reads the tile's dynamic records back into
    // tile.vegetation here, so that the kept state is the current one.
    void setBeforeEvict(std::function<void(WorldTile&)> hook) { beforeEvict_ = std::move(hook); }

    // The whole world's interaction state — touched fields of resident and evicted tiles — and the tick, written as a
    // SWARDWS1 file (interaction/state_file.h). Throws sward::Error naming the file.
    void saveState(const std::string& path, uint64_t tick, const TrackBlocks& tracks = {}) const;
    // Reads a state saved for this world (same tile counts): resident tiles take it at once, the others when they are
    // generated. Returns its tick. Throws sward::Error naming the file; the world is unchanged then.
    // `tracks` (optional) gets the world's ruts saved with it.
    uint64_t restoreState(const std::string& path, TrackBlocks* tracks = nullptr);
    // Every tile dropped, resident or evicted, with its touched fields, as before the first waitFor: a new episode (the
    // Python module's reset). No eviction hook is called. Waits for the worker's tile in progress and drops it.
    void clear();

private:
    using Key = std::pair<int32_t, int32_t>; // (y, x): maps iterate in (y, x) order
    struct Plan {
        std::vector<Key> load; // missing tiles within load_radius, nearest first
        std::vector<Key> keep; // resident tiles within evict_radius of a point
    };
    Plan plan(std::span<const glm::dvec2> points) const;
    void evictAllBut(const std::vector<Key>& keep);
    void fitBudget(Plan& plan, std::span<const glm::dvec2> points, uint64_t pendingBytes);
    void makeResident(WorldTile tile);
    uint32_t absorbFinished(std::span<const glm::dvec2> points);
    void dropHeld(std::vector<Key>& load) const;
    bool wantedNear(const Key& key, std::span<const glm::dvec2> points) const;
    void workerLoop();
    void stopWorker();

    Scene scene_;
    uint32_t threads_;
    std::vector<CategoryLook> looks_;
    uint64_t predictedTileBytes_;
    std::map<Key, WorldTile> resident_;
    std::map<Key, TileInteractionState> kept_; // evicted tiles with touched fields
    std::vector<glm::dvec2> lastPoints_;       // of the last request, for poll()
    std::function<void(WorldTile&)> beforeEvict_;
    WorldTileStats stats_;

    // The worker: queue_ and finished_ under mutex_.
    mutable std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<Key> queue_; // next tile at the back
    std::vector<WorldTile> finished_;
    std::optional<Key> inFlight_; // the tile the worker is generating
    bool stop_ = false;
    std::exception_ptr error_;
    double workerSeconds_ = 0.0;
    std::thread worker_;
};

} // namespace sward
