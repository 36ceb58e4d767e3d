// Fuzz harness: the sketch writer and reader as a round trip. The input is decoded into edits of
// a sketch through its public API (cameras, screen and point nodes, moves, removals, re-parenting,
// sampling sizes, kept circles) with extreme values; the API may refuse an edit (OptionsError).
// Contract checked: the writer refuses exactly the sketches that fail Sketch::validate, and a
// written sketch reads back identical (doubles bit for bit) and writes the same bytes again.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/sketch_file.h"
#include "treesketch/util/error.h"

using namespace treesketch;

namespace {

geom::Vec3 nextVec3(fuzz::ByteSource& in) {
  const double x = fuzz::nextDouble(in), y = fuzz::nextDouble(in);
  return {x, y, fuzz::nextDouble(in)};
}

sketch::SamplingParams nextParams(fuzz::ByteSource& in) {
  sketch::SamplingParams p;
  p.sliceHalfThickness = fuzz::nextDouble(in);
  p.lineEpsilon = fuzz::nextDouble(in);
  p.lineEpsilonStep = fuzz::nextDouble(in);
  const std::uint8_t flags = in.next<std::uint8_t>();
  p.enabled = (flags & 1) == 0;
  p.maxGrowthSteps = (flags & 2) ? static_cast<int>(in.next<std::int32_t>()) : -1;
  return p;
}

geom::Camera nextCamera(fuzz::ByteSource& in) {
  geom::Camera c;
  const std::uint8_t mode = in.next<std::uint8_t>();
  if (mode & 1) {
    for (int i = 0; i < 16; ++i) c.view.data()[i] = fuzz::nextDouble(in);
    for (int i = 0; i < 16; ++i) c.projection.data()[i] = fuzz::nextDouble(in);
  } else {
    const geom::Vec3 eye = nextVec3(in), target = nextVec3(in);
    c.view = geom::lookAt(eye, target, (mode & 2) ? geom::Vec3(0, 0, 1) : geom::Vec3(0, 1, 0));
    const double a = fuzz::nextDouble(in), b = fuzz::nextDouble(in);
    c.projection = (mode & 4) ? geom::perspective(a, 1.6, 0.1, 1000) : geom::orthographic(-a, a, -b, b, 0.1, 1000);
  }
  c.viewport = {fuzz::nextDouble(in), fuzz::nextDouble(in), fuzz::nextDouble(in), fuzz::nextDouble(in)};
  return c;
}

// A node id of the sketch picked by the input (or kNoNode, or one that does not exist).
sketch::NodeId pickNode(const sketch::Sketch& s, fuzz::ByteSource& in) {
  const std::uint8_t k = in.next<std::uint8_t>();
  const auto ids = s.ids();
  if (k == 255 || ids.empty()) return sketch::kNoNode;
  if (k == 254) return 1 << 20;
  return ids[k % ids.size()];
}

void applyEdit(sketch::Sketch& s, fuzz::ByteSource& in) {
  const std::uint8_t op = in.next<std::uint8_t>() % 9;
  const sketch::NodeId id = pickNode(s, in);
  switch (op) {
    case 0:
      s.addCamera(nextCamera(in));
      break;
    case 1: {
      const int camera = static_cast<int>(in.next<std::uint8_t>() % 4);
      const geom::Vec2 screen(fuzz::nextDouble(in), fuzz::nextDouble(in));
      s.addScreenNode(id, camera, screen, nextParams(in));
      break;
    }
    case 2: {
      const geom::Vec3 p = nextVec3(in), n = nextVec3(in);
      s.addPointNode(id, p, n, nextParams(in));
      break;
    }
    case 3:
      s.removeNode(id, in.next<std::uint8_t>() & 1);
      break;
    case 4:
      s.moveNode(id, geom::Vec2(fuzz::nextDouble(in), fuzz::nextDouble(in)));
      break;
    case 5: {
      const geom::Vec3 p = nextVec3(in), n = nextVec3(in);
      s.movePointNode(id, p, n);
      break;
    }
    case 6:
      s.setParams(id, nextParams(in));
      break;
    case 7: {
      const geom::Vec3 c = nextVec3(in);
      const double r = fuzz::nextDouble(in);
      s.setKeptCircle(id, (r == 0) ? std::nullopt : std::optional<sketch::KeptCircle>({c, r}));
      break;
    }
    case 8:
      s.setParent(id, pickNode(s, in));
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  fuzz::ByteSource in(data, size);
  sketch::Sketch s;
  s.up = (in.next<std::uint8_t>() & 1) ? geom::UpAxis::Z : geom::UpAxis::Y;
  s.defaults = nextParams(in);
  for (int edits = 0; in.remaining() > 0 && edits < 64; ++edits) {
    try {
      applyEdit(s, in);
    } catch (const OptionsError&) {
    }
  }
  bool valid = true;
  try {
    s.validate();
  } catch (const OptionsError&) {
    valid = false;
  }
  std::ostringstream out;
  try {
    io::writeSketch(out, s);
  } catch (const OptionsError&) {
    FUZZ_CHECK(!valid, "writeSketch refused a sketch that passes validate");
    return 0;
  }
  FUZZ_CHECK(valid, "writeSketch wrote a sketch that fails validate");
  std::istringstream back(out.str());
  const sketch::Sketch again = io::readSketch(back, "written.sketch.json");
  fuzz::checkSameSketch(s, again, "sketch write/read");
  std::ostringstream out2;
  io::writeSketch(out2, again);
  FUZZ_CHECK(out2.str() == out.str(), "sketch write/read/write: the bytes changed");
  return 0;
}
