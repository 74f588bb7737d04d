#include "rviz_projector/displays/status_cache.h"

namespace rviz_projector
{
bool StatusCache::set(int level, const QString& name, const QString& text)
{
  const auto it = statuses_.find(name);
  if (it != statuses_.end())
  {
    if (it->second.level == level && it->second.text == text)
    {
      return false;
    }
    it->second.level = level;
    it->second.text = text;
    return true;
  }
  statuses_.emplace(name, Shown{ level, text });
  return true;
}

bool StatusCache::remove(const QString& name)
{
  return statuses_.erase(name) > 0;
}

QString StatusCache::text(const QString& name) const
{
  const auto it = statuses_.find(name);
  return it == statuses_.end() ? QString() : it->second.text;
}
}  // namespace rviz_projector
