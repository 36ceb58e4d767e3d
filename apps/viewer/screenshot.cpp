#include "screenshot.h"

#include <GL/glew.h>
#include <stb_image_write.h>

#include <ostream>
#include <vector>

#include "treesketch/util/atomic_file.h"
#include "treesketch/util/error.h"

namespace treesketch::gui {

namespace {
void writeToStream(void* context, void* data, int size) {
  static_cast<std::ostream*>(context)->write(static_cast<const char*>(data), size);
}
}  // namespace

void writeScreenshot(const std::filesystem::path& path, int width, int height) {
  if (width <= 0 || height <= 0) throw OutputError(path.string() + ": the window has no pixels to save");
  std::vector<unsigned char> pixels(static_cast<std::size_t>(width) * height * 3);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, pixels.data());
  std::vector<unsigned char> flipped(pixels.size());
  std::size_t row = static_cast<std::size_t>(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy(pixels.begin() + static_cast<std::ptrdiff_t>((height - 1 - y) * row),
              pixels.begin() + static_cast<std::ptrdiff_t>((height - y) * row),
              flipped.begin() + static_cast<std::ptrdiff_t>(y * row));
  writeFileAtomically(path, [&](std::ostream& out) {
    if (!stbi_write_png_to_func(writeToStream, &out, width, height, 3, flipped.data(), static_cast<int>(row)))
      throw OutputError(path.string() + ": PNG encoding failed");
  });
}

}  // namespace treesketch::gui
