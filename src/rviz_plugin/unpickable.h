// Scene objects that rviz's Interact tool sees through.
#pragma once

#include <OgreMaterial.h>

namespace virtual_origami::rviz_plugin
{
/// Gives `material` techniques for rviz's picking and depth schemes ("Pick", "Pick1",
/// "Depth") that draw nothing: rviz renders every object it has no technique for as an
/// occluder in those passes, so a drawn frame would take the presses meant for the sheet
/// under it and shift the 3D points rviz reports. Idempotent.
void seeThroughForPicking(const Ogre::MaterialPtr& material);

}  // namespace virtual_origami::rviz_plugin
