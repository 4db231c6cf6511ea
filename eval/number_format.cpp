#include "eval/number_format.h"

#include <cmath>
#include <cstdio>

namespace sward {

std::string csvNumber(double v) {
    if (!std::isfinite(v)) return "";
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%.9g", v);
    return buffer;
}

std::string fixed(double v, int decimals) {
    if (!std::isfinite(v)) return "n/a";
    char buffer[48];
    std::snprintf(buffer, sizeof(buffer), "%.*f", decimals, v);
    return buffer;
}

std::string metres(double v) {
    char buffer[32];
    std::snprintf(buffer, sizeof(buffer), "%g", v);
    return buffer;
}

std::string percent(double fraction) {
    return std::isfinite(fraction) ? fixed(100.0 * fraction, 2) + " %" : "n/a";
}

std::string signedFixed(double v, int decimals) {
    return (v > 0 ? "+" : "") + fixed(v, decimals);
}

} // namespace sward
