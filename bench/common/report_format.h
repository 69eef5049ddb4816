#pragma once
// Number formatting of the benchmark reports: table cells and the one JSON
// line each benchmark prints last (scripts/bench.sh collects it).

#include <string>
#include <utility>
#include <vector>

namespace brick_pose
{
namespace bench
{
/// `value` printed with `format` (one double conversion), "n/a" for NaN.
std::string formatted(const char* format, double value);

/// A JSON number, "null" when not finite (no measurement).
std::string jsonNumber(double value);

/// A flat JSON object built field by field, printed on one line in the
/// order the fields were added.
class JsonLine
{
public:
  JsonLine& number(const std::string& key, double value);
  JsonLine& text(const std::string& key, const std::string& value);
  std::string str() const;

private:
  std::vector<std::pair<std::string, std::string>> fields_;  // key, encoded value
};
}  // namespace bench
}  // namespace brick_pose
