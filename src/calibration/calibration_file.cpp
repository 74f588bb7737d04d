#include "rviz_projector/calibration/calibration_file.h"

#include "rviz_projector/ros/ros_conversions.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <camera_calibration_parsers/parse.h>
#include <ros/package.h>
#include <yaml-cpp/yaml.h>

#include "rviz_projector/calibration/calibration_file_yaml.h"
#include "rviz_projector/core/ascii_lower.h"
#include "rviz_projector/core/pinhole_model.h"

namespace rviz_projector
{
namespace
{
const char* const kTemplateHint = " (rviz_projector's config/projector_template.yaml shows the format)";

std::string quoted(const std::string& field)
{
  return "'" + field + "'";
}

/// Reads a whole number; false when the node is not one.
bool wholeNumber(const YAML::Node& node, long long& value)
{
  if (!node.IsScalar())
  {
    return false;
  }
  try
  {
    value = node.as<long long>();
    return true;
  }
  catch (const YAML::Exception&)
  {
    return false;
  }
}

std::string checkImageSize(const YAML::Node& doc, const std::string& field)
{
  const YAML::Node node = doc[field];
  if (!node)
  {
    return "missing field " + quoted(field) + kTemplateHint;
  }
  long long value = 0;
  if (!wholeNumber(node, value))
  {
    return "field " + quoted(field) + " must be a whole number of pixels (got " + describeYamlNode(node) + ")";
  }
  if (value <= 0)
  {
    return field + " must be > 0 (got " + std::to_string(value) + ")";
  }
  if (value > static_cast<long long>(PinholeModel::kMaxResolution))
  {
    return field + " is " + std::to_string(value) + ", more than the " +
           std::to_string(PinholeModel::kMaxResolution) + " pixels rviz_projector supports";
  }
  return "";
}

/**
 * A matrix field: a map with whole-number `rows` and `cols` and a list `data` of rows x cols finite
 * numbers. `rows`/`cols` of -1 accept any size (distortion_coefficients).
 */
std::string checkMatrix(const YAML::Node& doc, const std::string& field, int rows, int cols)
{
  const YAML::Node node = doc[field];
  if (!node)
  {
    return "missing field " + quoted(field) + kTemplateHint;
  }
  if (!node.IsMap())
  {
    return "field " + quoted(field) + " must be a map with rows, cols and data (got " + describeYamlNode(node) + ")";
  }
  long long size[2] = {0, 0};
  const char* const keys[2] = {"rows", "cols"};
  for (int i = 0; i < 2; ++i)
  {
    const YAML::Node value = node[keys[i]];
    if (!value)
    {
      return "field " + quoted(field) + " has no '" + keys[i] + "'";
    }
    if (!wholeNumber(value, size[i]) || size[i] < 0)
    {
      return "field " + quoted(field) + ": '" + keys[i] + "' must be a whole number >= 0 (got " + describeYamlNode(value) +
             ")";
    }
  }
  if (rows >= 0 && (size[0] != rows || size[1] != cols))
  {
    std::ostringstream error;
    error << "field " << quoted(field) << " is " << size[0] << "x" << size[1] << ", expected " << rows << "x"
          << cols;
    return error.str();
  }
  const YAML::Node data = node["data"];
  if (!data)
  {
    return "field " + quoted(field) + " has no 'data'";
  }
  if (!data.IsSequence())
  {
    return "field " + quoted(field) + ": 'data' must be a list of numbers (got " + describeYamlNode(data) + ")";
  }
  // rows x cols can exceed long long (both up to 2^63 - 1): compare without multiplying when it would.
  const bool fits = size[1] == 0 || size[0] <= std::numeric_limits<long long>::max() / size[1];
  const long long expected = fits ? size[0] * size[1] : 0;
  if (!fits || static_cast<long long>(data.size()) != expected)
  {
    std::ostringstream error;
    error << "field " << quoted(field) << ": 'data' has " << data.size() << " numbers, expected rows x cols = "
          << size[0] << " x " << size[1];
    if (fits)
    {
      error << " = " << expected;
    }
    return error.str();
  }
  for (std::size_t i = 0; i < data.size(); ++i)
  {
    double value = 0.0;
    bool number = data[i].IsScalar();
    if (number)
    {
      try
      {
        value = data[i].as<double>();
      }
      catch (const YAML::Exception&)
      {
        number = false;
      }
    }
    if (!number)
    {
      return "field " + quoted(field) + ": data[" + std::to_string(i) + "] is not a number (got " +
             describeYamlNode(data[i]) + ")";
    }
    if (!std::isfinite(value))
    {
      return "field " + quoted(field) + ": data[" + std::to_string(i) + "] is not finite (got " +
             describeYamlNode(data[i]) + ")";
    }
  }
  return "";
}

std::string checkText(const YAML::Node& doc, const std::string& field)
{
  const YAML::Node node = doc[field];
  if (node && !node.IsScalar())
  {
    return "field " + quoted(field) + " must be a text (got " + describeYamlNode(node) + ")";
  }
  return "";
}

/// Checks the structure camera_calibration_parsers' YAML reader relies on, naming the field at fault.
std::string checkYaml(const std::string& path, std::vector<std::string>& warnings)
{
  YAML::Node doc;
  const std::string yaml_error = loadYamlFile(path, doc);
  if (!yaml_error.empty())
  {
    return yaml_error;
  }
  if (doc.IsNull())
  {
    return std::string("the file is empty") + kTemplateHint;
  }
  if (!doc.IsMap())
  {
    return "expected a map of calibration fields (image_width, image_height, camera_matrix, ...), got " +
           describeYamlNode(doc);
  }
  const YAML::Node& root = doc;
  for (const char* field : {"image_width", "image_height"})
  {
    const std::string error = checkImageSize(root, field);
    if (!error.empty())
    {
      return error;
    }
  }
  const std::string errors[] = {
      checkMatrix(root, "camera_matrix", 3, 3),
      checkMatrix(root, "distortion_coefficients", -1, -1),
      checkMatrix(root, "rectification_matrix", 3, 3),
      checkMatrix(root, "projection_matrix", 3, 4),
      checkText(root, "distortion_model"),
      checkText(root, "camera_name"),
  };
  for (const std::string& error : errors)
  {
    if (!error.empty())
    {
      return error;
    }
  }
  if (!root["distortion_model"])
  {
    warnings.push_back("no field 'distortion_model': assuming plumb_bob");
  }
  return "";
}

std::string lowerExtension(const std::string& path)
{
  return asciiLower(std::filesystem::path(path).extension().string());
}

bool near(double a, double b)
{
  return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
}

/// Remarks on numbers that are legal but unusual for a projector.
void addLensWarnings(const sensor_msgs::CameraInfo& info, std::vector<std::string>& warnings)
{
  const auto& K = info.K;
  const auto& P = info.P;
  if (!near(K[0], P[0]) || !near(K[4], P[5]) || !near(K[2], P[2]) || !near(K[5], P[6]))
  {
    std::ostringstream warning;
    warning << "camera_matrix (K: fx " << K[0] << ", fy " << K[4] << ", cx " << K[2] << ", cy " << K[5]
            << ") and projection_matrix (P: fx " << P[0] << ", fy " << P[5] << ", cx " << P[2] << ", cy " << P[6]
            << ") disagree; the projector displays use P, so give both the same numbers";
    warnings.push_back(warning.str());
  }
  const std::array<double, 9> identity = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  if (!std::equal(identity.begin(), identity.end(), info.R.begin(), [](double a, double b) { return near(a, b); }))
  {
    warnings.push_back("rectification_matrix is not the identity; the projector displays ignore it");
  }
}
}  // namespace

std::string inDirectory(const std::string& path, const std::string& base)
{
  return path.empty() || path[0] == '/' || base.empty() ? path : base + "/" + path;
}

std::string resolveCalibrationUrl(const std::string& url, std::string& path)
{
  static const std::string kPackage = "package://";
  static const std::string kFile = "file://";
  path.clear();
  if (url.empty())
  {
    return "no file given";
  }
  if (url.compare(0, kPackage.size(), kPackage) == 0)
  {
    const std::string rest = url.substr(kPackage.size());
    const std::size_t slash = rest.find('/');
    if (slash == 0 || slash == std::string::npos || slash + 1 == rest.size())
    {
      return "expected package://<package>/<path inside the package>";
    }
    const std::string package = rest.substr(0, slash);
    const std::string package_path = ros::package::getPath(package);
    if (package_path.empty())
    {
      return "package '" + package + "' not found (is its workspace sourced?)";
    }
    path = package_path + rest.substr(slash);
    return "";
  }
  if (url.compare(0, kFile.size(), kFile) == 0)
  {
    path = url.substr(kFile.size());
    if (path.empty() || path[0] != '/')
    {
      path.clear();
      return "expected file:///<absolute path>";
    }
    return "";
  }
  const std::size_t scheme = url.find("://");
  if (scheme != std::string::npos)
  {
    return "unsupported URL scheme '" + url.substr(0, scheme + 3) + "' (use a path, package:// or file://)";
  }
  path = url;
  return "";
}

std::string loadCalibrationFile(const std::string& url, CalibrationFile& out)
{
  out = CalibrationFile();
  std::string path;
  const std::string url_error = resolveCalibrationUrl(url, path);
  if (!url_error.empty())
  {
    return url + ": " + url_error;
  }
  out.path = path;
  // Name the file the way the user wrote it, plus the path it resolved to when that differs.
  const std::string name = path == url ? path : url + " (" + path + ")";

  std::error_code ec;
  const std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
  {
    std::string error = name + ": file not found";
    if (!path.empty() && path[0] != '/')
    {
      error += " (a relative path is taken from the node's working directory, " +
               std::filesystem::current_path(ec).string() + "; use an absolute path, $(find <package>)/... or "
               "package://)";
    }
    return error;
  }
  if (std::filesystem::is_directory(status))
  {
    return name + ": is a directory, not a calibration file";
  }
  if (!std::ifstream(path).good())
  {
    return name + ": cannot be read (check its permissions)";
  }

  const std::string extension = lowerExtension(path);
  if (extension == ".yaml" || extension == ".yml")
  {
    const std::string error = checkYaml(path, out.warnings);
    if (!error.empty())
    {
      return name + ": " + error;
    }
  }
  else if (extension != ".ini")
  {
    return name + ": unsupported file type '" + extension +
           "' (expected a .yaml or .yml calibration file in the camera_calibration_parsers format)";
  }

  if (!camera_calibration_parsers::readCalibration(path, out.camera_name, out.info))
  {
    return name + ": camera_calibration_parsers could not read it (see its message above)";
  }

  PinholeModel model;
  const LensCheck check = PinholeModel::fromCalibration(toLensCalibration(out.info), model);
  if (!check.ok())
  {
    return name + ": unusable calibration: " + check.error;
  }
  if (!check.warning.empty())
  {
    out.warnings.push_back(check.warning);
  }
  addLensWarnings(out.info, out.warnings);
  return "";
}
}  // namespace rviz_projector
