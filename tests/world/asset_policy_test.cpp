#include "world/asset_policy.h"

#include "test_files.h"

#include <gtest/gtest.h>

#include <filesystem>

using namespace sward;
using namespace sward::test;

namespace fs = std::filesystem;

namespace {

// <tmp>/scene (the scene's folder, holding models/m.gltf) beside <tmp>/outside/x.gltf.
struct Folders {
    fs::path root = fs::canonical(tempDir());
    fs::path scene = root / "scene", outside = root / "outside";
    Folders() {
        fs::create_directories(scene / "models");
        fs::create_directories(outside);
        std::ofstream(scene / "models" / "m.gltf") << "{}";
        std::ofstream(outside / "x.gltf") << "{}";
    }
};

} // namespace

TEST(AssetPolicy, PathsInsideTheSceneFolderResolveThere) {
    Folders f;
    const AssetPolicy policy = AssetPolicy::confinedTo(f.scene.string(), {});
    EXPECT_TRUE(policy.confined());
    EXPECT_EQ(policy.resolve("models/m.gltf", f.scene.string(), "s.json: 'k'"), (f.scene / "models/m.gltf").string());
    // `..` that stays inside, and an absolute path inside, are fine.
    EXPECT_EQ(policy.resolve("models/../models/m.gltf", f.scene.string(), "s.json: 'k'"),
              (f.scene / "models/m.gltf").string());
    EXPECT_EQ(policy.resolve((f.scene / "models/m.gltf").string(), "", "s.json: 'k'"),
              (f.scene / "models/m.gltf").string());
}

TEST(AssetPolicy, DotDotOutsideTheSceneFolderIsRefusedNamingKeyPathAndFolders) {
    Folders f;
    const AssetPolicy policy = AssetPolicy::confinedTo(f.scene.string(), {});
    expectError(
        [&] { policy.resolve("models/../../outside/x.gltf", f.scene.string(), "s.json: 'objects[0].model'"); },
        {"s.json: 'objects[0].model': 'models/../../outside/x.gltf' resolves to " + (f.outside / "x.gltf").string(),
         "outside the scene's folder " + f.scene.string(), "--allow-assets DIR"});
}

TEST(AssetPolicy, AbsolutePathsOutsideAreRefused) {
    Folders f;
    const AssetPolicy policy = AssetPolicy::confinedTo(f.scene.string(), {});
    expectError([&] { policy.resolve("/etc/passwd", f.scene.string(), "s.json: 'grass_map'"); },
                {"'grass_map': '/etc/passwd' resolves to /etc/passwd, outside"});
}

TEST(AssetPolicy, SymlinksAreResolvedBeforeTheCheck) {
    Folders f;
    fs::create_symlink(f.outside / "x.gltf", f.scene / "link.gltf");
    fs::create_directory_symlink(f.outside, f.scene / "dirlink");
    const AssetPolicy policy = AssetPolicy::confinedTo(f.scene.string(), {});
    expectError([&] { policy.resolve("link.gltf", f.scene.string(), "s.json: 'k'"); },
                {"'link.gltf' resolves to " + (f.outside / "x.gltf").string()});
    expectError([&] { policy.resolve("dirlink/x.gltf", f.scene.string(), "s.json: 'k'"); },
                {"'dirlink/x.gltf' resolves to " + (f.outside / "x.gltf").string()});
}

TEST(AssetPolicy, AllowedFoldersAcceptWhatTheSceneFolderRefuses) {
    Folders f;
    fs::create_symlink(f.outside / "x.gltf", f.scene / "link.gltf");
    const AssetPolicy policy = AssetPolicy::confinedTo(f.scene.string(), {f.outside.string()});
    const std::string target = (f.outside / "x.gltf").string();
    EXPECT_EQ(policy.resolve("../outside/x.gltf", f.scene.string(), "k"), target);
    EXPECT_EQ(policy.resolve(target, f.scene.string(), "k"), target);
    EXPECT_EQ(policy.resolve("link.gltf", f.scene.string(), "k"), target);
    // A sibling whose name merely starts with the allowed folder's is not inside it.
    fs::create_directories(f.root / "outside2");
    expectError([&] { policy.resolve("../outside2/y.gltf", f.scene.string(), "k"); }, {"outside the scene's folder"});
}

TEST(AssetPolicy, UnconfinedJoinsAndKeepsEveryPath) {
    const AssetPolicy policy;
    EXPECT_FALSE(policy.confined());
    EXPECT_EQ(policy.resolve("/etc/passwd", "scenes", "k"), "/etc/passwd");
    EXPECT_EQ(policy.resolve("../x.png", "scenes", "k"), "x.png");
    EXPECT_EQ(policy.resolve("x.png", "", "k"), "x.png");
}

TEST(AssetPolicy, AMissingAllowedFolderIsAnError) {
    Folders f;
    expectError([&] { AssetPolicy::confinedTo(f.scene.string(), {(f.root / "none").string()}); },
                {"--allow-assets '" + (f.root / "none").string() + "': no such folder"});
}
