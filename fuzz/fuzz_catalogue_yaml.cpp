// Fuzz target: BrickCatalogue::fromYamlString, the parser behind
// config/bricks.yaml and the catalogue_path / rosparam dumps.

#include <cmath>
#include <cstdint>
#include <string>

#include "brick_pose/catalogue/brick_catalogue.h"
#include "brick_pose/common/errors.h"
#include "fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using namespace brick_pose;
  const std::string text(reinterpret_cast<const char*>(data), size);
  try
  {
    const BrickCatalogue catalogue = BrickCatalogue::fromYamlString(text);
    // An accepted catalogue holds only valid types with distinct names.
    for (const BrickType& type : catalogue.types())
    {
      fuzz::require(type.length_m > 0.0 && std::isfinite(type.length_m));
      fuzz::require(type.width_m > 0.0 && type.width_m <= type.length_m);
      fuzz::require(type.height_m > 0.0 && std::isfinite(type.height_m));
      fuzz::require(catalogue.find(type.name) == &type);
    }
  }
  catch (const ConfigError&)
  {
  }
  return 0;
}
