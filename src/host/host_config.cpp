#include "host_config.h"

#include <map>

#include <QFileInfo>
#include <rviz/display.h>
#include <rviz/display_factory.h>
#include <rviz/properties/bool_property.h>
#include <rviz/properties/color_property.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/int_property.h>
#include <rviz/properties/parse_color.h>
#include <rviz/yaml_config_reader.h>

namespace rviz_projector
{
namespace
{
constexpr const char* kProjectorClass = "rviz_projector/ProjectorCamera";
constexpr const char* kGroupClass = "rviz/Group";

std::string str(const QString& s)
{
  return s.toStdString();
}

/// Why `value` cannot be the value of `property`; empty when it can.
QString valueProblem(const rviz::Property* property, const QVariant& value)
{
  const QString text = value.toString();
  bool ok = false;
  if (qobject_cast<const rviz::FloatProperty*>(property))
  {
    text.toDouble(&ok);
    return ok ? QString() : QString("'%1' is not a number").arg(text);
  }
  if (qobject_cast<const rviz::IntProperty*>(property))
  {
    text.toLongLong(&ok);
    return ok ? QString() : QString("'%1' is not a whole number").arg(text);
  }
  if (qobject_cast<const rviz::BoolProperty*>(property))
  {
    const QString lower = text.trimmed().toLower();
    return lower == "true" || lower == "false" ? QString() : QString("'%1' is not true or false").arg(text);
  }
  if (qobject_cast<const rviz::ColorProperty*>(property))
  {
    return rviz::parseColor(text).isValid() ? QString() : QString("'%1' is not a colour (R; G; B)").arg(text);
  }
  return QString();
}

rviz::Property* childNamed(const rviz::Property* parent, const QString& name)
{
  for (int i = 0; i < parent->numChildren(); ++i)
  {
    if (parent->childAt(i)->getName() == name)
    {
      return parent->childAt(i);
    }
  }
  return nullptr;
}

/// The first property value of `config` (a display's map) that its class cannot hold.
QString firstBadValue(const rviz::Property* property, rviz::Config config, const QString& path)
{
  for (rviz::Config::MapIterator it = config.mapIterator(); it.isValid(); it.advance())
  {
    const QString key = it.currentKey();
    const rviz::Property* child = childNamed(property, key);
    if (!child)
    {
      continue;  // rviz ignores keys it does not know (older configs): so does the host
    }
    rviz::Config value = it.currentChild();
    const QString where = path.isEmpty() ? key : path + "/" + key;
    if (value.getType() == rviz::Config::Map)
    {
      const QString nested = firstBadValue(child, value, where);
      if (!nested.isEmpty())
      {
        return nested;
      }
    }
    else if (value.getType() == rviz::Config::Value)
    {
      const QString problem = valueProblem(child, value.getValue());
      if (!problem.isEmpty())
      {
        return where + ": " + problem;
      }
    }
  }
  return QString();
}

class Checker
{
public:
  Checker(rviz::DisplayFactory& factory, MissingPlugin missing, HostConfigCheck& out)
    : factory_(factory), missing_(missing), out_(out), known_(factory.getDeclaredClassIds())
  {
  }

  void displays(rviz::Config list)
  {
    for (int i = 0; i < list.listLength() && out_.error.empty(); ++i)
    {
      display(list.listChildAt(i));
    }
  }

private:
  void display(rviz::Config config)
  {
    HostConfigDisplay entry;
    if (config.getType() != rviz::Config::Map || !config.mapGetString("Class", &entry.class_id) ||
        entry.class_id.isEmpty())
    {
      out_.error = "a display has no 'Class'";
      return;
    }
    config.mapGetString("Name", &entry.name);
    config.mapGetBool("Enabled", &entry.enabled);
    const QString label = QString("display '%1' (%2)").arg(entry.name, entry.class_id);
    entry.available = entry.class_id == kGroupClass || known_.contains(entry.class_id);
    out_.displays.push_back(entry);
    if (entry.class_id == kProjectorClass)
    {
      ++out_.projectors;
    }
    if (entry.class_id == kGroupClass)
    {
      displays(config.mapGetChild("Displays"));
      return;
    }
    if (!entry.available)
    {
      const std::string problem = str(label) + ": the plugin is not installed";
      if (missing_ == MissingPlugin::Refuse)
      {
        out_.error = problem;
      }
      else
      {
        out_.warnings.push_back(problem + "; the display is skipped");
      }
      return;
    }
    rviz::Display* prototype = prototypeOf(entry.class_id);
    if (!prototype)
    {
      const std::string problem = str(label) + ": the plugin cannot be loaded (" + str(load_errors_[entry.class_id]) + ")";
      if (missing_ == MissingPlugin::Refuse)
      {
        out_.error = problem;
      }
      else
      {
        out_.warnings.push_back(problem + "; the display is skipped");
      }
      return;
    }
    const QString bad = firstBadValue(prototype, config, QString());
    if (!bad.isEmpty())
    {
      out_.error = str(label) + ": " + str(bad);
    }
  }

  /// A display of `class_id` built (as rviz builds every display before it initialises it) and
  /// never initialised: no scene, no subscription, only its properties. Qt thread only.
  ///
  /// Deliberately never deleted: kept for the life of the process, one per class (a bounded set,
  /// reused by every later check). rviz's displays cannot be deleted uninitialised, and rviz itself
  /// never does it (it initialises every display it makes at once), so plugins need not support it:
  /// every MessageFilterDisplay (rviz/LaserScan, rviz/Path, rviz/PointCloud2, ...) clears its tf
  /// filter in its destructor, and that filter is made only by onInitialize(): deleting one
  /// dereferences a null pointer (tried with rviz 1.14: SIGSEGV). Initialising a prototype so that
  /// it can be deleted is no way out: that needs the running VisualizationManager (scene nodes, tf
  /// filters in the live scene), which a check must not touch. Not pluginlib: rviz makes its
  /// displays as unmanaged instances, after which class_loader never unloads a plugin library, so
  /// the prototypes' code stays loaded. doc/dev/decisions.md#projector_host says the same.
  rviz::Display* prototypeOf(const QString& class_id)
  {
    static auto* prototypes = new std::map<QString, rviz::Display*>();  // never freed: see above
    auto found = prototypes->find(class_id);
    if (found == prototypes->end())
    {
      QString error;
      rviz::Display* made = factory_.make(class_id, &error);
      load_errors_[class_id] = error;
      if (!made)
      {
        return nullptr;  // asked again next time: the plugin may have been installed meanwhile
      }
      found = prototypes->emplace(class_id, made).first;
    }
    return found->second;
  }

  rviz::DisplayFactory& factory_;
  MissingPlugin missing_;
  HostConfigCheck& out_;
  QStringList known_;
  std::map<QString, QString> load_errors_;
};
}  // namespace

HostConfigCheck checkHostConfig(const QString& path, rviz::DisplayFactory& factory, MissingPlugin missing)
{
  HostConfigCheck out;
  const std::string file = str(path);
  const QFileInfo info(path);
  if (!info.exists())
  {
    out.error = "config '" + file + "' does not exist";
    return out;
  }
  if (!info.isFile() || !info.isReadable())
  {
    out.error = "config '" + file + "' is not a readable file";
    return out;
  }
  rviz::Config config;
  rviz::YamlConfigReader reader;
  reader.readFile(config, path);
  if (reader.error())
  {
    out.error = "config '" + file + "' is not valid YAML: " + str(reader.errorMessage());
    return out;
  }
  rviz::Config manager = config.mapGetChild("Visualization Manager");
  if (!manager.isValid() || manager.getType() != rviz::Config::Map)
  {
    out.error = "config '" + file + "' is not an rviz config (no 'Visualization Manager')";
    return out;
  }
  Checker checker(factory, missing, out);
  checker.displays(manager.mapGetChild("Displays"));
  if (!out.error.empty())
  {
    out.error = "config '" + file + "': " + out.error;
    return out;
  }
  if (out.projectors == 0)
  {
    out.error = "config '" + file + "' has no rviz_projector/ProjectorCamera display: nothing to project";
    return out;
  }
  out.manager_config = manager;
  return out;
}
}  // namespace rviz_projector
