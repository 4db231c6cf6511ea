#include "world_drive.h"

#include "fly_camera.h"
#include "render/world_simulation.h"
#include "scene/world_tiles.h"

namespace sward {

namespace {

constexpr double kGroundMargin = 10.0; // the follow camera stands 6 m behind the rover
constexpr double kGroundMove = 4.0;

std::string tileList(const std::set<std::pair<int32_t, int32_t>>& tiles) {
    std::string out = std::to_string(tiles.size()) + " tile(s)";
    for (const auto& [x, y] : tiles) out += " (" + std::to_string(x) + "," + std::to_string(y) + ")";
    return out;
}

} // namespace

const Ground& WorldDrive::groundAround(glm::dvec2 xy) {
    if (!ground_ || glm::distance(xy, groundAt_) > kGroundMove) {
        ground_ = latticeGround(scene_, xy, xy, kGroundMargin + kGroundMove);
        groundAt_ = xy;
    }
    return *ground_;
}

Ground WorldDrive::groundAhead(const FlyCamera& camera) const {
    const glm::dvec2 eye(camera.position()), forward(camera.forward());
    const double flat = glm::length(forward);
    const glm::dvec2 ahead = flat > 1e-6 ? eye + forward / flat * 300.0 : eye;
    return latticeGround(scene_, eye, ahead, 1.0);
}

void WorldDrive::prepareTick(WorldSimulation& simulation, const WorldTiles& world, std::vector<Collider> wheels) {
    for (const Collider& wheel : wheels)
        for (TileCoord coord : tilesReached(scene_, wheel)) {
            crossed_.insert({coord.x, coord.y});
            if (world.find(coord)) pressed_.insert({coord.x, coord.y});
        }
    simulation.setWaitForTiles(false);
    simulation.setExternalColliders(std::move(wheels));
    simulation.prepare();
}

std::string WorldDrive::summary() const {
    return "rover's wheels reached " + tileList(crossed_) + ", pressed the plants of " + tileList(pressed_);
}

} // namespace sward
