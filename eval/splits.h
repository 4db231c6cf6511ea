// How every evaluation splits its pixels (docs/evaluation.md, "Splits"): by semantic class group and by distance
// band. Shared by the stereo and the optical-flow evaluation so both name and bound their groups the same way.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace sward {

// The class groups errors are split into, in report order. Dataset classes (dataset/naming.h) join the group of
// their broad class; sky and unknown ids fall into "other".
inline constexpr std::array<const char*, 4> kClassGroups = {"vegetation", "ground", "object", "other"};

// The kClassGroups index of a semantic/ pixel value.
uint8_t classGroupOf(uint8_t semanticClass);

// Distance bands [0, e0), [e0, e1), ..., [en, inf) of increasing edges in metres.
struct DistanceBand {
    std::string name;                    // "0-5 m", "50+ m"
    double minMetres = 0, maxMetres = 0; // maxMetres is +inf for the last band
};

// Throws sward::Error unless the edges are finite, positive and strictly increasing.
void requireBandEdges(const std::vector<double>& edges);
// The edges.size() + 1 bands the edges bound, named for reports.
std::vector<DistanceBand> distanceBands(const std::vector<double>& edges);
// The band of depth z (metres); z = +inf (or NaN) falls into the last band.
size_t bandIndex(const std::vector<double>& edges, double z);
// "5,10,20,50" as the --bands option takes it; throws sward::Error naming `flag` for a bad edge.
std::vector<double> parseBandEdges(const std::string& text, const std::string& flag);

} // namespace sward
