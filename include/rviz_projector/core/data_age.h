// How old the data behind a picture is, and whether it is too old to show (the "Path timeout" of
// ProjectedPath, the "TF timeout" of ProjectorCamera): stale data goes dark rather than showing a
// plan or a pose the robot has long left.
#pragma once

namespace rviz_projector
{
/// Seconds from `stamp` to `now` (both seconds on the same clock). A stamp of 0 is tf's "static,
/// valid at all times" and is never old: 0. Data stamped in the future (clock skew) is 0 s old.
double dataAge(double stamp, double now);
/// Whether data `age` seconds old is past `timeout` seconds. A timeout <= 0 (or not finite) means
/// never; a NaN age (no data) is never stale either: absent data is reported as absent.
bool isStale(double age, double timeout);
/// Whether data stamped `stamp` lies more than `timeout` seconds ahead of `now` (same clock): it
/// is from before a backward jump of ROS time (a bag loop) and must not count as fresh. A stamp of
/// 0 (static) or a timeout <= 0 (never stale): false. Clock skew within the timeout is tolerated.
bool isFromTheFuture(double stamp, double now, double timeout);
}  // namespace rviz_projector
