#include "io/raster_door.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <cpl_vsi.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

namespace sward {

namespace {

namespace fs = std::filesystem;

constexpr const char* kPrefix = "/vsisward/";

// The door GDAL's callbacks check against; set while a RasterDoor lives (under gDoorMutex).
struct OpenDoor {
    std::string owner; // the raster's path as readRasterBand was given it
    fs::path raster;   // its canonical path
    const InputFolders* folders = nullptr;
    std::string* refusal = nullptr;
};
std::mutex gDoorMutex;
OpenDoor* gDoor = nullptr;

struct Handle {
    int fd = -1;
    vsi_l_offset size = 0, offset = 0;
    bool eof = false;
};

std::string lower(std::string text) {
    for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
    return text;
}

bool companionKind(const fs::path& real) {
    const std::string name = lower(real.filename().string());
    return std::any_of(std::begin(kRasterCompanionSuffixes), std::end(kRasterCompanionSuffixes),
                       [&](const char* suffix) { return name.ends_with(suffix); });
}

void refuse(const std::string& name, const std::string& why) {
    if (gDoor && gDoor->refusal->empty())
        *gDoor->refusal = "raster '" + gDoor->owner + "': GDAL asked for '" + name + "', which " + why;
}

enum class Check { Missing, Refused, Folder, File };

// The absolute path GDAL names: its plugin handler passes the name after the prefix ("tmp/dem.tif").
std::string absoluteName(const char* gdalName) {
    if (std::strncmp(gdalName, kPrefix, std::strlen(kPrefix)) == 0) gdalName += std::strlen(kPrefix);
    return "/" + std::string(gdalName);
}

// What the door makes of the name GDAL asks for; `real` gets the canonical path.
Check check(const char* gdalName, fs::path& real) {
    if (!gDoor) return Check::Missing;
    const std::string name = absoluteName(gdalName);
    std::error_code error;
    real = fs::canonical(name, error);
    if (error) return Check::Missing;
    const bool allowed = gDoor->folders->allows(real);
    const fs::file_status status = fs::status(real, error);
    // A folder is never read, only looked at: outside the allowed ones it is absent to GDAL.
    if (fs::is_directory(status)) return allowed ? Check::Folder : Check::Missing;
    // The kind by the name GDAL asked for: a "dem.tif.aux.xml" symlinked to /dev/zero is still checked. A file
    // of no kind GDAL needs is absent, wherever it is.
    if (real != gDoor->raster && !companionKind(name)) return Check::Missing;
    if (!allowed) {
        refuse(name, "resolves to " + real.string() + ", outside the scene's folder (allow with --allow-assets DIR)");
        return Check::Refused;
    }
    if (!fs::is_regular_file(status)) {
        refuse(name, "is not a regular file");
        return Check::Refused;
    }
    return Check::File;
}

int statFile(void*, const char* name, VSIStatBufL* out, int) {
    fs::path real;
    const Check result = check(name, real);
    if (result == Check::Missing || result == Check::Refused) {
        errno = ENOENT;
        return -1;
    }
    return ::stat64(real.c_str(), out);
}

void* openFile(void*, const char* name, const char* access) {
    if (std::strpbrk(access, "wa+")) return nullptr; // read only: PAM's .aux.xml is never written
    fs::path real;
    if (check(name, real) != Check::File) return nullptr;
    // O_NONBLOCK: a FIFO swapped in since the check must not block; the fstat refuses it.
    const int fd = ::open(real.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOFOLLOW | O_NOCTTY);
    if (fd < 0) return nullptr;
    struct stat info {};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        ::close(fd);
        refuse(absoluteName(name), "is not a regular file");
        return nullptr;
    }
    gDoor->folders->record(gDoor->owner, real.string());
    return new Handle{.fd = fd, .size = vsi_l_offset(info.st_size), .offset = 0, .eof = false};
}

// GDAL lists a raster's siblings to learn which companion files exist; the door lists only those of the kinds it
// opens, so GDAL never reads the folder itself (it may hold thousands of files, or be outside the allowed ones).
char** siblingFiles(void*, const char* name) {
    fs::path real;
    if (check(name, real) != Check::File) return static_cast<char**>(CPLCalloc(1, sizeof(char*)));
    CPLStringList list;
    std::error_code error;
    for (fs::directory_iterator it(real.parent_path(), error), end; !error && it != end; it.increment(error))
        if (companionKind(it->path())) list.AddString(it->path().filename().c_str());
    char** names = list.StealList();
    return names ? names : static_cast<char**>(CPLCalloc(1, sizeof(char*)));
}

char** readFolder(void*, const char*, int) {
    return nullptr; // never listed: siblingFiles says what GDAL needs
}

vsi_l_offset tellFile(void* file) {
    return static_cast<Handle*>(file)->offset;
}

int seekFile(void* file, vsi_l_offset offset, int whence) {
    Handle& h = *static_cast<Handle*>(file);
    h.eof = false;
    if (whence == SEEK_SET)
        h.offset = offset;
    else if (whence == SEEK_CUR)
        h.offset += offset;
    else if (whence == SEEK_END)
        h.offset = h.size + offset;
    else
        return -1;
    return 0;
}

size_t readFile(void* file, void* buffer, size_t size, size_t count) {
    Handle& h = *static_cast<Handle*>(file);
    if (size == 0 || count == 0) return 0;
    const size_t wanted = size * count;
    size_t done = 0;
    while (done < wanted) {
        const ssize_t n = ::pread(h.fd, static_cast<char*>(buffer) + done, wanted - done, off_t(h.offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += size_t(n);
    }
    h.offset += done;
    if (done < wanted) h.eof = true;
    return done / size;
}

int eofFile(void* file) {
    return static_cast<Handle*>(file)->eof ? 1 : 0;
}

int closeFile(void* file) {
    Handle* h = static_cast<Handle*>(file);
    ::close(h->fd);
    delete h;
    return 0;
}

// GDAL's settings stay as they are, on purpose:
// - PAM stays on (GDAL_PAM_ENABLED): its .aux.xml can carry a raster's nodata, georeferencing and metadata, and it
//   is opened through this door like any companion, so it is confined, regular and hashed into the fingerprint.
//   Its writes are refused (openFile takes reads only).
// - GDAL_DISABLE_READDIR_ON_OPEN is not set: the door answers GDAL's question for the raster's siblings itself
//   (siblingFiles) and lists no folder (readFolder), so GDAL never reads a folder through it (EMPTY_DIR changes
//   nothing here; RasterDoor's tests pass with it).
// Both are process-wide settings, which would also change every other GDAL user of the process (a Python
// program that imports sward and rasterio).
void installHandler() {
    static std::once_flag once;
    std::call_once(once, [] {
        VSIFilesystemPluginCallbacksStruct* callbacks = VSIAllocFilesystemPluginCallbacksStruct();
        callbacks->stat = statFile;
        callbacks->open = openFile;
        callbacks->read_dir = readFolder;
        callbacks->sibling_files = siblingFiles;
        callbacks->tell = tellFile;
        callbacks->seek = seekFile;
        callbacks->read = readFile;
        callbacks->eof = eofFile;
        callbacks->close = closeFile;
        callbacks->nBufferSize = 64 * 1024; // GDAL reads headers a few bytes at a time
        VSIInstallPluginHandler(kPrefix, callbacks);
        VSIFreeFilesystemPluginCallbacksStruct(callbacks);
    });
}

} // namespace

RasterDoor::RasterDoor(const std::string& path, const InputFolders& folders) : lock_(gDoorMutex) {
    installHandler();
    std::error_code error;
    const fs::path absolute = fs::absolute(path, error);
    fs::path raster = fs::weakly_canonical(absolute, error);
    if (error) raster = absolute.lexically_normal();
    gdalPath_ = std::string(kPrefix) + raster.string().substr(1);
    static OpenDoor door;
    door = OpenDoor{.owner = path, .raster = raster, .folders = &folders, .refusal = &refusal_};
    gDoor = &door;
}

RasterDoor::~RasterDoor() {
    gDoor = nullptr;
}

} // namespace sward
