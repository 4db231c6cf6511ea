// Host-side sub-allocation of device memory blocks (no device needed).
#include "common/error.h"
#include "engine/memory.h"

#include <gtest/gtest.h>

using namespace sward;

TEST(RangeAllocator, AlignsReusesAndCoalesces) {
    RangeAllocator ranges(1024);
    auto a = ranges.allocate(100, 1);
    auto b = ranges.allocate(100, 256);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(*a, 0u);
    EXPECT_EQ(*b, 256u);
    EXPECT_EQ(ranges.used(), 200u);
    EXPECT_FALSE(ranges.allocate(2000, 1).has_value());
    ranges.free(*a, 100);
    ranges.free(*b, 100);
    EXPECT_EQ(ranges.used(), 0u);
    EXPECT_EQ(ranges.freeRangeCount(), 1u) << "free ranges were not merged";
    auto whole = ranges.allocate(1024, 1);
    ASSERT_TRUE(whole.has_value());
    EXPECT_EQ(*whole, 0u);
    EXPECT_THROW(ranges.free(0, 2048), Error);
}
