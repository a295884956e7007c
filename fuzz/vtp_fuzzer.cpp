// libFuzzer harness: breastfit::io::read_vtp_from_memory on arbitrary bytes.
#include <cstddef>
#include <cstdint>

#include "breastfit/io/read_vtp.h"
#include "check_mesh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return breastfit::fuzz::run_reader(&breastfit::io::read_vtp_from_memory, data, size, "fuzz.vtp");
}
