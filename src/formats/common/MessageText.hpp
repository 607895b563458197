// Loader messages quote text from the file (keys, type names, header lines,
// parser excerpts). Such text may hold line breaks, terminal escape sequences
// or bytes that are not UTF-8; these helpers keep every error and warning one
// printable line.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "util/Error.hpp"

namespace rt {

// Longer messages are cut (ending in "..."): quoted excerpts can be
// megabytes (a data URI, a JSON token), while what matters comes first.
constexpr size_t kMaxMessageLength = 1000;

// `text` with control characters written as \n, \r, \t or \xNN, bytes that
// do not form UTF-8 as \xNN, and cut to kMaxMessageLength characters.
// Idempotent: a printable line of at most that length is unchanged.
std::string printableLine(std::string_view text);

// Every warning made printable.
void makePrintable(std::vector<std::string>& lines);

// Runs `load`; an rt::Error it throws comes out with a printable message.
template <typename Load>
auto withPrintableErrors(Load&& load) -> decltype(std::forward<Load>(load)()) {
  try {
    return std::forward<Load>(load)();
  } catch (const Error& error) {
    throw Error(printableLine(error.what()));
  }
}

}  // namespace rt
