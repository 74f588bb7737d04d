// A headless OGRE for unit tests and microbenchmarks of the OGRE adapters: a Root without plugins
// or render system, vertex buffers in system memory (DefaultHardwareBufferManager), no log output.
// Enough to fill meshes and inspect them; nothing is drawn.
#pragma once

#include <OgreDefaultHardwareBufferManager.h>
#include <OgreLogManager.h>
#include <OgreMaterialManager.h>
#include <OgrePrerequisites.h>
#include <OgreRoot.h>
#include <OgreSceneManager.h>

namespace rviz_projector_test
{
/// The process's one headless scene (created on first use, kept to the end of the process).
inline Ogre::SceneManager* headlessScene()
{
  static Ogre::SceneManager* scene = [] {
    auto* log = new Ogre::LogManager();
    log->createLog("rviz_projector_headless_ogre.log", true, false, true);  // no file, no console
    auto* root = new Ogre::Root("", "", "");
    new Ogre::DefaultHardwareBufferManager();
    Ogre::MaterialManager::getSingleton().initialise();  // default technique + pass (Root::initialise would)
#if OGRE_VERSION >= ((1 << 16) | (10 << 8))
    return root->createSceneManager();
#else
    return root->createSceneManager(Ogre::ST_GENERIC);  // OGRE 1.9 (Noetic on Ubuntu 20.04)
#endif
  }();
  return scene;
}
}  // namespace rviz_projector_test
