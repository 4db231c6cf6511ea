// sward's classes in RELLIS-3D, RUGD, GOOSE and SemanticKITTI's training classes (export/label_maps.h).
#include "export/label_maps.h"

#include "common/error.h"
#include "dataset/naming.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

using namespace sward;

namespace {

std::string nameIn(LabelOntology ontology, uint32_t id) {
    for (const OntologyClass& c : ontologyClasses(ontology))
        if (c.id == id) return c.name;
    return "(no class " + std::to_string(id) + ")";
}

std::string mapped(LabelOntology ontology, const char* swardName) {
    for (const SemanticClass& c : semanticClasses())
        if (std::string(c.name) == swardName) return nameIn(ontology, mapLabel(ontology, c.id));
    return "(no sward class " + std::string(swardName) + ")";
}

} // namespace

TEST(LabelMaps, OntologiesHaveTheirDatasetsClassCountsWithIncreasingUniqueIds) {
    EXPECT_EQ(ontologyClasses(LabelOntology::Rellis).size(), 20u); // void + RELLIS-3D's 19 classes
    EXPECT_EQ(ontologyClasses(LabelOntology::Rugd).size(), 25u);   // void + RUGD's 24
    EXPECT_EQ(ontologyClasses(LabelOntology::Goose).size(), 64u);  // GOOSE's 64, ids 0..63
    EXPECT_EQ(semanticKittiTrainingClasses().size(), 20u);
    for (LabelOntology o : {LabelOntology::Sward, LabelOntology::Rellis, LabelOntology::Rugd, LabelOntology::Goose}) {
        uint32_t previous = 0;
        bool first = true;
        for (const OntologyClass& c : ontologyClasses(o)) {
            EXPECT_TRUE(first || c.id > previous) << ontologyName(o) << " " << c.name;
            previous = c.id, first = false;
        }
    }
    EXPECT_EQ(nameIn(LabelOntology::Rellis, 34), "rubble");
    EXPECT_EQ(nameIn(LabelOntology::Rugd, 24), "picnic-table");
    EXPECT_EQ(nameIn(LabelOntology::Goose, 63), "military_vehicle");
}

TEST(LabelMaps, EverySwardClassLandsOnANamedClassOfEachOntology) {
    for (const SemanticClass& c : semanticClasses()) {
        EXPECT_EQ(mapLabel(LabelOntology::Sward, c.id), c.id);
        for (LabelOntology o : {LabelOntology::Rellis, LabelOntology::Rugd, LabelOntology::Goose})
            EXPECT_EQ(nameIn(o, mapLabel(o, c.id)).rfind("(no", 0), std::string::npos)
                << c.name << " " << ontologyName(o);
        EXPECT_LT(semanticKittiTrainingClass(c.id), 20u);
        EXPECT_NE(mapLabel(LabelOntology::Rellis, c.id), 0u) << c.name << ": no row in the table (void)";
    }
    // A value no sward class uses is the void class, never another's id.
    EXPECT_EQ(mapLabel(LabelOntology::Rellis, 6), 0u);
    EXPECT_EQ(mapLabel(LabelOntology::Goose, 200), 0u);
}

TEST(LabelMaps, TheDocumentedChoices) {
    EXPECT_EQ(mapped(LabelOntology::Rellis, "vegetation category 1"), "grass");
    EXPECT_EQ(mapped(LabelOntology::Rellis, "vegetation category 0"), "bush");
    EXPECT_EQ(mapped(LabelOntology::Rellis, "ground"), "dirt");
    EXPECT_EQ(mapped(LabelOntology::Rellis, "sky"), "sky");
    EXPECT_EQ(mapped(LabelOntology::Rugd, "object"), "container/generic-object");
    EXPECT_EQ(mapped(LabelOntology::Rugd, "turf"), "grass");
    EXPECT_EQ(mapped(LabelOntology::Goose, "vegetation category 1"), "high_grass");
    EXPECT_EQ(mapped(LabelOntology::Goose, "cut"), "low_grass");
    EXPECT_EQ(mapped(LabelOntology::Goose, "track"), "soil");
    EXPECT_EQ(semanticKittiTrainingClasses()[semanticKittiTrainingClass(1)].name, std::string("terrain"));
    EXPECT_EQ(semanticKittiTrainingClasses()[semanticKittiTrainingClass(3)].name, std::string("vegetation"));
}

TEST(LabelMaps, ParsingNamesTheFlagAndTheChoices) {
    EXPECT_EQ(parseLabelOntology("goose", "--labels"), LabelOntology::Goose);
    EXPECT_EQ(parseLabelOntology("sward", "--labels"), LabelOntology::Sward);
    try {
        parseLabelOntology("RELLIS", "--labels");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "--labels 'RELLIS' is not a label ontology (expected sward, rellis, rugd or goose)");
    }
}
