// Marching cue of ProjectedPath: arrows move along the path towards the destination (no ROS, no OGRE).
#pragma once

namespace rviz_projector
{
/**
 * The offset PathSpacer adds to every arrow tip's arc length from the destination (its `phase`
 * argument) for arrows marching at `speed` m/s at time `time` (seconds, ROS time):
 *
 *   phase = (-speed * time) mod spacing, in [0, spacing)
 *
 * A function of time only (and of arc lengths measured from the destination by PathSpacer), so a
 * replan of the same route changes nothing and the same time always gives the same arrows. As time
 * grows the phase shrinks (arrows approach the destination) and jumps back from 0 to `spacing`: the
 * arrow nearest the destination then leaves (it reached the place of the static first arrow) and the
 * others continue without a jump; new arrows enter at the path's start when a whole arrow fits.
 * speed <= 0, NaN/Inf inputs or spacing <= 0: 0 (static arrows).
 */
double marchingPhase(double speed, double time, double spacing);
}  // namespace rviz_projector
