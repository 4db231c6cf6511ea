// Atlas files: the PNG image and its JSON description (schema in atlas.h), read with the one JSON reader and
// written atomically.
#include "vegetation/atlas.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/json_reader.h"
#include "io/image_files.h"
#include "io/image_io.h"

#include <fstream>

namespace sward {

namespace {

AtlasCell readCell(JsonReader& r, const AtlasCell& defaults) {
    return {.baseU = r.numberF("base_u", defaults.baseU, 0.0, 1.0),
            .baseV = r.numberF("base_v", defaults.baseV, 0.0, 1.0),
            .aspect = r.numberF("aspect", defaults.aspect, 0.01, 100.0)};
}

AtlasRow readRow(JsonReader r, const AtlasCell& defaults) {
    r.required("category", "the vegetation category the row shows");
    AtlasRow row{.category = r.string("category", ""), .cells = {}};
    r.required("columns", "the number of variants, 1..64");
    row.cells.assign(size_t(r.integer("columns", 1, 1, 64)), defaults);
    if (r.has("cells")) {
        std::vector<JsonReader> cells = r.objects("cells");
        if (cells.size() != row.cells.size()) r.fail(r.name("cells") + " must be an array with one entry per column");
        for (size_t c = 0; c < cells.size(); ++c) {
            row.cells[c] = readCell(cells[c], defaults);
            cells[c].finish();
        }
    }
    r.finish();
    return row;
}

AtlasDesc parseAtlasDesc(const nlohmann::json& json, const std::string& source) {
    JsonReader r(json, source);
    r.choice("format", 0, {"sward-atlas"});
    r.integer("version", 1, 1, 1);
    AtlasDesc desc;
    r.required("cell_size", "[width, height] in texels");
    const glm::uvec2 cellSize = r.wholeVector<2>("cell_size", glm::uvec2(0), 0, UINT32_MAX);
    desc.cellWidth = cellSize.x;
    desc.cellHeight = cellSize.y;
    const AtlasCell defaults = readCell(r, AtlasCell{});
    r.required("rows", "one object per vegetation category");
    const std::vector<JsonReader> rows = r.objects("rows");
    if (rows.empty()) r.fail(r.name("rows") + " must be a non-empty array");
    for (const JsonReader& row : rows) desc.rows.push_back(readRow(row, defaults));
    r.finish();
    validateAtlasDesc(desc, source);
    return desc;
}

nlohmann::json describe(const AtlasDesc& desc) {
    nlohmann::json rows = nlohmann::json::array();
    for (const AtlasRow& row : desc.rows) {
        nlohmann::json cells = nlohmann::json::array();
        for (const AtlasCell& c : row.cells)
            cells.push_back({{"base_u", c.baseU}, {"base_v", c.baseV}, {"aspect", c.aspect}});
        rows.push_back({{"category", row.category}, {"columns", row.cells.size()}, {"cells", cells}});
    }
    return {
        {"format", "sward-atlas"}, {"version", 1}, {"cell_size", {desc.cellWidth, desc.cellHeight}}, {"rows", rows}};
}

} // namespace

Atlas loadAtlas(const std::string& pngPath, const std::string& jsonPath) {
    Atlas atlas{.desc = parseAtlasDesc(readJsonFile(jsonPath, "atlas description"), jsonPath), .mips = {}};

    const ImageData image = loadImage(pngPath);
    require(image.channels == 4 && image.bitDepth == 8,
            "atlas image '" + pngPath + "' must be an 8-bit RGBA PNG (it has " + std::to_string(image.channels) +
                " channels of " + std::to_string(image.bitDepth) + " bits)");
    const AtlasDesc& desc = atlas.desc;
    require(image.width == desc.width() && image.height == desc.height(),
            "atlas image '" + pngPath + "' is " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                " but '" + jsonPath + "' describes " + std::to_string(desc.maxColumns()) + " columns x " +
                std::to_string(desc.rows.size()) + " rows of " + std::to_string(desc.cellWidth) + "x" +
                std::to_string(desc.cellHeight) + " cells = " + std::to_string(desc.width()) + "x" +
                std::to_string(desc.height()));
    AtlasMip& mip = atlas.mips.emplace_back(AtlasMip{image.width, image.height, {}});
    mip.rgba.resize(image.samples.size());
    // loadImage() normalised each byte b to b / 255; rounding recovers it exactly.
    for (size_t i = 0; i < image.samples.size(); ++i) mip.rgba[i] = uint8_t(image.samples[i] * 255.0f + 0.5f);
    return atlas;
}

void saveAtlas(const Atlas& atlas, const std::string& pngPath, const std::string& jsonPath) {
    const AtlasDesc& desc = atlas.desc;
    validateAtlasDesc(desc, "saveAtlas('" + jsonPath + "')");
    require(!atlas.mips.empty() && atlas.mips[0].width == desc.width() && atlas.mips[0].height == desc.height() &&
                atlas.mips[0].rgba.size() == size_t(desc.width()) * desc.height() * 4,
            "cannot write '" + pngPath + "': the atlas image does not match its description");
    const AtlasMip& image = atlas.mips[0];
    writePng8(pngPath, image.width, image.height, 4, image.rgba);
    writeTextAtomically(jsonPath, describe(desc).dump(2) + "\n");
}

} // namespace sward
