#include "world/asset_policy.h"

#include "common/error.h"

#include <system_error>

namespace sward {

namespace {

namespace fs = std::filesystem;

// Symlinks and `..` resolved as far as the path exists (a missing file is reported by its loader later).
fs::path resolved(const fs::path& path) {
    std::error_code error;
    fs::path result = fs::weakly_canonical(fs::absolute(path), error);
    if (error) result = fs::absolute(path).lexically_normal();
    // "dir/" canonicalises with an empty last element; drop it so folder comparisons see whole components.
    if (!result.has_filename() && result.has_parent_path() && result != result.root_path())
        result = result.parent_path();
    return result;
}

} // namespace

AssetPolicy AssetPolicy::confinedTo(const std::string& folder, const std::vector<std::string>& allowed) {
    AssetPolicy policy;
    policy.folder_ = resolved(folder.empty() ? fs::path(".") : fs::path(folder));
    std::vector<fs::path> folders{policy.folder_};
    for (const std::string& dir : allowed) {
        std::error_code error;
        require(!dir.empty() && fs::is_directory(dir, error), "--allow-assets '" + dir + "': no such folder");
        folders.push_back(resolved(dir));
    }
    policy.folders_ = InputFolders::confinedTo(std::move(folders));
    return policy;
}

std::string AssetPolicy::resolve(const std::string& path, const std::string& base, const std::string& where) const {
    const fs::path joined = base.empty() ? fs::path(path) : fs::path(base) / path;
    if (!confined()) return joined.lexically_normal().string();
    const fs::path real = resolved(joined);
    if (folders_.allows(real)) return real.string();
    throw Error(where + ": '" + path + "' resolves to " + real.string() + ", outside the scene's folder " +
                folder_.string() + " (allow with --allow-assets DIR)");
}

} // namespace sward
