// brick_pose_register: Super4PCS registration of two clouds from files.
//
//   brick_pose_register SOURCE TARGET [--overlap F] [--delta M] [--samples N]
//                       [--max-time S] [--seed N] [--view auto|on|off]
//                       [--viewpoint X,Y,Z] [--max-candidates N]
//                       [--min-confidence F] [--json]
//
// Prints the 4x4 matrix mapping SOURCE onto TARGET, the LCP score, the
// confidence and the time. A SOURCE of several faces (a cuboid model) is
// registered as a whole object seen from the viewpoint (whole-view mode),
// with the view checks. Exit status: 0 registered, 1 no alignment the tool is
// sure of (the reason says why), 2 bad arguments or unreadable input.

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "brick_pose/common/errors.h"
#include "brick_pose/registration/cloud_io.h"
#include "brick_pose/registration/super4pcs.h"

namespace
{
using brick_pose::registration::RegistrationResult;
using brick_pose::registration::Super4PCSParams;

constexpr int kExitRegistered = 0;
constexpr int kExitNotRegistered = 1;
constexpr int kExitUsage = 2;
// The work budget (bases, candidates) bounds the search and makes the result
// the same for a seed on any machine load; the wall clock is a safety net.
constexpr double kDefaultMaxTimeS = 2.0;

Super4PCSParams defaultParams()
{
  Super4PCSParams params;
  params.max_time_s = kDefaultMaxTimeS;
  params.view.mode = brick_pose::registration::ViewMode::kAuto;
  return params;
}

struct Options
{
  std::string source_path;
  std::string target_path;
  Super4PCSParams params = defaultParams();
  bool json = false;
  bool help = false;
};

void printUsage(std::ostream& out)
{
  const Super4PCSParams defaults = defaultParams();
  out << "usage: brick_pose_register SOURCE TARGET [options]\n"
         "\n"
         "Registers SOURCE onto TARGET (.pcd or .ply) with Super4PCS and prints the\n"
         "4x4 source-to-target matrix, the LCP score, the confidence and the time.\n"
         "\n"
         "options:\n"
         "  --overlap F    expected fraction of SOURCE seen in TARGET, (0, 1]   [" << defaults.overlap << "]\n"
         "  --delta M      accuracy in metres                                  [" << defaults.delta_m << "]\n"
         "  --samples N    points sampled from each cloud                      [" << defaults.sample_size << "]\n"
         "  --max-time S   time budget in seconds                              [" << defaults.max_time_s << "]\n"
         "  --seed N       random seed (same seed, same result)                [" << defaults.seed << "]\n"
         "  --view MODE    auto: whole-object view checks when SOURCE has several\n"
         "                 faces; on; off (LCP acceptance only)                [auto]\n"
         "  --viewpoint X,Y,Z  where TARGET was seen from, in its frame        [0,0,0]\n"
         "  --max-candidates N  whole-view work budget (candidate poses)      [" << defaults.view.max_candidates << "]\n"
         "  --min-confidence F  whole-view margin over the next best pose     [" << defaults.view.min_confidence << "]\n"
         "  --json         print one JSON object instead of text\n"
         "  --help         this text\n"
         "\n"
         "exit status: 0 registered, 1 not sure of any alignment (reason printed),\n"
         "             2 bad arguments or input\n";
}

/// Parses the whole of `text` as a number or throws ConfigError naming the option.
template <typename T>
T parseNumber(const std::string& option, const std::string& text)
{
  std::istringstream stream(text);
  T value{};
  stream >> value;
  if (stream.fail() || !stream.eof())
    throw brick_pose::ConfigError(option + ": '" + text + "' is not a number");
  return value;
}

brick_pose::registration::ViewMode parseViewMode(const std::string& text)
{
  using brick_pose::registration::ViewMode;
  if (text == "auto")
    return ViewMode::kAuto;
  if (text == "on")
    return ViewMode::kOn;
  if (text == "off")
    return ViewMode::kOff;
  throw brick_pose::ConfigError("--view: expected auto, on or off, got '" + text + "'");
}

Eigen::Vector3d parseViewpoint(const std::string& text)
{
  Eigen::Vector3d viewpoint;
  std::string rest = text;
  for (int axis = 0; axis < 3; ++axis)
  {
    const std::size_t comma = rest.find(',');
    if ((axis < 2) != (comma != std::string::npos))
      throw brick_pose::ConfigError("--viewpoint: expected X,Y,Z, got '" + text + "'");
    viewpoint[axis] = parseNumber<double>("--viewpoint", rest.substr(0, comma));
    rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
  }
  return viewpoint;
}

Options parseArguments(const std::vector<std::string>& args)
{
  Options options;
  std::vector<std::string> positional;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size())
        throw brick_pose::ConfigError(arg + " needs a value");
      return args[++i];
    };
    if (arg == "--help" || arg == "-h")
      options.help = true;
    else if (arg == "--json")
      options.json = true;
    else if (arg == "--overlap")
      options.params.overlap = parseNumber<double>(arg, value());
    else if (arg == "--delta")
      options.params.delta_m = parseNumber<double>(arg, value());
    else if (arg == "--samples")
      options.params.sample_size = parseNumber<int>(arg, value());
    else if (arg == "--max-time")
      options.params.max_time_s = parseNumber<double>(arg, value());
    else if (arg == "--seed")
      options.params.seed = parseNumber<unsigned long long>(arg, value());
    else if (arg == "--view")
      options.params.view.mode = parseViewMode(value());
    else if (arg == "--viewpoint")
      options.params.view.viewpoint_m = parseViewpoint(value());
    else if (arg == "--max-candidates")
      options.params.view.max_candidates = parseNumber<int>(arg, value());
    else if (arg == "--min-confidence")
      options.params.view.min_confidence = parseNumber<double>(arg, value());
    else if (arg.size() > 1 && arg[0] == '-' && arg[1] == '-')
      throw brick_pose::ConfigError("unknown option " + arg);
    else
      positional.push_back(arg);
  }
  if (options.help)
    return options;
  if (positional.size() != 2)
    throw brick_pose::ConfigError("expected SOURCE and TARGET, got " + std::to_string(positional.size()) +
                                  " file argument(s)");
  options.source_path = positional[0];
  options.target_path = positional[1];
  options.params.validate();
  return options;
}

std::string jsonEscaped(const std::string& text)
{
  std::string out;
  for (char c : text)
  {
    if (c == '"' || c == '\\')
      out += '\\';
    if (static_cast<unsigned char>(c) < 0x20)
      continue;
    out += c;
  }
  return out;
}

void printText(const RegistrationResult& result)
{
  const Eigen::Matrix4d m = result.source_to_target.matrix();
  std::printf("source_to_target:\n");
  for (int r = 0; r < 4; ++r)
    std::printf("  % .9f % .9f % .9f % .9f\n", m(r, 0), m(r, 1), m(r, 2), m(r, 3));
  std::printf("lcp_score: %.4f\n", result.lcp_score);
  std::printf("time_ms: %.2f\n", result.elapsed_s * 1e3);
  std::printf("confidence: %.4f\nsecond_best_score: %.4f\n", result.confidence, result.second_best_score);
  if (result.view_checked)
    std::printf("view_checked: true\nscan_coverage: %.4f\nmodel_coverage: %.4f\nfree_space_violation: %.4f\n"
                "true_symmetries: %d\n",
                result.view.target_coverage, result.view.model_coverage, result.view.free_space_violation,
                result.true_symmetries);
  std::printf("bases_tried: %d\ncandidates_verified: %d\n", result.bases_tried, result.candidates_verified);
  std::printf("success: %s\nreason: %s\n", result.success ? "true" : "false", result.reason.c_str());
}

void printJson(const RegistrationResult& result)
{
  const Eigen::Matrix4d m = result.source_to_target.matrix();
  std::printf("{\"source_to_target\": [");
  for (int r = 0; r < 4; ++r)
    std::printf("%s[%.9g, %.9g, %.9g, %.9g]", r ? ", " : "", m(r, 0), m(r, 1), m(r, 2), m(r, 3));
  std::printf("], \"lcp_score\": %.6g, \"confidence\": %.6g, \"second_best_score\": %.6g, \"view_checked\": %s, "
              "\"scan_coverage\": %.6g, \"model_coverage\": %.6g, \"free_space_violation\": %.6g, "
              "\"true_symmetries\": %d, \"time_ms\": %.4g, \"bases_tried\": %d, \"candidates_verified\": %d, "
              "\"success\": %s, \"reason\": \"%s\"}\n",
              result.lcp_score, result.confidence, result.second_best_score, result.view_checked ? "true" : "false",
              result.view.target_coverage, result.view.model_coverage, result.view.free_space_violation,
              result.true_symmetries, result.elapsed_s * 1e3, result.bases_tried, result.candidates_verified,
              result.success ? "true" : "false", jsonEscaped(result.reason).c_str());
}
}  // namespace

int main(int argc, char** argv)
{
  Options options;
  try
  {
    options = parseArguments(std::vector<std::string>(argv + 1, argv + argc));
  }
  catch (const brick_pose::ConfigError& e)
  {
    std::cerr << "brick_pose_register: " << e.what() << "\n\n";
    printUsage(std::cerr);
    return kExitUsage;
  }
  if (options.help)
  {
    printUsage(std::cout);
    return kExitRegistered;
  }

  try
  {
    using namespace brick_pose::registration;
    const LoadedCloud source = loadCloudFile(options.source_path);
    const LoadedCloud target = loadCloudFile(options.target_path);
    for (const auto* loaded : {&source, &target})
      if (loaded->dropped_non_finite > 0)
        std::cerr << "brick_pose_register: note: dropped " << loaded->dropped_non_finite << " NaN/Inf point(s) from "
                  << (loaded == &source ? options.source_path : options.target_path) << "\n";
    const RegistrationResult result = Super4PCS(options.params).align(source.cloud, target.cloud);
    if (options.json)
      printJson(result);
    else
      printText(result);
    if (!result.success)
      std::cerr << "brick_pose_register: not registered: " << result.reason << "\n";
    return result.success ? kExitRegistered : kExitNotRegistered;
  }
  catch (const brick_pose::InputError& e)
  {
    std::cerr << "brick_pose_register: " << e.what() << "\n";
    return kExitUsage;
  }
  catch (const brick_pose::ConfigError& e)
  {
    std::cerr << "brick_pose_register: " << e.what() << "\n";
    return kExitUsage;
  }
}
