#include "export/label_maps.h"

#include "common/error.h"
#include "dataset/naming.h"

#include <string_view>
#include <vector>

namespace sward {

namespace {

// RELLIS-3D's ontology (its README and rellis.yaml; ids are not contiguous).
constexpr OntologyClass kRellis[] = {{0, "void"},      {1, "dirt"},     {3, "grass"},   {4, "tree"},   {5, "pole"},
                                     {6, "water"},     {7, "sky"},      {8, "vehicle"}, {9, "object"}, {10, "asphalt"},
                                     {12, "building"}, {15, "log"},     {17, "person"}, {18, "fence"}, {19, "bush"},
                                     {23, "concrete"}, {27, "barrier"}, {31, "puddle"}, {33, "mud"},   {34, "rubble"}};
// RUGD's 25 classes (RUGD_annotation-colormap.txt).
constexpr OntologyClass kRugd[] = {
    {0, "void"},     {1, "dirt"},     {2, "sand"},      {3, "grass"},     {4, "tree"},
    {5, "pole"},     {6, "water"},    {7, "sky"},       {8, "vehicle"},   {9, "container/generic-object"},
    {10, "asphalt"}, {11, "gravel"},  {12, "building"}, {13, "mulch"},    {14, "rock-bed"},
    {15, "log"},     {16, "bicycle"}, {17, "person"},   {18, "fence"},    {19, "bush"},
    {20, "sign"},    {21, "rock"},    {22, "bridge"},   {23, "concrete"}, {24, "picnic-table"}};
// GOOSE's 64 classes (goose_label_mapping.csv).
constexpr OntologyClass kGoose[] = {{0, "undefined"},
                                    {1, "traffic_cone"},
                                    {2, "snow"},
                                    {3, "cobble"},
                                    {4, "obstacle"},
                                    {5, "leaves"},
                                    {6, "street_light"},
                                    {7, "bikeway"},
                                    {8, "ego_vehicle"},
                                    {9, "pedestrian_crossing"},
                                    {10, "road_block"},
                                    {11, "road_marking"},
                                    {12, "car"},
                                    {13, "bicycle"},
                                    {14, "person"},
                                    {15, "bus"},
                                    {16, "forest"},
                                    {17, "bush"},
                                    {18, "moss"},
                                    {19, "traffic_light"},
                                    {20, "motorcycle"},
                                    {21, "sidewalk"},
                                    {22, "curb"},
                                    {23, "asphalt"},
                                    {24, "gravel"},
                                    {25, "boom_barrier"},
                                    {26, "rail_track"},
                                    {27, "tree_crown"},
                                    {28, "tree_trunk"},
                                    {29, "debris"},
                                    {30, "crops"},
                                    {31, "soil"},
                                    {32, "rider"},
                                    {33, "animal"},
                                    {34, "truck"},
                                    {35, "on_rails"},
                                    {36, "caravan"},
                                    {37, "trailer"},
                                    {38, "building"},
                                    {39, "wall"},
                                    {40, "rock"},
                                    {41, "fence"},
                                    {42, "guard_rail"},
                                    {43, "bridge"},
                                    {44, "tunnel"},
                                    {45, "pole"},
                                    {46, "traffic_sign"},
                                    {47, "misc_sign"},
                                    {48, "barrier_tape"},
                                    {49, "kick_scooter"},
                                    {50, "low_grass"},
                                    {51, "high_grass"},
                                    {52, "scenery_vegetation"},
                                    {53, "sky"},
                                    {54, "water"},
                                    {55, "wire"},
                                    {56, "outlier"},
                                    {57, "heavy_machinery"},
                                    {58, "container"},
                                    {59, "hedge"},
                                    {60, "barrel"},
                                    {61, "pipe"},
                                    {62, "tree_root"},
                                    {63, "military_vehicle"}};
// semantic-kitti.yaml's learning_map targets.
constexpr OntologyClass kSemanticKittiTraining[] = {
    {0, "unlabeled"},     {1, "car"},       {2, "bicycle"},       {3, "motorcycle"},   {4, "truck"},
    {5, "other-vehicle"}, {6, "person"},    {7, "bicyclist"},     {8, "motorcyclist"}, {9, "road"},
    {10, "parking"},      {11, "sidewalk"}, {12, "other-ground"}, {13, "building"},    {14, "fence"},
    {15, "vegetation"},   {16, "trunk"},    {17, "terrain"},      {18, "pole"},        {19, "traffic-sign"}};

// One row per sward class: its class in RELLIS-3D, RUGD, GOOSE and SemanticKITTI's training classes. The reasons
// are in docs/dataset-format.md ("Label ontologies"); the vegetation categories follow the default meadow's
// (0 ferns, 1 grass, 2 shrubs and flowers).
struct Row {
    const char* sward; // dataset/naming.h's name of the class (its id there: export/ sees no shared/ constants)
    uint32_t rellis, rugd, goose, kitti;
};
constexpr Row kRows[] = {
    {"sky", 7, 7, 53, 0},
    {"ground", 1, 1, 31, 17},
    {"vegetation category 0", 19, 19, 17, 15},
    {"vegetation category 1", 3, 3, 51, 15},
    {"vegetation category 2", 19, 19, 17, 15},
    {"vegetation category 3", 19, 19, 17, 15},
    {"object", 9, 9, 4, 0},
    {"felled", 3, 3, 50, 15},
    {"cut", 3, 3, 50, 15},
    {"turf", 3, 3, 50, 17},
    {"track", 1, 1, 31, 17},
};

// The row of sward class `id`, or nullptr for a value no class uses.
const Row* rowOf(uint32_t id) {
    const SemanticClass* c = findSemanticClass(id);
    if (c == nullptr) return nullptr;
    for (const Row& row : kRows)
        if (std::string_view(row.sward) == c->name) return &row;
    return nullptr;
}

} // namespace

LabelOntology parseLabelOntology(const std::string& text, const std::string& what) {
    for (LabelOntology o : {LabelOntology::Sward, LabelOntology::Rellis, LabelOntology::Rugd, LabelOntology::Goose})
        if (text == ontologyName(o)) return o;
    throw Error(what + " '" + text + "' is not a label ontology (expected sward, rellis, rugd or goose)");
}

const char* ontologyName(LabelOntology ontology) {
    switch (ontology) {
    case LabelOntology::Sward:
        return "sward";
    case LabelOntology::Rellis:
        return "rellis";
    case LabelOntology::Rugd:
        return "rugd";
    case LabelOntology::Goose:
        return "goose";
    }
    return "?";
}

std::span<const OntologyClass> ontologyClasses(LabelOntology ontology) {
    switch (ontology) {
    case LabelOntology::Sward: {
        static const std::vector<OntologyClass> sward = [] {
            std::vector<OntologyClass> classes;
            for (const SemanticClass& c : semanticClasses()) classes.push_back({c.id, c.name});
            return classes;
        }();
        return sward;
    }
    case LabelOntology::Rellis:
        return kRellis;
    case LabelOntology::Rugd:
        return kRugd;
    case LabelOntology::Goose:
        return kGoose;
    }
    return {};
}

uint32_t mapLabel(LabelOntology ontology, uint32_t swardClass) {
    const Row* row = rowOf(swardClass);
    switch (ontology) {
    case LabelOntology::Sward:
        return swardClass;
    case LabelOntology::Rellis:
        return row ? row->rellis : 0u;
    case LabelOntology::Rugd:
        return row ? row->rugd : 0u;
    case LabelOntology::Goose:
        return row ? row->goose : 0u;
    }
    return 0;
}

std::span<const OntologyClass> semanticKittiTrainingClasses() {
    return kSemanticKittiTraining;
}

uint32_t semanticKittiTrainingClass(uint32_t swardClass) {
    const Row* row = rowOf(swardClass);
    return row ? row->kitti : 0u;
}

} // namespace sward
