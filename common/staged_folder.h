// A folder of outputs that appears whole or not at all (sward-eval's report, sward-export's layouts). Everything
// is written into a staging folder ".<name>.sward-<pid>.tmp" beside the final folder and moved in only by
// commit(): a run that fails half-way (a truncated input file at frame 40) leaves the final folder exactly as it
// was, and no half-made output or created parent folder behind.
//
// Safety of the final folder: it is locked for one writer (common/output_lock.h) from the constructor on, and holds
// no symbolic link anywhere below it (the constructor refuses one, naming it, before any work); commit() first
// checks again every place it will fill (no link, no file where a folder goes or the reverse) and then
// moves the files in relative to folder handles (O_NOFOLLOW), each replaced file swapped with its new version
// (renameat2 RENAME_EXCHANGE), so a failure part-way moves everything back. Links inside the final folder are
// never followed: one in the way is an error naming it. Staging folders of dead processes are removed.
#pragma once

#include "common/output_lock.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace sward {

// Creates `dir` and its parents; throws "cannot create <what> '<dir>': <reason>" otherwise.
void makeDirectory(const std::string& dir, const std::string& what);

class StagedFolder {
public:
    // `what` names the folder in errors ("report folder", "output folder"). Creates `outDir` (and its parents),
    // locks it and creates the staging folder; throws when `outDir` is a file, is locked by another writer, holds
    // a symbolic link, or its parent cannot be made. `outDir` may be a symbolic link to a folder when the user named it (the link is the
    // user's choice; its target is written); `outDirMayBeLink` false (a folder sward derived, like DATASET/eval)
    // refuses one.
    StagedFolder(const std::string& outDir, std::string what, bool outDirMayBeLink = true);
    StagedFolder(const StagedFolder&) = delete;
    StagedFolder& operator=(const StagedFolder&) = delete;
    // Removes the staging folder, and without commit() every folder the constructor created.
    ~StagedFolder();

    // Where to write: the staging folder.
    std::string path() const { return staging_.string(); }
    // Moves every staged file over its place in the final folder (replacing an earlier run's file of that name),
    // all or none: throws, leaving the final folder as it was, when a place is a link or of the wrong kind.
    void commit();

private:
    std::filesystem::path final_, staging_;
    std::vector<std::filesystem::path> createdFolders_; // by this process, outermost first
    std::string what_;
    std::unique_ptr<OutputLock> lock_;
    bool committed_ = false;
};

// Removes the folder `name` of the folder `parentFd` and everything below it without following a link (a link is
// removed, not its target). Never throws; false when something could not be removed.
bool removeTreeAt(int parentFd, const std::string& name);

} // namespace sward
