// Checks what a display made of the values in a loaded .rviz config: numbers that were not usable
// (clamped or replaced) and choices that do not exist, so the display can say so in a status.
#pragma once

#include <QString>
#include <QStringList>

namespace rviz
{
class Config;
class Display;
class FloatProperty;
class Property;
}  // namespace rviz

namespace rviz_projector
{
class ConfigCheck
{
public:
  /// `value` is the property's entry in the display's config (absent entries are fine).
  void number(const rviz::Config& value, rviz::Property* property);
  /// A choice outside `options` is replaced by `fallback`.
  void choice(const rviz::Config& value, rviz::Property* property, const QStringList& options,
              const QString& fallback);
  /// One line per adjusted value ("Spacing: -3 -> 0.01"), empty when everything was usable.
  QString report() const { return problems_.join("; "); }

private:
  QStringList problems_;
};

/// A float property limited to [min, max] whose changes call `slot` (SLOT(...)) of `display`: the
/// cue groups' numbers.
rviz::FloatProperty* boundedFloat(const QString& name, float value, float min, float max, const QString& help,
                                  rviz::Property* parent, rviz::Display* display, const char* slot);
/// A float property's value rounded to 6 decimals (as typed), as a double.
double decimal(const rviz::FloatProperty* p);
}  // namespace rviz_projector
