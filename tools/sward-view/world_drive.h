// WorldDrive: the keyboard rover in a world of several tiles (issue 51). The rover stands on the world's lattice
// ground around itself (latticeGround: the tiles' heights bitwise, resident or not), so it drives on whatever tiles
// are resident: the viewer never waits for a tile's generation. Its wheels press ruts wherever it goes (the rut layer
// needs no tile) and the plants of the resident tiles they reach (WorldSimulation::setWaitForTiles(false)); a tile
// still being generated when the rover reaches it is crossed without pressing its plants (they stand as generated).
// The viewer requests the tiles around the rover as around its camera, so they come as it drives.
#pragma once

#include "interaction/colliders.h"
#include "scene/scene.h"
#include "world/ground.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace sward {

class FlyCamera;
class WorldSimulation;
class WorldTiles;

class WorldDrive {
public:
    explicit WorldDrive(const Scene& scene) : scene_(scene) {} // `scene` (a world's) must outlive this
    // The lattice ground within 10 m of xy at least (made again once xy has moved 4 m from where it was made).
    const Ground& groundAround(glm::dvec2 xy);
    // The lattice ground under the camera's look, out to 300 m (where RoverControl::spawn places the rover).
    Ground groundAhead(const FlyCamera& camera) const;
    // One viewer tick: the rover's wheels `wheels` (empty without a rover) act from this tick on; prepares it without
    // waiting for tiles and notes the tiles the wheels cross and those whose plants they press (resident ones).
    void prepareTick(WorldSimulation& simulation, const WorldTiles& world, std::vector<Collider> wheels);
    // "crossed N tile(s) (x,y) ..., pressed the plants of M ...": what the summary prints.
    std::string summary() const;

private:
    using Key = std::pair<int32_t, int32_t>; // (x, y)
    const Scene& scene_;
    std::optional<Ground> ground_;
    glm::dvec2 groundAt_{0.0};
    std::set<Key> crossed_, pressed_;
};

} // namespace sward
