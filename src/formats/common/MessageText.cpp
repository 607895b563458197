#include "formats/common/MessageText.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>

namespace rt {
namespace {

// Length of the well-formed UTF-8 sequence at text[pos] (RFC 3629: no
// overlong forms, no surrogates, nothing above U+10FFFF), or 0.
size_t utf8Length(std::string_view text, size_t pos) {
  const auto byte = [&](size_t i) { return static_cast<uint8_t>(text[pos + i]); };
  const uint8_t lead = byte(0);
  size_t length = 0;
  uint8_t low = 0x80, high = 0xBF;  // allowed range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (pos + length > text.size() || byte(1) < low || byte(1) > high) return 0;
  for (size_t i = 2; i < length; ++i) {
    if (byte(i) < 0x80 || byte(i) > 0xBF) return 0;
  }
  return length;
}

// U+0080..U+009F: control characters too (U+009B starts terminal sequences).
bool isC1Control(std::string_view text, size_t pos) {
  return static_cast<uint8_t>(text[pos]) == 0xC2 && static_cast<uint8_t>(text[pos + 1]) < 0xA0;
}

void appendEscaped(std::string& out, char c) {
  switch (c) {
    case '\n': out += "\\n"; return;
    case '\r': out += "\\r"; return;
    case '\t': out += "\\t"; return;
    default: break;
  }
  char escape[5];
  std::snprintf(escape, sizeof escape, "\\x%02X", static_cast<unsigned>(static_cast<uint8_t>(c)));
  out += escape;
}

}  // namespace

std::string printableLine(std::string_view text) {
  std::string out;
  out.reserve(std::min(text.size(), kMaxMessageLength));
  size_t fits = 0;  // length of the longest prefix that leaves room for "..."
  for (size_t pos = 0; pos < text.size();) {
    const auto c = static_cast<uint8_t>(text[pos]);
    if (c >= 0x20 && c < 0x7F) {
      out += text[pos++];
    } else if (const size_t length = c >= 0x80 ? utf8Length(text, pos) : 0;
               length > 0 && !isC1Control(text, pos)) {
      out.append(text.substr(pos, length));
      pos += length;
    } else {
      appendEscaped(out, text[pos++]);
    }
    if (out.size() <= kMaxMessageLength - 3) fits = out.size();
    if (out.size() > kMaxMessageLength) {
      out.resize(fits);
      out += "...";
      break;
    }
  }
  return out;
}

void makePrintable(std::vector<std::string>& lines) {
  for (std::string& line : lines) line = printableLine(line);
}

}  // namespace rt
