#include "rviz_projector/displays/projection_gate.h"

#include "rviz_projector/core/fnv_hash.h"

#include <algorithm>

#include <rviz/display.h>
#include <rviz/display_group.h>
#include <rviz/properties/display_group_visibility_property.h>
#include <rviz/properties/display_visibility_property.h>

#include "rviz_projector/displays/scene_signature.h"

namespace rviz_projector
{
namespace
{
/// Reads which display a visibility entry belongs to (rviz keeps it in a protected member; a
/// pointer to member taken through a derived class is the legal way to read it).
struct VisibilityEntry : rviz::DisplayVisibilityProperty
{
  static rviz::Display* displayOf(const rviz::DisplayVisibilityProperty& entry)
  {
    return entry.*(&VisibilityEntry::display_);
  }
};

const rviz::DisplayVisibilityProperty* asEntry(const rviz::Property* p)
{
  return qobject_cast<const rviz::DisplayVisibilityProperty*>(p);
}

void mix(std::uint64_t& hash, std::uint64_t value)
{
  fnv1aMix(hash, value);
}

void signatureOf(const rviz::Property* entries, std::uint64_t& hash)
{
  for (int i = 0; i < entries->numChildren(); ++i)
  {
    const rviz::DisplayVisibilityProperty* entry = asEntry(entries->childAt(i));
    if (!entry)
    {
      continue;
    }
    const rviz::Display* display = VisibilityEntry::displayOf(*entry);
    mix(hash, reinterpret_cast<std::uintptr_t>(display));
    mix(hash, (display->isEnabled() ? 2u : 0u) | (entry->getValue().toBool() ? 1u : 0u));
    signatureOf(entry, hash);  // a display group's own entries
  }
}

/// Calls `visit` for each ticked, enabled display not from this package, groups walked into, in
/// list order, until `visit` returns true (then true).
template <typename Visit>
bool visitShownForeign(const rviz::Property* entries, const Visit& visit)
{
  for (int i = 0; i < entries->numChildren(); ++i)
  {
    const rviz::DisplayVisibilityProperty* entry = asEntry(entries->childAt(i));
    if (!entry || !entry->getValue().toBool())
    {
      continue;
    }
    const rviz::Display* display = VisibilityEntry::displayOf(*entry);
    if (!display->isEnabled())
    {
      continue;
    }
    if (qobject_cast<const rviz::DisplayGroup*>(display))
    {
      if (visitShownForeign(entry, visit))
      {
        return true;
      }
    }
    else if (!display->getClassId().startsWith(QLatin1String("rviz_projector/")) && visit(*display))
    {
      return true;
    }
  }
  return false;
}

bool foreignShown(const rviz::Property* entries)
{
  return visitShownForeign(entries, [](const rviz::Display&) { return true; });
}

/// Mixes the scene graphs of the shown displays not from this package (host policy, render_policy.h).
void foreignScene(const rviz::Property* entries, std::uint64_t& hash)
{
  visitShownForeign(entries, [&hash](const rviz::Display& display) {
    mixSceneSignature(display.getSceneNode(), hash);
    return false;
  });
}

rviz::Property* findTick(const rviz::Property* entries, const rviz::Display* display)
{
  for (int i = 0; i < entries->numChildren(); ++i)
  {
    rviz::Property* child = entries->childAt(i);
    const rviz::DisplayVisibilityProperty* entry = asEntry(child);
    if (!entry)
    {
      continue;
    }
    if (VisibilityEntry::displayOf(*entry) == display)
    {
      return child;
    }
    if (rviz::Property* nested = findTick(entry, display))
    {
      return nested;
    }
  }
  return nullptr;
}
}  // namespace

bool FrameState::operator==(const FrameState& o) const
{
  return pose == o.pose && changes == o.changes && visibility == o.visibility && image == o.image &&
         drawable == o.drawable && foreign_scene == o.foreign_scene;
}

ProjectionGate::ProjectionGate(rviz::DisplayGroup* group, rviz::Display* owner, const RenderPolicy& policy)
  : group_(group), owner_(owner), policy_(policy)
{
  connect(group_, &rviz::DisplayGroup::displayRemoved, this, &ProjectionGate::onDisplayRemoved);
}

void ProjectionGate::attach(rviz::DisplayGroupVisibilityProperty* visibility)
{
  visibility_ = visibility;
  // After the property's own slot (connected in its constructor): the new display's entry exists.
  connect(group_, &rviz::DisplayGroup::displayAdded, this, &ProjectionGate::onDisplayAdded);
  for (int i = 0; i < group_->numDisplays(); ++i)
  {
    onDisplayAdded(group_->getDisplayAt(i));
  }
}

bool ProjectionGate::shownByDefault(const rviz::Display* display)
{
  const QString id = display->getClassId();
  return id.startsWith("rviz_projector/") && id != "rviz_projector/ProjectorCamera";
}

rviz::Property* ProjectionGate::tickOf(const rviz::Display* display) const
{
  return visibility_ ? findTick(visibility_, display) : nullptr;
}

void ProjectionGate::onDisplayRemoved(rviz::Display* display)
{
  if (rviz::Property* tick = tickOf(display))
  {
    taken_out_[display] = tick->getValue().toBool();
    // A display that is deleted, not moved: forget it (its address may be reused).
    connect(display, &QObject::destroyed, this, &ProjectionGate::onDisplayDestroyed, Qt::UniqueConnection);
  }
}

void ProjectionGate::onDisplayAdded(rviz::Display* display)
{
  if (display == owner_ || qobject_cast<rviz::DisplayGroup*>(display))
  {
    return;
  }
  rviz::Property* tick = tickOf(display);
  if (!tick)
  {
    return;
  }
  const auto known = taken_out_.find(display);
  if (known != taken_out_.end())
  {
    tick->setValue(known->second);  // moved in the list: same display, same tick
    taken_out_.erase(known);
  }
  else
  {
    tick->setValue(shownByDefault(display));
  }
}

void ProjectionGate::onDisplayDestroyed(QObject* display)
{
  taken_out_.erase(display);
}

std::uint64_t ProjectionGate::visibilitySignature() const
{
  std::uint64_t hash = 1469598103934665603ull;
  mix(hash, visibility_ && visibility_->getBool() ? 1u : 0u);
  if (visibility_)
  {
    signatureOf(visibility_, hash);
  }
  return hash;
}

bool ProjectionGate::showsForeignDisplays() const
{
  return visibility_ && visibility_->getBool() && foreignShown(visibility_);
}

std::uint64_t ProjectionGate::foreignSceneSignature() const
{
  std::uint64_t hash = 1469598103934665603ull;
  if (visibility_ && visibility_->getBool())
  {
    foreignScene(visibility_, hash);
  }
  return hash;
}

bool ProjectionGate::needsFrame(const FrameState& requested)
{
  FrameState state = requested;
  bool every_tick = showsForeignDisplays();
  if (every_tick && policy_.host)
  {
    // projector_host: other packages' displays are seen through their scene graph; a keep-alive
    // frame catches content they change in place (colours, a texture).
    state.foreign_scene = foreignSceneSignature();
    const double keep_alive = policy_.keep_alive_s;
    every_tick = keep_alive > 0.0 && (!since_last_frame_.isValid() || since_last_frame_.elapsed() >= keep_alive * 1000.0);
  }
  if (have_last_ && state == last_ && !every_tick)
  {
    return false;
  }
  last_ = state;
  have_last_ = true;
  since_last_frame_.start();
  return true;
}
}  // namespace rviz_projector
