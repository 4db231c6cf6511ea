// The one strict parser of numbers typed on a command line (and of the numbers inside option texts such as
// "1280x720", "0:60" or "0/4"). sscanf/strtoul/stoul accept signs, spaces and hex and wrap modulo 2^32 or 2^64
// ("4294967616" became 320); these functions accept exactly the documented form or throw sward::Error.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

namespace sward {

// Frame numbers end below this: per-frame files have six-digit names (dataset/naming.h) and scenes hold at most
// this many frames (sequence.frames).
inline constexpr uint32_t kFrameLimit = 1000000;

// `text` as a decimal whole number: ASCII digits only (no sign, space, '+', hex or exponent), no overflow, within
// [min, max]. Otherwise throws "<what> must be a whole number from <min> to <max>, got '<text>'".
uint64_t parseUnsigned(std::string_view text, uint64_t min, uint64_t max, std::string_view what);

// parseUnsigned with an optional leading '-': a whole number within [min, max].
int64_t parseInteger(std::string_view text, int64_t min, int64_t max, std::string_view what);

// `text` as a finite decimal real number (digits, optional sign, '.', exponent; the whole text, no inf/nan, no
// spaces) within [min, max]. Otherwise throws "<what> must be a number from <min> to <max>, got '<text>'".
double parseReal(std::string_view text, double min, double max, std::string_view what);

// "A<separator>B" split at its one separator; throws "<what> must be <form>, got '<text>'" if there is none or
// more than one.
std::pair<std::string_view, std::string_view> splitPair(std::string_view text, char separator, std::string_view what,
                                                        std::string_view form);

// "A:B" with min <= A < B <= max, as [A, B). Throws naming `what` (e.g. "--frames") otherwise.
std::pair<uint64_t, uint64_t> parseHalfOpenRange(std::string_view text, uint64_t min, uint64_t max,
                                                 std::string_view what);

} // namespace sward
