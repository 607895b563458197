#include <doctest/doctest.h>

#include <cmath>
#include <fstream>

#include "io/AtomicFile.hpp"
#include "io/Image.hpp"
#include "util/Error.hpp"

using namespace rt;

namespace {

std::filesystem::path outputDir() {
  auto dir = std::filesystem::path(RT_TEST_OUTPUT_DIR) / "image-io";
  std::filesystem::create_directories(dir);
  return dir;
}

ImageF gradient(uint32_t width, uint32_t height) {
  ImageF image{width, height, std::vector<float>(size_t(width) * height * 4)};
  for (uint32_t y = 0; y < height; ++y) {
    for (uint32_t x = 0; x < width; ++x) {
      float* p = image.pixel(x, y);
      p[0] = float(x) / float(width - 1);
      p[1] = float(y) / float(height - 1);
      p[2] = 2.5f;  // above 1: clipped in 8-bit output, kept in float output
      p[3] = 1.0f;
    }
  }
  return image;
}

std::string readBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_SUITE("image-io") {
  TEST_CASE("PPM is binary P6 with the tone-mapped bytes") {
    auto path = outputDir() / "g.ppm";
    writeImage(path, gradient(4, 3), {});
    std::string bytes = readBytes(path);
    std::string header = "P6\n4 3\n255\n";
    REQUIRE(bytes.size() == header.size() + 4 * 3 * 3);
    CHECK(bytes.substr(0, header.size()) == header);
    // Last pixel: x = 1, y = 1, z clipped to 1.
    CHECK(static_cast<unsigned char>(bytes[bytes.size() - 3]) == 255);
    CHECK(static_cast<unsigned char>(bytes[bytes.size() - 1]) == 255);
    CHECK(static_cast<unsigned char>(bytes[header.size()]) == 0);
  }

  TEST_CASE("PNG round-trips through stb_image") {
    auto path = outputDir() / "g.png";
    ImageF image = gradient(16, 9);
    writeImage(path, image, {});
    Image8 back = readImage8(path);
    CHECK(back.width == 16);
    CHECK(back.height == 9);
    CHECK(back.rgb == toneMap(image, {}).rgb);
  }

  TEST_CASE("JPEG (quality 95) reads back within a few levels of the tone-mapped bytes") {
    ImageF image = gradient(32, 24);
    const std::vector<uint8_t> expected = toneMap(image, {}).rgb;
    for (const char* name : {"g.jpg", "g.JPEG"}) {
      auto path = outputDir() / name;
      writeImage(path, image, {});
      CHECK(readBytes(path).substr(0, 3) == "\xFF\xD8\xFF");  // a JPEG's start of image
      Image8 back = readImage8(path);
      REQUIRE(back.rgb.size() == expected.size());
      double squared = 0.0;
      for (size_t i = 0; i < expected.size(); ++i) {
        const double d = double(back.rgb[i]) - double(expected[i]);
        squared += d * d;
      }
      CHECK(std::sqrt(squared / double(expected.size())) < 3.0);
    }
    writeImage8(outputDir() / "e.jpg", toneMap(image, {}));
    CHECK(readImage8(outputDir() / "e.jpg").width == 32);
  }

  TEST_CASE("EXR keeps linear float values, exposure applied") {
    auto path = outputDir() / "g.exr";
    ImageF image = gradient(7, 5);
    ToneMapping mapping;
    mapping.exposure = 2.0f;
    writeImage(path, image, mapping);
    ImageF back = readExr(path);
    REQUIRE(back.rgba.size() == image.rgba.size());
    for (size_t i = 0; i < image.rgba.size(); ++i) {
      float expected = i % 4 == 3 ? image.rgba[i] : 2.0f * image.rgba[i];
      CHECK(back.rgba[i] == doctest::Approx(expected));
    }
  }

  TEST_CASE("EXR layers are extra float channels beside RGBA") {
    auto path = outputDir() / "layers.exr";
    ImageF image = gradient(20, 17);  // above tinyexr's no-compression size
    std::vector<float> counts(20 * 17), errors(20 * 17);
    for (size_t i = 0; i < counts.size(); ++i) {
      counts[i] = float(i % 7 + 4);
      errors[i] = 0.001f * float(i);
    }
    writeImage(path, image, {}, {{"samples.Y", counts}, {"error.Y", errors}});
    CHECK(readExrChannel(path, "samples.Y") == counts);
    CHECK(readExrChannel(path, "error.Y") == errors);
    ImageF back = readExr(path);  // RGBA as before
    CHECK(back.rgba == image.rgba);
    CHECK_THROWS_WITH_AS(readExrChannel(path, "depth.Z"), doctest::Contains("no such channel"),
                         Error);
    CHECK_THROWS_AS(writeImage(outputDir() / "bad-layer.exr", image, {}, {{"x.Y", {1.0f}}}), Error);
    CHECK_FALSE(std::filesystem::exists(outputDir() / "bad-layer.exr"));
  }

  TEST_CASE("HDR (Radiance RGBE) files are written") {
    auto path = outputDir() / "g.hdr";
    writeImage(path, gradient(8, 8), {});
    CHECK(readBytes(path).rfind("#?RADIANCE", 0) == 0);
  }

  TEST_CASE("tone mapping: exposure, clamp, Reinhard, ACES and sRGB") {
    ImageF one{1, 1, {0.5f, 1.0f, 3.0f, 1.0f}};
    ToneMapping mapping;
    CHECK(toneMap(one, mapping).rgb == std::vector<uint8_t>{128, 255, 255});
    mapping.curve = ToneCurve::Reinhard;
    CHECK(toneMap(one, mapping).rgb == std::vector<uint8_t>{85, 128, 191});
    // x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14): 0.6163, 0.8038, 0.9537.
    mapping.curve = ToneCurve::Aces;
    CHECK(toneMap(one, mapping).rgb == std::vector<uint8_t>{157, 205, 243});
    ImageF bright{1, 1, {100.0f, 0.0f, 0.0f, 1.0f}};
    CHECK(toneMap(bright, mapping).rgb[0] == 255);  // the fit passes 1 near 12: clamped
    CHECK(toneCurveNamed("ACES") == ToneCurve::Aces);
    CHECK(toneCurveNamed("none") == ToneCurve::Clamp);
    CHECK(toneCurveNamed("Reinhard") == ToneCurve::Reinhard);
    CHECK_FALSE(toneCurveNamed("filmic").has_value());
    mapping = {};
    mapping.srgbEncode = true;
    CHECK(toneMap(one, mapping).rgb[0] == 188);  // sRGB(0.5) = 0.7354
    ImageF nan{1, 1, {std::nanf(""), -1.0f, 0.25f, 1.0f}};
    CHECK(toneMap(nan, {}).rgb == std::vector<uint8_t>{0, 0, 64});
  }

  TEST_CASE("unsupported extensions and unwritable paths fail without leaving files") {
    auto dir = outputDir() / "failures";
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    CHECK_THROWS_WITH_AS(writeImage(dir / "x.bmp", gradient(2, 2), {}),
                         doctest::Contains("x.bmp: unsupported output format (use .png, .jpg, "
                                           ".ppm, .exr or .hdr)"),
                         Error);
    CHECK_THROWS_AS(writeImage(dir / "missing" / "x.png", gradient(2, 2), {}), Error);
    CHECK(std::filesystem::is_empty(dir));
  }

  TEST_CASE("atomic writes replace the target only when complete") {
    auto path = outputDir() / "atomic.txt";
    writeFileAtomically(path, "old", 3);
    CHECK_THROWS(writeAtomically(path, [](const std::filesystem::path& tmp) {
      std::ofstream(tmp) << "partial";
      throw Error("interrupted");
    }));
    CHECK(readBytes(path) == "old");
    for (const auto& entry : std::filesystem::directory_iterator(outputDir())) {
      CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
    }
  }
}
