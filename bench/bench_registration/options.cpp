#include "bench_registration/options.h"

#include <cstdlib>
#include <iostream>
#include <string>

#include "brick_pose/common/errors.h"

namespace bench_registration
{
using brick_pose::ConfigError;

Options parseOptions(int argc, char** argv)
{
  Options options;
  for (int i = 1; i < argc; ++i)
  {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc)
        throw ConfigError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--frames")
      options.frames = std::stoi(value());
    else if (arg == "--views")
      options.views = std::stoi(value());
    else if (arg == "--first-view")
      options.first_view = std::stoi(value());
    else if (arg == "--seed")
      options.seed = std::stoull(value());
    else if (arg == "--pcl-time")
      options.pcl_time_s = std::stoi(value());
    else if (arg == "--min-visible")
      options.min_visible_fraction = std::stod(value());
    else if (arg == "--verbose")
      options.verbose = true;
    else if (arg == "--only-ours")
      options.only_ours = true;
    else if (arg == "--only-views")
      options.only_views = true;
    else if (arg == "--no-refine")
      options.no_refine = true;
    else if (arg == "--sweep-frames")
      options.sweep_frames = std::stoi(value());
    else if (arg == "--sweep-time")
      options.sweep_time_s = std::stoi(value());
    else if (arg == "--help" || arg == "-h")
    {
      std::cout << "usage: bench_registration [--frames N (200)] [--views N (200)] [--first-view I (0)] [--seed S (1)]\n"
                   "                          [--pcl-time S (1)]\n"
                   "                          [--min-visible F (0.95)] [--verbose] [--only-ours] [--only-views]\n"
                   "                          [--no-refine] [--sweep-frames N (50, 0 = off)] [--sweep-time S (10)]\n";
      std::exit(0);
    }
    else
      throw ConfigError("unknown argument " + arg);
  }
  if (options.frames < 1 || options.pcl_time_s < 1 || options.sweep_time_s < 1)
    throw ConfigError("--frames, --pcl-time and --sweep-time must be at least 1");
  if (options.sweep_frames < 0 || options.views < 0)
    throw ConfigError("--sweep-frames and --views must be >= 0");
  return options;
}
}  // namespace bench_registration
