#include "rviz_projector/core/person_tracker.h"

#include <algorithm>
#include <cmath>

namespace rviz_projector
{
void PersonTracker::clear()
{
  tracks_.clear();
  started_ = false;
  latest_ = 0.0;
}

void PersonTracker::update(const std::vector<PersonCluster>& clusters, double time, const TrackerParameters& parameters)
{
  if (!std::isfinite(time) || (started_ && time < latest_))
  {
    clear();
  }
  if (!std::isfinite(time))
  {
    return;
  }
  started_ = true;
  latest_ = time;
  candidates_.clear();
  for (std::size_t t = 0; t < tracks_.size(); ++t)
  {
    const double gate = parameters.max_speed * (time - tracks_[t].last_seen) + parameters.margin;
    for (std::size_t c = 0; c < clusters.size(); ++c)
    {
      if (!isFinite(clusters[c].centre))
      {
        continue;
      }
      const double d = distance(tracks_[t].position, clusters[c].centre);
      if (d <= gate)
      {
        candidates_.push_back({d, {t, c}});
      }
    }
  }
  std::sort(candidates_.begin(), candidates_.end());
  track_taken_.assign(tracks_.size(), 0);
  cluster_taken_.assign(clusters.size(), 0);
  for (PersonTrack& track : tracks_)
  {
    track.seen = false;
  }
  for (const auto& candidate : candidates_)
  {
    const std::size_t t = candidate.second.first, c = candidate.second.second;
    if (track_taken_[t] || cluster_taken_[c])
    {
      continue;
    }
    track_taken_[t] = cluster_taken_[c] = 1;
    tracks_[t].position = clusters[c].centre;
    tracks_[t].radius = clusters[c].radius;
    tracks_[t].last_seen = time;
    tracks_[t].seen = true;
  }
  for (std::size_t c = 0; c < clusters.size(); ++c)
  {
    if (!cluster_taken_[c] && isFinite(clusters[c].centre))
    {
      tracks_.push_back(PersonTrack{next_id_++, clusters[c].centre, clusters[c].radius, time, true});
    }
  }
  expire(time, parameters);
}

bool PersonTracker::expire(double now, const TrackerParameters& parameters)
{
  const std::size_t before = tracks_.size();
  tracks_.erase(std::remove_if(tracks_.begin(), tracks_.end(),
                               [&](const PersonTrack& t) { return !t.seen && !(now - t.last_seen <= parameters.hold); }),
                tracks_.end());
  return tracks_.size() != before;
}

double PersonTracker::opacity(const PersonTrack& track, double now, const TrackerParameters& parameters)
{
  if (track.seen)
  {
    return 1.0;
  }
  if (!(parameters.hold > 0.0))
  {
    return 0.0;
  }
  return std::clamp(1.0 - (now - track.last_seen) / parameters.hold, 0.0, 1.0);
}

bool PersonTracker::fading() const
{
  return std::any_of(tracks_.begin(), tracks_.end(), [](const PersonTrack& t) { return !t.seen; });
}
}  // namespace rviz_projector
