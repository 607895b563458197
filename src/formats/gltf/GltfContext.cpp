#include "formats/gltf/GltfContext.hpp"

#include "util/Error.hpp"

namespace rt::gltf {
namespace {

constexpr uint64_t kBaseBudget = uint64_t(64) << 20;
constexpr uint64_t kBudgetPerBufferByte = 8;
constexpr size_t kMaxPlacesListed = 6;

}  // namespace

std::string percentDecoded(const std::string& uri) {
  auto hex = [](char c) -> int {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
  };
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && hex(uri[i + 1]) >= 0 && hex(uri[i + 2]) >= 0) {
      out += static_cast<char>(hex(uri[i + 1]) * 16 + hex(uri[i + 2]));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string item(const char* array, int index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

std::string item(const char* array, size_t index) {
  return std::string(array) + "[" + std::to_string(index) + "]";
}

Context::Context(std::string fileName, const tinygltf::Model& model)
    : diagnostics_(std::move(fileName)), model_(model), budgetLeft_(kBaseBudget) {
  for (const tinygltf::Buffer& buffer : model.buffers) {
    budgetLeft_ += kBudgetPerBufferByte * uint64_t(buffer.data.size());
  }
}

void Context::fail(const std::string& where, const std::string& what) const {
  diagnostics_.fail(where, what);
}

void Context::warn(const std::string& where, const std::string& what) {
  diagnostics_.warn(where, what);
}

void Context::ignored(const std::string& feature, const std::string& where) {
  Places& places = ignored_[feature];
  if (places.count > 0 && places.last == where) return;
  places.last = where;
  ++places.count;
  if (places.first.size() < kMaxPlacesListed) places.first.push_back(where);
}

void Context::charge(uint64_t bytes, const std::string& where) {
  if (bytes > budgetLeft_) {
    fail(where, "the model needs more memory than its buffers justify (budget of " +
                    std::to_string(kBaseBudget >> 20) + " MiB + " +
                    std::to_string(kBudgetPerBufferByte) +
                    " x buffer bytes exhausted; is data reused absurdly often?)");
  }
  budgetLeft_ -= bytes;
}

std::vector<std::string> Context::takeWarnings() {
  for (const auto& [feature, places] : ignored_) {
    std::string list;
    for (const std::string& place : places.first) list += (list.empty() ? "" : ", ") + place;
    if (places.count > places.first.size()) {
      list += ", ... (" + std::to_string(places.count) + " in all)";
    }
    warn("", feature + " ignored (" + list + ")");
  }
  ignored_.clear();
  return diagnostics_.takeWarnings();
}

}  // namespace rt::gltf
