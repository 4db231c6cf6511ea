// How plants respond to colliders: per category fell thresholds and push gains, and the recovery spring, as the
// scene file's "interaction" object sets them.
#pragma once

#include "interaction/recovery.h"

#include "shared/gpu_layout.h"

#include <nlohmann/json_fwd.hpp>

#include <array>
#include <cmath>
#include <string>

namespace sward {

// The largest bend a push leaves: a bend of 1 would lay the tip on the ground, which is left to felled plants.
inline constexpr float kMaxPush = 0.95f;

// How the plants of one category respond to colliders.
struct CategoryInteraction {
    float fellForce = 0.6f; // a Push collider with a larger force flattens the plant for good (collider units)
    float pushGain = 2.0f;  // bend per unit of force * penetration / plant height
    // A Push collider bending the tip further than this (plant heights, before the kMaxPush clamp) fells the plant as
    // well (paper 3.3: "exceeds a maximum bend"); none by default.
    float maxBend = INFINITY;
};

// Interaction configuration: per category responses (index = atlas row, as VegetationParams::categories) and the
// recovery spring. Defaults: ferns 1.0, grass 0.6, flowers 0.8, extra 0.8 fell force; push gain 2.
struct InteractionParams {
    std::array<CategoryInteraction, gpu::kMaxPlantCategories> categories = {
        CategoryInteraction{1.0f, 2.0f}, CategoryInteraction{0.6f, 2.0f}, CategoryInteraction{0.8f, 2.0f},
        CategoryInteraction{0.8f, 2.0f}};
    RecoveryParams recovery;
};

// Reads the scene file's "interaction" object (every key optional, unknown keys are errors):
//   categories  array of 1..4 objects {"fell_force": 0..1e6, "push_gain": 0..1000, "max_bend": 0.01..1e6};
//               entry i sets category i
//   recovery    {"time_step": [1e-6, 1], "stiffness": 0..1e6, "damping": 0..1e6, "rest_bend": 0..0.5,
//                "fell_bend": 0..kMaxPush, "rest_ticks": 1..1e6}
// Throws sward::Error in common/json_reader.h's wording: "<source>: 'interaction.<key>' must be ...".
InteractionParams parseInteractionParams(const nlohmann::json& json, const std::string& source);

} // namespace sward
