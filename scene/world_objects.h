// Scene objects and gusts in a world of several tiles (issue 51): what stands on and blows over the world's lattice
// ground instead of one tile's, so that it is the same whichever tiles are resident.
//
// Objects: each object stands on the lattice ground around itself (latticeGround, widened by its footprint), as the
// vehicles do: it is drawn, collides and carries a mounted camera on that ground. Its path position is an interest
// point (actorPoints), so the tiles its colliders reach are resident.
//
// Gusts: in one tile they drift over the tile's square. A world has no one square they could drift over without
// either emptying it (the same `count` over 64 km^2) or forcing tiles resident far from the camera, so here they drift
// over the whole world (vegetation.world_origin + tile_size * [0, N] x [0, M]; the same hashed starts, radii, forces
// and drifts as makeGusts), their centres at a hashed height of 0 .. `height` above the lattice ground under them, and
// they blow only where every tile they reach lies within world.view_distance of the left camera: beyond it the air is
// calm. That range is where plants can be seen (lod.far + band / 2 <= view_distance), and since view_distance <=
// load_radius every tile a blowing gust reaches is resident; it depends on the camera's pose at the tick alone, never
// on which tiles are resident, so a streamed world presses the same plants as a resident one.
#pragma once

#include "interaction/colliders.h"
#include "scene/camera_rig.h"
#include "scene/objects.h"
#include "world/ground.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

namespace sward {

struct Scene;

// The lattice ground `object` (with its `model`) stands on at `time`: latticeGround around its path position,
// widened by its footprint, whichever tiles are resident. Requires scene.world.enabled.
Ground objectGround(const Scene& scene, const ObjectParams& object, const ObjectModel& model, double time);

// The rig of a world scene at `time` (sceneRig): on cameraGround, or mounted on an object, on that object's
// objectGround (so the camera rides the object as it is drawn).
RigCameras worldRig(const Scene& scene, const std::vector<ObjectModel>& models, uint32_t width, uint32_t height,
                    double time);

// The gusts of a world scene during tick `tick` whose every reached tile (tilesReached) lies within
// world.view_distance of `camera` (the left camera's xy at that tick), in id order (ids 0x80000000 + i, as makeGusts).
std::vector<Collider> worldGusts(const Scene& scene, uint64_t tick, glm::dvec2 camera);

// Every collider of a world scene during tick `tick`, in sceneColliders' order: the vehicles' and free colliders'
// (worldActorColliders), the gusts (worldGusts around worldRig's left camera) and the objects'
// node colliders (objectColliders, each object on its objectGround). `models`: loadObjectModels(scene.objects).
std::vector<Collider> worldColliders(const Scene& scene, const std::vector<ObjectModel>& models, uint64_t tick);

} // namespace sward
