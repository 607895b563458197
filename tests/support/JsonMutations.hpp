// Mutation testing of JSON inputs: every value of a document replaced by each
// of a list of wrong values, or removed. Loaders must survive every variant.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace rt::test {

// Every value's JSON pointer in `value`, the root included.
template <class Json>
void collectPointers(const Json& value, const typename Json::json_pointer& at,
                     std::vector<typename Json::json_pointer>& out) {
  out.push_back(at);
  if (value.is_object()) {
    for (const auto& [key, child] : value.items()) collectPointers(child, at / key, out);
  } else if (value.is_array()) {
    for (size_t i = 0; i < value.size(); ++i) collectPointers(value[i], at / i, out);
  }
}

// Calls `visit(pointer, variant)` for each value of `document` replaced by
// each of `replacements`, and (except for the root) with the value removed.
template <class Json>
void forEachMutation(
    const Json& document, const std::vector<Json>& replacements,
    const std::function<void(const typename Json::json_pointer&, const Json&)>& visit) {
  std::vector<typename Json::json_pointer> pointers;
  collectPointers(document, typename Json::json_pointer(), pointers);
  for (const auto& pointer : pointers) {
    for (const Json& replacement : replacements) {
      Json variant = document;
      variant[pointer] = replacement;
      visit(pointer, variant);
    }
    if (pointer.empty()) continue;
    Json variant = document;
    Json& parent = variant[pointer.parent_pointer()];
    if (parent.is_object()) {
      parent.erase(pointer.back());
    } else {
      parent.erase(std::stoul(pointer.back()));
    }
    visit(pointer, variant);
  }
}

}  // namespace rt::test
