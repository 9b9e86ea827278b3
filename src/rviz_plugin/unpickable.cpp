#include "unpickable.h"

#include <OgrePass.h>
#include <OgreTechnique.h>

namespace virtual_origami::rviz_plugin
{
void seeThroughForPicking(const Ogre::MaterialPtr& material)
{
  if (!material)
    return;
  for (const char* scheme : { "Pick", "Pick1", "Depth" })
  {
    bool present = false;
    for (unsigned short i = 0; i < material->getNumTechniques(); ++i)
      present = present || material->getTechnique(i)->getSchemeName() == scheme;
    if (present)
      continue;
    Ogre::Technique* technique = material->createTechnique();
    technique->setSchemeName(scheme);
    Ogre::Pass* pass = technique->getNumPasses() > 0 ? technique->getPass(0) : technique->createPass();
    pass->setColourWriteEnabled(false);
    pass->setDepthWriteEnabled(false);
    pass->setDepthCheckEnabled(false);
    pass->setLightingEnabled(false);
  }
  material->compile();
}

}  // namespace virtual_origami::rviz_plugin
