// Compares two 8-bit images for the viewer tests and prints
// "psnr=<dB> maxdiff=<0..255> differing=<pixels>". Exit status: 0 when the
// bounds given hold, 1 when not, 2 on bad arguments or unreadable files.
//   rt_image_compare A.png B.png [--min-psnr DB] [--max-psnr DB] [--max-diff N]
//                    [--max-differing F]   (F: the largest fraction of pixels that differ)
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "io/Image.hpp"

namespace {

struct Difference {
  double psnr = 0.0;  // infinity when identical
  int maxDiff = 0;
  size_t differingPixels = 0;
};

Difference compare(const rt::Image8& a, const rt::Image8& b) {
  Difference d;
  double squared = 0.0;
  for (size_t pixel = 0; pixel < a.rgb.size() / 3; ++pixel) {
    bool differs = false;
    for (size_t c = 0; c < 3; ++c) {
      int delta = std::abs(int(a.rgb[pixel * 3 + c]) - int(b.rgb[pixel * 3 + c]));
      squared += double(delta) * delta;
      d.maxDiff = std::max(d.maxDiff, delta);
      differs = differs || delta != 0;
    }
    if (differs) ++d.differingPixels;
  }
  double mse = squared / double(a.rgb.size());
  d.psnr = mse == 0.0 ? INFINITY : 10.0 * std::log10(255.0 * 255.0 / mse);
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s A.png B.png [--min-psnr DB] [--max-psnr DB] [--max-diff N]\n",
                 argv[0]);
    return 2;
  }
  std::optional<double> minPsnr;
  std::optional<double> maxPsnr;
  std::optional<int> maxDiff;
  std::optional<double> maxDiffering;
  for (int i = 3; i + 1 < argc; i += 2) {
    std::string name = argv[i];
    if (name == "--min-psnr")
      minPsnr = std::atof(argv[i + 1]);
    else if (name == "--max-psnr")
      maxPsnr = std::atof(argv[i + 1]);
    else if (name == "--max-diff")
      maxDiff = std::atoi(argv[i + 1]);
    else if (name == "--max-differing")
      maxDiffering = std::atof(argv[i + 1]);
    else {
      std::fprintf(stderr, "unknown option %s\n", argv[i]);
      return 2;
    }
  }
  try {
    rt::Image8 a = rt::readImage8(argv[1]);
    rt::Image8 b = rt::readImage8(argv[2]);
    if (a.width != b.width || a.height != b.height) {
      std::printf("size differs: %ux%u vs %ux%u\n", a.width, a.height, b.width, b.height);
      return 1;
    }
    Difference d = compare(a, b);
    const double fraction = double(d.differingPixels) / double(size_t(a.width) * a.height);
    std::printf("psnr=%.2f maxdiff=%d differing=%zu (%.3f of the pixels)\n", d.psnr, d.maxDiff,
                d.differingPixels, fraction);
    bool ok = (!minPsnr || d.psnr >= *minPsnr) && (!maxPsnr || d.psnr <= *maxPsnr) &&
              (!maxDiff || d.maxDiff <= *maxDiff) && (!maxDiffering || fraction <= *maxDiffering);
    return ok ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}
