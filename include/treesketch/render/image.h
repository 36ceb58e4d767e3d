// Images for the offline renderer: 8-bit RGB or RGBA pixels in rows from the top-left, as PNG
// stores them. Plain data, so tests and writers can read every pixel.
#pragma once

#include <cstdint>
#include <vector>

namespace treesketch::render {

/// An 8-bit colour.
struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb&) const = default;
};
// Three bytes, no padding: the viewer uploads its std::vector<Rgb> point colours to OpenGL as
// packed bytes.
static_assert(sizeof(Rgb) == 3);

/// Pixels row by row from the top-left; `channels` is 3 (RGB) or 4 (RGBA).
struct Image {
  int width = 0;
  int height = 0;
  int channels = 3;
  std::vector<std::uint8_t> pixels;  ///< width * height * channels bytes

  Image() = default;
  /// A width x height image filled with `fill` (alpha 255 when channels is 4). Negative sizes count as 0.
  Image(int w, int h, Rgb fill = {255, 255, 255}, int ch = 3)
      : width(w < 0 ? 0 : w), height(h < 0 ? 0 : h), channels(ch == 4 ? 4 : 3) {
    pixels.resize(static_cast<std::size_t>(width) * height * channels);
    for (std::size_t i = 0; i < pixels.size(); i += channels) {
      pixels[i] = fill.r;
      pixels[i + 1] = fill.g;
      pixels[i + 2] = fill.b;
      if (channels == 4) pixels[i + 3] = 255;
    }
  }
  std::size_t offset(int x, int y) const { return (static_cast<std::size_t>(y) * width + x) * channels; }
  /// Colour of pixel (x, y); the caller keeps x, y inside the image.
  Rgb at(int x, int y) const {
    std::size_t o = offset(x, y);
    return {pixels[o], pixels[o + 1], pixels[o + 2]};
  }
  void set(int x, int y, Rgb c) {
    std::size_t o = offset(x, y);
    pixels[o] = c.r;
    pixels[o + 1] = c.g;
    pixels[o + 2] = c.b;
  }
};

}  // namespace treesketch::render
