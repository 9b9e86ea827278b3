// state_markers: draws whatever `state` says as `markers`, e.g. while `rosbag play` plays a
// recording without a paper_model running. Parameters ~layer_gap, ~colour_by_strain and
// ~strain_scale as in paper_model (read at start).
#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/markers.h"

int main(int argc, char** argv)
{
  ros::init(argc, argv, "state_markers");
  ros::NodeHandle nh, private_nh("~");
  virtual_origami::MarkerStyle style;
  style.layer_gap = private_nh.param("layer_gap", style.layer_gap);
  style.colour_by_strain = private_nh.param("colour_by_strain", style.colour_by_strain);
  style.strain_scale = private_nh.param("strain_scale", style.strain_scale);
  ros::Publisher markers = nh.advertise<visualization_msgs::MarkerArray>("markers", 1, true);
  ros::Subscriber state = nh.subscribe<virtual_origami::PaperState>(
      "state", 10, [&](const virtual_origami::PaperState::ConstPtr& s) {
        const auto paper = virtual_origami::fromMessage(*s);
        if (!paper)
        {
          ROS_WARN_THROTTLE(5, "state_markers: %s", paper.message().c_str());
          return;
        }
        style.frame_id = s->header.frame_id.empty() ? "paper" : s->header.frame_id;
        markers.publish(virtual_origami::paperMarkers(*paper, style, ros::Time::now()));
      });
  ros::spin();
  return 0;
}
