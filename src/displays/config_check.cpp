#include "rviz_projector/displays/config_check.h"

#include <cmath>

#include <rviz/config.h>
#include <rviz/properties/float_property.h>
#include <rviz/properties/property.h>

namespace rviz_projector
{
void ConfigCheck::number(const rviz::Config& value, rviz::Property* property)
{
  if (!value.isValid() || value.getType() != rviz::Config::Value)
  {
    return;
  }
  const QString text = value.getValue().toString();
  bool ok = false;
  const double wanted = text.trimmed().toDouble(&ok);
  const double used = property->getValue().toDouble();
  const double tolerance = 1e-5 * std::max(1.0, std::abs(used));
  if (!ok || !std::isfinite(wanted) || std::abs(wanted - used) > tolerance)
  {
    // Floats print with 6 significant digits ("0.01", not "0.009999999776482582").
    problems_ << QString("%1: '%2' -> %3").arg(property->getName(), text, QString::number(used, 'g', 6));
  }
}

void ConfigCheck::choice(const rviz::Config& value, rviz::Property* property, const QStringList& options,
                         const QString& fallback)
{
  const QString current = property->getValue().toString();
  if (options.contains(current))
  {
    return;
  }
  property->setValue(fallback);
  problems_ << QString("%1: '%2' -> %3").arg(property->getName(), value.isValid() ? value.getValue().toString() : current,
                                            fallback);
}
rviz::FloatProperty* boundedFloat(const QString& name, float value, float min, float max, const QString& help,
                                  rviz::Property* parent, rviz::Display* display, const char* slot)
{
  auto* property = new rviz::FloatProperty(name, value, help, parent, slot, display);
  property->setMin(min);
  property->setMax(max);
  return property;
}

double decimal(const rviz::FloatProperty* p)
{
  return std::round(static_cast<double>(p->getFloat()) * 1e6) / 1e6;
}
}  // namespace rviz_projector
