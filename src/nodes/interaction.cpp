// interaction: folds the paper with the mouse in rviz; see include/virtual_origami/ros/interaction_node.h.
#include <ros/ros.h>

#include "virtual_origami/ros/interaction_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "interaction");
  virtual_origami::InteractionNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
