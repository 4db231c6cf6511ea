// The one door for every input file sward reads: scene files, JSON descriptions, images, glTF files and their
// buffers, rasters and their companion files (io/raster_file.cpp routes GDAL's own opens through it).
//
// openInputFile opens with O_NONBLOCK and O_CLOEXEC, then fstat-s the open descriptor: a FIFO, a device
// (/dev/zero), a socket or a folder is refused before a byte is read, so no input can block sward or never end,
// and what was checked is what is read (no gap between a stat and an open). InputFolders says where inputs may be
// read from and logs every file read on its behalf, so a dataset's fingerprint lists exactly the files its loaders
// opened (dataset/fingerprint.h).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sward {

// Largest input file read whole (a glTF buffer, a texture, a scene file has a lower limit of its own).
inline constexpr uint64_t kMaxInputFileBytes = uint64_t(2) << 30;

// An open regular file (read only). Move-only; closes its descriptor.
class InputFile {
public:
    InputFile() = default;
    InputFile(InputFile&& other) noexcept;
    InputFile& operator=(InputFile&& other) noexcept;
    InputFile(const InputFile&) = delete;
    InputFile& operator=(const InputFile&) = delete;
    ~InputFile();

    int fd() const { return fd_; }
    uint64_t size() const { return size_; }

private:
    friend InputFile openInputFile(const std::string& path, const std::string& what);
    int fd_ = -1;
    uint64_t size_ = 0;
};

// Opens `path` (symlinks followed) for reading; `what` names the kind of file in errors ("scene file"). Throws
// one sward::Error: "<path>: cannot open the <what> (missing or unreadable)" or "<path>: the <what> is not a
// regular file".
InputFile openInputFile(const std::string& path, const std::string& what);

// The whole file, opened as openInputFile does. A file over `maxBytes` is refused before it is read: "<path>: the
// <what> has N bytes, over the limit of L" (L in MiB when a whole number of them).
std::string readInputFile(const std::string& path, const std::string& what, uint64_t maxBytes = kMaxInputFileBytes);
std::vector<unsigned char> readInputBytes(const std::string& path, const std::string& what,
                                          uint64_t maxBytes = kMaxInputFileBytes);

// One file read on behalf of an asset: `owner` is the asset's path as its loader was given it (a glTF, a raster),
// `path` the file opened (canonical; the owner itself, a buffer, an image or a companion file).
struct OpenedInput {
    std::string owner, path;
    bool operator==(const OpenedInput&) const = default;
};

// Where input files may be read from, and the log of the files read on its behalf. Copies share one log, so the
// scene's policy and the copies its objects hold record into one list. Thread-safe.
class InputFolders {
public:
    // Unconfined: every file may be read.
    InputFolders();
    // Confined to `folders` (canonical paths).
    static InputFolders confinedTo(std::vector<std::filesystem::path> folders);

    bool confined() const { return confined_; }
    // True when the canonical path `real` lies inside one of the folders (component-wise: "/a/bc" is not inside
    // "/a/b"); always true when unconfined.
    bool allows(const std::filesystem::path& real) const;

    // Logs that `path` was opened for `owner` (once per pair).
    void record(const std::string& owner, const std::string& path) const;
    // Every file logged, in the order first opened.
    std::vector<OpenedInput> opened() const;

private:
    struct Log;
    bool confined_ = false;
    std::vector<std::filesystem::path> folders_;
    std::shared_ptr<Log> log_;
};

} // namespace sward
