// Every seed of the fuzz corpora (tests/fuzz/corpus/<harness>/) through its harness, in the
// ordinary build: the seeds include the inputs of issue 15's findings, so each is a regression
// test, and the harnesses themselves are built and run on every CI run. A harness swallows
// sst::Error only; anything else escaping fails here (a crash fails the test binary).
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int sst_fuzz_gltf(const uint8_t* data, size_t size);
extern "C" int sst_fuzz_texture(const uint8_t* data, size_t size);
extern "C" int sst_fuzz_config(const uint8_t* data, size_t size);
extern "C" int sst_fuzz_image(const uint8_t* data, size_t size);

namespace {

TEST(FuzzCorpus, EverySeedLoadsOrIsRefusedWithAnError) {
  const struct {
    const char* name;
    int (*run)(const uint8_t*, size_t);
  } harnesses[] = {{"gltf", sst_fuzz_gltf}, {"texture", sst_fuzz_texture}, {"config", sst_fuzz_config},
                   {"image", sst_fuzz_image}};
  for (const auto& h : harnesses) {
    int seeds = 0;
    for (const auto& entry : std::filesystem::directory_iterator(std::string(SST_SOURCE_DIR) + "/tests/fuzz/corpus/" + h.name)) {
      std::ifstream in(entry.path(), std::ios::binary);
      std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      EXPECT_NO_THROW(h.run(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size())) << entry.path();
      ++seeds;
    }
    EXPECT_GE(seeds, 4) << h.name;
  }
}

}  // namespace
