#include "host_display_status.h"

#include <rviz/display.h>
#include <rviz/properties/status_list.h>
#include <rviz/properties/status_property.h>

namespace rviz_projector
{
std::vector<DisplayStatusLine> displayStatusLines(const rviz::Display& display)
{
  std::vector<DisplayStatusLine> lines;
  for (int i = 0; i < display.numChildren(); ++i)
  {
    const auto* list = qobject_cast<const rviz::StatusList*>(display.childAt(i));
    if (!list)
    {
      continue;
    }
    for (int j = 0; j < list->numChildren(); ++j)
    {
      const auto* item = qobject_cast<const rviz::StatusProperty*>(list->childAt(j));
      if (item)
      {
        lines.push_back({item->getName().toStdString(), static_cast<int>(item->getLevel()),
                         item->getValue().toString().toStdString()});
      }
    }
  }
  return lines;
}

std::string displayLabel(const rviz::Display& display)
{
  return display.getName().toStdString() + " (" + display.getClassId().toStdString() + ")";
}
}  // namespace rviz_projector
