// A folder of outputs that appears whole or not at all (sward-eval's report, sward-export's layouts). Everything
// is written into a staging folder ".<name>.sward-<pid>.tmp" beside the final folder and moved in only by
// commit(): a run that fails half-way (a truncated input file at frame 40) leaves the final folder exactly as it
// was, and no half-made output or created parent folder behind.
#pragma once

#include <filesystem>
#include <string>

namespace sward {

// Creates `dir` and its parents; throws "cannot create <what> '<dir>': <reason>" otherwise.
void makeDirectory(const std::string& dir, const std::string& what);

class StagedFolder {
public:
    // `what` names the folder in errors ("report folder", "output folder"). Throws when `outDir` is a file or
    // its parent cannot be made; creates the staging folder.
    StagedFolder(const std::string& outDir, std::string what);
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;
    // Removes the staging folder, and without commit() every folder the constructor created.
    ~StagedFolder();

    // Where to write: the staging folder.
    std::string path() const { return staging_.string(); }
    // Moves every staged file over its place in the final folder (replacing an earlier run's file of that name).
    void commit();

private:
    void moveInto(const std::filesystem::path& from, const std::filesystem::path& to) const;
    std::filesystem::path final_, staging_, firstCreated_;
    std::string what_;
    bool committed_ = false;
};

} // namespace sward
