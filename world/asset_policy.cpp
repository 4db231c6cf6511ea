#include "world/asset_policy.h"

#include "common/error.h"

#include <algorithm>
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

// Component-wise: "/a/bc" is not inside "/a/b".
bool inside(const fs::path& path, const fs::path& folder) {
    auto p = path.begin();
    for (auto f = folder.begin(); f != folder.end(); ++f, ++p) {
        if (f->empty()) continue; // a trailing separator
        if (p == path.end() || *p != *f) return false;
    }
    return true;
}

} // namespace

AssetPolicy AssetPolicy::confinedTo(const std::string& folder, const std::vector<std::string>& allowed) {
    AssetPolicy policy;
    policy.confined_ = true;
    policy.folder_ = resolved(folder.empty() ? fs::path(".") : fs::path(folder));
    for (const std::string& dir : allowed) {
        std::error_code error;
        require(!dir.empty() && fs::is_directory(dir, error), "--allow-assets '" + dir + "': no such folder");
        policy.allowed_.push_back(resolved(dir));
    }
    return policy;
}

std::string AssetPolicy::resolve(const std::string& path, const std::string& base, const std::string& where) const {
    const fs::path joined = base.empty() ? fs::path(path) : fs::path(base) / path;
    if (!confined_) return joined.lexically_normal().string();
    const fs::path real = resolved(joined);
    if (inside(real, folder_) ||
        std::any_of(allowed_.begin(), allowed_.end(), [&](const fs::path& dir) { return inside(real, dir); }))
        return real.string();
    throw Error(where + ": '" + path + "' resolves to " + real.string() + ", outside the scene's folder " +
                folder_.string() + " (allow with --allow-assets DIR)");
}

} // namespace sward
