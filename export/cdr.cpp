#include "export/cdr.h"

#include "common/little_endian.h" // appendRaw copies native bytes: little-endian (asserted there)

#include <cassert>

namespace sward {

namespace {
constexpr size_t kEncapsulationSize = 4;
}

CdrWriter::CdrWriter() : bytes_{'\0', '\1', '\0', '\0'} {}

CdrWriter& CdrWriter::string(std::string_view text) {
    assert(text.find('\0') == std::string_view::npos);
    put(uint32_t(text.size() + 1));
    appendRaw(text.data(), text.size());
    bytes_.push_back('\0');
    return *this;
}

CdrWriter& CdrWriter::sequenceLength(size_t count) {
    assert(count <= UINT32_MAX);
    return put(uint32_t(count));
}

CdrWriter& CdrWriter::byteSequence(std::string_view bytes) {
    sequenceLength(bytes.size());
    appendRaw(bytes.data(), bytes.size());
    return *this;
}

void CdrWriter::align(size_t size) {
    // Offsets count from the end of the encapsulation header, not from the start of the buffer.
    const size_t offset = bytes_.size() - kEncapsulationSize;
    bytes_.append((size - offset % size) % size, '\0');
}

void CdrWriter::appendRaw(const void* data, size_t size) {
    bytes_.append(static_cast<const char*>(data), size);
}

} // namespace sward
