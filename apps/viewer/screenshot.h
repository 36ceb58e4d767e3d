// Screenshots: the current back buffer (read before swapping) written as an 8-bit RGB PNG, rows
// flipped from OpenGL's bottom-up order, through a temporary file renamed on success.
#pragma once

#include <filesystem>

namespace treesketch::gui {

/// Reads the `width` x `height` back buffer and writes it to `path`. Throws OutputError when the
/// PNG cannot be encoded or written.
void writeScreenshot(const std::filesystem::path& path, int width, int height);

}  // namespace treesketch::gui
