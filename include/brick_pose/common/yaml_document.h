#pragma once
// Plain YAML files (the brick catalogue, a user's parameter file) read with
// OpenCV's FileStorage, guarded against the inputs its reader mishandles.

#include <map>
#include <string>

#include <opencv2/core.hpp>

#include "brick_pose/common/param_parsing.h"

namespace brick_pose
{
/// Opens YAML text whose root must be a map. `what` names the document in
/// errors ("brick catalogue"), `root_hint` says what its root should hold.
/// Throws ConfigError for an empty text, a root that is not a map, or text
/// OpenCV cannot parse.
cv::FileStorage openYamlDocument(const std::string& text, const std::string& what, const std::string& root_hint);

/// The whole file as text; throws ConfigError naming `what` and the path
/// when it cannot be read.
std::string readTextFile(const std::string& path, const std::string& what);

/// The top-level scalar (and list-of-scalar) keys of a YAML parameter file
/// such as config/pipeline.yaml, as text: numbers as written, lists joined
/// with commas. Nested maps are not parameters and are rejected (a key
/// nested under a nodelet's name only worked by accident). Throws
/// ConfigError naming the file and the key at fault.
std::map<std::string, std::string> readYamlParamFile(const std::string& path);
}  // namespace brick_pose
