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

/// The node as a number (a scalar yaml-cpp converts to double; .nan/.inf included); false otherwise.
bool yamlNumber(const YAML::Node& node, double& value);
}  // namespace rviz_projector
