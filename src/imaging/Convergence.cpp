#include "imaging/Convergence.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "formats/json/JsonSceneLoader.hpp"
#include "imaging/ImageError.hpp"
#include "util/Error.hpp"

namespace rt {
namespace {

// Keeps the reference's sample points apart from the measured renders'.
constexpr uint32_t kReferenceSeedOffset = 0x9e3779b9u;

struct LogPoint {
  double samples;
  double seconds;
  double rmse;
};

// The middle value (the mean of the middle two for an even count).
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t middle = values.size() / 2;
  return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

double secondsOf(const ConvergencePoint& point, ConvergenceClock clock) {
  return clock == ConvergenceClock::Cpu ? point.cpuSeconds : point.seconds;
}

std::vector<LogPoint> logPoints(const std::vector<ConvergencePoint>& points,
                                ConvergenceClock clock) {
  std::vector<LogPoint> logs;
  for (const ConvergencePoint& p : points) {
    double seconds = secondsOf(p, clock);
    if (p.rmse > 0 && seconds > 0) {
      logs.push_back({std::log(double(p.samples)), std::log(seconds), std::log(p.rmse)});
    }
  }
  return logs;
}

// Least squares log rmse = intercept + slope * log samples.
std::pair<double, double> fitPowerLaw(const std::vector<LogPoint>& logs) {
  double n = double(logs.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const LogPoint& p : logs) {
    sx += p.samples, sy += p.rmse, sxx += p.samples * p.samples, sxy += p.samples * p.rmse;
  }
  double denominator = n * sxx - sx * sx;
  if (!(std::abs(denominator) > 1e-12)) throw Error("convergence fit needs two sample counts");
  double slope = (n * sxy - sx * sy) / denominator;
  return {slope, (sy - slope * sx) / n};
}

Rgb8 seriesColor(const SeriesKind& series) {
  if (series.adaptive) return {148, 103, 189};
  switch (series.sampler) {
    case SamplerKind::Random: return {214, 39, 40};
    case SamplerKind::Jittered: return {31, 119, 180};
    case SamplerKind::Sobol: return {44, 160, 44};
  }
  return {0, 0, 0};
}

}  // namespace

const char* seriesName(const SeriesKind& kind) {
  return kind.adaptive ? "adaptive" : samplerKindName(kind.sampler);
}

std::optional<SeriesKind> seriesNamed(const std::string& name) {
  if (name == "adaptive") return SeriesKind{SamplerKind::Sobol, true};
  if (std::optional<SamplerKind> sampler = samplerKindNamed(name)) return SeriesKind{*sampler};
  return std::nullopt;
}

ConvergenceStudy::ConvergenceStudy(Renderer& renderer, const Scene& scene,
                                   const ConvergenceSetup& setup)
    : renderer_(renderer), scene_(scene), setup_(setup) {}

RenderOptions ConvergenceStudy::optionsFor(SamplerKind sampler, uint32_t samples,
                                           uint32_t seed) const {
  RenderOptions options;
  options.width = setup_.width;
  options.height = setup_.height;
  options.region = setup_.region;
  options.samplesPerPixel = samples;
  options.sampler = sampler;
  options.seed = seed;
  options.shading = setup_.shading;
  options.displayMapping = setup_.mapping;
  return options;
}

ImageF ConvergenceStudy::renderReference(uint32_t samples, const ProgressCallback& onProgress) {
  RenderOptions options =
      optionsFor(SamplerKind::Sobol, samples, setup_.seed + kReferenceSeedOffset);
  return renderer_.render(scene_, options, onProgress);
}

std::vector<ConvergencePoint> ConvergenceStudy::measure(const ImageF& reference,
                                                        const SeriesKind& series,
                                                        const std::vector<uint32_t>& counts,
                                                        const PointCallback& onPoint) {
  auto seriesOptions = [&](uint32_t samples) {
    RenderOptions options = optionsFor(series.sampler, samples, setup_.seed);
    options.estimateError = setup_.estimateError;
    options.adaptive = series.adaptive;
    return options;
  };
  // An untimed render first: lavapipe compiles a kernel to machine code at
  // its first dispatch (0.3-1.5 s, measured), which the series' first point
  // would otherwise count as rendering time.
  if (!counts.empty()) renderer_.render(scene_, seriesOptions(counts.front()));
  std::vector<ConvergencePoint> points;
  for (uint32_t samples : counts) {
    RenderOptions options = seriesOptions(samples);
    RenderStats stats;
    ImageF image = renderer_.render(scene_, options, {}, &stats);
    std::vector<double> seconds{stats.renderSeconds}, cpuSeconds{stats.renderCpuSeconds};
    for (uint32_t repeat = 1; repeat < setup_.repeats; ++repeat) {
      RenderStats again;
      renderer_.render(scene_, options, {}, &again);
      seconds.push_back(again.renderSeconds);
      cpuSeconds.push_back(again.renderCpuSeconds);
    }
    ConvergencePoint point{series.sampler,
                           samples,
                           median(seconds),
                           median(cpuSeconds),
                           displayRmse(image, reference, setup_.mapping, setup_.region),
                           stats.rmseEstimate,
                           series.adaptive};
    if (onPoint) onPoint(point);
    points.push_back(point);
  }
  return points;
}

std::vector<uint32_t> geometricSampleCounts(uint32_t first, uint32_t last, double ratio) {
  if (first == 0 || last < first || !(ratio > 1)) {
    throw Error(fmt::format("bad sample series {}..{} (ratio {})", first, last, ratio));
  }
  std::vector<uint32_t> counts;
  for (double value = first; value < last * (1 - 1e-9); value *= ratio) {
    uint32_t rounded = static_cast<uint32_t>(std::lround(value));
    if (counts.empty() || rounded > counts.back()) counts.push_back(rounded);
  }
  if (counts.empty() || counts.back() < last) counts.push_back(last);
  return counts;
}

ConvergenceSummary summarizeConvergence(const std::vector<ConvergencePoint>& points,
                                        double targetRmse, ConvergenceClock clock) {
  std::vector<LogPoint> logs = logPoints(points, clock);
  if (logs.size() < 2) throw Error("convergence summary needs at least two measured points");
  ConvergenceSummary summary;
  summary.series = points.front().series();
  auto [slope, intercept] = fitPowerLaw(logs);
  summary.slope = slope;
  const double target = std::log(targetRmse);
  for (size_t i = 1; i < logs.size(); ++i) {
    const LogPoint& a = logs[i - 1];
    const LogPoint& b = logs[i];
    if (a.rmse > target && b.rmse <= target) {
      double t = (a.rmse - target) / (a.rmse - b.rmse);
      summary.samplesToTarget = std::exp(a.samples + t * (b.samples - a.samples));
      summary.secondsToTarget = std::exp(a.seconds + t * (b.seconds - a.seconds));
      return summary;
    }
  }
  // Not bracketed: follow the fitted power law, and take time as linear in
  // samples from the nearest point.
  summary.extrapolated = true;
  summary.samplesToTarget = slope < 0 ? std::exp((target - intercept) / slope) : INFINITY;
  const LogPoint& nearest = logs.front().rmse <= target ? logs.front() : logs.back();
  summary.secondsToTarget =
      summary.samplesToTarget * std::exp(nearest.seconds) / std::exp(nearest.samples);
  return summary;
}

std::string convergenceCsv(const std::vector<ConvergencePoint>& points) {
  std::string csv = "sampler,samples,seconds,cpu_seconds,rmse,estimated_rmse\n";
  for (const ConvergencePoint& p : points) {
    csv += fmt::format("{},{},{:.6f},{:.6f},{:.8f},{}\n", seriesName(p.series()), p.samples,
                       p.seconds, p.cpuSeconds, p.rmse,
                       p.estimatedRmse ? fmt::format("{:.8f}", *p.estimatedRmse) : "");
  }
  return csv;
}

std::vector<PlotPanel> convergencePlotPanels(const std::vector<ConvergencePoint>& points,
                                             double targetRmse, const std::string& title,
                                             ConvergenceClock clock) {
  PlotPanel bySamples{title + ": error vs samples", "samples per pixel", "RMSE", {}, targetRmse};
  PlotPanel bySeconds{title + ": error vs time",
                      clock == ConvergenceClock::Cpu ? "render CPU seconds (all threads)"
                                                     : "render seconds (wall clock)",
                      "RMSE",
                      {},
                      targetRmse};
  for (SeriesKind kind : {SeriesKind{SamplerKind::Random}, SeriesKind{SamplerKind::Jittered},
                          SeriesKind{SamplerKind::Sobol}, SeriesKind{SamplerKind::Sobol, true}}) {
    PlotSeries samples{seriesName(kind), seriesColor(kind), {}};
    PlotSeries seconds = samples;
    for (const ConvergencePoint& p : points) {
      if (!(p.series() == kind)) continue;
      samples.points.push_back({double(p.samples), p.rmse});
      seconds.points.push_back({secondsOf(p, clock), p.rmse});
    }
    if (samples.points.empty()) continue;
    bySamples.series.push_back(samples);
    bySeconds.series.push_back(seconds);
  }
  return {bySamples, bySeconds};
}

}  // namespace rt
