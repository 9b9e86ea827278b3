// paper_model: owns the paper and its history; see include/virtual_origami/ros/paper_model_node.h.
#include <ros/ros.h>

#include "virtual_origami/ros/paper_model_node.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "paper_model");
  virtual_origami::PaperModelNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  ros::spin();
  return 0;
}
