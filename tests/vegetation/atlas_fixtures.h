// Atlases shared by the atlas tests (atlas_test.cpp, atlas_paint_test.cpp, atlas_file_test.cpp).
#pragma once

#include "vegetation/atlas.h"

namespace sward::test {

// Generating the full default atlas takes about a second; the tests share one copy.
inline const Atlas& defaultAtlas() {
    static const Atlas atlas = generateAtlas({});
    return atlas;
}

inline const Atlas& defaultAtlasWithMips(bool preserveCoverage) {
    static const Atlas preserved = [] {
        Atlas a = defaultAtlas();
        buildMipChain(a);
        return a;
    }();
    static const Atlas plain = [] {
        Atlas a = defaultAtlas();
        buildMipChain(a, 0.5f, false);
        return a;
    }();
    return preserveCoverage ? preserved : plain;
}

// A small atlas (2 rows of 32-texel cells) for tests that do not need the real one.
inline AtlasGenParams smallParams() {
    return {.seed = 7,
            .cellSize = 32,
            .rows = {{"grass", AtlasPlantKind::Grass, 2}, {"flowers", AtlasPlantKind::Flowers, 3}}};
}

} // namespace sward::test
