#include "export/colmap_database.h"

#include "common/error.h"
#include "common/little_endian.h"

#include <sqlite3.h>

#include <memory>

namespace sward {

namespace {

// COLMAP 3.8's schema (src/base/database.cc), as `colmap database_creator` writes it: COLMAP opens a database with
// CREATE TABLE IF NOT EXISTS, so these tables are taken as they are.
constexpr const char* kSchema = R"(
CREATE TABLE cameras (camera_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, model INTEGER NOT NULL,
  width INTEGER NOT NULL, height INTEGER NOT NULL, params BLOB, prior_focal_length INTEGER NOT NULL);
CREATE TABLE images (image_id INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, name TEXT NOT NULL UNIQUE,
  camera_id INTEGER NOT NULL, prior_qw REAL, prior_qx REAL, prior_qy REAL, prior_qz REAL, prior_tx REAL,
  prior_ty REAL, prior_tz REAL, CONSTRAINT image_id_check CHECK(image_id >= 0 and image_id < 2147483647),
  FOREIGN KEY(camera_id) REFERENCES cameras(camera_id));
CREATE UNIQUE INDEX index_name ON images(name);
CREATE TABLE keypoints (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL,
  data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE descriptors (image_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL,
  data BLOB, FOREIGN KEY(image_id) REFERENCES images(image_id) ON DELETE CASCADE);
CREATE TABLE matches (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL, cols INTEGER NOT NULL, data BLOB);
CREATE TABLE two_view_geometries (pair_id INTEGER PRIMARY KEY NOT NULL, rows INTEGER NOT NULL,
  cols INTEGER NOT NULL, data BLOB, config INTEGER NOT NULL, F BLOB, E BLOB, H BLOB, qvec BLOB, tvec BLOB);
)";

struct CloseDatabase {
    void operator()(sqlite3* db) const { sqlite3_close(db); }
};
struct FinalizeStatement {
    void operator()(sqlite3_stmt* statement) const { sqlite3_finalize(statement); }
};
using Database = std::unique_ptr<sqlite3, CloseDatabase>;
using Statement = std::unique_ptr<sqlite3_stmt, FinalizeStatement>;

void check(sqlite3* db, int result, const char* what) {
    require(result == SQLITE_OK || result == SQLITE_DONE,
            std::string("COLMAP database: ") + what + " failed: " + sqlite3_errmsg(db));
}

Statement prepare(sqlite3* db, const char* sql) {
    sqlite3_stmt* statement = nullptr;
    check(db, sqlite3_prepare_v2(db, sql, -1, &statement, nullptr), sql);
    return Statement(statement);
}

void insertCamera(sqlite3* db, sqlite3_stmt* insert, const ColmapCameraRow& camera) {
    std::string params; // COLMAP: the parameters as float64, little-endian
    for (double p : camera.params) appendLittleEndian(params, p);
    sqlite3_reset(insert);
    sqlite3_bind_int64(insert, 1, camera.id);
    sqlite3_bind_int(insert, 2, camera.model);
    sqlite3_bind_int64(insert, 3, camera.width);
    sqlite3_bind_int64(insert, 4, camera.height);
    sqlite3_bind_blob(insert, 5, params.data(), int(params.size()), SQLITE_TRANSIENT);
    sqlite3_bind_int(insert, 6, 1); // the focal length is known, not a guess from the image size
    check(db, sqlite3_step(insert), "inserting a camera");
}

void insertImage(sqlite3* db, sqlite3_stmt* insert, const ColmapImageRow& image) {
    sqlite3_reset(insert);
    sqlite3_bind_int64(insert, 1, image.id);
    sqlite3_bind_text(insert, 2, image.name.c_str(), -1, SQLITE_TRANSIENT);
    sqlite3_bind_int64(insert, 3, image.cameraId);
    const double prior[7] = {image.rotation.x,    image.rotation.y,    image.rotation.z,   image.rotation.w,
                             image.translation.x, image.translation.y, image.translation.z};
    for (int i = 0; i < 7; ++i) sqlite3_bind_double(insert, 4 + i, prior[i]);
    check(db, sqlite3_step(insert), "inserting an image");
}

} // namespace

std::vector<char> colmapDatabaseBytes(const std::vector<ColmapCameraRow>& cameras,
                                      const std::vector<ColmapImageRow>& images) {
    // Built in memory and serialised, then written like every other file (atomically): no journal files beside
    // the output, and a failure leaves nothing.
    sqlite3* opened = nullptr;
    const int result = sqlite3_open(":memory:", &opened);
    Database db(opened);
    check(db.get(), result, "opening an in-memory database");
    check(db.get(), sqlite3_exec(db.get(), kSchema, nullptr, nullptr, nullptr), "creating COLMAP's tables");
    check(db.get(), sqlite3_exec(db.get(), "BEGIN", nullptr, nullptr, nullptr), "BEGIN");
    const Statement camera = prepare(db.get(), "INSERT INTO cameras VALUES (?, ?, ?, ?, ?, ?)");
    for (const ColmapCameraRow& c : cameras) insertCamera(db.get(), camera.get(), c);
    const Statement image = prepare(db.get(), "INSERT INTO images VALUES (?, ?, ?, ?, ?, ?, ?, ?, ?, ?)");
    for (const ColmapImageRow& i : images) insertImage(db.get(), image.get(), i);
    check(db.get(), sqlite3_exec(db.get(), "COMMIT", nullptr, nullptr, nullptr), "COMMIT");
    sqlite3_int64 size = 0;
    std::unique_ptr<unsigned char, decltype(&sqlite3_free)> bytes(sqlite3_serialize(db.get(), "main", &size, 0),
                                                                  sqlite3_free);
    require(bytes != nullptr, "COLMAP database: SQLite could not serialise it (out of memory?)");
    return std::vector<char>(bytes.get(), bytes.get() + size);
}

} // namespace sward
