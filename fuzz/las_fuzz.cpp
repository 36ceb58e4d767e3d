// Fuzz harness: the LAS reader (header block and point records, formats 0-10, LAS 1.0-1.4).
// Contract checked: bad input throws InputError and nothing else; an accepted file gives exactly
// the header's point count of finite points, less the records flagged withheld.
#include <sstream>

#include "fuzz_support.h"
#include "treesketch/io/las.h"
#include "treesketch/util/error.h"

using namespace treesketch;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes = fuzz::asText(data, size);
  try {
    io::parseLasHeader(bytes, "fuzz.las");
  } catch (const InputError&) {
  }
  io::CloudReadOptions options;
  options.minPoints = 1;
  std::istringstream in{std::string(bytes)};
  io::LasHeader header;
  geom::PointCloud cloud;
  try {
    cloud = io::readLas(in, "fuzz.las", options, &header);
  } catch (const InputError&) {
    return 0;
  }
  fuzz::checkCloud(cloud, 1);
  FUZZ_CHECK(cloud.size() + header.withheld == header.pointCount, "LAS: point count differs from the header's");
  FUZZ_CHECK(header.pointFormat <= 10, "LAS: point format above 10 accepted");
  FUZZ_CHECK(header.recordLength >= io::lasMinRecordLength(header.pointFormat), "LAS: short record accepted");
  return 0;
}
