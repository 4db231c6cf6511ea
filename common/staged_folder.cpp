#include "common/staged_folder.h"

#include "common/error.h"

#include <unistd.h>

namespace fs = std::filesystem;

namespace sward {

void makeDirectory(const std::string& dir, const std::string& what) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    require(!ec && fs::is_directory(dir), "cannot create " + what + " '" + dir +
                                              "': " + (ec ? ec.message() : std::string("a file of that name exists")));
}

StagedFolder::StagedFolder(const std::string& outDir, std::string what)
    : final_(fs::absolute(outDir).lexically_normal()), what_(std::move(what)) {
    if (final_.filename().empty()) final_ = final_.parent_path();
    std::error_code ec;
    require(!fs::exists(final_, ec) || fs::is_directory(final_, ec),
            "cannot create " + what_ + " '" + outDir + "': a file of that name exists");
    for (fs::path p = final_; !p.empty() && !fs::exists(p, ec); p = p.parent_path()) {
        firstCreated_ = p;
        if (p == p.parent_path()) break;
    }
    makeDirectory(final_.parent_path().string(), what_);
    staging_ = final_.parent_path() / ("." + final_.filename().string() + ".sward-" + std::to_string(getpid()) + ".tmp");
    fs::remove_all(staging_, ec);
    makeDirectory(staging_.string(), what_);
}

StagedFolder::~StagedFolder() {
    std::error_code ec;
    fs::remove_all(staging_, ec);
    if (!committed_ && !firstCreated_.empty()) fs::remove_all(firstCreated_, ec);
}

void StagedFolder::commit() {
    makeDirectory(final_.string(), what_);
    moveInto(staging_, final_);
    committed_ = true;
}

void StagedFolder::moveInto(const fs::path& from, const fs::path& to) const {
    for (const fs::directory_entry& entry : fs::directory_iterator(from)) {
        const fs::path target = to / entry.path().filename();
        if (entry.is_directory()) {
            makeDirectory(target.string(), what_);
            moveInto(entry.path(), target);
        } else {
            std::error_code ec;
            fs::rename(entry.path(), target, ec);
            require(!ec, "cannot move '" + entry.path().string() + "' to '" + target.string() + "': " + ec.message());
        }
    }
}

} // namespace sward
