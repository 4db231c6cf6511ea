// CDR: how ROS 2 serialises a message (OMG XCDR version 1, little-endian, the encoding rmw_fastrtps and
// rosbag2 store as "cdr"). A 4-byte encapsulation header {0, 1, 0, 0} (CDR_LE), then each field in order, every
// primitive aligned to its own size (8 at most) counted from the end of that header; strings as a uint32 length
// including the terminating NUL, the bytes and the NUL; sequences as a uint32 element count and the elements;
// fixed arrays as their elements only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

namespace sward {

class CdrWriter {
public:
    CdrWriter(); // writes the encapsulation header

    // One primitive, aligned to its size (bool and char as uint8).
    template <typename T> CdrWriter& put(T value) {
        static_assert(std::is_arithmetic_v<T> && sizeof(T) <= 8);
        align(sizeof(T));
        appendRaw(&value, sizeof(T));
        return *this;
    }
    CdrWriter& string(std::string_view text);
    // A sequence's element count (the elements follow through put / putArray).
    CdrWriter& sequenceLength(size_t count);
    // Elements of a fixed array or of a sequence whose length was just written: aligned once, then packed.
    template <typename T> CdrWriter& putArray(std::span<const T> values) {
        align(sizeof(T));
        appendRaw(values.data(), values.size_bytes());
        return *this;
    }
    // uint8[]: the count and the bytes.
    CdrWriter& byteSequence(std::string_view bytes);

    // The encoded message, header included.
    const std::string& bytes() const { return bytes_; }

private:
    void align(size_t size);
    void appendRaw(const void* data, size_t size);
    std::string bytes_;
};

} // namespace sward
