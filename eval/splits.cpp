#include "eval/splits.h"

#include "common/error.h"
#include "common/parse_number.h"
#include "dataset/naming.h"
#include "eval/number_format.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>

namespace sward {

namespace {

std::array<uint8_t, 256> classGroupTable() {
    std::array<uint8_t, 256> table;
    table.fill(uint8_t(kClassGroups.size() - 1)); // "other"
    for (const SemanticClass& c : semanticClasses())
        for (size_t g = 0; g + 1 < kClassGroups.size(); ++g)
            if (std::string_view(c.group) == kClassGroups[g]) table[c.id] = uint8_t(g);
    return table;
}

} // namespace

uint8_t classGroupOf(uint8_t semanticClass) {
    static const std::array<uint8_t, 256> table = classGroupTable();
    return table[semanticClass];
}

void requireBandEdges(const std::vector<double>& edges) {
    for (size_t i = 0; i < edges.size(); ++i)
        require(edges[i] > 0 && std::isfinite(edges[i]) && (i == 0 || edges[i] > edges[i - 1]),
                "distance band edges must be positive and increasing");
}

std::vector<DistanceBand> distanceBands(const std::vector<double>& edges) {
    std::vector<DistanceBand> bands;
    for (size_t i = 0; i <= edges.size(); ++i) {
        DistanceBand band;
        band.minMetres = i == 0 ? 0.0 : edges[i - 1];
        band.maxMetres = i == edges.size() ? INFINITY : edges[i];
        band.name = metres(band.minMetres) + (i == edges.size() ? "+ m" : "-" + metres(band.maxMetres) + " m");
        bands.push_back(std::move(band));
    }
    return bands;
}

size_t bandIndex(const std::vector<double>& edges, double z) {
    if (std::isnan(z)) return edges.size();
    return size_t(std::upper_bound(edges.begin(), edges.end(), z) - edges.begin());
}

std::vector<double> parseBandEdges(const std::string& text, const std::string& flag) {
    std::vector<double> edges;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        edges.push_back(parseReal(item, 0.001, 1e6, flag + " '" + text + "': band edge (metres)"));
    return edges;
}

} // namespace sward
