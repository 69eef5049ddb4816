#include "brick_pose/common/yaml_document.h"

#include <cctype>
#include <fstream>
#include <map>
#include <sstream>

#include "brick_pose/common/errors.h"

namespace brick_pose
{
namespace
{
// OpenCV's FileStorage reads YAML only after its "%YAML:1.0" directive, which
// rosparam's YAML loader rejects. Files stay plain YAML; the directive is
// added here in memory.
/// "---" alone (trailing blanks or a comment allowed); "----x" is content.
bool isDocumentMarker(const std::string& line)
{
  if (line.rfind("---", 0) != 0) return false;
  const std::size_t rest = line.find_first_not_of(" \t\r", 3);
  return rest == std::string::npos || (rest > 3 && line[rest] == '#');
}

/// The first line that holds content: not blank, not a comment, not a
/// directive (%...) and not a document marker.
std::string firstContentLine(const std::string& text)
{
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line))
  {
    const std::size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#' || line[0] == '%' || isDocumentMarker(line))
      continue;
    return line;
  }
  return "";
}

/// Rejects a root that is not a map before OpenCV parses it: OpenCV 4.6's
/// YAML reader loops forever on some roots that start with an indented
/// sequence, a line of dashes or a tag (e.g. " - 0\nb%\n-" and
/// "---\n!- -\n-", found by fuzz_catalogue_yaml), and the documents read here
/// always have a map at their root.
void requireMapRoot(const std::string& text, const std::string& what, const std::string& root_hint)
{
  const std::string line = firstContentLine(text);
  if (line.empty()) throw ConfigError(what + ": empty, expected " + root_hint);
  // A key starts the root map: a letter, '_', a quote, or a flow map's '{'.
  // Tags, anchors, sequences and indentation are not a map's key.
  const unsigned char first = static_cast<unsigned char>(line[0]);
  if (!(std::isalpha(first) || first == '_' || first == '"' || first == '\'' || first == '{'))
    throw ConfigError(what + ": the root must be a map with " + root_hint + ", found '" + line.substr(0, 40) + "'");
}
/// YAML comments removed: a '#' at the start of a line or after white space,
/// outside quotes, to the end of its line. OpenCV's reader keeps a comment
/// after a plain scalar as part of the value ("hsv   # mode" would be the
/// mode's name).
std::string withoutComments(const std::string& text)
{
  std::string result;
  result.reserve(text.size());
  char quote = 0;
  bool in_comment = false;
  for (std::size_t i = 0; i < text.size(); ++i)
  {
    const char c = text[i];
    if (c == '\n')
    {
      in_comment = false;
      quote = 0;
      result += c;
      continue;
    }
    if (in_comment) continue;
    if (quote != 0)
    {
      if (c == quote) quote = 0;
    }
    else if (c == '"' || c == '\'')
      quote = c;
    else if (c == '#' && (i == 0 || text[i - 1] == ' ' || text[i - 1] == '\t' || text[i - 1] == '\n'))
    {
      in_comment = true;
      // Trailing blanks before the comment are not part of the value either.
      while (!result.empty() && (result.back() == ' ' || result.back() == '\t')) result.pop_back();
      continue;
    }
    result += c;
  }
  return result;
}
}  // namespace

cv::FileStorage openYamlDocument(const std::string& text, const std::string& what, const std::string& root_hint)
{
  requireMapRoot(text, what, root_hint);
  const std::string directive = "%YAML:1.0\n";
  const bool has_directive = text.rfind("%YAML", 0) == 0;
  const std::string content = withoutComments(text);
  try
  {
    return cv::FileStorage(has_directive ? content : directive + content,
                           cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
  }
  catch (const cv::Exception& e)
  {
    throw ConfigError(what + ": not valid YAML: " + e.what());
  }
  catch (const std::exception& e)
  {
    // OpenCV's YAML reader also fails with standard exceptions (e.g.
    // std::length_error on an unterminated flow map).
    throw ConfigError(what + ": not valid YAML: " + e.what());
  }
}

std::string readTextFile(const std::string& path, const std::string& what)
{
  std::ifstream file(path);
  if (!file) throw ConfigError(what + ": cannot read '" + path + "'");
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

namespace
{
/// A scalar node as the text a rosparam lookup would give.
std::string scalarText(const cv::FileNode& node)
{
  if (node.isInt()) return std::to_string(static_cast<int>(node));
  if (node.isReal())
  {
    std::ostringstream text;
    text.precision(17);
    text << static_cast<double>(node);
    return text.str();
  }
  return static_cast<std::string>(node);
}
}  // namespace

std::map<std::string, std::string> readYamlParamFile(const std::string& path)
{
  const std::string what = "parameter file " + path;
  cv::FileStorage storage = openYamlDocument(readTextFile(path, what), what, "parameter names as keys");
  std::map<std::string, std::string> values;
  try
  {
    const cv::FileNode root = storage.root();
    for (const cv::FileNode& node : root)
    {
      const std::string name = node.name();
      if (node.isMap()) throw ConfigError(what + ": '" + name + "' is a map; parameters are top-level keys");
      if (node.isSeq())
      {
        std::string joined;
        for (const cv::FileNode& item : node)
        {
          if (item.isMap() || item.isSeq()) throw ConfigError(what + ": '" + name + "' holds a nested list or map");
          joined += (joined.empty() ? "" : ",") + scalarText(item);
        }
        values[name] = joined;
      }
      else
        values[name] = scalarText(node);
    }
  }
  catch (const cv::Exception& e)
  {
    throw ConfigError(what + ": unreadable: " + e.what());
  }
  return values;
}
}  // namespace brick_pose
