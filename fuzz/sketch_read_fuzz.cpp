// Fuzz harness: the sketch file (JSON) and camera file readers. Contract checked: bad input
// throws InputError and nothing else; an accepted sketch passes Sketch::validate, and writing it
// and reading that back gives the same sketch.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"

using namespace treesketch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(fuzz::asText(data, size));
  try {
    std::istringstream in(text);
    const geom::Camera camera = io::readCamera(in, "fuzz.camera.json");
    camera.validate("accepted camera");
  } catch (const InputError&) {
  }
  std::istringstream in(text);
  sketch::Sketch sketch;
  try {
    sketch = io::readSketch(in, "fuzz.sketch.json");
  } catch (const InputError&) {
    return 0;
  }
  sketch.validate();  // an OptionsError escaping here is a failure: the reader promised a valid sketch
  std::ostringstream out;
  io::writeSketch(out, sketch);
  std::istringstream back(out.str());
  fuzz::checkSameSketch(sketch, io::readSketch(back, "written.sketch.json"), "sketch read/write/read");
  return 0;
}
