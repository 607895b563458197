// Convergence studies (`raytracer converge`): error against a reference
// image as the sample count grows, per sampler, with wall times. The error
// is displayRmse (ImageError.hpp) over a region of the image.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "imaging/PixelRegion.hpp"
#include "io/Image.hpp"
#include "io/Plot.hpp"
#include "render/Renderer.hpp"
#include "scene/Scene.hpp"

namespace rt {

struct ConvergenceSetup {
  uint32_t width = 0;  // 0: the scene camera's size
  uint32_t height = 0;
  PixelRegion region;  // rendered and measured (empty: the whole image)
  uint32_t seed = 0;
  std::optional<ShadingModel> shading;
  ToneMapping mapping;  // display space of the error (toneMappingFor(scene))
  // Also record the renderer's own estimate (RenderOptions::estimateError:
  // independent halves, so the measured errors are those of such renders).
  bool estimateError = false;
  // Renders of each point; its times are their medians (one render's time
  // moves by 20-40% between runs on a shared machine). The images are the
  // same each time: sampling is deterministic.
  uint32_t repeats = 1;
};

// What one series of a study measures: a sampler with uniform sampling, or
// adaptive sampling (RenderOptions::adaptive) on Sobol samples.
struct SeriesKind {
  SamplerKind sampler = SamplerKind::Random;
  bool adaptive = false;
  bool operator==(const SeriesKind&) const = default;
};
// "random", "jittered", "sobol" or "adaptive".
const char* seriesName(const SeriesKind& kind);
std::optional<SeriesKind> seriesNamed(const std::string& name);

struct ConvergencePoint {
  SamplerKind sampler = SamplerKind::Random;
  uint32_t samples = 0;                 // per pixel; adaptive: the mean
  double seconds = 0;                   // render wall time (dispatches), without setup
  double cpuSeconds = 0;                // process CPU time over the same span (lavapipe's work)
  double rmse = 0;                      // against the reference
  std::optional<double> estimatedRmse;  // the renderer's own (ConvergenceSetup::estimateError)
  bool adaptive = false;
  SeriesKind series() const { return {sampler, adaptive}; }
};

// One sampler's points reduced to numbers: the least-squares slope of
// log RMSE against log samples, and the samples and seconds at which the
// RMSE first reaches a target (log-log interpolation between the points
// around the crossing, or the fitted power law when no pair of points
// brackets it: `extrapolated`).
struct ConvergenceSummary {
  SeriesKind series;
  double slope = 0;
  double samplesToTarget = 0;
  double secondsToTarget = 0;
  bool extrapolated = false;
};

class ConvergenceStudy {
 public:
  ConvergenceStudy(Renderer& renderer, const Scene& scene, const ConvergenceSetup& setup);

  // A Sobol render with a seed unrelated to the measured renders' (shared
  // sample points would hide their error).
  ImageF renderReference(uint32_t samples, const ProgressCallback& onProgress = {});

  // Renders `counts` samples per pixel (adaptive: on average) of one
  // series, one render per count.
  using PointCallback = std::function<void(const ConvergencePoint&)>;
  std::vector<ConvergencePoint> measure(const ImageF& reference, const SeriesKind& series,
                                        const std::vector<uint32_t>& counts,
                                        const PointCallback& onPoint = {});

 private:
  RenderOptions optionsFor(SamplerKind sampler, uint32_t samples, uint32_t seed) const;

  Renderer& renderer_;
  const Scene& scene_;
  ConvergenceSetup setup_;
};

// first, first * ratio, ... rounded, strictly increasing, ending at last.
std::vector<uint32_t> geometricSampleCounts(uint32_t first, uint32_t last, double ratio);

// Which time the summary and the plot use.
enum class ConvergenceClock { Wall, Cpu };

// Points of one series, by increasing sample count (at least two).
ConvergenceSummary summarizeConvergence(const std::vector<ConvergencePoint>& points,
                                        double targetRmse,
                                        ConvergenceClock clock = ConvergenceClock::Wall);

// "sampler,samples,seconds,cpu_seconds,rmse,estimated_rmse" and one row per
// point (the sampler column holds the series name).
std::string convergenceCsv(const std::vector<ConvergencePoint>& points);

// Two panels: RMSE against samples and against seconds, a line per sampler,
// the target as a dashed line.
std::vector<PlotPanel> convergencePlotPanels(const std::vector<ConvergencePoint>& points,
                                             double targetRmse, const std::string& title,
                                             ConvergenceClock clock = ConvergenceClock::Wall);

}  // namespace rt
