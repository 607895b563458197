#include "viewer/CameraPath.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "util/Error.hpp"

namespace rt::viewer {
namespace {

using Kind = PathStep::Kind;

struct StepSyntax {
  Kind kind;
  size_t numbers;  // how many numbers follow the name
  bool takesFile;
};

const std::map<std::string, StepSyntax>& syntax() {
  static const std::map<std::string, StepSyntax> table = {
      {"orbit", {Kind::Orbit, 2, false}},   {"pan", {Kind::Pan, 2, false}},
      {"zoom", {Kind::Zoom, 1, false}},     {"fly", {Kind::Fly, 3, false}},
      {"lookat", {Kind::LookAt, 6, false}}, {"lens", {Kind::Lens, 2, false}},
      {"focus", {Kind::Focus, 2, false}},   {"resize", {Kind::Resize, 2, false}},
      {"reset", {Kind::Reset, 0, false}},   {"screenshot", {Kind::Screenshot, 0, true}},
      {"save", {Kind::Save, 0, true}},
  };
  return table;
}

float parseNumber(const std::string& word, const std::string& where) {
  float value = 0.0f;
  auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size() || !std::isfinite(value)) {
    throw Error(fmt::format("{}: expected a number, got '{}'", where, word));
  }
  return value;
}

PathStep parseWait(const std::vector<std::string>& words, const std::string& where) {
  PathStep step;
  step.kind = Kind::Wait;
  if (words.size() > 2) throw Error(fmt::format("{}: 'wait' takes at most one count", where));
  if (words.size() == 2) {
    float frames = parseNumber(words[1], where);
    if (frames < 1.0f || frames > 1e6f || frames != std::floor(frames)) {
      throw Error(fmt::format("{}: wait count must be a whole number 1..1000000", where));
    }
    step.frames = static_cast<uint32_t>(frames);
  }
  return step;
}

PathStep parseStep(const std::vector<std::string>& words, const std::string& where) {
  if (words[0] == "wait") return parseWait(words, where);
  auto found = syntax().find(words[0]);
  if (found == syntax().end()) throw Error(fmt::format("{}: unknown step '{}'", where, words[0]));
  const StepSyntax& expected = found->second;
  size_t arguments = expected.numbers + (expected.takesFile ? 1 : 0);
  if (words.size() - 1 != arguments) {
    throw Error(fmt::format("{}: '{}' takes {} argument(s), got {}", where, words[0], arguments,
                            words.size() - 1));
  }
  PathStep step;
  step.kind = expected.kind;
  if (expected.takesFile) step.file = words[1];
  for (size_t i = 0; i < expected.numbers; ++i) {
    step.values.push_back(parseNumber(words[1 + i], where));
  }
  return step;
}

}  // namespace

std::vector<PathStep> loadCameraPath(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw Error(fmt::format("{}: cannot open camera path", file.string()));
  std::vector<PathStep> steps;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    text = text.substr(0, text.find('#'));
    std::istringstream words(text);
    std::vector<std::string> list;
    for (std::string word; words >> word;) list.push_back(word);
    if (list.empty()) continue;
    PathStep step = parseStep(list, fmt::format("{}:{}", file.string(), line));
    step.line = line;
    steps.push_back(std::move(step));
  }
  return steps;
}

const PathStep* CameraPathPlayer::next() {
  if (finished()) return nullptr;
  const PathStep& step = steps_[index_];
  if (step.kind == Kind::Wait) {
    if (++waited_ >= step.frames) {
      waited_ = 0;
      ++index_;
    }
    return nullptr;
  }
  ++index_;
  return &step;
}

}  // namespace rt::viewer
