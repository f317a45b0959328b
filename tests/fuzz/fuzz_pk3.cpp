// libFuzzer target: .pk3 (zip) archives in memory: open, list, read every
// entry's image header, and load every map inside with texture sizes from
// the archive (load_bsp_from_archive), as --scene FILE.pk3:maps/X.bsp does.
#include <cstddef>
#include <cstdint>

#include "loaders/bsp.hpp"
#include "loaders/file_io.hpp"
#include "loaders/image_size.hpp"
#include "loaders/pk3.hpp"
#include "triangle.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  try {
    const cdsim::Pk3Archive archive =
        cdsim::Pk3Archive::open_memory(std::vector<uint8_t>(data, data + size), "fuzz.pk3");
    int entries = 0;
    for (const std::string& entry : archive.entries()) {
      if (++entries > 16) break;
      try {
        if (cdsim::ends_with_ignoring_case(entry, ".bsp")) {
          cdsim::load_bsp_from_archive(archive, entry, {256, 256});
        } else if (const auto bytes = archive.read(entry)) {
          cdsim::image_size_from_memory(bytes->data(), bytes->size(), entry);
        }
      } catch (const cdsim::InputError&) {
      }
    }
    (void)cdsim::split_pk3_spec(std::string(reinterpret_cast<const char*>(data), size));
  } catch (const cdsim::InputError&) {
  }
  return 0;
}
