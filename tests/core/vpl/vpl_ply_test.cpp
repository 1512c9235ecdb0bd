// VPL point clouds: PLY round trip, header layout, atomic write, malformed input.
#include "core/vpl/vpl_ply.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "core/util/error.h"
#include "core/vpl/vpl_generator.h"
#include "core/scene/default_scene.h"
#include "tests/core/vpl/vpl_test_util.h"
#include "tests/test_util.h"

namespace sst {
namespace {

std::string read_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(VplPly, RoundTripKeepsEveryBit) {
  test::PreparedScene p(load_default_scene());
  VplParams params;
  params.vpls = 5000;
  VplSet vpls = generate_vpls(p.scene, *p.accel, *p.lights, params, 1, false, nullptr);
  auto dir = test::temp_dir();
  std::string path = (dir / "sub" / "vpls.ply").string();  // parent folders are created
  write_vpls_ply(path, vpls);
  VplSet back = read_vpls_ply(path);
  ASSERT_EQ(back.size(), vpls.size());
  EXPECT_EQ(std::memcmp(back.data(), vpls.data(), vpls.size() * sizeof(Vpl)), 0);
  // Only the file itself is left: the temporary was renamed onto it.
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir / "sub")) files += e.is_regular_file();
  EXPECT_EQ(files, 1);
  std::string bytes = read_file(path);
  EXPECT_EQ(bytes.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
  EXPECT_NE(bytes.find("element vertex 5000\n"), std::string::npos);
  EXPECT_NE(bytes.find("property uchar red\n"), std::string::npos);
  size_t header = bytes.find("end_header\n") + std::strlen("end_header\n");
  EXPECT_EQ(bytes.size() - header, vpls.size() * (9 * sizeof(float) + 3));
}

TEST(VplPly, EmptySetRoundTrips) {
  std::string path = (test::temp_dir() / "empty.ply").string();
  write_vpls_ply(path, {});
  EXPECT_TRUE(read_vpls_ply(path).empty());
}

TEST(VplPly, MalformedFilesAreOneLineErrorsNamingTheFile) {
  auto dir = test::temp_dir();
  auto expect_error = [&](const std::string& name, const std::string& content, const std::string& what) {
    std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << content;
    try {
      read_vpls_ply(path);
      ADD_FAILURE() << name << ": no error";
    } catch (const Error& e) {
      std::string m = e.what();
      EXPECT_NE(m.find(path), std::string::npos) << m;
      EXPECT_NE(m.find(what), std::string::npos) << m;
      EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    }
  };
  expect_error("magic.ply", "PLY\n", "magic");
  expect_error("ascii.ply", "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nend_header\n", "binary");
  expect_error("noprop.ply",
               "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nend_header\n", "'y'");
  std::string header = "ply\nformat binary_little_endian 1.0\nelement vertex 2\n";
  for (const char* n : {"x", "y", "z", "nx", "ny", "nz", "r", "g", "b"}) header += std::string("property float ") + n + "\n";
  expect_error("short.ply", header + "end_header\n" + std::string(40, '\0'), "truncated");
  try {
    read_vpls_ply((dir / "missing.ply").string());
    ADD_FAILURE() << "no error for a missing file";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("missing.ply"), std::string::npos);
  }
}

}  // namespace
}  // namespace sst
