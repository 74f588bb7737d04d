#include "rviz_projector/calibration/calibration_file_yaml.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace rviz_projector
{
std::string describeYamlNode(const YAML::Node& node)
{
  switch (node.Type())
  {
    case YAML::NodeType::Scalar:
      return "'" + node.Scalar() + "'";
    case YAML::NodeType::Sequence:
      return "a list";
    case YAML::NodeType::Map:
      return "a map";
    case YAML::NodeType::Null:
      return "nothing";
    default:
      return "an undefined value";
  }
}

std::string loadYamlFile(const std::string& path, YAML::Node& doc)
{
  try
  {
    doc = YAML::LoadFile(path);
  }
  catch (const YAML::ParserException& e)
  {
    std::ostringstream error;
    error << "not valid YAML: line " << e.mark.line + 1 << ", column " << e.mark.column + 1 << ": " << e.msg;
    return error.str();
  }
  catch (const YAML::Exception& e)
  {
    return std::string("cannot be read as YAML: ") + e.what();
  }
  return "";
}

std::string readYamlFile(const std::string& path, YAML::Node& doc)
{
  if (!std::ifstream(path).good())
  {
    return path + ": cannot be read (no such file, or no permission)";
  }
  const std::string yaml_error = loadYamlFile(path, doc);
  return yaml_error.empty() ? yaml_error : path + ": " + yaml_error;
}

bool yamlNumber(const YAML::Node& node, double& value)
{
  if (!node.IsScalar())
  {
    return false;
  }
  try
  {
    value = node.as<double>();
    return true;
  }
  catch (const YAML::Exception&)
  {
    return false;
  }
}

std::string yamlFiniteNumberProblem(const YAML::Node& node, double& value)
{
  if (!yamlNumber(node, value))
  {
    return "is not a number (got " + describeYamlNode(node) + ")";
  }
  if (!std::isfinite(value))
  {
    return "is not finite (got " + describeYamlNode(node) + ")";
  }
  return "";
}

std::string readYamlFrameName(const YAML::Node& doc, const std::string& field, const std::string& what,
                              std::string& out)
{
  const YAML::Node frame = doc[field];
  if (!frame)
  {
    return "missing field '" + field + "' (" + what + ")";
  }
  if (!frame.IsScalar() || frame.Scalar().empty())
  {
    return "field '" + field + "' must be a frame name, e.g. base_link (got " + describeYamlNode(frame) + ")";
  }
  out = frame.Scalar();
  return "";
}
}  // namespace rviz_projector
