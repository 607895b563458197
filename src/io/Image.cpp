#include "io/Image.hpp"

#include <fmt/format.h>
#include <stb_image.h>
#include <stb_image_write.h>
#include <tinyexr.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include "io/AtomicFile.hpp"
#include "tone_mapping.h"
#include "util/Error.hpp"
#include "util/Text.hpp"

static_assert(static_cast<uint32_t>(rt::ToneCurve::Clamp) == RT_TONE_CURVE_CLAMP &&
              static_cast<uint32_t>(rt::ToneCurve::Reinhard) == RT_TONE_CURVE_REINHARD &&
              static_cast<uint32_t>(rt::ToneCurve::Aces) == RT_TONE_CURVE_ACES);

namespace rt {
namespace {

uint8_t quantize(float unit, Quantization quantization) {
  float scaled = std::clamp(unit, 0.0f, 1.0f) * 255.0f;
  return static_cast<uint8_t>(quantization == Quantization::Round ? std::round(scaled) : scaled);
}

void writePpm(const std::filesystem::path& path, const Image8& image) {
  std::string bytes = fmt::format("P6\n{} {}\n255\n", image.width, image.height);
  bytes.append(reinterpret_cast<const char*>(image.rgb.data()), image.rgb.size());
  writeFileAtomically(path, bytes.data(), bytes.size());
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<size_t>(size));
}

void writePng(const std::filesystem::path& path, const Image8& image) {
  std::string bytes;
  int ok = stbi_write_png_to_func(appendBytes, &bytes, static_cast<int>(image.width),
                                  static_cast<int>(image.height), 3, image.rgb.data(),
                                  static_cast<int>(image.width * 3));
  if (!ok) throw Error(fmt::format("{}: PNG encoding failed", path.string()));
  writeFileAtomically(path, bytes.data(), bytes.size());
}

// Quality 95 of 100: no visible blocking on renders' smooth gradients.
constexpr int kJpegQuality = 95;

void writeJpeg(const std::filesystem::path& path, const Image8& image) {
  std::string bytes;
  int ok =
      stbi_write_jpg_to_func(appendBytes, &bytes, static_cast<int>(image.width),
                             static_cast<int>(image.height), 3, image.rgb.data(), kJpegQuality);
  if (!ok) throw Error(fmt::format("{}: JPEG encoding failed", path.string()));
  writeFileAtomically(path, bytes.data(), bytes.size());
}

// An 8-bit image by extension (is8BitImagePath), or false.
bool write8BitByExtension(const std::filesystem::path& path, const Image8& image) {
  std::string ext = lowerExtension(path);
  if (ext == ".ppm") {
    writePpm(path, image);
  } else if (ext == ".png") {
    writePng(path, image);
  } else if (ext == ".jpg" || ext == ".jpeg") {
    writeJpeg(path, image);
  } else {
    return false;
  }
  return true;
}

std::vector<float> exposed(const ImageF& image, float exposure, int channels) {
  std::vector<float> out;
  out.reserve(size_t(image.width) * image.height * channels);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    for (int c = 0; c < channels; ++c) {
      float v = image.rgba[i * 4 + c];
      out.push_back(c == 3 ? v : v * exposure);
    }
  }
  return out;
}

void writeHdr(const std::filesystem::path& path, const ImageF& image, float exposure) {
  std::vector<float> rgb = exposed(image, exposure, 3);
  std::string bytes;
  int ok = stbi_write_hdr_to_func(appendBytes, &bytes, static_cast<int>(image.width),
                                  static_cast<int>(image.height), 3, rgb.data());
  if (!ok) throw Error(fmt::format("{}: HDR encoding failed", path.string()));
  writeFileAtomically(path, bytes.data(), bytes.size());
}

// RGBA and the extra layers as float32 channels, sorted by name as EXR
// readers expect.
void writeExr(const std::filesystem::path& path, const ImageF& image, float exposure,
              const std::vector<ExrLayer>& layers) {
  const size_t pixels = size_t(image.width) * image.height;
  std::vector<ExrLayer> channels(4);
  const char* names[4] = {"R", "G", "B", "A"};
  for (int c = 0; c < 4; ++c) {
    channels[c].name = names[c];
    channels[c].values.resize(pixels);
    for (size_t i = 0; i < pixels; ++i) {
      float v = image.rgba[i * 4 + c];
      channels[c].values[i] = c == 3 ? v : v * exposure;
    }
  }
  for (const ExrLayer& layer : layers) {
    if (layer.values.size() != pixels || layer.name.empty() || layer.name.size() > 255) {
      throw Error(
          fmt::format("{}: EXR layer '{}' does not fit the image", path.string(), layer.name));
    }
    channels.push_back(layer);
  }
  std::sort(channels.begin(), channels.end(),
            [](const ExrLayer& a, const ExrLayer& b) { return a.name < b.name; });
  std::vector<EXRChannelInfo> infos(channels.size());
  std::vector<int> types(channels.size(), TINYEXR_PIXELTYPE_FLOAT);
  std::vector<unsigned char*> planes(channels.size());
  for (size_t c = 0; c < channels.size(); ++c) {
    std::snprintf(infos[c].name, sizeof(infos[c].name), "%s", channels[c].name.c_str());
    planes[c] = reinterpret_cast<unsigned char*>(channels[c].values.data());
  }
  EXRHeader header;
  InitEXRHeader(&header);
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  header.num_channels = static_cast<int>(channels.size());
  header.channels = infos.data();
  header.pixel_types = types.data();
  header.requested_pixel_types = types.data();
  EXRImage exr;
  InitEXRImage(&exr);
  exr.num_channels = header.num_channels;
  exr.images = planes.data();
  exr.width = static_cast<int>(image.width);
  exr.height = static_cast<int>(image.height);
  writeAtomically(path, [&](const std::filesystem::path& tmp) {
    const char* error = nullptr;
    if (SaveEXRImageToFile(&exr, &header, tmp.c_str(), &error) != TINYEXR_SUCCESS) {
      std::string message = error ? error : "unknown error";
      if (error) FreeEXRErrorMessage(error);
      throw Error(fmt::format("{}: EXR encoding failed: {}", path.string(), message));
    }
  });
}

}  // namespace

std::optional<ToneCurve> toneCurveNamed(const std::string& name) {
  const std::string lower = lowercase(name);
  if (lower == "clamp" || lower == "none" || lower == "linear" || lower == "off") {
    return ToneCurve::Clamp;
  }
  if (lower == "reinhard") return ToneCurve::Reinhard;
  if (lower == "aces" || lower == "aces_filmic" || lower == "acesfilmic") return ToneCurve::Aces;
  return std::nullopt;
}

const char* toneCurveName(ToneCurve curve) {
  switch (curve) {
    case ToneCurve::Reinhard: return "reinhard";
    case ToneCurve::Aces: return "aces";
    case ToneCurve::Clamp: break;
  }
  return "clamp";
}

float displayValue(float linear, const ToneMapping& mapping) {
  return gpu::displayChannel(linear, mapping.exposure, static_cast<uint32_t>(mapping.curve),
                             mapping.srgbEncode ? 1u : 0u);
}

uint8_t displayByte(float linear, const ToneMapping& mapping) {
  return quantize(displayValue(linear, mapping), mapping.quantization);
}

Image8 toneMap(const ImageF& image, const ToneMapping& mapping) {
  Image8 out{image.width, image.height, {}};
  out.rgb.reserve(size_t(image.width) * image.height * 3);
  for (size_t i = 0; i < size_t(image.width) * image.height; ++i) {
    for (int c = 0; c < 3; ++c) out.rgb.push_back(displayByte(image.rgba[i * 4 + c], mapping));
  }
  return out;
}

bool isExrPath(const std::filesystem::path& path) { return hasExtension(path, {".exr"}); }

bool is8BitImagePath(const std::filesystem::path& path) {
  return hasExtension(path, {".png", ".ppm", ".jpg", ".jpeg"});
}

bool isSupportedImageExtension(const std::filesystem::path& path) {
  return is8BitImagePath(path) || hasExtension(path, {".exr", ".hdr"});
}

std::string unsupportedOutputMessage(const std::filesystem::path& path) {
  return fmt::format("{}: unsupported output format (use {})", path.string(), kOutputFormats);
}

void writeImage(const std::filesystem::path& path, const ImageF& image, const ToneMapping& mapping,
                const std::vector<ExrLayer>& layers) {
  if (is8BitImagePath(path)) {
    write8BitByExtension(path, toneMap(image, mapping));
    return;
  }
  std::string ext = lowerExtension(path);
  if (ext == ".exr") return writeExr(path, image, mapping.exposure, layers);
  if (ext == ".hdr") return writeHdr(path, image, mapping.exposure);
  throw Error(unsupportedOutputMessage(path));
}

void writeImage8(const std::filesystem::path& path, const Image8& image) {
  if (!write8BitByExtension(path, image)) {
    throw Error(
        fmt::format("{}: 8-bit images are written as {}", path.string(), k8BitOutputFormats));
  }
}

Image8 readImage8(const std::filesystem::path& path) {
  int width = 0;
  int height = 0;
  int channels = 0;
  stbi_uc* data = stbi_load(path.c_str(), &width, &height, &channels, 3);
  if (!data)
    throw Error(fmt::format("{}: cannot read image: {}", path.string(), stbi_failure_reason()));
  Image8 image{static_cast<uint32_t>(width), static_cast<uint32_t>(height), {}};
  image.rgb.assign(data, data + size_t(width) * height * 3);
  stbi_image_free(data);
  return image;
}

namespace {

constexpr uint64_t kMaxTexturePixels = uint64_t(1) << 26;  // 8k x 8k

ImageRgba8 takeDecoded(stbi_uc* data, int width, int height, const std::string& name) {
  if (!data) throw Error(fmt::format("{}: cannot read image: {}", name, stbi_failure_reason()));
  ImageRgba8 image{static_cast<uint32_t>(width), static_cast<uint32_t>(height), {}};
  image.rgba.assign(data, data + size_t(width) * height * 4);
  stbi_image_free(data);
  return image;
}

void checkSize(int width, int height, const std::string& name) {
  if (width <= 0 || height <= 0 || uint64_t(width) * uint64_t(height) > kMaxTexturePixels) {
    throw Error(fmt::format("{}: image of {}x{} pixels is empty or larger than {} pixels", name,
                            width, height, kMaxTexturePixels));
  }
}

}  // namespace

ImageRgba8 readImageRgba8(const std::filesystem::path& path) {
  int width = 0;
  int height = 0;
  int channels = 0;
  // Check the header first so that a hostile size never allocates.
  if (!stbi_info(path.c_str(), &width, &height, &channels)) {
    throw Error(fmt::format("{}: cannot read image: {}", path.string(), stbi_failure_reason()));
  }
  checkSize(width, height, path.string());
  return takeDecoded(stbi_load(path.c_str(), &width, &height, &channels, 4), width, height,
                     path.string());
}

ImageRgba8 decodeImageRgba8(const uint8_t* bytes, size_t size, const std::string& name) {
  int width = 0;
  int height = 0;
  int channels = 0;
  int length = static_cast<int>(std::min<size_t>(size, INT32_MAX));
  if (!stbi_info_from_memory(bytes, length, &width, &height, &channels)) {
    throw Error(fmt::format("{}: cannot read image: {}", name, stbi_failure_reason()));
  }
  checkSize(width, height, name);
  return takeDecoded(stbi_load_from_memory(bytes, length, &width, &height, &channels, 4), width,
                     height, name);
}

ImageF readExr(const std::filesystem::path& path) {
  float* rgba = nullptr;
  int width = 0;
  int height = 0;
  const char* error = nullptr;
  if (LoadEXR(&rgba, &width, &height, path.c_str(), &error) != TINYEXR_SUCCESS) {
    std::string message = error ? error : "unknown error";
    if (error) FreeEXRErrorMessage(error);
    throw Error(fmt::format("{}: cannot read EXR: {}", path.string(), message));
  }
  ImageF image{static_cast<uint32_t>(width), static_cast<uint32_t>(height), {}};
  image.rgba.assign(rgba, rgba + size_t(width) * height * 4);
  std::free(rgba);
  return image;
}

}  // namespace rt

namespace rt {

std::vector<float> readExrChannel(const std::filesystem::path& path, const std::string& name) {
  EXRVersion version;
  EXRHeader header;
  EXRImage image;
  InitEXRHeader(&header);
  InitEXRImage(&image);
  const char* error = nullptr;
  auto fail = [&](const std::string& why) {
    std::string message = error ? error : why;
    if (error) FreeEXRErrorMessage(error);
    FreeEXRImage(&image);
    FreeEXRHeader(&header);
    throw Error(fmt::format("{}: cannot read EXR channel '{}': {}", path.string(), name, message));
  };
  if (ParseEXRVersionFromFile(&version, path.c_str()) != TINYEXR_SUCCESS) fail("not an EXR file");
  if (ParseEXRHeaderFromFile(&header, &version, path.c_str(), &error) != TINYEXR_SUCCESS ||
      LoadEXRImageFromFile(&image, &header, path.c_str(), &error) != TINYEXR_SUCCESS) {
    fail("unreadable");
  }
  for (int c = 0; c < header.num_channels; ++c) {
    if (name != header.channels[c].name) continue;
    if (header.pixel_types[c] != TINYEXR_PIXELTYPE_FLOAT || image.tiles) fail("not a float plane");
    const float* plane = reinterpret_cast<const float*>(image.images[c]);
    std::vector<float> values(plane, plane + size_t(image.width) * image.height);
    FreeEXRImage(&image);
    FreeEXRHeader(&header);
    return values;
  }
  fail("no such channel");
  return {};
}

}  // namespace rt
