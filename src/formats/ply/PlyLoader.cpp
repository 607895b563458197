#include "formats/ply/PlyLoader.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include "formats/common/Diagnostics.hpp"
#include "formats/common/FileBytes.hpp"
#include "formats/common/MeshNormals.hpp"
#include "formats/common/MessageText.hpp"
#include "formats/common/ModelFraming.hpp"
#include "formats/common/SceneTextures.hpp"
#include "formats/common/VertexColors.hpp"
#include "util/Error.hpp"
#include "util/Text.hpp"

namespace rt {

namespace fs = std::filesystem;

namespace {

// Indices are 32-bit on the GPU; one value is kept free as the strip restart marker.
constexpr uint64_t kMaxVertices = std::numeric_limits<uint32_t>::max() - 1;
constexpr uint64_t kMaxTriangles = uint64_t{1} << 31;
constexpr uint32_t kStripRestart = std::numeric_limits<uint32_t>::max();

// --------------------------------------------------------------- messages

// ------------------------------------------------------------------ types

enum class Scalar : uint8_t { Int8, UInt8, Int16, UInt16, Int32, UInt32, Float32, Float64 };

struct ScalarName {
  std::string_view name;
  Scalar type;
};

// The original names and the sized ones later writers use; both are common.
constexpr std::array<ScalarName, 16> kScalarNames = {{
    {"char", Scalar::Int8},
    {"uchar", Scalar::UInt8},
    {"short", Scalar::Int16},
    {"ushort", Scalar::UInt16},
    {"int", Scalar::Int32},
    {"uint", Scalar::UInt32},
    {"float", Scalar::Float32},
    {"double", Scalar::Float64},
    {"int8", Scalar::Int8},
    {"uint8", Scalar::UInt8},
    {"int16", Scalar::Int16},
    {"uint16", Scalar::UInt16},
    {"int32", Scalar::Int32},
    {"uint32", Scalar::UInt32},
    {"float32", Scalar::Float32},
    {"float64", Scalar::Float64},
}};

std::optional<Scalar> scalarNamed(std::string_view name) {
  for (const ScalarName& entry : kScalarNames) {
    if (entry.name == name) return entry.type;
  }
  return std::nullopt;
}

std::string_view nameOf(Scalar type) {
  for (const ScalarName& entry : kScalarNames) {
    if (entry.type == type) return entry.name;
  }
  return "?";
}

size_t sizeOf(Scalar type) {
  switch (type) {
    case Scalar::Int8:
    case Scalar::UInt8: return 1;
    case Scalar::Int16:
    case Scalar::UInt16: return 2;
    case Scalar::Int32:
    case Scalar::UInt32:
    case Scalar::Float32: return 4;
    case Scalar::Float64: return 8;
  }
  return 1;
}

bool isInteger(Scalar type) { return type != Scalar::Float32 && type != Scalar::Float64; }

// Inclusive range of an integer type, for checking ASCII values.
std::pair<int64_t, int64_t> rangeOf(Scalar type) {
  switch (type) {
    case Scalar::Int8: return {-128, 127};
    case Scalar::UInt8: return {0, 255};
    case Scalar::Int16: return {-32768, 32767};
    case Scalar::UInt16: return {0, 65535};
    case Scalar::Int32: return {std::numeric_limits<int32_t>::min(), 2147483647};
    case Scalar::UInt32: return {0, 4294967295};
    default: return {std::numeric_limits<int64_t>::min(), std::numeric_limits<int64_t>::max()};
  }
}

// ----------------------------------------------------------------- header

struct Property {
  std::string name;
  Scalar type = Scalar::Float32;    // the item type of a list
  std::optional<Scalar> countType;  // set for list properties
  bool isList() const { return countType.has_value(); }
};

struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> properties;
  size_t offset = 0;  // where its header line starts, for messages

  const Property* find(std::string_view property) const {
    for (const Property& candidate : properties) {
      if (candidate.name == property) return &candidate;
    }
    return nullptr;
  }
};

enum class Format { Ascii, BinaryLittleEndian, BinaryBigEndian };

struct Header {
  Format format = Format::Ascii;
  std::vector<Element> elements;
  std::vector<std::string> textureFiles;  // `comment TextureFile NAME` lines, in order
  size_t endLine = 0;                     // offset of the end_header line
  size_t dataStart = 0;                   // first byte after it
};

struct HeaderLine {
  size_t offset = 0;
  std::vector<std::string_view> words;
};

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\v' || c == '\f'; }
bool isLineEnd(char c) { return c == '\n' || c == '\r'; }
bool isSpace(char c) { return isBlank(c) || isLineEnd(c); }

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  size_t pos = 0;
  while (pos < line.size()) {
    while (pos < line.size() && isBlank(line[pos])) ++pos;
    const size_t start = pos;
    while (pos < line.size() && !isBlank(line[pos])) ++pos;
    if (pos > start) words.push_back(line.substr(start, pos - start));
  }
  return words;
}

// Splits the header into lines ending in LF, CRLF or CR alone. The ending of
// the first line decides whether "\r\n" is one ending or two, which matters
// for the single ending between end_header and binary data.
class HeaderLines {
 public:
  explicit HeaderLines(std::string_view bytes) : bytes_(bytes) {
    const size_t end = bytes.find_first_of("\r\n");
    crOnly_ = end != std::string_view::npos && bytes[end] == '\r' &&
              (end + 1 == bytes.size() || bytes[end + 1] != '\n');
  }

  bool next(HeaderLine& line) {
    if (pos_ >= bytes_.size()) return false;
    const size_t end = std::min(bytes_.find_first_of("\r\n", pos_), bytes_.size());
    line.offset = pos_;
    line.words = splitWords(bytes_.substr(pos_, end - pos_));
    pos_ = end;
    if (pos_ < bytes_.size()) {
      const bool crlf =
          bytes_[pos_] == '\r' && pos_ + 1 < bytes_.size() && bytes_[pos_ + 1] == '\n';
      pos_ += crlf && !crOnly_ ? 2 : 1;
    }
    return true;
  }

  size_t position() const { return pos_; }

 private:
  std::string_view bytes_;
  size_t pos_ = 0;
  bool crOnly_ = false;
};

std::string joined(const std::vector<std::string_view>& words) {
  std::string text;
  for (std::string_view word : words) text += (text.empty() ? "" : " ") + std::string(word);
  return text.size() > 60 ? text.substr(0, 60) + "..." : text;
}

Format readFormat(const HeaderLine& line, const Diagnostics& diagnostics) {
  if (line.words.size() != 3) diagnostics.failAtByte(line.offset, "expected 'format <kind> 1.0'");
  if (line.words[2].empty() || line.words[2][0] != '1') {
    diagnostics.failAtByte(line.offset,
                           "unsupported PLY version '" + std::string(line.words[2]) + "'");
  }
  const std::string_view kind = line.words[1];
  if (kind == "ascii") return Format::Ascii;
  if (kind == "binary_little_endian") return Format::BinaryLittleEndian;
  if (kind == "binary_big_endian") return Format::BinaryBigEndian;
  diagnostics.failAtByte(line.offset,
                         "unknown format '" + std::string(kind) +
                             "' (expected ascii, binary_little_endian or binary_big_endian)");
}

Element readElement(const HeaderLine& line, const std::vector<Element>& before,
                    const Diagnostics& diagnostics) {
  if (line.words.size() != 3)
    diagnostics.failAtByte(line.offset, "expected 'element <name> <count>'");
  Element element;
  element.name = line.words[1];
  element.offset = line.offset;
  const std::string_view count = line.words[2];
  const auto [end, error] =
      std::from_chars(count.data(), count.data() + count.size(), element.count);
  if (error != std::errc() || end != count.data() + count.size()) {
    diagnostics.failAtByte(line.offset, "element '" + element.name +
                                            "': the count must be a non-negative integer, got '" +
                                            std::string(count) + "'");
  }
  for (const Element& other : before) {
    if (other.name == element.name) {
      diagnostics.failAtByte(line.offset, "element '" + element.name + "' is declared twice");
    }
  }
  return element;
}

Scalar readType(std::string_view word, size_t offset, const Diagnostics& diagnostics) {
  if (const std::optional<Scalar> type = scalarNamed(word)) return *type;
  diagnostics.failAtByte(offset,
                         "unknown property type '" + std::string(word) +
                             "' (expected char, uchar, short, ushort, int, uint, float, double or "
                             "int8, uint8, int16, uint16, int32, uint32, float32, float64)");
}

void addProperty(const HeaderLine& line, Element& element, const Diagnostics& diagnostics) {
  const std::vector<std::string_view>& words = line.words;
  Property property;
  if (words.size() == 5 && words[1] == "list") {
    property.countType = readType(words[2], line.offset, diagnostics);
    if (!isInteger(*property.countType)) {
      diagnostics.failAtByte(
          line.offset, "a list length type must be an integer type, not " + std::string(words[2]));
    }
    property.type = readType(words[3], line.offset, diagnostics);
  } else if (words.size() == 3 && words[1] != "list") {
    property.type = readType(words[1], line.offset, diagnostics);
  } else {
    diagnostics.failAtByte(
        line.offset, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
  }
  property.name = words.back();
  if (element.find(property.name)) {
    diagnostics.failAtByte(line.offset, "property '" + property.name + "' of element '" +
                                            element.name + "' is declared twice");
  }
  element.properties.push_back(std::move(property));
}

// MeshLab's and photogrammetry tools' `comment TextureFile NAME`: the rest
// of the line is the image's name, spaces and all.
std::optional<std::string> textureFileComment(const HeaderLine& line) {
  if (line.words.size() < 3 || line.words[0] != "comment" ||
      lowercase(std::string(line.words[1])) != "texturefile") {
    return std::nullopt;
  }
  const char* begin = line.words[2].data();
  const char* end = line.words.back().data() + line.words.back().size();
  return std::string(begin, static_cast<size_t>(end - begin));
}

// Returns true at end_header.
bool readHeaderLine(const HeaderLine& line, Header& header, bool& haveFormat,
                    const Diagnostics& diagnostics) {
  const std::string_view keyword = line.words[0];
  if (std::optional<std::string> texture = textureFileComment(line)) {
    header.textureFiles.push_back(std::move(*texture));
  }
  if (keyword == "comment" || keyword == "obj_info") return false;
  if (keyword == "format") {
    if (haveFormat) diagnostics.failAtByte(line.offset, "a second 'format' line");
    header.format = readFormat(line, diagnostics);
    haveFormat = true;
  } else if (keyword == "element") {
    header.elements.push_back(readElement(line, header.elements, diagnostics));
  } else if (keyword == "property") {
    if (header.elements.empty())
      diagnostics.failAtByte(line.offset, "a property before any element");
    addProperty(line, header.elements.back(), diagnostics);
  } else if (keyword == "end_header") {
    if (!haveFormat) diagnostics.failAtByte(line.offset, "the header has no 'format' line");
    return true;
  } else if (!header.elements.empty()) {
    // Before the first element such a line cannot change the data layout:
    // Blender 2.47 wrote its banner there without "comment".
    diagnostics.failAtByte(line.offset, "unknown header line '" + joined(line.words) + "'");
  }
  return false;
}

Header readHeader(std::string_view bytes, const Diagnostics& diagnostics) {
  if (bytes.empty()) diagnostics.failAtByte(0, "empty file");
  HeaderLines lines(bytes);
  HeaderLine line;
  if (!lines.next(line) || line.words.size() != 1 || line.words[0] != "ply") {
    diagnostics.failAtByte(0, "not a PLY file (the first line must be 'ply')");
  }
  Header header;
  bool haveFormat = false;
  while (lines.next(line)) {
    if (line.words.empty()) continue;
    if (readHeaderLine(line, header, haveFormat, diagnostics)) {
      header.endLine = line.offset;
      header.dataStart = lines.position();
      return header;
    }
  }
  diagnostics.failAtByte(bytes.size(), "the header has no 'end_header' line");
}

// ------------------------------------------------------------------ plan

enum class Role { Skip, Vertices, Faces, Strips };

// Where the kept vertex properties go.
enum Slot : int {
  kX,
  kY,
  kZ,
  kNx,
  kNy,
  kNz,
  kU,
  kV,
  kRed,
  kGreen,
  kBlue,
  kSlotCount,
  kUnused = -1
};

// The slots of a face record's lists.
constexpr int kIndexList = 0;
constexpr int kTexcoordList = 1;

struct ElementPlan {
  const Element* element = nullptr;
  Role role = Role::Skip;
  // Per property: a Slot for vertices; kIndexList or kTexcoordList for faces.
  std::vector<int> slots;
  bool hasTexcoords() const {
    return std::find(slots.begin(), slots.end(), kTexcoordList) != slots.end();
  }
};

constexpr std::array<std::array<std::string_view, 2>, 4> kUvNames = {
    {{"u", "v"}, {"s", "t"}, {"texture_u", "texture_v"}, {"texture_s", "texture_t"}}};

// Vertex colours: the Stanford names, short ones, and those of MeshLab's
// material properties.
constexpr std::array<std::array<std::string_view, 3>, 3> kColorNames = {
    {{"red", "green", "blue"}, {"r", "g", "b"}, {"diffuse_red", "diffuse_green", "diffuse_blue"}}};

int propertyIndex(const Element& element, std::string_view name) {
  for (size_t i = 0; i < element.properties.size(); ++i) {
    if (element.properties[i].name == name) return static_cast<int>(i);
  }
  return -1;
}

// Assigns `slots` to the named properties when all of them are plain scalars.
bool assignSlots(ElementPlan& plan, std::initializer_list<std::string_view> names, int firstSlot) {
  std::vector<int> found;
  for (std::string_view name : names) {
    const int index = propertyIndex(*plan.element, name);
    if (index < 0 || plan.element->properties[static_cast<size_t>(index)].isList()) return false;
    found.push_back(index);
  }
  for (size_t i = 0; i < found.size(); ++i) {
    plan.slots[static_cast<size_t>(found[i])] = firstSlot + static_cast<int>(i);
  }
  return true;
}

ElementPlan planVertices(const Element& element, const Diagnostics& diagnostics) {
  ElementPlan plan{&element, Role::Vertices, std::vector<int>(element.properties.size(), kUnused)};
  for (std::string_view axis : {"x", "y", "z"}) {
    const Property* property = element.find(axis);
    if (!property || property->isList()) {
      diagnostics.failAtByte(
          element.offset, "element 'vertex' needs a scalar property '" + std::string(axis) + "'");
    }
  }
  assignSlots(plan, {"x", "y", "z"}, kX);
  assignSlots(plan, {"nx", "ny", "nz"}, kNx);
  for (const auto& [u, v] : kUvNames) {
    if (assignSlots(plan, {u, v}, kU)) break;
  }
  for (const auto& [r, g, b] : kColorNames) {
    if (assignSlots(plan, {r, g, b}, kRed)) break;
  }
  if (element.count > kMaxVertices) {
    diagnostics.failAtByte(element.offset, "too many vertices (" + std::to_string(element.count) +
                                               "; at most " + std::to_string(kMaxVertices) + ")");
  }
  return plan;
}

ElementPlan planIndexLists(const Element& element, Role role, const Diagnostics& diagnostics) {
  ElementPlan plan{&element, role, std::vector<int>(element.properties.size(), kUnused)};
  int index = propertyIndex(element, "vertex_indices");
  if (index < 0) index = propertyIndex(element, "vertex_index");
  if (index < 0) {
    diagnostics.failAtByte(element.offset, "element '" + element.name +
                                               "' has no 'vertex_indices' or 'vertex_index' list");
  }
  const Property& list = element.properties[static_cast<size_t>(index)];
  if (!list.isList() || !isInteger(list.type)) {
    diagnostics.failAtByte(element.offset, "property '" + list.name + "' of element '" +
                                               element.name + "' must be a list of integers");
  }
  plan.slots[static_cast<size_t>(index)] = kIndexList;
  // MeshLab's per-face texture coordinates: u and v for each corner in turn.
  const int texcoords = propertyIndex(element, "texcoord");
  if (role == Role::Faces && texcoords >= 0 &&
      element.properties[static_cast<size_t>(texcoords)].isList()) {
    plan.slots[static_cast<size_t>(texcoords)] = kTexcoordList;
  }
  return plan;
}

bool hasFaces(const std::vector<ElementPlan>& plans) {
  return std::any_of(plans.begin(), plans.end(), [](const ElementPlan& plan) {
    return plan.role != Role::Skip && plan.role != Role::Vertices && plan.element->count > 0;
  });
}

std::vector<ElementPlan> planElements(const Header& header, const Diagnostics& diagnostics) {
  std::vector<ElementPlan> plans;
  bool haveVertices = false;
  for (const Element& element : header.elements) {
    if (element.name == "vertex") {
      plans.push_back(planVertices(element, diagnostics));
      haveVertices = true;
    } else if (element.name == "face") {
      plans.push_back(planIndexLists(element, Role::Faces, diagnostics));
    } else if (element.name == "tristrips") {
      plans.push_back(planIndexLists(element, Role::Strips, diagnostics));
    } else {
      plans.push_back({&element, Role::Skip, std::vector<int>(element.properties.size(), kUnused)});
    }
  }
  if (!hasFaces(plans)) {
    diagnostics.failAtByte(
        header.endLine,
        "no faces: the header declares no 'face' or 'tristrips' records (a point cloud or "
        "range scan is not a mesh)");
  }
  if (!haveVertices)
    diagnostics.failAtByte(header.endLine, "the header declares no 'vertex' element");
  return plans;
}

// The fewest bytes one record can take, to check declared counts against the
// file size before allocating: binary, the scalars and list lengths (faces
// have at least 3 indices); ASCII, two bytes per number (digit and separator).
uint64_t minimumRecordBytes(const ElementPlan& plan, Format format) {
  uint64_t bytes = 0;
  for (size_t i = 0; i < plan.element->properties.size(); ++i) {
    const Property& property = plan.element->properties[i];
    const uint64_t items = plan.role == Role::Faces && plan.slots[i] == kIndexList ? 3 : 0;
    if (format == Format::Ascii) {
      bytes += 2 * (1 + items);
    } else {
      bytes += property.isList() ? sizeOf(*property.countType) + items * sizeOf(property.type)
                                 : sizeOf(property.type);
    }
  }
  return bytes;
}

void checkCountsFit(const std::vector<ElementPlan>& plans, Format format, uint64_t dataBytes,
                    const Diagnostics& diagnostics) {
  // The last ASCII number needs no separator after it.
  uint64_t budget = dataBytes + (format == Format::Ascii ? 1 : 0);
  for (const ElementPlan& plan : plans) {
    const uint64_t recordBytes = minimumRecordBytes(plan, format);
    if (recordBytes == 0) continue;
    const uint64_t count = plan.element->count;
    if (count > budget / recordBytes) {
      diagnostics.failAtByte(plan.element->offset,
                             "element '" + plan.element->name + "' declares " +
                                 std::to_string(count) + " records, more than the " +
                                 std::to_string(dataBytes) + " bytes of data can hold");
    }
    budget -= count * recordBytes;
  }
}

// ---------------------------------------------------------------- readers

// What both readers share: position, the record being read (for messages)
// and the failure reporter.
class Cursor {
 public:
  Cursor(std::string_view bytes, size_t start, const Diagnostics& diagnostics)
      : bytes_(bytes), pos_(start), diagnostics_(diagnostics) {}

  std::string where() const { return element_->name + " " + std::to_string(record_); }
  [[noreturn]] void failValue(const std::string& what) const {
    diagnostics_.failAtByte(valueStart_, where() + ": " + what);
  }

 protected:
  void setRecord(const Element& element, uint64_t record) {
    element_ = &element;
    record_ = record;
  }
  // Trailing data usually means the header under-declares a count.
  std::string afterLastRecord() const {
    if (!element_) return " after the header";
    return " after " + where() + ", the last record the header declares";
  }
  std::string declared() const {
    return " (the header declares " + std::to_string(element_->count) + " '" + element_->name +
           "' records)";
  }

  std::string_view bytes_;
  size_t pos_;
  size_t valueStart_ = 0;
  const Diagnostics& diagnostics_;
  const Element* element_ = nullptr;
  uint64_t record_ = 0;
};

template <typename T>
T decodeBinary(const char* data, bool reverse) {
  std::array<char, sizeof(T)> raw;
  std::memcpy(raw.data(), data, sizeof(T));
  if (reverse) std::reverse(raw.begin(), raw.end());
  return std::bit_cast<T>(raw);
}

class BinaryReader : public Cursor {
 public:
  BinaryReader(std::string_view bytes, size_t start, bool bigEndian, const Diagnostics& diagnostics)
      : Cursor(bytes, start, diagnostics),
        reverse_(bigEndian != (std::endian::native == std::endian::big)) {}

  void startRecord(const Element& element, uint64_t record) { setRecord(element, record); }
  void endRecord() const {}

  double real(const Property& property) { return value(property.type, property); }

  int64_t integer(Scalar type, const Property& property) {
    const double number = value(type, property);
    return static_cast<int64_t>(number);  // exact: only called with integer types
  }

  // A list length, checked to be non-negative and to fit in the bytes left.
  uint64_t listLength(const Property& property) {
    const int64_t length = integer(*property.countType, property);
    if (length < 0) failValue("negative list length " + std::to_string(length));
    const uint64_t left = bytes_.size() - pos_;
    if (static_cast<uint64_t>(length) > left / sizeOf(property.type)) {
      failValue("list length " + std::to_string(length) + " of '" + property.name +
                "' does not fit in the " + std::to_string(left) + " bytes left");
    }
    return static_cast<uint64_t>(length);
  }

  void skip(const Property& property) {
    if (!property.isList()) {
      need(sizeOf(property.type), property);
      pos_ += sizeOf(property.type);
      return;
    }
    pos_ += listLength(property) * sizeOf(property.type);
  }

  void finish() const {
    if (pos_ == bytes_.size()) return;
    diagnostics_.failAtByte(pos_, std::to_string(bytes_.size() - pos_) +
                                      " bytes of unexpected data" + afterLastRecord());
  }

 private:
  void need(size_t size, const Property& property) {
    valueStart_ = pos_;
    if (bytes_.size() - pos_ >= size) return;
    diagnostics_.failAtByte(pos_, "the file ends inside " + where() + " at property '" +
                                      property.name + "'" + declared());
  }

  double value(Scalar type, const Property& property) {
    need(sizeOf(type), property);
    const char* data = bytes_.data() + pos_;
    pos_ += sizeOf(type);
    switch (type) {
      case Scalar::Int8: return decodeBinary<int8_t>(data, false);
      case Scalar::UInt8: return decodeBinary<uint8_t>(data, false);
      case Scalar::Int16: return decodeBinary<int16_t>(data, reverse_);
      case Scalar::UInt16: return decodeBinary<uint16_t>(data, reverse_);
      case Scalar::Int32: return decodeBinary<int32_t>(data, reverse_);
      case Scalar::UInt32: return decodeBinary<uint32_t>(data, reverse_);
      case Scalar::Float32: return decodeBinary<float>(data, reverse_);
      case Scalar::Float64: return decodeBinary<double>(data, reverse_);
    }
    return 0.0;
  }

  bool reverse_;
};

// ASCII records are one line each; numbers are separated by blanks.
class AsciiReader : public Cursor {
 public:
  using Cursor::Cursor;

  void startRecord(const Element& element, uint64_t record) {
    setRecord(element, record);
    while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) ++pos_;
    if (pos_ == bytes_.size())
      diagnostics_.failAtByte(pos_, "the file ends before " + where() + declared());
  }

  void endRecord() {
    while (pos_ < bytes_.size() && isBlank(bytes_[pos_])) ++pos_;
    if (pos_ < bytes_.size() && !isLineEnd(bytes_[pos_])) {
      diagnostics_.failAtByte(
          pos_, "the line of " + where() + " has more values than the header declares");
    }
  }

  double real(const Property& property) {
    if (isInteger(property.type)) return static_cast<double>(integer(property.type, property));
    const std::string_view text = token(property);
    double number = 0.0;
    if (!parseWhole(text, number)) failValue("'" + std::string(text) + "' is not a number");
    return number;
  }

  int64_t integer(Scalar type, const Property& property) {
    const std::string_view text = token(property);
    int64_t number = 0;
    if (!parseWhole(text, number)) {
      failValue("expected an integer (" + std::string(nameOf(type)) + ") for '" + property.name +
                "', got '" + std::string(text) + "'");
    }
    const auto [low, high] = rangeOf(type);
    if (number < low || number > high) {
      failValue(std::string(text) + " is out of range for " + std::string(nameOf(type)));
    }
    return number;
  }

  uint64_t listLength(const Property& property) {
    const int64_t length = integer(*property.countType, property);
    if (length < 0) failValue("negative list length " + std::to_string(length));
    // Each number takes two bytes or more; this bounds what callers reserve.
    if (static_cast<uint64_t>(length) > (bytes_.size() - pos_) / 2) {
      failValue("list length " + std::to_string(length) + " of '" + property.name +
                "' does not fit in the " + std::to_string(bytes_.size() - pos_) + " bytes left");
    }
    return static_cast<uint64_t>(length);
  }

  void skip(const Property& property) {
    const uint64_t count = property.isList() ? listLength(property) : 1;
    for (uint64_t i = 0; i < count; ++i) token(property);
  }

  void finish() {
    while (pos_ < bytes_.size() && isSpace(bytes_[pos_])) ++pos_;
    if (pos_ < bytes_.size()) diagnostics_.failAtByte(pos_, "unexpected data" + afterLastRecord());
  }

 private:
  std::string_view token(const Property& property) {
    while (pos_ < bytes_.size() && isBlank(bytes_[pos_])) ++pos_;
    valueStart_ = pos_;
    if (pos_ == bytes_.size()) {
      diagnostics_.failAtByte(pos_, "the file ends inside " + where() + " before property '" +
                                        property.name + "'" + declared());
    }
    if (isLineEnd(bytes_[pos_])) {
      diagnostics_.failAtByte(
          pos_, "the line of " + where() + " ends before property '" + property.name + "'");
    }
    while (pos_ < bytes_.size() && !isSpace(bytes_[pos_])) ++pos_;
    return bytes_.substr(valueStart_, pos_ - valueStart_);
  }

  // from_chars rejects a leading '+', which some writers emit ("+inf", "+1e-3").
  template <typename Number>
  static bool parseWhole(std::string_view text, Number& number) {
    if (text.size() > 1 && text[0] == '+' && text[1] != '-') text.remove_prefix(1);
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, number);
    return error == std::errc() && stop == end;
  }
};

// ---------------------------------------------------------------- decoding

// The mesh as the elements fill it in.
struct PlyMeshInProgress {
  TriangleMesh mesh;
  uint64_t vertexCount = 0;       // from the header: faces may come before vertices
  std::vector<uint32_t> corners;  // one polygon or strip, reused
  // Per-face texture coordinates: one list a record (reused), and once any
  // face has them, three per triangle in mesh.faces (zero for strips).
  std::vector<glm::vec2> faceUvs;
  std::vector<glm::vec2> cornerUvs;
  bool perCornerUvs = false;
};

float finiteFloat(double value, const Property& property, const Cursor& cursor) {
  if (!(std::abs(value) <= static_cast<double>(std::numeric_limits<float>::max()))) {
    cursor.failValue("'" + property.name + "' is not a finite float");
  }
  return static_cast<float>(value);
}

// What a colour channel of this type is at full intensity: integers span
// their range (uchar 255), floats [0, 1].
double fullColor(Scalar type) {
  return isInteger(type) ? static_cast<double>(rangeOf(type).second) : 1.0;
}

// A colour channel in [0, 1] (clamped in double: a huge value must not
// reach the float cast; not finite: 0).
float colorChannel(double value, Scalar type) {
  const double unit = value / fullColor(type);
  return std::isfinite(unit) ? static_cast<float>(std::clamp(unit, 0.0, 1.0)) : 0.0f;
}

template <typename Reader>
void readVertices(Reader& reader, const ElementPlan& plan, PlyMeshInProgress& out) {
  const Element& element = *plan.element;
  const bool hasNormals = std::count(plan.slots.begin(), plan.slots.end(), kNx) > 0;
  const bool hasUvs = std::count(plan.slots.begin(), plan.slots.end(), kU) > 0;
  const bool hasColors = std::count(plan.slots.begin(), plan.slots.end(), kRed) > 0;
  out.mesh.positions.reserve(element.count);
  if (hasNormals) out.mesh.normals.reserve(element.count);
  if (hasUvs) out.mesh.uvs.reserve(element.count);
  if (hasColors) out.mesh.colors.reserve(element.count);
  std::array<float, kSlotCount> values{};
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.startRecord(element, record);
    for (size_t i = 0; i < element.properties.size(); ++i) {
      const Property& property = element.properties[i];
      const int slot = plan.slots[i];
      if (slot == kUnused) {
        reader.skip(property);
      } else if (slot >= kRed) {
        values[static_cast<size_t>(slot)] = colorChannel(reader.real(property), property.type);
      } else {
        values[static_cast<size_t>(slot)] = finiteFloat(reader.real(property), property, reader);
      }
    }
    reader.endRecord();
    out.mesh.positions.emplace_back(values[kX], values[kY], values[kZ]);
    if (hasNormals) out.mesh.normals.emplace_back(values[kNx], values[kNy], values[kNz]);
    if (hasUvs) out.mesh.uvs.emplace_back(values[kU], values[kV]);
    if (hasColors) {
      out.mesh.colors.push_back(
          linearFromDisplayColor({values[kRed], values[kGreen], values[kBlue]}));
    }
  }
}

// Reads one index list into out.corners; -1 becomes kStripRestart when allowed.
template <typename Reader>
void readIndexList(Reader& reader, const Property& list, bool allowRestart,
                   PlyMeshInProgress& out) {
  const uint64_t length = reader.listLength(list);
  if (!allowRestart && length < 3) {
    reader.failValue("a face needs at least 3 vertex indices, got " + std::to_string(length));
  }
  out.corners.clear();
  for (uint64_t i = 0; i < length; ++i) {
    const int64_t index = reader.integer(list.type, list);
    if (allowRestart && index == -1) {
      out.corners.push_back(kStripRestart);
    } else if (index < 0 || static_cast<uint64_t>(index) >= out.vertexCount) {
      reader.failValue("vertex index " + std::to_string(index) + " is out of range (the file has " +
                       std::to_string(out.vertexCount) + " vertices)");
    } else {
      out.corners.push_back(static_cast<uint32_t>(index));
    }
  }
}

// Reads a face's texture coordinates into out.faceUvs: two numbers a corner.
template <typename Reader>
void readTexcoordList(Reader& reader, const Property& list, PlyMeshInProgress& out) {
  const uint64_t length = reader.listLength(list);
  if (length % 2 != 0) {
    reader.failValue("'" + list.name + "' has " + std::to_string(length) +
                     " values, not a u and a v for each corner");
  }
  out.faceUvs.clear();
  for (uint64_t i = 0; i < length; i += 2) {
    const float u = finiteFloat(reader.real(list), list, reader);
    const float v = finiteFloat(reader.real(list), list, reader);
    out.faceUvs.emplace_back(u, v);
  }
}

void addTriangle(PlyMeshInProgress& out, uint32_t a, uint32_t b, uint32_t c, const Cursor& cursor) {
  if (out.mesh.faces.size() >= kMaxTriangles) {
    cursor.failValue("more than " + std::to_string(kMaxTriangles) + " triangles");
  }
  out.mesh.faces.emplace_back(a, b, c);
  if (out.perCornerUvs) out.cornerUvs.resize(out.cornerUvs.size() + 3);
}

// Polygons become a fan around their first corner; its corners' texture
// coordinates follow them.
void addPolygon(PlyMeshInProgress& out, bool withUvs, const Cursor& cursor) {
  const std::vector<uint32_t>& c = out.corners;
  if (withUvs && out.faceUvs.empty()) out.faceUvs.assign(c.size(), glm::vec2(0.0f));  // untextured
  if (withUvs && out.faceUvs.size() != c.size()) {
    cursor.failValue("the face has " + std::to_string(c.size()) +
                     " corners but texture coordinates for " + std::to_string(out.faceUvs.size()));
  }
  if (withUvs && !out.perCornerUvs) {  // the faces before this one had none
    out.perCornerUvs = true;
    out.cornerUvs.assign(3 * out.mesh.faces.size(), glm::vec2(0.0f));
  }
  for (size_t i = 1; i + 1 < c.size(); ++i) {
    addTriangle(out, c[0], c[i], c[i + 1], cursor);
    if (withUvs) {
      glm::vec2* uvs = &out.cornerUvs[out.cornerUvs.size() - 3];
      uvs[0] = out.faceUvs[0];
      uvs[1] = out.faceUvs[i];
      uvs[2] = out.faceUvs[i + 1];
    }
  }
}

// Strip triangles alternate their winding; the repeated-index triangles that
// stitch strips together are dropped.
void addStrip(PlyMeshInProgress& out, const Cursor& cursor) {
  const std::vector<uint32_t>& c = out.corners;
  size_t start = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    if (c[i] == kStripRestart) {
      start = i + 1;
      continue;
    }
    if (i < start + 2) continue;
    const bool odd = (i - start) % 2 == 1;
    const uint32_t a = odd ? c[i - 1] : c[i - 2];
    const uint32_t b = odd ? c[i - 2] : c[i - 1];
    if (a != b && b != c[i] && a != c[i]) addTriangle(out, a, b, c[i], cursor);
  }
}

template <typename Reader>
void readIndexElement(Reader& reader, const ElementPlan& plan, PlyMeshInProgress& out) {
  const Element& element = *plan.element;
  const bool strips = plan.role == Role::Strips;
  if (!strips) out.mesh.faces.reserve(out.mesh.faces.size() + element.count);
  const bool withUvs = plan.hasTexcoords();
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.startRecord(element, record);
    for (size_t i = 0; i < element.properties.size(); ++i) {
      if (plan.slots[i] == kIndexList) {
        readIndexList(reader, element.properties[i], strips, out);
      } else if (plan.slots[i] == kTexcoordList) {
        readTexcoordList(reader, element.properties[i], out);
      } else {
        reader.skip(element.properties[i]);
      }
    }
    reader.endRecord();
    if (strips) {
      addStrip(out, reader);
    } else {
      addPolygon(out, withUvs, reader);
    }
  }
}

template <typename Reader>
void readSkipped(Reader& reader, const Element& element) {
  if (element.properties.empty()) return;
  for (uint64_t record = 0; record < element.count; ++record) {
    reader.startRecord(element, record);
    for (const Property& property : element.properties) reader.skip(property);
    reader.endRecord();
  }
}

template <typename Reader>
void readElements(Reader& reader, const std::vector<ElementPlan>& plans, PlyMeshInProgress& out) {
  for (const ElementPlan& plan : plans) {
    switch (plan.role) {
      case Role::Vertices: readVertices(reader, plan, out); break;
      case Role::Faces:
      case Role::Strips: readIndexElement(reader, plan, out); break;
      case Role::Skip: readSkipped(reader, *plan.element); break;
    }
  }
  reader.finish();
}

uint64_t vertexCountOf(const std::vector<ElementPlan>& plans) {
  for (const ElementPlan& plan : plans) {
    if (plan.role == Role::Vertices) return plan.element->count;
  }
  return 0;
}

// Per-face texture coordinates made per-vertex: one vertex for each distinct
// (vertex, coordinates) pair among the faces' corners, which splits vertices
// only along the texture's seams. Vertices no face uses are dropped.
void splitAtUvSeams(PlyMeshInProgress& out) {
  const TriangleMesh& mesh = out.mesh;
  struct Corner {
    uint32_t vertex;
    glm::vec2 uv;
    size_t index;  // face * 3 + corner
  };
  std::vector<Corner> corners(out.cornerUvs.size());
  for (size_t c = 0; c < corners.size(); ++c) {
    corners[c] = {mesh.faces[c / 3][static_cast<int>(c % 3)], out.cornerUvs[c], c};
  }
  auto key = [](const Corner& c) { return std::tuple(c.vertex, c.uv.x, c.uv.y); };
  std::sort(corners.begin(), corners.end(),
            [&](const Corner& a, const Corner& b) { return key(a) < key(b); });
  TriangleMesh split;
  split.faces.resize(mesh.faces.size());
  for (size_t c = 0; c < corners.size(); ++c) {
    const Corner& corner = corners[c];
    if (c == 0 || key(corner) != key(corners[c - 1])) {
      split.positions.push_back(mesh.positions[corner.vertex]);
      if (!mesh.normals.empty()) split.normals.push_back(mesh.normals[corner.vertex]);
      if (!mesh.colors.empty()) split.colors.push_back(mesh.colors[corner.vertex]);
      split.uvs.push_back(corner.uv);
    }
    split.faces[corner.index / 3][static_cast<int>(corner.index % 3)] =
        static_cast<uint32_t>(split.positions.size() - 1);
  }
  out.mesh = std::move(split);
}

PlyModel parseModel(std::string_view bytes, std::string_view name) {
  const Diagnostics diagnostics{std::string(name)};
  const Header header = readHeader(bytes, diagnostics);
  const std::vector<ElementPlan> plans = planElements(header, diagnostics);
  checkCountsFit(plans, header.format, bytes.size() - header.dataStart, diagnostics);
  PlyMeshInProgress out;
  out.vertexCount = vertexCountOf(plans);
  if (header.format == Format::Ascii) {
    AsciiReader reader(bytes, header.dataStart, diagnostics);
    readElements(reader, plans, out);
  } else {
    BinaryReader reader(bytes, header.dataStart, header.format == Format::BinaryBigEndian,
                        diagnostics);
    readElements(reader, plans, out);
  }
  if (out.mesh.faces.empty())
    diagnostics.failAtByte(bytes.size(), "no faces: every tristrip is degenerate");
  completeVertexNormals(out.mesh);  // before the seams split: smooth across them
  if (out.perCornerUvs) splitAtUvSeams(out);
  dropWhiteColors(out.mesh);
  return {std::move(out.mesh), header.textureFiles};
}

// The PLY's own texture (`comment TextureFile`) on its material, when it is
// rendered on its own. Its texture coordinates run up the image, as MeshLab
// and OBJ have them; the renderer's rows run down.
void applyTextureFile(Scene& scene, const PlyModel& model, const fs::path& file) {
  if (model.textureFiles.empty()) return;
  TriangleMesh& mesh = scene.meshes[0];
  const std::string& written = model.textureFiles[0];
  const std::string where = file.string() + ": TextureFile " + written;
  if (mesh.uvs.empty()) {
    scene.warnings.push_back(where + ": ignored, the mesh has no texture coordinates");
    return;
  }
  if (model.textureFiles.size() > 1) {
    scene.warnings.push_back(file.string() + ": " + std::to_string(model.textureFiles.size()) +
                             " TextureFile comments; only the first is used");
  }
  for (glm::vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;
  if (!mesh.colors.empty()) {
    scene.warnings.push_back(where + ": the vertex colours are ignored, the texture is drawn");
    mesh.colors.clear();
  }
  Material& material = scene.materials[0];
  const fs::path found = (file.parent_path() / portablePath(written)).lexically_normal();
  try {
    if (useDiffuseTextureFile(scene, material, found)) return;
  } catch (const Error& error) {
    throw Error(where + ": " + error.what());
  }
  scene.warnings.push_back(where + ": file not found; drawn with the missing-texture squares");
  material.texture = found;
}

}  // namespace

TriangleMesh parsePly(std::string_view bytes, std::string_view name) {
  return withPrintableErrors([&] { return parseModel(bytes, name).mesh; });
}

PlyModel loadPlyModel(const fs::path& file) {
  return withPrintableErrors([&] { return parseModel(readFileOrThrow(file), file.string()); });
}

TriangleMesh loadPly(const fs::path& file) { return loadPlyModel(file).mesh; }

Scene loadPlyScene(const fs::path& file) {
  Scene scene;
  scene.sourcePath = file;
  PlyModel model = loadPlyModel(file);
  scene.meshes.push_back(std::move(model.mesh));
  scene.materials.push_back(Material{});
  withPrintableErrors([&] { applyTextureFile(scene, model, file); });
  Shape shape;
  shape.geometry = MeshInstance{0, WorldTransform(1.0)};
  shape.label = file.filename().string();
  scene.shapes.push_back(std::move(shape));
  frameModelScene(scene, {"a PLY file"});
  return scene;
}

bool isPlyFile(const fs::path& file) { return hasExtension(file, {".ply"}); }

}  // namespace rt
