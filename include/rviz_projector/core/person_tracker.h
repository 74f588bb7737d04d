// Who is who from one scan to the next, for the Acknowledge cue of ProjectionMask (issue 25,
// part 4): an arc follows a walking person and fades out after they leave. Plain code (no ROS, no
// OGRE).
//
// Association (documented in doc/reference/displays.md and the README too): at every scan, each
// pair of a track and a new cluster closer than the track's gate is a candidate; the gate is
// max_speed x (time since the track was last seen) + margin, so a person can have walked at most
// that far. Candidates are taken greedily, nearest first: a pair is kept when neither its track nor
// its cluster was taken already. A matched track moves to its cluster (same id); a cluster left
// over starts a new track (a new id); a track left over keeps its last place and fades. Two people
// walking past each other at a normal pace keep their ids (each is nearer its own last place than
// the other's); a cluster that "teleports" further than the gate is a new person, and the old track
// fades out.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "rviz_projector/core/person_clusters.h"
#include "rviz_projector/core/vec2.h"

namespace rviz_projector
{
struct TrackerParameters
{
  double max_speed = 2.5;  ///< m/s: fastest walking speed believed
  double margin = 0.2;     ///< metres added to every gate (cluster centres wobble with the legs)
  double hold = 1.0;       ///< seconds a track is kept (fading) after it was last seen
};

struct PersonTrack
{
  std::uint32_t id = 0;
  Vec2 position;            ///< the centre of the cluster it was last matched with
  double radius = 0.0;      ///< that cluster's radius
  double last_seen = 0.0;   ///< time of that scan, seconds
  bool seen = false;        ///< matched in the latest update
};

class PersonTracker
{
public:
  /// Associates the clusters of a scan at `time` (seconds) with the tracks (see the header's
  /// comment), then drops the tracks older than hold. Time going backwards (or NaN) forgets every
  /// track first. Non-finite cluster centres are ignored.
  void update(const std::vector<PersonCluster>& clusters, double time, const TrackerParameters& parameters);
  /// Drops the tracks last seen more than hold before `now`; true when some were dropped.
  bool expire(double now, const TrackerParameters& parameters);
  void clear();

  /// How visible a track's cue is at `now`: 1 while it is seen (matched in the latest update), then
  /// falling linearly from 1 at its last_seen to 0 at last_seen + hold. hold <= 0: 0 once unseen.
  static double opacity(const PersonTrack& track, double now, const TrackerParameters& parameters);
  /// Whether any track is fading (unseen, not yet dropped): its opacity changes with time.
  bool fading() const;

  const std::vector<PersonTrack>& tracks() const { return tracks_; }

private:
  std::vector<PersonTrack> tracks_;
  std::vector<std::pair<double, std::pair<std::size_t, std::size_t>>> candidates_;  // (distance, (track, cluster))
  std::vector<char> track_taken_, cluster_taken_;
  std::uint32_t next_id_ = 1;
  double latest_ = 0.0;
  bool started_ = false;
};
}  // namespace rviz_projector
