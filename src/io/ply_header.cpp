// PLY headers: parsing the description at the top of a PLY file (format, elements, properties and
// their types). Format reference: Greg Turk, "The PLY Polygon File Format" (1994), and the type
// aliases (int8 ... float64) written by later tools such as VTK and Open3D. The body is read in
// ply_read.cpp and written in ply_write.cpp.
#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>

#include "io/io_util.h"
#include "treesketch/io/ply.h"
#include "treesketch/util/error.h"

namespace treesketch::io {

std::optional<geom::UpAxis> declaredUpAxis(const PlyHeader& header) {
  for (const std::string& c : header.comments) {
    std::istringstream in(c);
    std::string key, value;
    if (!(in >> key >> value) || key != kPlyUpKey) continue;
    if (value == "y" || value == "Y") return geom::UpAxis::Y;
    if (value == "z" || value == "Z") return geom::UpAxis::Z;
  }
  return std::nullopt;
}

using detail::quoted;

namespace {

bool parseType(std::string_view s, PlyType& t) {
  struct Name {
    const char* a;
    const char* b;
    PlyType t;
  };
  static const Name kNames[] = {{"char", "int8", PlyType::Int8},        {"uchar", "uint8", PlyType::UInt8},
                                {"short", "int16", PlyType::Int16},     {"ushort", "uint16", PlyType::UInt16},
                                {"int", "int32", PlyType::Int32},       {"uint", "uint32", PlyType::UInt32},
                                {"float", "float32", PlyType::Float32}, {"double", "float64", PlyType::Float64}};
  for (const auto& n : kNames) {
    if (s == n.a || s == n.b) {
      t = n.t;
      return true;
    }
  }
  return false;
}

std::vector<std::string_view> splitWords(std::string_view line) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    if (i == line.size()) break;
    std::size_t s = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    words.push_back(line.substr(s, i - s));
  }
  return words;
}

}  // namespace

int PlyElement::find(std::string_view n) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == n) return static_cast<int>(i);
  return -1;
}

const PlyElement* PlyHeader::find(std::string_view n) const {
  for (const auto& e : elements)
    if (e.name == n) return &e;
  return nullptr;
}

const char* toString(PlyFormat f) {
  switch (f) {
    case PlyFormat::Ascii:
      return "ascii";
    case PlyFormat::BinaryLittleEndian:
      return "binary_little_endian";
    case PlyFormat::BinaryBigEndian:
      return "binary_big_endian";
  }
  return "?";
}

const char* toString(PlyType t) {
  switch (t) {
    case PlyType::Int8:
      return "char";
    case PlyType::UInt8:
      return "uchar";
    case PlyType::Int16:
      return "short";
    case PlyType::UInt16:
      return "ushort";
    case PlyType::Int32:
      return "int";
    case PlyType::UInt32:
      return "uint";
    case PlyType::Float32:
      return "float";
    case PlyType::Float64:
      return "double";
  }
  return "?";
}

PlyHeader parsePlyHeader(std::string_view data, const std::string& source) {
  if (data.empty()) throw InputError(source + ": file is empty, expected a PLY header starting with 'ply'");
  PlyHeader h;
  detail::Lines lines(data);
  std::string_view line;
  bool haveFormat = false;
  auto fail = [&](const std::string& what) { throw InputError(atLine(source, lines.number(), what)); };
  while (true) {
    if (!lines.next(line)) fail("header not terminated: expected an 'end_header' line");
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    auto w = splitWords(line);
    if (lines.number() == 1) {
      if (w.size() != 1 || w[0] != "ply") fail("not a PLY file: expected 'ply' on the first line, got " + quoted(line));
      continue;
    }
    if (w.empty()) continue;
    std::string_view key = w[0];
    if (key == "comment" || key == "obj_info") {
      std::string_view rest = line.substr(std::min(line.size(), key.size() + 1));
      h.comments.emplace_back(rest);
    } else if (key == "format") {
      if (w.size() != 3) fail("expected 'format <ascii|binary_little_endian|binary_big_endian> 1.0'");
      if (w[1] == "ascii")
        h.format = PlyFormat::Ascii;
      else if (w[1] == "binary_little_endian")
        h.format = PlyFormat::BinaryLittleEndian;
      else if (w[1] == "binary_big_endian")
        h.format = PlyFormat::BinaryBigEndian;
      else
        fail("unsupported PLY format " + quoted(w[1]) + ", expected ascii, binary_little_endian or binary_big_endian");
      if (w[2].substr(0, 2) != "1." && w[2] != "1") fail("unsupported PLY version " + quoted(w[2]) + ", expected 1.0");
      haveFormat = true;
    } else if (key == "element") {
      if (w.size() != 3) fail("expected 'element <name> <count>'");
      PlyElement e;
      e.name = std::string(w[1]);
      auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (r.ec != std::errc() || r.ptr != w[2].data() + w[2].size())
        fail("element count " + quoted(w[2]) + " is not a non-negative integer");
      h.elements.push_back(std::move(e));
    } else if (key == "property") {
      if (h.elements.empty()) fail("'property' before any 'element' line");
      PlyProperty p;
      if (w.size() >= 2 && w[1] == "list") {
        if (w.size() != 5) fail("expected 'property list <count type> <item type> <name>'");
        if (!parseType(w[2], p.countType) || !isIntegerType(p.countType))
          fail("list count type " + quoted(w[2]) + " is not an integer PLY type");
        if (!parseType(w[3], p.type))
          fail("unknown PLY type " + quoted(w[3]) +
               ", expected char, uchar, short, ushort, int, uint, float, double (or int8 ... float64)");
        p.isList = true;
        p.name = std::string(w[4]);
      } else {
        if (w.size() != 3) fail("expected 'property <type> <name>'");
        if (!parseType(w[1], p.type))
          fail("unknown PLY type " + quoted(w[1]) +
               ", expected char, uchar, short, ushort, int, uint, float, double (or int8 ... float64)");
        p.name = std::string(w[2]);
      }
      h.elements.back().properties.push_back(std::move(p));
    } else if (key == "end_header") {
      if (!haveFormat) fail("'end_header' before any 'format' line");
      break;
    } else {
      fail("unknown PLY header keyword " + quoted(key) + ", expected format, comment, element, property or end_header");
    }
  }
  h.dataOffset = lines.offset();
  h.headerLines = lines.number();
  return h;
}

PlyHeader readPlyHeader(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string() + ": file not found");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  std::string head(1 << 16, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  return parsePlyHeader(head, path.string());
}

}  // namespace treesketch::io
