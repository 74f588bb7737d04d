// Drawing in image space, shared by the parts that draw in the projector's pixels rather than in
// rviz's scene (ProjectorCrosshairs, DistortionWarp): an unlit material without depth test or
// culling, and a ManualObject positioned in normalised device coordinates.
#pragma once

#include <OgreMaterial.h>

namespace Ogre
{
class ManualObject;
}  // namespace Ogre

namespace rviz_projector
{
/// A new material (unique name from `prefix`): no lighting, no depth check or write, no culling,
/// no shadows. The caller removes it from the MaterialManager when done.
Ogre::MaterialPtr createImageSpaceMaterial(const char* prefix);
/// `object`'s positions are normalised device coordinates (identity view and projection); static.
void useImageSpace(Ogre::ManualObject* object);
}  // namespace rviz_projector
