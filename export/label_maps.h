// sward's semantic classes in the ontologies off-road models train on (sward-export --labels; docs/dataset-format.md,
// "Label ontologies", has the tables with the reasons): RELLIS-3D, RUGD and GOOSE, with their own class ids and
// names, and SemanticKITTI's 20 training classes for the label config of the semantickitti layout.
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace sward {

enum class LabelOntology { Sward, Rellis, Rugd, Goose };

// "sward", "rellis", "rugd" or "goose"; throws one error naming `what` (the flag) and the choices.
LabelOntology parseLabelOntology(const std::string& text, const std::string& what);
const char* ontologyName(LabelOntology ontology);

struct OntologyClass {
    uint32_t id;
    const char* name;
};

// Every class the ontology defines, by increasing id, as the dataset names them (sward: dataset/naming.h's table).
std::span<const OntologyClass> ontologyClasses(LabelOntology ontology);

// The ontology's class for sward class `swardClass`; a value no sward class uses maps to the ontology's
// void / undefined class (0 in all four).
uint32_t mapLabel(LabelOntology ontology, uint32_t swardClass);

// SemanticKITTI's training classes (semantic-kitti.yaml's learning_map targets: 0 unlabeled .. 19 traffic-sign)
// and the one each sward class trains as.
std::span<const OntologyClass> semanticKittiTrainingClasses();
uint32_t semanticKittiTrainingClass(uint32_t swardClass);

} // namespace sward
