#include "common/staged_folder.h"

#include "common/atomic_file.h"
#include "common/error.h"

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;

namespace sward {

namespace {

// A folder handle, closed on every path out.
struct FolderHandle {
    int fd = -1;
    explicit FolderHandle(int descriptor) : fd(descriptor) {}
    FolderHandle(const FolderHandle&) = delete;
    FolderHandle& operator=(const FolderHandle&) = delete;
    ~FolderHandle() {
        if (fd >= 0) ::close(fd);
    }
};

// The folder `name` of `parentFd`, never through a link; -1 (errno set) otherwise.
int openFolderAt(int parentFd, const std::string& name) {
    return ::openat(parentFd, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
}

// The names in the folder `fd` (not "." and ".."), sorted: moves and rollbacks run in one fixed order.
std::vector<std::string> entriesOf(int fd) {
    std::vector<std::string> names;
    const int copy = ::dup(fd); // closedir closes it
    DIR* folder = copy >= 0 ? ::fdopendir(copy) : nullptr;
    if (!folder) {
        if (copy >= 0) ::close(copy);
        return names;
    }
    ::rewinddir(folder);
    while (const dirent* entry = ::readdir(folder)) {
        const std::string name = entry->d_name;
        if (name != "." && name != "..") names.push_back(name);
    }
    ::closedir(folder);
    std::sort(names.begin(), names.end());
    return names;
}

std::string linkInTheWay(const fs::path& place) {
    return "'" + place.string() +
           "' is a symbolic link: sward never writes through links in an output folder; remove it or choose "
           "another folder";
}

std::string wrongKind(const fs::path& place, const std::string& what, bool folderThere) {
    return "cannot write the " + what + ": '" + place.string() + "' is " +
           (folderThere ? "a folder where the output has a file" : "a file where the output has a folder");
}

struct EntryKinds {
    bool exists = false, link = false, stagedFolder = false, finalFolder = false;
};

EntryKinds kindsOf(int stagedFd, int finalFd, const std::string& name, const fs::path& place) {
    struct stat staged, existing;
    if (::fstatat(stagedFd, name.c_str(), &staged, AT_SYMLINK_NOFOLLOW) != 0)
        throw Error("cannot read the staged '" + name + "': " + ioErrorReason(errno));
    EntryKinds kinds{.stagedFolder = S_ISDIR(staged.st_mode)};
    if (::fstatat(finalFd, name.c_str(), &existing, AT_SYMLINK_NOFOLLOW) != 0) {
        if (errno != ENOENT) throw Error("cannot write '" + place.string() + "': " + ioErrorReason(errno));
        return kinds;
    }
    kinds.exists = true;
    kinds.link = S_ISLNK(existing.st_mode);
    kinds.finalFolder = S_ISDIR(existing.st_mode);
    return kinds;
}

// Checks, moving nothing, that every staged entry under `stagedFd` can take its place under `finalFd`: no link
// in the way, a folder where a folder goes, a non-folder where a file goes.
void checkPlaces(int stagedFd, int finalFd, const fs::path& finalPath, const std::string& what) {
    for (const std::string& name : entriesOf(stagedFd)) {
        const fs::path place = finalPath / name;
        const EntryKinds kinds = kindsOf(stagedFd, finalFd, name, place);
        if (!kinds.exists) continue;
        if (kinds.link) throw Error(linkInTheWay(place));
        if (kinds.stagedFolder != kinds.finalFolder) throw Error(wrongKind(place, what, kinds.finalFolder));
        if (!kinds.stagedFolder) continue;
        FolderHandle staged(openFolderAt(stagedFd, name)), existing(openFolderAt(finalFd, name));
        if (staged.fd < 0 || existing.fd < 0)
            throw Error("cannot write '" + place.string() + "': " + ioErrorReason(errno));
        checkPlaces(staged.fd, existing.fd, place, what);
    }
}

// Refuses any link below the folder `fd` (`path`), entering real folders only: the output folder holds no link
// that a later write could go through. Checked when the run starts, so it fails before any work.
void refuseLinksBelow(int fd, const fs::path& path) {
    for (const std::string& name : entriesOf(fd)) {
        struct stat info;
        if (::fstatat(fd, name.c_str(), &info, AT_SYMLINK_NOFOLLOW) != 0) continue;
        if (S_ISLNK(info.st_mode)) throw Error(linkInTheWay(path / name));
        if (!S_ISDIR(info.st_mode)) continue;
        FolderHandle folder(openFolderAt(fd, name));
        if (folder.fd >= 0) refuseLinksBelow(folder.fd, path / name);
    }
}

// One step of the move-in, and how to undo it.
struct Move {
    enum Kind { Created, Exchanged, Replaced } kind;
    fs::path staged, final, backup;
};

[[noreturn]] void failMove(const fs::path& from, const fs::path& to, int error) {
    throw Error("cannot move '" + from.string() + "' to '" + to.string() + "': " + ioErrorReason(error));
}

// Moves the entries of `stagedFd` into `finalFd`: a new one by one rename (a whole new folder at once), an
// existing file swapped with its new version (the old one lands in the staging folder, removed with it), an
// existing folder entry by entry. Every step is recorded in `done` before the next.
void moveEntries(int stagedFd, int finalFd, const fs::path& stagedPath, const fs::path& finalPath,
                 const std::string& what, std::vector<Move>& done) {
    for (const std::string& name : entriesOf(stagedFd)) {
        const fs::path from = stagedPath / name, to = finalPath / name;
        const EntryKinds kinds = kindsOf(stagedFd, finalFd, name, to);
        if (!kinds.exists) {
            int result = ::renameat2(stagedFd, name.c_str(), finalFd, name.c_str(), RENAME_NOREPLACE);
            if (result != 0 && errno == EINVAL) result = ::renameat(stagedFd, name.c_str(), finalFd, name.c_str());
            if (result != 0) failMove(from, to, errno);
            done.push_back({Move::Created, from, to, {}});
            continue;
        }
        if (kinds.link) throw Error(linkInTheWay(to));
        if (kinds.stagedFolder != kinds.finalFolder) throw Error(wrongKind(to, what, kinds.finalFolder));
        if (kinds.stagedFolder) {
            FolderHandle staged(openFolderAt(stagedFd, name)), existing(openFolderAt(finalFd, name));
            if (staged.fd < 0 || existing.fd < 0) failMove(from, to, errno);
            moveEntries(staged.fd, existing.fd, from, to, what, done);
            continue;
        }
        if (::renameat2(stagedFd, name.c_str(), finalFd, name.c_str(), RENAME_EXCHANGE) == 0) {
            done.push_back({Move::Exchanged, from, to, {}});
            continue;
        }
        if (errno != EINVAL) failMove(from, to, errno);
        // A file system without RENAME_EXCHANGE: the old file keeps a second name in the staging folder first.
        const std::string old = name + ".sward-old";
        if (::linkat(finalFd, name.c_str(), stagedFd, old.c_str(), 0) != 0) failMove(from, to, errno);
        if (::renameat(stagedFd, name.c_str(), finalFd, name.c_str()) != 0) {
            const int error = errno;
            ::unlinkat(stagedFd, old.c_str(), 0);
            failMove(from, to, error);
        }
        done.push_back({Move::Replaced, from, to, stagedPath / old});
    }
}

// Undoes `done`, last step first. The final folder is locked and was checked free of links.
void rollBack(const std::vector<Move>& done) noexcept {
    for (auto it = done.rbegin(); it != done.rend(); ++it) {
        switch (it->kind) {
        case Move::Created:
            ::rename(it->final.c_str(), it->staged.c_str());
            break;
        case Move::Exchanged:
            ::renameat2(AT_FDCWD, it->staged.c_str(), AT_FDCWD, it->final.c_str(), RENAME_EXCHANGE);
            break;
        case Move::Replaced:
            ::rename(it->backup.c_str(), it->final.c_str());
            break;
        }
    }
}

// Removes `path` and everything below it, never through a link.
void removeTree(const fs::path& path) {
    FolderHandle parent(::open(path.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (parent.fd >= 0) removeTreeAt(parent.fd, path.filename().string());
}

std::string stagingName(const fs::path& final, long pid) {
    return "." + final.filename().string() + ".sward-" + std::to_string(pid) + ".tmp";
}

// Removes the staging folders of `final` that dead processes left beside it (a killed export or evaluation).
void removeStaleStagings(const fs::path& final) {
    FolderHandle parent(::open(final.parent_path().c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
    if (parent.fd < 0) return;
    for (const std::string& name : entriesOf(parent.fd)) {
        long pid = 0;
        if (!isSwardTemporary(name, pid) || name != stagingName(final, pid) || pid == long(::getpid())) continue;
        if (::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue; // still running
        removeTreeAt(parent.fd, name);
    }
}

} // namespace

void makeDirectory(const std::string& dir, const std::string& what) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    require(!ec && fs::is_directory(dir), "cannot create " + what + " '" + dir +
                                              "': " + (ec ? ec.message() : std::string("a file of that name exists")));
}

bool removeTreeAt(int parentFd, const std::string& name) {
    if (::unlinkat(parentFd, name.c_str(), 0) == 0 || errno == ENOENT) return true; // a file or a link
    const int folder = openFolderAt(parentFd, name);
    if (folder < 0) return false;
    bool removed = true;
    for (const std::string& entry : entriesOf(folder)) removed = removeTreeAt(folder, entry) && removed;
    ::close(folder);
    return ::unlinkat(parentFd, name.c_str(), AT_REMOVEDIR) == 0 && removed;
}

StagedFolder::StagedFolder(const std::string& outDir, std::string what, bool outDirMayBeLink)
    : final_(fs::absolute(outDir).lexically_normal()), what_(std::move(what)) {
    if (final_.filename().empty()) final_ = final_.parent_path();
    struct stat info;
    if (::lstat(final_.c_str(), &info) == 0) {
        if (S_ISLNK(info.st_mode)) {
            require(outDirMayBeLink, linkInTheWay(final_) + " (a link of the user's choice is taken from --out only)");
            // The user's link: write its target, and stage beside the target (one file system for the renames).
            std::error_code ec;
            final_ = fs::canonical(final_, ec);
            require(!ec && fs::is_directory(final_, ec),
                    "cannot create " + what_ + " '" + outDir + "': it is a link to no folder");
        } else {
            require(S_ISDIR(info.st_mode), "cannot create " + what_ + " '" + outDir + "': a file of that name exists");
        }
    }
    std::error_code ec;
    std::vector<fs::path> missing; // innermost first
    for (fs::path p = final_; !fs::exists(p, ec) && p.has_relative_path(); p = p.parent_path()) missing.push_back(p);
    try {
        // Only the folders this process made are removed again: a concurrent writer may make the same ones.
        for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
            if (::mkdir(it->c_str(), 0777) == 0)
                createdFolders_.push_back(*it);
            else if (errno != EEXIST || !fs::is_directory(*it, ec))
                throw Error("cannot create " + what_ + " '" + it->string() + "': " + ioErrorReason(errno));
        }
        lock_ = std::make_unique<OutputLock>(final_.string(), OutputLock::Mode::Exclusive);
        FolderHandle finalFd(::open(final_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
        if (finalFd.fd < 0) throw Error("cannot open " + what_ + " '" + final_.string() + "': " + ioErrorReason(errno));
        refuseLinksBelow(finalFd.fd, final_);
        removeStaleStagings(final_);
        staging_ = final_.parent_path() / stagingName(final_, long(::getpid()));
        removeTree(staging_);
        if (::mkdir(staging_.c_str(), 0777) != 0)
            throw Error("cannot create " + what_ + " '" + staging_.string() + "': " + ioErrorReason(errno));
    } catch (...) {
        staging_.clear();
        lock_.reset();
        for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) ::rmdir(it->c_str());
        throw;
    }
}

StagedFolder::~StagedFolder() {
    if (!staging_.empty()) removeTree(staging_);
    if (committed_) return;
    lock_.reset(); // removes the lock file, so that the folders this run made are empty again
    for (auto it = createdFolders_.rbegin(); it != createdFolders_.rend(); ++it) ::rmdir(it->c_str());
}

void StagedFolder::commit() {
    FolderHandle finalFd(::open(final_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    FolderHandle stagedFd(::open(staging_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC));
    if (finalFd.fd < 0 || stagedFd.fd < 0)
        throw Error("cannot write " + what_ + " '" + final_.string() + "': " + ioErrorReason(errno));
    checkPlaces(stagedFd.fd, finalFd.fd, final_, what_);
    std::vector<Move> done;
    try {
        moveEntries(stagedFd.fd, finalFd.fd, staging_, final_, what_, done);
    } catch (...) {
        rollBack(done);
        throw;
    }
    committed_ = true;
}

} // namespace sward
