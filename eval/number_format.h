// How the evaluation's reports print numbers; non-finite values print as "n/a" (or an empty CSV cell).
#pragma once

#include <string>

namespace sward {

std::string csvNumber(double v);                 // "%.9g"; "" when not finite
std::string fixed(double v, int decimals);       // "%.*f"; "n/a" when not finite
std::string signedFixed(double v, int decimals); // fixed() with a "+" before positive values
std::string percent(double fraction);            // "12.34 %"; "n/a" when not finite
std::string metres(double v);                    // band edges as typed: "5", "12.5", "0.25"

} // namespace sward
