// sward-atlas: writes the procedural vegetation texture atlas (atlas.png + atlas.json). Parses the command line
// and calls generateAtlas()/saveAtlas(); nothing else.
#include "common/error.h"
#include "vegetation/atlas.h"

#include "tools/tool_main.h"

#include <CLI/CLI.hpp>

#include <bit>
#include <cstdio>
#include <filesystem>

int main(int argc, char** argv) {
    CLI::App app{"sward-atlas: paint the procedural vegetation texture atlas (one row per category)"};
    std::string outDir;
    sward::AtlasGenParams params;
    uint32_t variants = 0;
    app.add_option("--out,-o", outDir, "Output folder (created if missing)")->required();
    sward::addParsed(app, "--cell", params.cellSize, "Cell edge in texels, a power of two 32..2048", "UINT",
                     [](const std::string& text, const std::string& flag) {
                         const uint64_t cell = sward::parseUnsigned(text, 32, 2048, flag);
                         sward::require(std::has_single_bit(cell),
                                        flag + " must be a power of two, got '" + text + "'");
                         return uint32_t(cell);
                     });
    sward::addUnsigned(app, "--seed", params.seed, 0, UINT64_MAX, "Random seed; every texel is a pure function of it");
    // An atlas row holds at most 64 columns (vegetation/atlas.cpp).
    sward::addUnsigned(app, "--variants", variants, 1, 64, "Columns per row (default: each category's variants)");
    return sward::runTool(app, argc, argv, "sward-atlas", [&] {
        if (variants > 0) params.rows = sward::defaultAtlasRows(variants);
        std::error_code error;
        std::filesystem::create_directories(outDir, error);
        sward::require(!error, "cannot create output folder '" + outDir + "': " + error.message());
        const sward::Atlas atlas = sward::generateAtlas(params);
        const std::string png = (std::filesystem::path(outDir) / "atlas.png").string();
        const std::string json = (std::filesystem::path(outDir) / "atlas.json").string();
        sward::saveAtlas(atlas, png, json);
        std::printf("sward-atlas: wrote %s (%ux%u, %ux%u cells) and %s\n", png.c_str(), atlas.desc.width(),
                    atlas.desc.height(), atlas.desc.cellWidth, atlas.desc.cellHeight, json.c_str());
        for (const sward::AtlasRow& row : atlas.desc.rows)
            std::printf("  row %-8s %zu variants\n", row.category.c_str(), row.cells.size());
        return 0;
    });
}
