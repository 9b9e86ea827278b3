// One service call on a connection of its own, that the caller closes.
#pragma once

#include <string>

#include <ros/node_handle.h>
#include <ros/service_client.h>

namespace virtual_origami
{
/// Calls the service `resolved_name` once, as ros::service::call does (a master lookup and a
/// connection for this call), but with the connection opened as persistent, so that it is the
/// caller who closes it after the answer. On a connection made per call, the server closes its
/// end as it answers, and roscpp drops an answer that comes before the caller has begun to read
/// (ros/ros_comm#1976): a refusal answered at once was now and then lost ("did not answer") under
/// load. False when the service cannot be reached or the connection breaks.
template <class Service>
bool callService(const std::string& resolved_name, Service& srv)
{
  ros::ServiceClient client = ros::NodeHandle().serviceClient<Service>(resolved_name, /*persistent=*/true);
  return client.call(srv);
}
}  // namespace virtual_origami
