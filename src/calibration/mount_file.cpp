#include "rviz_projector/calibration/mount_file.h"

#include "rviz_projector/calibration/number_format.h"

#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "rviz_projector/calibration/calibration_file_yaml.h"

namespace rviz_projector
{
namespace
{
std::string readNumber(const YAML::Node& doc, const char* field, const char* unit, double& value)
{
  const YAML::Node node = doc[field];
  if (!node)
  {
    return std::string("missing field '") + field + "' (" + unit + ")";
  }
  const std::string problem = yamlFiniteNumberProblem(node, value);
  return problem.empty() ? problem : std::string("field '") + field + "' " + problem;
}

std::string readDocument(const YAML::Node& doc, MountFile& out)
{
  if (doc.IsNull())
  {
    return "the file is empty (calibrate_projector --output writes a mount file)";
  }
  if (!doc.IsMap())
  {
    return "expected a map with parent_frame, x, y, z, roll, pitch, yaw, got " + describeYamlNode(doc);
  }
  const std::string frame_error = readYamlFrameName(
      doc, "parent_frame", "the frame the projector is mounted on, e.g. base_link", out.parent_frame);
  if (!frame_error.empty())
  {
    return frame_error;
  }
  struct Field
  {
    const char* name;
    const char* unit;
    double* value;
  };
  const Field fields[] = {
      {"x", "metres", &out.mount.x},        {"y", "metres", &out.mount.y},
      {"z", "metres", &out.mount.z},        {"roll", "radians", &out.mount.roll},
      {"pitch", "radians", &out.mount.pitch}, {"yaw", "radians", &out.mount.yaw},
  };
  for (const Field& field : fields)
  {
    const std::string error = readNumber(doc, field.name, field.unit, *field.value);
    if (!error.empty())
    {
      return error;
    }
  }
  return "";
}
}  // namespace

std::string mountFileYaml(const std::string& parent_frame, const MountSolution& solution,
                          const std::string& header_comment)
{
  const ProjectorMount& m = solution.mount;
  std::ostringstream text;
  text << header_comment << "parent_frame: " << parent_frame << "\n"
       << "x: " << fixedDecimals(m.x, 6) << "\n"
       << "y: " << fixedDecimals(m.y, 6) << "\n"
       << "z: " << fixedDecimals(m.z, 6) << "\n"
       << "roll: " << fixedDecimals(m.roll, 8) << "\n"
       << "pitch: " << fixedDecimals(m.pitch, 8) << "\n"
       << "yaw: " << fixedDecimals(m.yaw, 8) << "\n"
       << "rms_px: " << fixedDecimals(solution.rms_px, 3) << "\n"
       << "rms_mm: " << fixedDecimals(solution.rms_mm, 2) << "\n"
       << "outliers: [";
  for (std::size_t i = 0; i < solution.outliers.size(); ++i)
  {
    text << (i == 0 ? "" : ", ") << solution.outliers[i];
  }
  text << "]\nresiduals: [";
  for (std::size_t i = 0; i < solution.residuals.size(); ++i)
  {
    const PointResidual& r = solution.residuals[i];
    text << (i == 0 ? "" : ", ") << "{id: " << r.id << ", px: " << fixedDecimals(r.px, 3) << ", mm: " << fixedDecimals(r.mm, 2)
         << "}";
  }
  text << "]\n";
  return text.str();
}

std::string readMountFile(const std::string& path, MountFile& out)
{
  out = MountFile();
  YAML::Node doc;
  if (const std::string problem = readYamlFile(path, doc); !problem.empty())
  {
    return problem;
  }
  const std::string error = readDocument(doc, out);
  if (!error.empty())
  {
    out = MountFile();
    return path + ": " + error;
  }
  return "";
}
}  // namespace rviz_projector
