// Images in memory: linear float RGBA as rendered, and 8-bit RGB as written
// to PNG/PPM or read back for comparisons.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rt {

struct ImageF {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<float> rgba;  // row-major, top row first, linear radiance
  float* pixel(uint32_t x, uint32_t y) { return &rgba[(size_t(y) * width + x) * 4]; }
  const float* pixel(uint32_t x, uint32_t y) const { return &rgba[(size_t(y) * width + x) * 4]; }
};

struct Image8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgb;  // row-major, top row first
};

// 8-bit RGBA as decoded from a texture file (sRGB-encoded values).
struct ImageRgba8 {
  uint32_t width = 0;
  uint32_t height = 0;
  std::vector<uint8_t> rgba;  // row-major, top row first
};

// How linear radiance becomes display values (see README "Conventions"):
// the curve from exposed linear values to display values in [0, 1] is a
// clamp at 1 (the courseworks), Reinhard's x / (1 + x), or Narkowicz's fit of
// the ACES filmic curve, x (2.51 x + 0.03) / (x (2.43 x + 0.59) + 0.14),
// clamped (students' renderers that tone-map use one of the two; README
// "Student scenes", tone curve). The values are those of RT_TONE_CURVE_*
// (tone_mapping.h, the one definition of the curves for the host and the shaders).
enum class ToneCurve { Clamp = 0, Reinhard = 1, Aces = 2 };

// "clamp" (also "none", "linear", "off"), "reinhard" or "aces" (any case).
std::optional<ToneCurve> toneCurveNamed(const std::string& name);
const char* toneCurveName(ToneCurve curve);

// 8-bit value of a display value v in [0, 1]: round(255 v), or floor(255 v)
// as (unsigned char)(255 * v) in many coursework renderers.
enum class Quantization { Round, Truncate };

struct ToneMapping {
  float exposure = 1.0f;  // linear scale before the curve
  ToneCurve curve = ToneCurve::Clamp;
  bool srgbEncode = false;  // sRGB transfer function after the curve
  Quantization quantization = Quantization::Round;
};

// One linear channel value as displayed, in [0, 1] before 8-bit quantization.
float displayValue(float linear, const ToneMapping& mapping);
// The same as an 8-bit image stores it.
uint8_t displayByte(float linear, const ToneMapping& mapping);

Image8 toneMap(const ImageF& image, const ToneMapping& mapping);

// One more float32 channel of an EXR file, e.g. "error.Y"; one value per
// pixel, row-major.
struct ExrLayer {
  std::string name;
  std::vector<float> values;
};

// The output formats, for help texts and messages: all, and the 8-bit ones.
constexpr const char* kOutputFormats = ".png, .jpg, .ppm, .exr or .hdr";
constexpr const char* k8BitOutputFormats = ".png, .jpg or .ppm";

// Writes by extension: .ppm (binary P6), .png and .jpg (quality 95) are tone
// mapped to 8 bits;
// .exr (float32 RGBA, then `layers`) and .hdr (RGBE) keep linear radiance,
// exposure applied. The file appears atomically. Throws rt::Error naming
// the file.
void writeImage(const std::filesystem::path& path, const ImageF& image, const ToneMapping& mapping,
                const std::vector<ExrLayer>& layers = {});

// Writes an 8-bit image as .png, .jpg or .ppm (by extension), atomically.
void writeImage8(const std::filesystem::path& path, const Image8& image);

// True for the extensions writeImage understands.
bool isSupportedImageExtension(const std::filesystem::path& path);
bool isExrPath(const std::filesystem::path& path);
bool is8BitImagePath(const std::filesystem::path& path);  // .png, .jpg/.jpeg or .ppm

// "<path>: unsupported output format (use .png, .jpg, ...)".
std::string unsupportedOutputMessage(const std::filesystem::path& path);

// Reads PNG/JPEG/PPM/... (8-bit RGB) through stb_image; throws rt::Error.
Image8 readImage8(const std::filesystem::path& path);
// Reads a PNG/JPEG/BMP/TGA/PPM/... file as RGBA; throws rt::Error naming the
// file and stb_image's reason. Images above 2^26 pixels are rejected.
ImageRgba8 readImageRgba8(const std::filesystem::path& path);
// Same from bytes in memory (embedded glTF images); `name` is for messages.
ImageRgba8 decodeImageRgba8(const uint8_t* bytes, size_t size, const std::string& name);
// Reads an OpenEXR file written by writeImage (its RGBA; layers ignored).
ImageF readExr(const std::filesystem::path& path);
// One named channel of an EXR file, row-major; throws rt::Error naming the
// file if it has no such channel.
std::vector<float> readExrChannel(const std::filesystem::path& path, const std::string& name);

}  // namespace rt
