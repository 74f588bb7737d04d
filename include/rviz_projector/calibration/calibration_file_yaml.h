// YAML reading with messages that name what is wrong, shared by the package's file readers:
// the calibration (calibration_file), the calibration points and the mount file.
#pragma once

#include <string>

#include <yaml-cpp/yaml.h>

namespace rviz_projector
{
/// What a YAML node holds, for error messages: its text in quotes, or the kind of node it is.
std::string describeYamlNode(const YAML::Node& node);

/// Parses the file into `doc`: "" on success, otherwise "not valid YAML: line L, column C: ..." or
/// "cannot be read as YAML: ..." (without the path: the caller prefixes it).
std::string loadYamlFile(const std::string& path, YAML::Node& doc);
/// The points and mount files' reader: "" on success, otherwise the problem with the path in front:
/// "<path>: cannot be read (no such file, or no permission)" or "<path>: " + loadYamlFile's error.
std::string readYamlFile(const std::string& path, YAML::Node& doc);

/// The node as a number (a scalar yaml-cpp converts to double; .nan/.inf included); false otherwise.
bool yamlNumber(const YAML::Node& node, double& value);

/// "" when the node is a finite number (stored in `value`), else "is not a number (got ...)" or
/// "is not finite (got ...)": the caller prefixes the field.
std::string yamlFiniteNumberProblem(const YAML::Node& node, double& value);

/// Reads `doc[field]`, a frame name, into `out`: "" on success, else "missing field 'F' (<what>)"
/// or "field 'F' must be a frame name, e.g. base_link (got ...)".
std::string readYamlFrameName(const YAML::Node& doc, const std::string& field, const std::string& what,
                              std::string& out);
}  // namespace rviz_projector
