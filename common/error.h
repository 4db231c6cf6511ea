// sward::Error: the one exception type for bad input and unrecoverable failures. Its message is a complete,
// user-facing sentence that names the offending file or value; tools print it as one line and exit non-zero.
#pragma once

#include <stdexcept>
#include <string>

namespace sward {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

inline void require(bool condition, const std::string& message) {
    if (!condition) throw Error(message);
}

} // namespace sward
