// The default scene object: a small four-wheeled skid-steer rover, generated procedurally and saved as glTF 2.0
// (examples/assets/rover.gltf, written by tools/sward-rover) so the shipped examples need no outside assets.
//
// Size: 1.0 m long, 0.7 m wide, 0.5 m tall; wheels of radius 0.15 m and width 0.12 m, wheel base 0.7 m, track
// 0.58 m (wheel centre to wheel centre). glTF frame: +Y up, the rover faces +Z (the glTF "front"), its left is +X;
// the origin is on the ground between the four wheel contact points. Nodes (names are the interface):
//   rover                root, no mesh
//     chassis            body box, deck, bumpers, axle stubs
//       mast             sensor mast on the front of the deck
//         camera_mount   stereo camera head; origin midway between the two lenses on the head's front face,
//                        axes parallel to the rover's (looks along +Z in glTF, -y in sward's model frame)
//       wheel_fl, wheel_fr, wheel_rl, wheel_rr   wheels (front/rear, left/right), origin at the hub, axle along X
// Every primitive has a plain material (pbrMetallicRoughness.baseColorFactor, no textures). ~700 triangles.
#pragma once

#include <string>

namespace sward {

struct RoverDimensions {
    double wheelRadius = 0.15, wheelWidth = 0.12;
    double wheelBase = 0.70;      // front axle to rear axle
    double trackWidth = 0.58;     // left wheel centre to right wheel centre
    double cameraBaseline = 0.12; // lens centre to lens centre
    double cameraHeight = 0.475;  // camera_mount origin above the ground
    double cameraForward = 0.30;  // camera_mount origin ahead of the rover origin
};

// The rover as glTF 2.0 JSON text with its buffer embedded as a base64 data URI. Deterministic: the same bytes
// on every run and machine (no transcendental functions: the wheel circles come from square roots).
std::string roverGltf(const RoverDimensions& dimensions = {});

// Writes roverGltf() to `path` atomically (<path>.tmp, then rename). Throws sward::Error naming the file.
void saveRoverGltf(const std::string& path, const RoverDimensions& dimensions = {});

} // namespace sward
