// PNG output for the offline renderer, with no image library: 8-bit RGB or RGBA, one IDAT
// chunk compressed by render/deflate.h, each scanline filtered (None/Sub/Up/Paeth, chosen per
// row by the usual smallest-sum-of-absolute-differences rule of the PNG specification §12.8).
#pragma once

#include <cstdint>
#include <filesystem>
#include <ostream>
#include <vector>

#include "treesketch/render/deflate.h"
#include "treesketch/render/image.h"

namespace treesketch::render {

struct PngOptions {
  DeflateOptions deflate;
  /// true: pick a filter per row (smaller files); false: filter type 0 (None) on every row.
  bool adaptiveFilter = true;
};

/// The bytes of a PNG file holding `image` (signature, IHDR, IDAT, IEND). Throws OptionsError for
/// an empty image (0 width or height), channels other than 3 or 4, or a pixel buffer whose size
/// is not width * height * channels.
std::vector<std::uint8_t> encodePng(const Image& image, const PngOptions& options = {});

/// Writes encodePng(image) to a stream; throws OutputError if the stream fails.
void writePng(std::ostream& out, const Image& image, const PngOptions& options = {});
/// Writes encodePng(image) to `path` atomically (temporary file, renamed on success); throws
/// OutputError if the file cannot be written, OptionsError for an invalid image.
void writePng(const std::filesystem::path& path, const Image& image, const PngOptions& options = {});

}  // namespace treesketch::render
