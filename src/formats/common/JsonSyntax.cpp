#include "formats/common/JsonSyntax.hpp"

namespace rt {
namespace {

// nlohmann prefixes "[json.exception.parse_error.101] "; users need only the rest.
std::string withoutExceptionId(std::string_view message) {
  const size_t end = message.find("] ");
  return std::string(end == std::string_view::npos ? message : message.substr(end + 2));
}

// Number overflow (e.g. 1e400) comes without an offset: the offset of the
// number's text (quoted in the message), 0 when it cannot be found.
size_t offsetOfOverflow(std::string_view text, const std::string& message) {
  const size_t open = message.find('\'');
  const size_t close = message.rfind('\'');
  if (open == std::string::npos || close <= open) return 0;
  const size_t found = text.find(std::string_view(message).substr(open + 1, close - open - 1));
  return found == std::string_view::npos ? 0 : found + 1;
}

}  // namespace

Error jsonSyntaxError(const std::string& where, std::string_view,
                      const nlohmann::json::parse_error& error) {
  return Error(where + ": byte " + std::to_string(error.byte) + ": " +
               withoutExceptionId(error.what()));
}

Error jsonSyntaxError(const std::string& where, std::string_view text,
                      const nlohmann::json::out_of_range& error) {
  const std::string message = withoutExceptionId(error.what());
  return Error(where + ": byte " + std::to_string(offsetOfOverflow(text, message)) + ": " +
               message);
}

}  // namespace rt
