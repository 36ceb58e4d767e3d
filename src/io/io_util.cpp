#include "io/io_util.h"

#include <algorithm>
#include <fstream>

#include "treesketch/util/error.h"
#include "treesketch/util/text.h"

namespace treesketch::io::detail {

namespace fs = std::filesystem;

std::string readAll(std::istream& in, const std::string& source) {
  if (!in) throw InputError(source + ": cannot read (stream is not readable)");
  std::string data;
  // Size by seeking when the stream allows it, so a large file is read in one block.
  auto start = in.tellg();
  if (start != std::istream::pos_type(-1)) {
    in.seekg(0, std::ios::end);
    auto end = in.tellg();
    in.seekg(start);
    if (end != std::istream::pos_type(-1) && end >= start && in) {
      data.resize(static_cast<std::size_t>(end - start));
      in.read(data.data(), static_cast<std::streamsize>(data.size()));
      data.resize(static_cast<std::size_t>(in.gcount()));
    }
  }
  in.clear(in.rdstate() & ~std::ios::failbit);
  // Whatever is left (or everything, for streams that cannot seek), in blocks.
  char block[1 << 16];
  while (in) {
    in.read(block, sizeof block);
    data.append(block, static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw InputError(source + ": read error after " + std::to_string(data.size()) + " bytes");
  return data;
}

std::string readFile(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path.string() + ": file not found");
  if (fs::is_directory(path, ec)) throw InputError(path.string() + ": is a directory, expected a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string() + ": cannot open for reading");
  return readAll(in, path.string());
}

std::string lowerExtension(const fs::path& path) { return lowercase(path.extension().string()); }

std::string quoted(std::string_view s) {
  std::string out = "'";
  std::size_t n = std::min<std::size_t>(s.size(), 40);
  for (std::size_t i = 0; i < n; ++i) {
    unsigned char c = static_cast<unsigned char>(s[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  if (s.size() > n) out += "...";
  return out + "'";
}

}  // namespace treesketch::io::detail
