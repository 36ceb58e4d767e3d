// Fuzz harness: the XYZ/TXT/CSV text cloud reader. Contract checked: bad input throws InputError
// and nothing else; an accepted cloud is finite, and writing it as XYZ and reading that back gives
// the same coordinates bit for bit (shortest exact decimals).
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/xyz.h"
#include "treesketch/util/error.h"

using namespace treesketch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  io::CloudReadOptions options;
  options.minPoints = 1;
  options.maxHeaderLines = 3;  // small, so the fuzzer also reaches the "too many header lines" error
  std::istringstream in{std::string(fuzz::asText(data, size))};
  geom::PointCloud cloud;
  try {
    cloud = io::readXyz(in, "fuzz.xyz", options);
  } catch (const InputError&) {
    return 0;
  }
  fuzz::checkCloud(cloud, 1);
  std::ostringstream out;
  io::writeXyz(out, cloud);
  std::istringstream back(out.str());
  geom::PointCloud again = io::readXyz(back, "written.xyz", options);
  geom::PointCloud positionsOnly;  // XYZ keeps positions only
  positionsOnly.positions = cloud.positions;
  fuzz::checkSameCloud(positionsOnly, again, "XYZ write/read");
  return 0;
}
