// COLMAP's database.db as the export writes it, read back through SQLite as COLMAP reads it.
#include "export/colmap_database.h"

#include <gtest/gtest.h>
#include <sqlite3.h>

#include <cstring>

using namespace sward;

namespace {

// The bytes opened as a read-only in-memory database.
sqlite3* openBytes(std::vector<char>& bytes) {
    sqlite3* db = nullptr;
    EXPECT_EQ(sqlite3_open(":memory:", &db), SQLITE_OK);
    EXPECT_EQ(sqlite3_deserialize(db, "main", reinterpret_cast<unsigned char*>(bytes.data()),
                                  sqlite3_int64(bytes.size()), sqlite3_int64(bytes.size()),
                                  SQLITE_DESERIALIZE_READONLY),
              SQLITE_OK);
    return db;
}

} // namespace

TEST(ColmapDatabase, CamerasAndImagesKeepTheirIdsParametersAndPriors) {
    const ColmapCameraRow camera{.id = 1, .model = 1, .width = 160, .height = 120, .params = {103.5, 104.25, 80, 60}};
    const std::vector<ColmapImageRow> images = {
        {.id = 1, .name = "left/000000.png", .rotation = {0.1, 0.2, 0.3, 0.9}, .translation = {1, 2, 3}},
        {.id = 2, .name = "right/000000.png"},
        {.id = 7, .name = "left/000003.png"}};
    std::vector<char> bytes = colmapDatabaseBytes({camera}, images);
    EXPECT_EQ(colmapDatabaseBytes({camera}, images), bytes); // the same rows, the same bytes
    sqlite3* db = openBytes(bytes);

    sqlite3_stmt* query = nullptr;
    ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT camera_id, model, width, height, params, prior_focal_length FROM cameras",
                                 -1, &query, nullptr),
              SQLITE_OK);
    ASSERT_EQ(sqlite3_step(query), SQLITE_ROW);
    EXPECT_EQ(sqlite3_column_int(query, 0), 1);
    EXPECT_EQ(sqlite3_column_int(query, 1), 1); // PINHOLE
    EXPECT_EQ(sqlite3_column_int(query, 2), 160);
    EXPECT_EQ(sqlite3_column_int(query, 3), 120);
    ASSERT_EQ(sqlite3_column_bytes(query, 4), 4 * 8); // float64 each, as COLMAP reads them
    double params[4];
    std::memcpy(params, sqlite3_column_blob(query, 4), sizeof params);
    EXPECT_EQ(params[0], 103.5);
    EXPECT_EQ(params[1], 104.25);
    EXPECT_EQ(params[3], 60.0);
    EXPECT_EQ(sqlite3_column_int(query, 5), 1);
    EXPECT_EQ(sqlite3_step(query), SQLITE_DONE);
    sqlite3_finalize(query);

    ASSERT_EQ(sqlite3_prepare_v2(db,
                                 "SELECT image_id, name, camera_id, prior_qw, prior_qx, prior_tz FROM images "
                                 "ORDER BY image_id",
                                 -1, &query, nullptr),
              SQLITE_OK);
    for (const ColmapImageRow& image : images) {
        ASSERT_EQ(sqlite3_step(query), SQLITE_ROW);
        EXPECT_EQ(uint32_t(sqlite3_column_int(query, 0)), image.id);
        EXPECT_EQ(reinterpret_cast<const char*>(sqlite3_column_text(query, 1)), image.name);
        EXPECT_EQ(sqlite3_column_int(query, 2), 1);
        EXPECT_EQ(sqlite3_column_double(query, 3), image.rotation.x); // qw is the vector's x
        EXPECT_EQ(sqlite3_column_double(query, 4), image.rotation.y);
        EXPECT_EQ(sqlite3_column_double(query, 5), image.translation.z);
    }
    EXPECT_EQ(sqlite3_step(query), SQLITE_DONE);
    sqlite3_finalize(query);

    // Every table COLMAP 3.8 creates is there, so it opens the file without adding any.
    ASSERT_EQ(sqlite3_prepare_v2(db, "SELECT name FROM sqlite_master WHERE type = 'table' ORDER BY name", -1, &query,
                                 nullptr),
              SQLITE_OK);
    std::vector<std::string> tables;
    while (sqlite3_step(query) == SQLITE_ROW)
        tables.emplace_back(reinterpret_cast<const char*>(sqlite3_column_text(query, 0)));
    sqlite3_finalize(query);
    EXPECT_EQ(tables, (std::vector<std::string>{"cameras", "descriptors", "images", "keypoints", "matches",
                                                "sqlite_sequence", "two_view_geometries"}));
    sqlite3_close(db);
}
