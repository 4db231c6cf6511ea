#include "vegetation/vegetation_tile.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>

using namespace sward;

namespace {

// A 4 x 4 grid of 5 m clusters, 1 m tall, numbered row-major (x fastest) like a field's.
std::vector<ClusterBox> grid() {
    std::vector<ClusterBox> boxes;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            boxes.push_back({glm::vec3(5.0f * x, 5.0f * y, 0.0f), glm::vec3(5.0f * x + 5.0f, 5.0f * y + 5.0f, 1.0f)});
    return boxes;
}

float squaredDistance(const ClusterBox& b, glm::vec3 eye) {
    const glm::vec3 d = glm::max(glm::max(b.min - eye, eye - b.max), glm::vec3(0.0f));
    return glm::dot(d, d);
}

} // namespace

// The expansion lays instances out cluster by cluster in this order: nearest box first, ties by index, every
// cluster once.
TEST(DrawOrder, ClustersRunFrontToBackWithTiesByIndex) {
    const std::vector<ClusterBox> boxes = grid();
    std::vector<uint32_t> order;
    for (glm::vec3 eye : {glm::vec3(19.0f, 19.0f, 1.8f), glm::vec3(-3.0f, 7.5f, 1.8f), glm::vec3(7.5f, 2.5f, 0.5f)}) {
        frontToBack(boxes, eye, order);
        ASSERT_EQ(order.size(), boxes.size());
        std::vector<uint32_t> sorted = order;
        std::sort(sorted.begin(), sorted.end());
        std::vector<uint32_t> all(boxes.size());
        std::iota(all.begin(), all.end(), 0u);
        EXPECT_EQ(sorted, all) << "a permutation of the clusters";
        for (size_t i = 1; i < order.size(); ++i) {
            const float before = squaredDistance(boxes[order[i - 1]], eye),
                        after = squaredDistance(boxes[order[i]], eye);
            ASSERT_LE(before, after) << "position " << i;
            if (before == after) {
                EXPECT_LT(order[i - 1], order[i]) << "ties by index, position " << i;
            }
        }
    }
    // From the far corner the index order is back to front, so the front-to-back order is not it.
    frontToBack(boxes, glm::vec3(19.0f, 19.0f, 1.8f), order);
    EXPECT_EQ(order.front(), 15u);
    EXPECT_EQ(order.back(), 0u);
    // Inside a cluster (distance 0): that cluster first.
    frontToBack(boxes, glm::vec3(7.5f, 2.5f, 0.5f), order);
    EXPECT_EQ(order.front(), 1u);
}
