#include "common/run_environment.h"

#include <cstdlib>
#include <ctime>
#include <sys/stat.h>

namespace brick_pose
{
namespace bench
{
std::string sourceDirectory()
{
#ifdef BRICK_POSE_SOURCE_DIR
  return BRICK_POSE_SOURCE_DIR;
#else
  const char* source_dir = std::getenv("BRICK_POSE_SOURCE_DIR");
  return source_dir ? std::string(source_dir) : std::string(".");
#endif
}

std::string defaultOutputDir() { return sourceDirectory() + "/bench/results"; }

bool makeDirectories(const std::string& path)
{
  for (std::size_t slash = path.find('/', 1);; slash = path.find('/', slash + 1))
  {
    const std::string prefix = path.substr(0, slash);
    if (!prefix.empty()) mkdir(prefix.c_str(), 0755);
    if (slash == std::string::npos) break;
  }
  struct stat info;
  return stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode);
}

double loadAverage()
{
  double load[1] = {0.0};
  return getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

double processCpuMs()
{
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return 1e3 * static_cast<double>(now.tv_sec) + 1e-6 * static_cast<double>(now.tv_nsec);
}
}  // namespace bench
}  // namespace brick_pose
