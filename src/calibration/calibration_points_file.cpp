#include "rviz_projector/calibration/calibration_points_file.h"

#include "rviz_projector/calibration/number_format.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "rviz_projector/calibration/calibration_file_yaml.h"

namespace rviz_projector
{
namespace
{
/// "3" from a list of ids: "1, 4, 7".
std::string idList(const std::vector<int>& ids)
{
  std::string text;
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    text += (i == 0 ? "" : ", ") + std::to_string(ids[i]);
  }
  return text;
}

/// Reads one entry of `points`. Returns "" or the problem (without the file name). `measured` is
/// false when x or y is still null (or left out).
class EntryReader
{
public:
  EntryReader(const YAML::Node& entry, std::size_t index) : entry_(entry), index_(index) {}

  std::string where() const
  {
    std::string text = "entry " + std::to_string(index_ + 1) + " of 'points'";
    return has_id_ ? "point " + std::to_string(id_) + " (" + text + ")" : text;
  }

  std::string read(const std::vector<Crosshair>& pattern, const std::string& pattern_name, FloorPoint& point,
                   bool& measured)
  {
    if (!entry_.IsMap())
    {
      return where() + " must be a map like {id: 1, u: 192.0, v: 120.0, x: 2.013, y: 0.871} (got " +
             describeYamlNode(entry_) + ")";
    }
    std::string error = readId();
    if (!error.empty())
    {
      return error;
    }
    for (const auto& key_value : entry_)
    {
      const std::string key = key_value.first.IsScalar() ? key_value.first.Scalar() : "?";
      if (key != "id" && key != "u" && key != "v" && key != "x" && key != "y" && key != "z")
      {
        return where() + ": unknown field '" + key + "' (expected id, u, v, x, y and optionally z)";
      }
    }
    point.id = id_;
    const YAML::Node u = entry_["u"];
    const YAML::Node v = entry_["v"];
    if (static_cast<bool>(u) != static_cast<bool>(v))
    {
      return where() + ": give both 'u' and 'v' (the crosshair's pixel) or neither (then they come from the "
                       "pattern by id)";
    }
    if (u)
    {
      if (!(error = number(u, "u", point.pixel.x)).empty() || !(error = number(v, "v", point.pixel.y)).empty())
      {
        return error;
      }
    }
    else
    {
      bool found = false;
      for (const Crosshair& crosshair : pattern)
      {
        if (crosshair.id == id_)
        {
          point.pixel = crosshair.pixel;
          found = true;
        }
      }
      if (!found)
      {
        return where() + ": unknown id " + std::to_string(id_) + ": " + pattern_name + " has ids 1.." +
               std::to_string(pattern.size()) + " (give the point's u and v, or the pattern's --rows/--cols)";
      }
    }
    measured = true;
    for (const char* key : {"x", "y"})
    {
      const YAML::Node value = entry_[key];
      if (!value || value.IsNull())
      {
        measured = false;
      }
    }
    if (measured)
    {
      if (!(error = metres(entry_["x"], "x", point.world.x)).empty() ||
          !(error = metres(entry_["y"], "y", point.world.y)).empty())
      {
        return error;
      }
    }
    point.world.z = 0.0;
    const YAML::Node z = entry_["z"];
    if (z && !z.IsNull())
    {
      return metres(z, "z", point.world.z);
    }
    return "";
  }

  int id() const { return id_; }

private:
  std::string readId()
  {
    const YAML::Node node = entry_["id"];
    if (!node)
    {
      return where() + " has no 'id' (the crosshair's number)";
    }
    double value = 0.0;
    if (!yamlNumber(node, value) || !std::isfinite(value) || value != std::floor(value) || value < 0.0 ||
        value > std::numeric_limits<int>::max())
    {
      return where() + ": 'id' must be a whole number >= 0, the crosshair's number (got " + describeYamlNode(node) + ")";
    }
    id_ = static_cast<int>(value);
    has_id_ = true;
    return "";
  }

  std::string number(const YAML::Node& node, const std::string& field, double& value) const
  {
    const std::string problem = yamlFiniteNumberProblem(node, value);
    return problem.empty() ? problem : where() + ": '" + field + "' " + problem;
  }

  std::string metres(const YAML::Node& node, const std::string& field, double& value) const
  {
    const std::string error = number(node, field, value);
    if (!error.empty())
    {
      return error;
    }
    if (std::abs(value) > kMaxPointCoordinate)
    {
      std::ostringstream text;
      text << where() << ": '" << field << "' is " << value << ", which looks like millimetres: the file is in "
           << "metres (|" << field << "| <= " << kMaxPointCoordinate << ")";
      return text.str();
    }
    return "";
  }

  const YAML::Node& entry_;
  std::size_t index_;
  int id_ = 0;
  bool has_id_ = false;
};

std::string readDocument(const YAML::Node& doc, const std::vector<Crosshair>& pattern,
                         const std::string& pattern_name, CalibrationPoints& out)
{
  if (doc.IsNull())
  {
    return "the file is empty (calibrate_projector --pattern writes a template)";
  }
  if (!doc.IsMap())
  {
    return "expected a map with 'frame' and 'points', got " + describeYamlNode(doc);
  }
  for (const auto& key_value : doc)
  {
    const std::string key = key_value.first.IsScalar() ? key_value.first.Scalar() : "?";
    if (key != "frame" && key != "points")
    {
      return "unknown field '" + key + "' (expected 'frame' and 'points')";
    }
  }
  const std::string frame_error =
      readYamlFrameName(doc, "frame", "the frame the points are measured in, e.g. base_link", out.frame);
  if (!frame_error.empty())
  {
    return frame_error;
  }
  const YAML::Node points = doc["points"];
  if (!points)
  {
    return "missing field 'points' (the list of measured crosshairs)";
  }
  if (!points.IsSequence())
  {
    return "field 'points' must be a list of {id, u, v, x, y} (got " + describeYamlNode(points) + ")";
  }
  std::map<int, std::size_t> entry_of_id;
  std::vector<int> not_measured;
  for (std::size_t i = 0; i < points.size(); ++i)
  {
    const YAML::Node entry = points[i];
    EntryReader reader(entry, i);
    FloorPoint point;
    bool measured = false;
    const std::string error = reader.read(pattern, pattern_name, point, measured);
    if (!error.empty())
    {
      return error;
    }
    const auto duplicate = entry_of_id.find(point.id);
    if (duplicate != entry_of_id.end())
    {
      return "duplicate id " + std::to_string(point.id) + " (entries " + std::to_string(duplicate->second + 1) +
             " and " + std::to_string(i + 1) + " of 'points')";
    }
    entry_of_id[point.id] = i;
    if (!measured)
    {
      not_measured.push_back(point.id);
    }
    out.points.push_back(point);
  }
  if (!not_measured.empty())
  {
    return std::string(not_measured.size() == 1 ? "point " : "points ") + idList(not_measured) +
           (not_measured.size() == 1 ? " is" : " are") +
           " not measured yet (x or y is null or missing): fill in x and y in metres, or delete the points you "
           "could not measure";
  }
  return "";
}

}  // namespace

std::string readCalibrationPoints(const std::string& path, const std::vector<Crosshair>& pattern,
                                  const std::string& pattern_name, CalibrationPoints& out)
{
  out = CalibrationPoints();
  YAML::Node doc;
  if (const std::string problem = readYamlFile(path, doc); !problem.empty())
  {
    return problem;
  }
  const std::string error = readDocument(doc, pattern, pattern_name, out);
  if (!error.empty())
  {
    out = CalibrationPoints();
    return path + ": " + error;
  }
  return "";
}

std::string calibrationPointsTemplate(const std::vector<Crosshair>& pattern, const std::string& frame,
                                      const std::string& header_comment)
{
  std::ostringstream text;
  text << header_comment << "frame: " << frame << "\n"
       << "points:\n";
  for (const Crosshair& crosshair : pattern)
  {
    text << "  - {id: " << crosshair.id << ", u: " << fixedDecimals(crosshair.pixel.x, 1)
         << ", v: " << fixedDecimals(crosshair.pixel.y, 1) << ", x: null, y: null}\n";
  }
  return text.str();
}

std::string calibrationPointsYaml(const CalibrationPoints& points, const std::string& header_comment)
{
  std::ostringstream text;
  text << header_comment << "frame: " << points.frame << "\n"
       << "points:\n";
  for (const FloorPoint& point : points.points)
  {
    text << "  - {id: " << point.id << ", u: " << fixedDecimals(point.pixel.x, 3) << ", v: " << fixedDecimals(point.pixel.y, 3)
         << ", x: " << fixedDecimals(point.world.x, 6) << ", y: " << fixedDecimals(point.world.y, 6)
         << ", z: " << fixedDecimals(point.world.z, 6) << "}\n";
  }
  return text.str();
}

std::string writeTextFile(const std::string& path, const std::string& text)
{
  return writeTextFiles({{path, text}});
}

std::string writeTextFiles(const std::vector<std::pair<std::string, std::string>>& files)
{
  std::vector<std::string> written;  // temporaries, removed again on any failure
  const auto fail = [&written](const std::string& error) {
    for (const std::string& temporary : written)
    {
      std::remove(temporary.c_str());
    }
    return error;
  };
  for (const auto& [path, text] : files)
  {
    const std::string temporary = path + ".tmp";
    std::ofstream file(temporary, std::ios::trunc);
    if (!file)
    {
      return fail(path + ": cannot be written (no such directory, or no permission)");
    }
    written.push_back(temporary);
    file << text;
    file.flush();
    if (!file)
    {
      return fail(path + ": writing failed (disk full?)");
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i)
  {
    if (std::rename(written[i].c_str(), files[i].first.c_str()) != 0)
    {
      // Only a rename in the same directory is left to fail here, and practically never does.
      written.erase(written.begin(), written.begin() + static_cast<std::ptrdiff_t>(i));
      return fail(files[i].first + ": cannot be written (rename of " + files[i].first + ".tmp failed)");
    }
  }
  return "";
}
}  // namespace rviz_projector
