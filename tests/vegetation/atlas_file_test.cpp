// Atlas files (vegetation/atlas_file.cpp): PNG + JSON description, saved atomically, loaded with named errors.
#include "vegetation/atlas.h"

#include "atlas_fixtures.h"
#include "test_files.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace sward;
using namespace sward::test;

TEST(Atlas, SaveLoadRoundTripsExactly) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    saveAtlas(a, (dir / "a.png").string(), (dir / "a.json").string());
    EXPECT_FALSE(std::filesystem::exists(dir / "a.png.tmp"));
    const Atlas b = loadAtlas((dir / "a.png").string(), (dir / "a.json").string());
    EXPECT_EQ(a.desc, b.desc);
    ASSERT_EQ(b.mips.size(), 1u);
    EXPECT_TRUE(a.mips[0] == b.mips[0]);
}

TEST(Atlas, LoadsMinimalUserDescription) {
    const auto dir = tempDir();
    writePng(dir / "user.png", 8, 4, 4, 8, std::vector<float>(8 * 4 * 4, 1.0f));
    std::ofstream(dir / "user.json")
        << R"({"cell_size": [4, 4], "base_v": 0.9, "rows": [{"category": "grass", "columns": 2}]})";
    const Atlas atlas = loadAtlas((dir / "user.png").string(), (dir / "user.json").string());
    ASSERT_EQ(atlas.desc.rows.size(), 1u);
    EXPECT_EQ(atlas.desc.rows[0].cells.size(), 2u);
    EXPECT_FLOAT_EQ(atlas.desc.rows[0].cells[1].baseV, 0.9f);
    EXPECT_FLOAT_EQ(atlas.desc.rows[0].cells[1].baseU, 0.5f);
}

TEST(Atlas, MissingFilesAreNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    saveAtlas(a, (dir / "a.png").string(), (dir / "a.json").string());
    expectError([&] { loadAtlas((dir / "a.png").string(), (dir / "none.json").string()); }, {"none.json", "missing"});
    expectError([&] { loadAtlas((dir / "none.png").string(), (dir / "a.json").string()); }, {"none.png"});
}

TEST(Atlas, BadJsonIsNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    const std::string png = (dir / "a.png").string(), json = (dir / "a.json").string();
    saveAtlas(a, png, json);
    std::ofstream(json) << "{\"cell_size\": [32, 32], ";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "not valid JSON"});
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2}], "colour": 1})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "unknown key 'colour'"});
    std::ofstream(json) << R"({"cell_size": [30, 32], "rows": [{"category": "grass", "columns": 2}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "powers of two"});
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2, "cells": []}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.json", "one entry per column"});
}

TEST(Atlas, ImageNotMatchingTheGridIsNamed) {
    const auto dir = tempDir();
    const Atlas a = generateAtlas(smallParams());
    const std::string png = (dir / "a.png").string(), json = (dir / "a.json").string();
    saveAtlas(a, png, json);
    std::ofstream(json) << R"({"cell_size": [32, 32], "rows": [{"category": "grass", "columns": 2}]})";
    expectError([&] { loadAtlas(png, json); }, {"a.png", "96x64", "64x32"});
}

TEST(Atlas, ImageThatIsNotRgba8IsNamed) {
    const auto dir = tempDir();
    const std::string json = (dir / "a.json").string();
    std::ofstream(json) << R"({"cell_size": [4, 4], "rows": [{"category": "grass", "columns": 1}]})";
    writePng(dir / "rgb.png", 4, 4, 3, 8, std::vector<float>(4 * 4 * 3, 0.5f));
    expectError([&] { loadAtlas((dir / "rgb.png").string(), json); }, {"rgb.png", "8-bit RGBA"});
    writePng(dir / "wide.png", 4, 4, 4, 16, std::vector<float>(4 * 4 * 4, 0.5f));
    expectError([&] { loadAtlas((dir / "wide.png").string(), json); }, {"wide.png", "8-bit RGBA"});
}
