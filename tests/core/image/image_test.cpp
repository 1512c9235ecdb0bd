#include "core/image/image.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <set>

#include "core/util/error.h"
#include "tests/test_util.h"

namespace fs = std::filesystem;
using sst::Image;
using sst::Layer;

namespace {

// Values that a lossy or rounding writer would change: tiny, huge, negative, non-round.
Image varied_image(int w, int h, int channels, float seed) {
  Image im(w, h, channels);
  for (size_t i = 0; i < im.data.size(); ++i) {
    const float t = float(i) + seed;
    im.data[i] = std::sin(t * 12.9898f) * std::pow(10.0f, float(int(i % 7)) - 3.0f);
  }
  return im;
}

bool bit_equal(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.channels == b.channels &&
         std::memcmp(a.data.data(), b.data.data(), a.data.size() * sizeof(float)) == 0;
}

std::set<std::string> channel_names(const fs::path& path) {
  auto in = OIIO::ImageInput::open(path.string());
  EXPECT_TRUE(in) << OIIO::geterror();
  if (!in) return {};
  EXPECT_FALSE(in->seek_subimage(1, 0)) << "expected a single-part file";
  const auto& names = in->spec().channelnames;
  return {names.begin(), names.end()};
}

// 8-bit levels as stored in a PNG.
std::vector<int> png_levels(const fs::path& path) {
  const Image stored = sst::read_image_stored(path.string());
  std::vector<int> levels;
  for (float v : stored.data) levels.push_back(int(std::lround(v * 255.0f)));
  return levels;
}

std::string error_of(const std::function<void()>& body) {
  try {
    body();
  } catch (const sst::Error& e) {
    return e.what();
  }
  return "(no sst::Error thrown)";
}

}  // namespace

TEST(ImageDisplay, SrgbCurveKnownValues) {
  EXPECT_EQ(sst::srgb_encode(0.0f), 0.0f);
  EXPECT_NEAR(sst::srgb_encode(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(sst::srgb_encode(0.5f), 0.735356983f, 1e-6f);
  EXPECT_NEAR(sst::srgb_encode(0.0031308f), 0.0404500f, 1e-6f);  // the two pieces meet
  EXPECT_NEAR(sst::srgb_encode(0.001f), 0.01292f, 1e-7f);        // linear segment
  EXPECT_NEAR(sst::srgb_decode(0.735356983f), 0.5f, 1e-6f);
  for (float v : {0.0f, 0.002f, 0.01f, 0.2f, 0.7f, 1.0f})
    EXPECT_NEAR(sst::srgb_decode(sst::srgb_encode(v)), v, 1e-6f);
}

TEST(ImageDisplay, ToDisplayClampsAppliesExposureAndZeroesNonFinite) {
  Image im(5, 1, 1);
  im.data = {-1.0f, 0.25f, 3.0f, std::numeric_limits<float>::quiet_NaN(),
             std::numeric_limits<float>::infinity()};
  const Image d = sst::to_display(im, 1.0f);  // 0.25 * 2 = 0.5
  EXPECT_EQ(d.channels, 1);
  EXPECT_EQ(d.data[0], 0.0f);
  EXPECT_NEAR(d.data[1], 0.735356983f, 1e-6f);
  EXPECT_EQ(d.data[2], 1.0f);
  EXPECT_EQ(d.data[3], 0.0f);
  EXPECT_EQ(d.data[4], 0.0f);
  const Image back = sst::from_display(sst::to_display(im));
  EXPECT_NEAR(back.data[1], 0.25f, 1e-6f);
}

TEST(ImageAccess, RgbAndSetRgb) {
  Image im(3, 2);
  im.set_rgb(2, 1, {0.1f, 0.2f, 0.3f});
  EXPECT_EQ(im.rgb(2, 1), sst::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(im.at(2, 1, 1), 0.2f);
  EXPECT_EQ(im.rgb(0, 0), sst::vec3(0.0f));
  Image gray(2, 2, 1);
  gray.at(1, 1, 0) = 0.7f;
  EXPECT_EQ(gray.rgb(1, 1), sst::vec3(0.7f));
  gray.set_rgb(0, 0, sst::vec3(0.5f));
  EXPECT_NEAR(gray.at(0, 0, 0), 0.5f, 1e-6f);
}

TEST(ImagePng, EncodesDisplayLevels) {
  const fs::path path = sst::test::temp_dir() / "levels.png";
  Image im(6, 1);
  const float values[6] = {0.0f, 0.5f, 1.0f, 2.0f, -0.5f, 0.001f};
  for (int x = 0; x < 6; ++x) im.set_rgb(x, 0, sst::vec3(values[x]));
  im.at(1, 0, 2) = std::numeric_limits<float>::quiet_NaN();
  sst::write_image(path.string(), im);
  const std::vector<int> levels = png_levels(path);
  ASSERT_EQ(levels.size(), 18u);
  const int expected[6] = {0, 188, 255, 255, 0, 3};  // 0.001 -> 0.01292 * 255 = 3.29
  for (int x = 0; x < 6; ++x) EXPECT_EQ(levels[x * 3 + 0], expected[x]) << "pixel " << x;
  EXPECT_EQ(levels[1 * 3 + 2], 0) << "NaN must be written as 0";
}

TEST(ImagePng, ExposureScalesBeforeEncoding) {
  const fs::path path = sst::test::temp_dir() / "exposure.png";
  Image im(1, 1);
  im.set_rgb(0, 0, sst::vec3(0.125f));
  sst::write_image(path.string(), im, {}, 2.0f);  // 0.125 * 4 = 0.5
  EXPECT_EQ(png_levels(path), (std::vector<int>{188, 188, 188}));
}

TEST(ImageRead, PngDecodesToLinearAndSaysSo) {
  const fs::path path = sst::test::temp_dir() / "half.png";
  Image im(2, 2);
  for (float& v : im.data) v = 0.5f;
  sst::write_image(path.string(), im);
  bool display = false;
  const Image linear = sst::read_image(path.string(), &display);
  EXPECT_TRUE(display);
  EXPECT_NEAR(linear.data[0], sst::srgb_decode(188.0f / 255.0f), 1e-7f);
  EXPECT_NEAR(linear.data[0], 0.5f, 0.003f);
  const Image stored = sst::read_image_stored(path.string());
  EXPECT_EQ(stored.data[0], 188.0f / 255.0f);
}

TEST(ImageRead, GrayscaleReplicatesAndAlphaIsDroppedUnpremultiplied) {
  const fs::path dir = sst::test::temp_dir();
  const auto write_raw = [](const fs::path& path, int channels, std::vector<uint8_t> pixels) {
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out);
    OIIO::ImageSpec spec(1, 1, channels, OIIO::TypeDesc::UINT8);
    if (channels == 4) {
      spec.alpha_channel = 3;
      spec.attribute("oiio:UnassociatedAlpha", 1);  // store 200,100,50 as given, not divided by alpha
    }
    ASSERT_TRUE(out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
  };
  write_raw(dir / "gray.png", 1, {51});
  write_raw(dir / "rgba.png", 4, {200, 100, 50, 128});
  const Image gray = sst::read_image_stored((dir / "gray.png").string());
  EXPECT_EQ(gray.channels, 3);
  EXPECT_EQ(gray.rgb(0, 0), sst::vec3(51.0f / 255.0f));
  const Image rgba = sst::read_image_stored((dir / "rgba.png").string());
  EXPECT_EQ(rgba.channels, 3);
  EXPECT_EQ(rgba.rgb(0, 0), sst::vec3(200.0f, 100.0f, 50.0f) / 255.0f);
}

TEST(ImageExr, RoundTripWithLayersIsBitExact) {
  const fs::path path = sst::test::temp_dir() / "frame.exr";
  const Image rgb = varied_image(7, 5, 3, 0.0f);
  const std::vector<Layer> layers{{"albedo", varied_image(7, 5, 3, 1.0f)},
                                  {"depth", varied_image(7, 5, 1, 2.0f)},
                                  {"indirect", varied_image(7, 5, 3, 3.0f)}};
  sst::write_image(path.string(), rgb, layers);
  bool display = true;
  EXPECT_TRUE(bit_equal(sst::read_image(path.string(), &display), rgb));
  EXPECT_FALSE(display);
  for (const Layer& layer : layers)
    EXPECT_TRUE(bit_equal(sst::read_layer(path.string(), layer.name), layer.image)) << layer.name;
  EXPECT_EQ(sst::list_layers(path.string()), (std::vector<std::string>{"albedo", "depth", "indirect"}));
}

TEST(ImageExr, ChannelNamesInOnePart) {
  const fs::path path = sst::test::temp_dir() / "names.exr";
  sst::write_image(path.string(), Image(4, 3), {{"albedo", Image(4, 3)}, {"depth", Image(4, 3, 1)}});
  EXPECT_EQ(channel_names(path),
            (std::set<std::string>{"R", "G", "B", "albedo.R", "albedo.G", "albedo.B", "depth.Y"}));
}

TEST(ImageExr, NonFiniteValuesAreWrittenAsZero) {
  const fs::path path = sst::test::temp_dir() / "nan.exr";
  Image im(2, 1);
  im.data = {1.0f, std::numeric_limits<float>::quiet_NaN(),
             2.0f, -std::numeric_limits<float>::infinity(),
             3.0f, 4.0f};
  Image depth(2, 1, 1);
  depth.data = {std::numeric_limits<float>::infinity(), 5.0f};
  sst::write_image(path.string(), im, {{"depth", depth}});
  EXPECT_EQ(sst::read_image(path.string()).data, (std::vector<float>{1, 0, 2, 0, 3, 4}));
  EXPECT_EQ(sst::read_layer(path.string(), "depth").data, (std::vector<float>{0, 5}));
}

TEST(ImageExr, MissingLayerNamesItAndListsTheOthers) {
  const fs::path path = sst::test::temp_dir() / "layers.exr";
  sst::write_image(path.string(), Image(2, 2), {{"albedo", Image(2, 2)}, {"depth", Image(2, 2, 1)}});
  const std::string message = error_of([&] { sst::read_layer(path.string(), "indirect"); });
  EXPECT_NE(message.find("'indirect'"), std::string::npos) << message;
  EXPECT_NE(message.find("albedo, depth"), std::string::npos) << message;
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
}

TEST(ImageHdr, RoundTripWithinRgbePrecision) {
  const fs::path path = sst::test::temp_dir() / "frame.hdr";
  Image im(3, 2);
  for (size_t i = 0; i < im.data.size(); ++i) im.data[i] = 0.01f + 7.3f * float(i);
  sst::write_image(path.string(), im);
  const Image back = sst::read_image(path.string());
  ASSERT_EQ(back.width, 3);
  ASSERT_EQ(back.height, 2);
  for (size_t i = 0; i < im.data.size(); ++i) {
    // RGBE shares one exponent per pixel: 8 bits of mantissa relative to the pixel's largest channel.
    const float pixel_max = std::max({im.data[i / 3 * 3], im.data[i / 3 * 3 + 1], im.data[i / 3 * 3 + 2]});
    EXPECT_NEAR(back.data[i], im.data[i], pixel_max / 128.0f) << i;
  }
}

TEST(ImageWrite, AtomicRenameLeavesNoTempFileAndCreatesFolders) {
  const fs::path dir = sst::test::temp_dir() / "a" / "b";
  for (const char* name : {"out.exr", "out.png", "out.hdr"}) {
    sst::write_image((dir / name).string(), varied_image(3, 3, 3, 0.0f));
    sst::write_image((dir / name).string(), varied_image(3, 3, 3, 1.0f));  // overwrite in place
  }
  std::set<std::string> files;
  for (const auto& entry : fs::directory_iterator(dir)) files.insert(entry.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"out.exr", "out.png", "out.hdr"}));
  EXPECT_TRUE(bit_equal(sst::read_image((dir / "out.exr").string()), varied_image(3, 3, 3, 1.0f)));
}

TEST(ImageWrite, UnknownExtensionIsAnErrorAndWritesNothing) {
  const fs::path path = sst::test::temp_dir() / "out.bmp";
  const std::string message = error_of([&] { sst::write_image(path.string(), Image(2, 2)); });
  EXPECT_EQ(message, "unsupported image extension '.bmp' in " + path.string() + " (use .exr, .png or .hdr)");
  EXPECT_TRUE(fs::is_empty(path.parent_path()));
}

TEST(ImageWrite, LayerOfWrongSizeIsAnError) {
  const fs::path path = sst::test::temp_dir() / "bad.exr";
  const std::string message = error_of([&] {
    sst::write_image(path.string(), Image(4, 4), {{"albedo", Image(2, 2)}});
  });
  EXPECT_NE(message.find("albedo"), std::string::npos) << message;
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(path));
}

TEST(ImageRead, MissingFileNamesThePath) {
  const fs::path path = sst::test::temp_dir() / "nowhere.exr";
  const std::string message = error_of([&] { sst::read_image(path.string()); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_NE(error_of([&] { sst::read_layer(path.string(), "albedo"); }).find(path.string()),
            std::string::npos);
}

TEST(ImageRead, UnreadableFileNamesThePath) {
  const fs::path path = sst::test::temp_dir() / "garbage.exr";
  { std::ofstream(path) << "this is not an image"; }
  const std::string message = error_of([&] { sst::read_image(path.string()); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
}
