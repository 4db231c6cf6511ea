#include "interaction/interaction_params.h"

#include "common/json_reader.h"

namespace sward {

namespace {

// Bounds are doubles, as the values are read: a float bound (1e-6f) would move the edge of the accepted range.
void readCategory(JsonReader& in, CategoryInteraction& category) {
    category.fellForce = float(in.number("fell_force", category.fellForce, 0.0, 1e6));
    category.pushGain = float(in.number("push_gain", category.pushGain, 0.0, 1000.0));
    if (in.has("max_bend")) category.maxBend = float(in.number("max_bend", 1.0, 0.01, 1e6));
    in.finish();
}

void readRecovery(JsonReader in, RecoveryParams& r) {
    r.timeStep = float(in.number("time_step", r.timeStep, 1e-6, 1.0));
    r.stiffness = float(in.number("stiffness", r.stiffness, 0.0, 1e6));
    r.damping = float(in.number("damping", r.damping, 0.0, 1e6));
    r.restBend = float(in.number("rest_bend", r.restBend, 0.0, 0.5));
    r.fellBend = float(in.number("fell_bend", r.fellBend, 0.0, kMaxPush));
    r.restTicks = uint32_t(in.integer("rest_ticks", r.restTicks, 1, 1000000));
    in.finish();
}

} // namespace

InteractionParams parseInteractionParams(const nlohmann::json& json, const std::string& source) {
    InteractionParams p;
    JsonReader in(json, source, "interaction");
    if (in.has("categories")) {
        std::vector<JsonReader> categories = in.objects("categories");
        if (categories.empty() || categories.size() > gpu::kMaxPlantCategories)
            in.fail(in.name("categories") + " must be an array of 1 to 4 objects");
        for (size_t i = 0; i < categories.size(); ++i) readCategory(categories[i], p.categories[i]);
    }
    readRecovery(in.child("recovery"), p.recovery);
    in.finish();
    return p;
}

} // namespace sward
