#include "world/heightfield_mesh.h"

namespace sward {

std::vector<uint32_t> heightfieldTriangleIndices(const Heightfield& h) {
    std::vector<uint32_t> indices;
    indices.reserve(size_t(h.columns() - 1) * (h.rows() - 1) * 6);
    for (uint32_t j = 0; j + 1 < h.rows(); ++j)
        for (uint32_t i = 0; i + 1 < h.columns(); ++i) {
            const uint32_t p00 = j * h.columns() + i, p10 = p00 + 1, p01 = p00 + h.columns(), p11 = p01 + 1;
            indices.insert(indices.end(), {p00, p10, p11, p00, p11, p01});
        }
    return indices;
}

} // namespace sward
