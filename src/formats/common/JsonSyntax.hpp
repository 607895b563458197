// JSON syntax errors as every loader reports them: "<where>: byte <N>:
// <message>", for the scene files and for glTF's JSON alike. nlohmann's
// exception ids are dropped, and a number beyond double (which comes
// without an offset) is pointed at by its text.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "util/Error.hpp"

namespace rt {

// The rt::Error for a parse of `text` that threw `error`.
Error jsonSyntaxError(const std::string& where, std::string_view text,
                      const nlohmann::json::parse_error& error);
Error jsonSyntaxError(const std::string& where, std::string_view text,
                      const nlohmann::json::out_of_range& error);

// Runs `parse` (a parse of `text`), turning its syntax errors into those above.
template <typename Parse>
auto withJsonSyntaxErrors(const std::string& where, std::string_view text, Parse&& parse)
    -> decltype(parse()) {
  try {
    return parse();
  } catch (const nlohmann::json::parse_error& error) {
    throw jsonSyntaxError(where, text, error);
  } catch (const nlohmann::json::out_of_range& error) {
    throw jsonSyntaxError(where, text, error);
  }
}

}  // namespace rt
