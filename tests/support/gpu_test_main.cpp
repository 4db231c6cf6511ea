#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    // OpenCV reads this once, at its first EXR access: set it before any test runs.
    setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
