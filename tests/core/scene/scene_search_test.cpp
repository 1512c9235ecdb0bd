#include "core/scene/scene_search.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <optional>

#include "core/util/error.h"
#include "tests/test_util.h"

namespace sst {
namespace {
namespace fs = std::filesystem;

fs::path touch(const fs::path& p) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << "{}";
  return p;
}

// Sets SST_SCENE_PATH for one test and restores the previous value.
class ScopedScenePath {
 public:
  explicit ScopedScenePath(const std::optional<std::string>& value) {
    if (const char* old = std::getenv("SST_SCENE_PATH")) old_ = old;
    if (value) setenv("SST_SCENE_PATH", value->c_str(), 1);
    else unsetenv("SST_SCENE_PATH");
  }
  ~ScopedScenePath() {
    if (old_) setenv("SST_SCENE_PATH", old_->c_str(), 1);
    else unsetenv("SST_SCENE_PATH");
  }

 private:
  std::optional<std::string> old_;
};

TEST(SceneSearch, ExistingFileIsUsedAsIs) {
  ScopedScenePath env(std::nullopt);
  fs::path f = touch(test::temp_dir() / "x.gltf");
  EXPECT_EQ(resolve_scene(f.string(), {}), f.string());
}

TEST(SceneSearch, FindsNameWithOrWithoutExtension) {
  ScopedScenePath env(std::nullopt);
  fs::path dir = test::temp_dir();
  fs::path gltf = touch(dir / "box.gltf");
  fs::path glb = touch(dir / "ball.glb");
  fs::path nested = touch(dir / "room" / "room.gltf");
  EXPECT_EQ(resolve_scene("box", {dir.string()}), gltf.string());
  EXPECT_EQ(resolve_scene("box.gltf", {dir.string()}), gltf.string());
  EXPECT_EQ(resolve_scene("ball", {dir.string()}), glb.string());
  EXPECT_EQ(resolve_scene("room", {dir.string()}), nested.string());
}

TEST(SceneSearch, FindsVariantsInTheirBaseFolder) {
  ScopedScenePath env(std::nullopt);
  fs::path dir = test::temp_dir();
  fs::path stairs = touch(dir / "staircase" / "staircase-point.gltf");
  fs::path cornell = touch(dir / "cornell-box" / "cornell-box-point.gltf");
  fs::path living = touch(dir / "living-room-2" / "living-room-2-point.gltf");
  EXPECT_EQ(resolve_scene("staircase-point", {dir.string()}), stairs.string());
  EXPECT_EQ(resolve_scene("cornell-box-point", {dir.string()}), cornell.string());
  EXPECT_EQ(resolve_scene("living-room-2-point", {dir.string()}), living.string());
}

TEST(SceneSearch, SceneDirsComeBeforeTheEnvironmentPath) {
  fs::path dir = test::temp_dir();
  fs::path a = touch(dir / "a" / "s.gltf");
  fs::path b = touch(dir / "b" / "s.gltf");
  fs::path c = touch(dir / "c" / "only-in-c.gltf");
  ScopedScenePath env((dir / "b").string() + "::" + (dir / "c").string());
  EXPECT_EQ(resolve_scene("s", {(dir / "a").string()}), a.string());
  EXPECT_EQ(resolve_scene("s", {}), b.string());
  EXPECT_EQ(resolve_scene("only-in-c", {(dir / "a").string()}), c.string());
  std::vector<std::string> dirs = scene_search_dirs({(dir / "a").string()});
  ASSERT_EQ(dirs.size(), 3u);  // the empty entry between the colons is skipped
  EXPECT_EQ(dirs[0], (dir / "a").string());
  EXPECT_EQ(dirs[1], (dir / "b").string());
  EXPECT_EQ(dirs[2], (dir / "c").string());
}

TEST(SceneSearch, NotFoundListsTheFoldersSearched) {
  fs::path dir = test::temp_dir();
  ScopedScenePath env((dir / "env").string());
  try {
    resolve_scene("nowhere", {(dir / "flag").string()});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    std::string msg = e.what();
    EXPECT_NE(msg.find("nowhere"), std::string::npos) << msg;
    EXPECT_NE(msg.find((dir / "flag").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find((dir / "env").string()), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  }
}

TEST(SceneSearch, NotFoundWithoutFoldersSaysHowToAddThem) {
  ScopedScenePath env(std::nullopt);
  try {
    resolve_scene("nowhere", {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("SST_SCENE_PATH"), std::string::npos) << e.what();
  }
}

TEST(SceneSearch, FindsTheSharedScenesByName) {
  fs::path root = test::shared_scene("");
  if (root.empty() || test::shared_scene("staircase/staircase-point.gltf").empty()) GTEST_SKIP() << "shared scenes not present";
  ScopedScenePath env(std::nullopt);
  EXPECT_EQ(fs::path(resolve_scene("staircase-point", {root.string()})), root / "staircase" / "staircase-point.gltf");
  EXPECT_EQ(fs::path(resolve_scene("cornell-box", {root.string()})), root / "cornell-box" / "cornell-box.gltf");
}

}  // namespace
}  // namespace sst
