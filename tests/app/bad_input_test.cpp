// The fuzz findings of issue 15, each with the small input that found it, generated here: bad
// input gives one line "error: ..." naming the file or flag and a non-zero exit (or, where the
// input is valid, a correct render), within 10 s, and leaves nothing half-written.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "core/render/render_options.h"
#include "core/util/json_io.h"
#include "core/util/machine_info.h"
#include "core/util/temp_files.h"
#include "tests/core/scene/gltf_test_files.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;

namespace sst {
namespace {

using nlohmann::json;
using test::GltfBuilder;

// Every command runs under `timeout 10`: a hang fails the test (exit 124) instead of blocking it.
test::CommandResult render(const std::string& args) {
  return test::run_command("timeout 10 " + std::string(SST_RENDER_EXE) + " " + args);
}
test::CommandResult eval(const std::string& args) {
  return test::run_command("timeout 10 " + std::string(SST_EVAL_EXE) + " " + args);
}

// Exactly one line, "error: ...", containing `needle`, and the exit code `code` (1: bad input,
// 2: command-line usage).
void expect_error(const test::CommandResult& r, const std::string& needle, int code = 1) {
  EXPECT_EQ(r.exit_code, code) << r.output;
  EXPECT_EQ(r.output.rfind("error: ", 0), 0u) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  EXPECT_NE(r.output.find(needle), std::string::npos) << "expected '" << needle << "' in: " << r.output;
}

void write_file(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string nested(size_t depth) { return std::string(depth, '[') + std::string(depth, ']'); }

// A triangle seen by a camera, lit by a point light: a scene that renders.
GltfBuilder lit_triangle(float far_vertex = 1.0f) {
  GltfBuilder b;
  json prim = {{"attributes", {{"POSITION", b.vec3s({0, 0, 0, far_vertex, 0, 0, 0, 1, 0})},
                               {"NORMAL", b.vec3s({0, 0, 1, 0, 0, 1, 0, 0, 1})}}}};
  int mesh = b.mesh(prim);
  b.doc["cameras"] = json::array({{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.01}}}}});
  b.doc["extensionsUsed"] = {"KHR_lights_punctual"};
  b.doc["extensions"]["KHR_lights_punctual"]["lights"] = json::array({{{"type", "point"}, {"intensity", 10.0}}});
  int m = b.node({{"mesh", mesh}});
  int c = b.node({{"camera", 0}, {"translation", {0.3, 0.3, 2.0}}});
  int l = b.node({{"translation", {0.3, 0.3, 1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  b.scene({m, c, l});
  return b;
}

// A glTF whose one material has the texture `image_file` (written beside it by the caller).
fs::path textured_triangle(const fs::path& dir, const std::string& image_file) {
  GltfBuilder b;
  b.doc["images"] = json::array({{{"uri", image_file}}});
  b.doc["textures"] = json::array({{{"source", 0}}});
  int mat = b.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  b.scene({b.node({{"mesh", b.triangle_mesh(mat)}})});
  return b.write(dir, "textured");
}

std::string be32(uint32_t v) { return {char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; }

uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char c : bytes) {
    crc ^= c;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

std::string png_chunk(const std::string& type, const std::string& data) {
  return be32(uint32_t(data.size())) + type + data + be32(crc32(type + data));
}

// A PNG signature and IHDR declaring w x h 8-bit RGB, then `idat` (none by default) and IEND:
// 45 bytes that ask a decoder for w * h * 3 bytes.
std::string png_header_only(uint32_t w, uint32_t h, const std::string& idat = "") {
  std::string png = "\x89PNG\r\n\x1a\n";
  png += png_chunk("IHDR", be32(w) + be32(h) + std::string("\x08\x02\x00\x00\x00", 5));
  if (!idat.empty()) png += png_chunk("IDAT", idat);
  return png + png_chunk("IEND", "");
}

// ---- Crashes ----

TEST(BadInput, GltfExtrasNestedDeepIsRefused) {
  auto dir = test::temp_dir();
  fs::path f = dir / "deep.gltf";
  write_file(f, R"({"asset":{"version":"2.0"},"extras":)" + nested(20000) + "}");
  expect_error(render(f.string() + " -q -o " + (dir / "x.exr").string()), f.string() + ": JSON nested deeper than 256 levels");
  fs::path g = dir / "deep-ext.gltf";
  write_file(g, R"({"asset":{"version":"2.0"},"extensions":{"X":)" + nested(20000) + "}}");
  expect_error(render(g.string() + " -q -o " + (dir / "x.exr").string()), "nested deeper than 256");
  // A depth a real file has still loads.
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  b.doc["extras"] = json::parse(nested(100));
  EXPECT_EQ(test::load_error(b.write(dir, "ok")), "");
}

// The loader's animation errors (tests/core/scene/animation_test.cpp) reach the command line as
// one line naming the file.
TEST(BadInput, AnAnimationErrorIsOneLineOfTheProgram) {
  auto dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  std::vector<float> times = {0, 1}, values = {0, 0, 0, 1, 0, 0};
  int input = b.accessor(b.view(times), test::kFloat, times.size(), "SCALAR");
  int output = b.accessor(b.view(values), test::kFloat, 2, "VEC3");
  b.doc["animations"] = json::array({{{"name", "anim0"},
                                      {"samplers", {{{"input", input}, {"output", output}, {"interpolation", "QUADRATIC"}}}},
                                      {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}}}}}});
  fs::path path = b.write(dir, "bad");
  expect_error(render(path.string() + " -q -o " + (dir / "out.exr").string()),
               path.string() + ": animation 0 ('anim0') channel 0 sampler 0 has unknown interpolation");
}

TEST(BadInput, ConfigNestedDeepIsRefused) {
  auto dir = test::temp_dir();
  for (std::string where : {"axes", "reference", "nonsense"}) {
    fs::path cfg = dir / (where + ".json");
    write_file(cfg, "{\"" + where + "\": " + nested(20000) + "}");
    expect_error(eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string()), cfg.string() + ": JSON nested deeper");
  }
}

TEST(BadInput, HugeBlockSizeRendersLikeOneBlock) {
  auto dir = test::temp_dir();
  for (const char* method : {"rtslc", "hybrid"}) {
    std::string common = std::string(" --method ") + method + " --vpls 500 --width 12 --spp 1 -q --json /dev/null";
    auto huge = render("--block-size 2147483647 -o " + (dir / "huge.exr").string() + common);
    ASSERT_EQ(huge.exit_code, 0) << method << ": " << huge.output;
    // One block covers the image whatever its size beyond it, so the image equals block size 12's.
    ASSERT_EQ(render("--block-size 12 -o " + (dir / "twelve.exr").string() + common).exit_code, 0);
    auto same = eval("compare " + (dir / "huge.exr").string() + " " + (dir / "twelve.exr").string() + " --json");
    ASSERT_EQ(same.exit_code, 0) << same.output;
    EXPECT_EQ(json::parse(same.output)["rmse"], 0.0) << method;
  }
}

TEST(BadInput, CoordinatesBeyondFloatsUsefulRangeAreRefused) {
  auto dir = test::temp_dir();
  fs::path far = lit_triangle(1e18f).write(dir, "far-vertex");
  expect_error(render(far.string() + " -q --width 8 -o " + (dir / "x.exr").string()),
               far.string() + ": vertex 1 at (1e+18, 0, 0) lies beyond the largest coordinate");
  GltfBuilder b = lit_triangle();
  b.doc["nodes"][1]["translation"] = {0.3, 0.3, 1e18};
  fs::path camera = b.write(dir, "far-camera");
  expect_error(render(camera.string() + " -q --width 8 -o " + (dir / "x.exr").string()), "at (0.3, 0.3, 1e+18) lies beyond");
  // The same scene at an ordinary distance renders.
  fs::path near = lit_triangle().write(dir, "near");
  auto ok = render(near.string() + " -q --width 8 --spp 1 -o " + (dir / "near.exr").string());
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

// ---- Memory errors ----

TEST(BadInput, GlbBinChunkRunningPastTheFileIsRefused) {
  auto dir = test::temp_dir();
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  fs::path glb = b.write_glb(dir, "tri");
  ASSERT_EQ(test::load_error(glb), "");
  std::string bytes;
  {
    std::ifstream in(glb, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  uint32_t json_length;
  std::memcpy(&json_length, bytes.data() + 12, 4);
  uint32_t bin_length;
  std::memcpy(&bin_length, bytes.data() + 20 + json_length, 4);
  bin_length += 8;  // exactly what tinygltf 2.7 lets through: the chunk header not counted
  std::memcpy(bytes.data() + 20 + json_length, &bin_length, 4);
  write_file(glb, bytes);
  test::expect_one_line_naming(test::load_error(glb), glb, "invalid GLB: chunk at byte");
  // A header length that is not the file's.
  bytes += std::string(4, '\0');
  write_file(glb, bytes);
  test::expect_one_line_naming(test::load_error(glb), glb, "invalid GLB: header says");
}

TEST(BadInput, JpegWithMoreThan256HuffmanSymbolsIsRefusedBeforeStbSeesIt) {
  auto dir = test::temp_dir();
  // SOI, then a DHT segment whose counts declare 510 codes of lengths 15 and 16 (a prefix code,
  // but more symbols than a table holds), then a frame header and EOI.
  std::string counts(16, '\0');
  counts[14] = char(255);
  counts[15] = char(255);
  std::string dht = std::string("\x00", 1) + counts + std::string(510, '\x01');
  std::string jpeg = "\xFF\xD8";
  jpeg += std::string("\xFF\xC4") + char((dht.size() + 2) >> 8) + char((dht.size() + 2) & 255) + dht;
  jpeg += std::string("\xFF\xC0\x00\x0B\x08\x00\x01\x00\x01\x01\x01\x11\x00", 13);
  jpeg += "\xFF\xD9";
  write_file(dir / "bad.jpg", jpeg);
  fs::path gltf = textured_triangle(dir, "bad.jpg");
  test::expect_one_line_naming(test::load_error(gltf), gltf, "cannot decode image 'bad.jpg': corrupt JPEG: Huffman table of 510 symbols");
}

TEST(BadInput, AccessorByteOffsetNear2To64IsReportedWithoutOverflow) {
  auto dir = test::temp_dir();
  GltfBuilder b;
  int view = b.view(std::vector<float>{0, 0, 0, 1, 0, 0, 0, 1, 0});
  int positions = b.accessor(view, test::kFloat, 3, "VEC3");
  b.doc["accessors"][positions]["byteOffset"] = 18446744073709551615ull;
  b.scene({b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", positions}}}})}})});
  fs::path f = b.write(dir, "offset");
  std::string message = test::load_error(f);
  // 2^64 - 1 + 2 x 12 + 12 bytes, printed from the long double (a cast to uint64 was undefined).
  test::expect_one_line_naming(message, f, "reaches beyond bufferView 0 (needs 1844674407370955");
}

TEST(BadInput, SeedOutOfRangeInAConfigIsRefused) {
  auto dir = test::temp_dir();
  for (const char* seed : {"-1", "1e39", "4294967296"}) {
    fs::path cfg = dir / "cfg.json";
    write_file(cfg, std::string(R"({"width": 8, "spp": 1, "seed": )") + seed + "}");
    expect_error(eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string()),
                 "seed must be an integer in 0..4294967295");
  }
}

TEST(BadInput, HugeRussianRouletteStartRendersWithoutRoulette) {
  auto dir = test::temp_dir();
  std::string common = " --width 12 --spp 2 --max-bounces 3 -q --json /dev/null";
  ASSERT_EQ(render("--rr-min-bounces 2147483647 -o " + (dir / "a.exr").string() + common).exit_code, 0);
  ASSERT_EQ(render("--rr-min-bounces 3 -o " + (dir / "b.exr").string() + common).exit_code, 0);
  // rr_min_bounces >= max_bounces: no roulette either way, the same image.
  auto same = eval("compare " + (dir / "a.exr").string() + " " + (dir / "b.exr").string() + " --json");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_EQ(json::parse(same.output)["rmse"], 0.0);
}

// ---- Inputs that would take all memory or hang ----

TEST(BadInput, AccessorsWithoutBufferViewAreBoundedInAll) {
  auto dir = test::temp_dir();
  GltfBuilder b;
  std::vector<int> roots;
  for (int i = 0; i < 40; ++i) {
    b.doc["accessors"].push_back({{"componentType", test::kFloat}, {"count", (1 << 22) + 1}, {"type", "VEC3"}});
    roots.push_back(b.node({{"mesh", b.mesh({{"attributes", {{"POSITION", i}}}})}}));
  }
  b.scene(roots);
  fs::path f = b.write(dir, "implicit");
  test::expect_one_line_naming(test::load_error(f), f, "accessor 3 has no bufferView and count 4194305: accessors without data may hold at most 16777216 elements in all");
}

TEST(BadInput, TextureDecompressionBombIsRefusedFromItsHeader) {
  auto dir = test::temp_dir();
  write_file(dir / "bomb.png", png_header_only(20000, 20000));
  fs::path gltf = textured_triangle(dir, "bomb.png");
  test::expect_one_line_naming(test::load_error(gltf), gltf,
                               "image 'bomb.png' is 20000x20000 pixels: textures may have at most 16384 per side");
}

TEST(BadInput, CompareRefusesADecompressionBombFromItsHeader) {
  auto dir = test::temp_dir();
  // An empty zlib stream as its IDAT: enough for the header to be read, nothing to inflate.
  write_file(dir / "bomb.png", png_header_only(30000, 30000, std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)));
  write_file(dir / "small.png", png_header_only(1, 1));
  expect_error(eval("compare " + (dir / "bomb.png").string() + " " + (dir / "small.png").string()),
               (dir / "bomb.png").string() + ": 30000x30000 pixels is too large");
}

TEST(BadInput, CompareCountsTheMemoryLimitOfTheEnvironment) {
  // 2048 x 2048 x 3 channels needs 192 MiB to read: more than a quarter of 64 MiB. The same limit
  // on every machine is what makes fuzzing refuse the same inputs everywhere.
  auto dir = test::temp_dir();
  write_file(dir / "big.png", png_header_only(2048, 2048, std::string("\x78\x9c\x03\x00\x00\x00\x00\x01", 8)));
  write_file(dir / "small.png", png_header_only(1, 1));
  const std::string args = "compare " + (dir / "big.png").string() + " " + (dir / "small.png").string();
  expect_error(test::run_command("SST_MEMORY_LIMIT_MB=64 timeout 10 " + std::string(SST_EVAL_EXE) + " " + args),
               (dir / "big.png").string() + ": 2048x2048 pixels of 3 channels need 192 MiB to read, more than a quarter of this machine's memory (64 MiB)");
  expect_error(test::run_command("SST_MEMORY_LIMIT_MB=64k timeout 10 " + std::string(SST_EVAL_EXE) + " " + args),
               "SST_MEMORY_LIMIT_MB must be a whole number of MiB from 1 to 2^40 (got '64k')");
}

TEST(BadInput, ATextureStbCannotDecodeWithoutAReasonIsRefused) {
  // Found by fuzz_texture: stb_image fails on this 119-byte PNG (a run of 0xFF after its IDAT)
  // but leaves its failure reason empty; the empty error let the undecoded image through to a
  // null read. The bytes are the fuzzer's, from tests/fuzz/corpus/texture/.
  auto dir = test::temp_dir();
  std::ifstream in(std::string(SST_SOURCE_DIR) + "/tests/fuzz/corpus/texture/corrupt_idat_empty_reason.png", std::ios::binary);
  write_file(dir / "bad.png", std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
  fs::path gltf = textured_triangle(dir, "bad.png");
  test::expect_one_line_naming(test::load_error(gltf), gltf, "cannot decode image 'bad.png': cannot decode");
}

TEST(BadInput, CompareRefusesAnExrDataWindowBeyondTheMemory) {
  // Found by fuzz_image: 552 bytes whose data window is one line of 16187393 pixels (the fuzzer's
  // file). OpenEXR sizes its buffers from the data window as it opens a file, which took 25-32 s
  // under ASan, whose allocator writes what it hands out; the header is now checked before
  // OpenEXR opens the file (0.7 s under ASan; the sanitizer job's fuzz_image is what times it).
  auto dir = test::temp_dir();
  write_file(dir / "small.png", png_header_only(1, 1));
  const std::string wide = std::string(SST_SOURCE_DIR) + "/tests/data/exr_wide_line.exr";
  expect_error(test::run_command("SST_MEMORY_LIMIT_MB=256 timeout 10 " + std::string(SST_EVAL_EXE) + " compare " +
                                 wide + " " + (dir / "small.png").string()),
               wide + ": 16187393x1 pixels of 3 channels need 741 MiB to read, more than a quarter of this machine's memory (256 MiB)");
}

TEST(BadInput, CompareRefusesAnExrAttributeLongerThanTheFile) {
  // Found by fuzz_image: OpenEXR allocated an attribute's declared size (here 1.9 GB) before
  // reading it. A minimal header: magic, version 2, one string attribute declaring 2^30 bytes.
  auto dir = test::temp_dir();
  std::string exr("\x76\x2f\x31\x01\x02\x00\x00\x00", 8);
  exr += std::string("comments\0string\0", 16) + std::string("\x00\x00\x00\x40", 4) + "abc";
  write_file(dir / "attr.exr", exr);
  write_file(dir / "small.png", png_header_only(1, 1));
  expect_error(eval("compare " + (dir / "attr.exr").string() + " " + (dir / "small.png").string()),
               "invalid OpenEXR file: header attribute 'comments' declares 1073741824 bytes, 3 follow");
}

TEST(BadInput, ImageLargerThanTheMachineCanHoldIsRefusedBeforeRendering) {
  // 16384 x 16384 needs ~48 GiB: refused on a machine with less; on a larger one 16385 x 16384
  // exceeds the 2^28-pixel cap. Either way, refused in well under 10 s.
  bool small = render_pixel_limit(usable_memory_bytes()) < (uint64_t(1) << 28);
  std::string size = small ? "--width 16384 --height 16384" : "--width 16385 --height 16384";
  auto dir = test::temp_dir();
  expect_error(render(size + " -q -o " + (dir / "x.exr").string()), "pixels is too large");
  EXPECT_EQ(render_pixel_limit(uint64_t(24) << 30), (uint64_t(24) << 30) / 4 * 3 / kRenderBytesPerPixel);
  EXPECT_EQ(render_pixel_limit(uint64_t(1) << 40), uint64_t(1) << 28);
}

TEST(BadInput, ThreadCountBeyondAnyMachineIsRefused) {
  auto dir = test::temp_dir();
  expect_error(render("--threads 2147483647 -q -o " + (dir / "x.exr").string()), "threads must be in 0..4096 (got 2147483647)");
}

TEST(BadInput, SweepOfAHundredMillionRunsIsRefusedBeforeExpanding) {
  auto dir = test::temp_dir();
  json spp = json::array(), width = json::array();
  for (int i = 1; i <= 1000; ++i) spp.push_back(i);
  for (int i = 1; i <= 100; ++i) width.push_back(i);
  fs::path cfg = dir / "huge.json";
  std::ofstream(cfg) << json{{"axes", {{"spp", spp}, {"width", width}}}, {"seeds", 1000}}.dump();
  expect_error(eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string()),
               "experiment 'huge' has 100000000 runs (scenes x axes x variants x seeds); at most 100000");
}

TEST(BadInput, UrisNamingAFifoOrADirectoryAreRefusedWithoutReading) {
  auto dir = test::temp_dir();
  ASSERT_EQ(mkfifo((dir / "fifo").c_str(), 0600), 0);
  fs::create_directory(dir / "folder");
  for (const char* uri : {"fifo", "folder"}) {
    GltfBuilder b;
    b.scene({b.node({{"mesh", b.triangle_mesh()}})});
    fs::path f = b.write(dir, std::string("buffer-") + uri);
    json doc = read_json_file(f.string());
    doc["buffers"][0]["uri"] = uri;
    write_file(f, doc.dump());
    expect_error(render(f.string() + " -q -o " + (dir / "x.exr").string()),
                 f.string() + ": cannot read buffer file " + (dir / uri).string() + ": not a regular file");
    fs::path tex = textured_triangle(dir, uri);
    test::expect_one_line_naming(test::load_error(tex), tex, std::string("image '") + uri + "' not found, empty or not a regular file");
  }
  expect_error(eval("compare " + (dir / "fifo").string() + " " + (dir / "fifo").string()), "not a regular file");
  expect_error(eval("sweep " + (dir / "fifo").string() + " -q"), (dir / "fifo").string() + ": not a regular file");
}

// ---- Wrong numbers accepted ----

TEST(BadInput, IntegerFlagsAreParsedWithoutNarrowing) {
  auto dir = test::temp_dir();
  std::string out = " -q -o " + (dir / "x.exr").string();
  expect_error(render("--width 4294967297" + out), "--width expects an integer in -2147483648..2147483647, got '4294967297'");
  expect_error(render("--spp 4294967297" + out), "--spp expects an integer in -2147483648..2147483647, got '4294967297'");
  expect_error(render("--method slc --vpls 9999999999999" + out), "--vpls expects an integer in -2147483648..2147483647, got '9999999999999'");
  expect_error(render("--seed -1" + out), "--seed expects an integer in 0..4294967295, got '-1'");
  expect_error(render("--spp 99999999999999999999999" + out), "--spp expects an integer");
  expect_error(render("--camera 99999999999999999999999 --width 8" + out), "no camera '99999999999999999999999'");
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

TEST(BadInput, FloatFlagsMustBeFiniteAndInRange) {
  auto dir = test::temp_dir();
  std::string out = " --method sst --vpls 500 --width 8 --spp 1 -q -o " + (dir / "x.exr").string();
  for (const char* v : {"nan", "inf", "-inf", "1e39"})
    expect_error(render(std::string("--distance-floor ") + v + out),
                 std::string("--distance-floor expects a finite number of magnitude at most 3.40282e+38, got '") + v + "'");
  expect_error(render("--distance-floor -1" + out), "sst: parameter 'distance_floor' must be finite and >= 0");
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
}

// ---- Messages ----

TEST(BadInput, CommandLineErrorsAreOneLineWithExitCode2) {
  expect_error(render("--bogus"), "error: The following argument was not expected: --bogus", 2);
  expect_error(render("--width"), "--width", 2);
  expect_error(eval("compare only-one.exr"), "reference", 2);
  expect_error(eval(""), "subcommand", 2);
  auto help = render("--help");
  EXPECT_EQ(help.exit_code, 0);
}

TEST(BadInput, ConfigTypeErrorsNameTheFileAndKey) {
  auto dir = test::temp_dir();
  fs::path cfg = dir / "cfg.json";
  write_file(cfg, R"({"name": 5})");
  expect_error(eval("sweep " + cfg.string() + " -q"), cfg.string() + ": 'name' must be a string, got 5");
  write_file(cfg, R"({"method": 7, "width": 8})");
  expect_error(eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string()), "'method' must be a string, got 7");
  write_file(cfg, R"({"width": 8, "reference": {"spp": -5}})");
  expect_error(eval("sweep " + cfg.string() + " -q -o " + (dir / "out").string()),
               cfg.string() + ": reference: 'spp' must be an integer >= 1, got -5");
}

TEST(BadInput, BufferProblemsAreOneShortLine) {
  auto dir = test::temp_dir();
  // A data URI that is not base64: reported without echoing the (long) URI.
  GltfBuilder b;
  b.scene({b.node({{"mesh", b.triangle_mesh()}})});
  fs::path f = b.write(dir, "datauri");
  json doc = read_json_file(f.string());
  doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + std::string(20000, '!');
  write_file(f, doc.dump());
  std::string message = test::load_error(f);
  test::expect_one_line_naming(message, f, "a buffer's data URI is not base64 of byteLength bytes");
  EXPECT_LT(message.size(), 300u) << message;
  // A GLB whose buffer declares 0 bytes beside a BIN chunk that has some (tinygltf copied it
  // with vector::at(0) and said "vector::_M_range_check").
  GltfBuilder g;
  g.scene({g.node({{"mesh", g.triangle_mesh()}})});
  fs::path glb = g.write_glb(dir, "empty");
  std::string bytes;
  {
    std::ifstream in(glb, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::string declared = "\"buffers\":[{\"byteLength\":" + std::to_string(g.bin.size()) + "}]";
  size_t at = bytes.find(declared);
  ASSERT_NE(at, std::string::npos);
  std::string empty = "\"buffers\":[{\"byteLength\":0}]";
  bytes.replace(at, declared.size(), empty + std::string(declared.size() - empty.size(), ' '));
  write_file(glb, bytes);
  test::expect_one_line_naming(test::load_error(glb), glb, "buffer 0 has byteLength 0 (glTF requires >= 1)");
}

TEST(BadInput, TextureDecodeFailureKeepsStbsReason) {
  auto dir = test::temp_dir();
  // A valid 1x1 header, then IDAT bytes that are not a zlib stream.
  write_file(dir / "broken.png", png_header_only(1, 1, "\x01\x02\x03\x04"));
  fs::path gltf = textured_triangle(dir, "broken.png");
  std::string message = test::load_error(gltf);
  test::expect_one_line_naming(message, gltf, "cannot decode image 'broken.png': ");
  EXPECT_EQ(message.find("Unknown image format"), std::string::npos) << message;  // tinygltf's generic text
}

TEST(BadInput, LibpngsOwnLineIsNotPrinted) {
  auto dir = test::temp_dir();
  std::string png = png_header_only(2, 2);
  png[29] = char(png[29] ^ 0xFF);  // the IHDR's CRC
  write_file(dir / "crc.png", png);
  // Only our line, which carries libpng's reason.
  expect_error(eval("compare " + (dir / "crc.png").string() + " " + (dir / "crc.png").string()), "CRC error");
}

// ---- Partial outputs ----

TEST(BadInput, AnUnwritableOutputLeavesNoOtherOutput) {
  auto dir = test::temp_dir();
  write_file(dir / "file", "");
  auto r = render("--width 8 --spp 1 -q -o " + (dir / "first.exr").string() + " -o " + (dir / "file" / "second.png").string());
  expect_error(r, (dir / "file" / "second.png").string());
  for (const auto& entry : fs::directory_iterator(dir))
    EXPECT_EQ(entry.path().filename(), "file") << "left behind: " << entry.path();
}

TEST(BadInput, ARecordWrittenToADeviceLeavesTheDeviceInPlace) {
  // Outputs are renamed into place, but never over a device: --json /dev/null once replaced
  // /dev/null with a regular file.
  auto dir = test::temp_dir();
  struct stat before {};
  ASSERT_EQ(stat("/dev/null", &before), 0);
  ASSERT_TRUE(S_ISCHR(before.st_mode));
  auto r = render("--width 8 --spp 1 -q -o " + (dir / "x.exr").string() + " --json /dev/null");
  EXPECT_EQ(r.exit_code, 0) << r.output;
  struct stat after {};
  ASSERT_EQ(stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode)) << "/dev/null is no longer a character device";
  EXPECT_TRUE(fs::exists(dir / "x.exr"));
  ASSERT_EQ(mkfifo((dir / "fifo.exr").c_str(), 0600), 0);
  expect_error(render("--width 8 --spp 1 -q -o " + (dir / "fifo.exr").string()), "fifo.exr: not a regular file");
}

TEST(BadInput, ASignalRemovesTheTemporaryBeingWritten) {
  auto dir = test::temp_dir();
  fs::path temp = dir / ".out.exr.tmp-1";
  pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    remove_temp_files_on_signals();
    TempFile file(temp.string());
    std::ofstream(temp) << "half an image";
    raise(SIGINT);
    _exit(0);  // not reached: the signal ends the process
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_FALSE(fs::exists(temp));
}

}  // namespace
}  // namespace sst
