#!/usr/bin/env python3
"""The client of multihost_test.sh, on the solver's host: checks where the services run, then
creases, rotates and pulls a pinned corner through paper_model on the other host.

Usage: multihost_client.py MODEL_IP SOLVER_IP   (exit 0: every check held)
"""
import math
import sys

import rosgraph
import rospy
from geometry_msgs.msg import Point, TransformStamped
from tf2_msgs.msg import TFMessage
from virtual_origami.msg import PaperState
from virtual_origami.srv import Crease, PinVertex, Rotate

NS = "/origami"
TOLERANCE = 1e-9


def fail(message):
    print("FAIL: " + message)
    sys.exit(1)


def service_host(name):
    uri = rosgraph.Master("/multihost_client").lookupService(name)
    return uri.split("//", 1)[1].split(":", 1)[0]


class States:
    def __init__(self):
        self.latest = None
        rospy.Subscriber(NS + "/state", PaperState, self.received)

    def received(self, state):
        self.latest = state

    def at(self, revision, timeout=15.0):
        end = rospy.get_time() + timeout
        while not rospy.is_shutdown() and rospy.get_time() < end:
            if self.latest is not None and self.latest.revision >= revision:
                return self.latest
            rospy.sleep(0.02)
        fail("no state of revision %d (latest %s)" % (revision, self.latest and self.latest.revision))


def vertex_at(state, x, y):
    for v, p in enumerate(state.vertices_crease_pattern):
        if abs(p.x - x) < 1e-9 and abs(p.y - y) < 1e-9:
            return v
    fail("no vertex at (%g, %g)" % (x, y))


def expect_near(what, got, want):
    error = math.dist((got.x, got.y, got.z), want)
    print("  %-34s (%.6f, %.6f, %.6f), off by %.2g" % (what, got.x, got.y, got.z, error))
    if error > TOLERANCE:
        fail("%s is at (%g, %g, %g), expected %s" % (what, got.x, got.y, got.z, want))


def crease_angle(state):
    angles = [e.fold_angle for e in state.edges if e.face_left >= 0 and e.face_right >= 0]
    if len(angles) != 1:
        fail("expected one crease, found %d" % len(angles))
    return angles[0]


def main():
    model_ip, solver_ip = sys.argv[1], sys.argv[2]
    rospy.init_node("multihost_client", anonymous=True)
    for name in ("crease", "rotate", "pin", "solve"):
        rospy.wait_for_service(NS + "/" + name, timeout=30)
    hosts = {name: service_host(NS + "/" + name) for name in ("crease", "solve")}
    print("crease served from %s, solve from %s" % (hosts["crease"], hosts["solve"]))
    if hosts["crease"] != model_ip or hosts["solve"] != solver_ip:
        fail("the services do not run on their hosts: %s" % hosts)
    states = States()
    start = states.at(0)

    made = rospy.ServiceProxy(NS + "/crease", Crease)(start=Point(0.5, -0.1, 0), end=Point(0.5, 1.1, 0))
    if not made.success:
        fail("crease: " + made.message)
    turned = rospy.ServiceProxy(NS + "/rotate", Rotate)(face=-1, axis_edge=-1, click=Point(0.8, 0.5, 0),
                                                          angle=math.pi / 2, commit=True)
    if not turned.success:
        fail("rotate: " + turned.message)
    state = states.at(turned.revision)
    print("crease + rotate by 90 degrees, revision %d:" % state.revision)
    corner, far = vertex_at(state, 1, 0), vertex_at(state, 1, 1)
    expect_near("corner (1, 0)", state.vertices_folded[corner], (0.5, 0, 0.5))
    expect_near("corner (1, 1)", state.vertices_folded[far], (0.5, 1, 0.5))
    expect_near("corner (0, 0)", state.vertices_folded[vertex_at(state, 0, 0)], (0, 0, 0))
    if abs(crease_angle(state) - math.pi / 2) > TOLERANCE:
        fail("fold angle %g, expected pi/2" % crease_angle(state))

    # A pull needs the solver, on the other host: hold the half x <= 0.5, pin the corner to a frame
    # at the corner swung to 135 degrees.
    pin = rospy.ServiceProxy(NS + "/pin", PinVertex)
    for v, p in enumerate(state.vertices_crease_pattern):
        if p.x < 0.5 + 1e-9 and not pin(vertex=v, frame_id="", release=False).success:
            fail("pinning vertex %d in place" % v)
    angle = 3 * math.pi / 4
    target = (0.5 + 0.5 * math.cos(angle), 0.0, 0.5 * math.sin(angle))
    frames = rospy.Publisher("/tf_static", TFMessage, queue_size=1, latch=True)
    grip = TransformStamped()
    grip.header.stamp = rospy.Time.now()
    grip.header.frame_id = "paper"
    grip.child_frame_id = "grip"
    grip.transform.translation.x, grip.transform.translation.y, grip.transform.translation.z = target
    grip.transform.rotation.w = 1.0
    frames.publish(TFMessage([grip]))
    pinned = pin(vertex=corner, frame_id="grip", release=False)
    if not pinned.success:
        fail("pinning the corner to grip: " + pinned.message)
    state = states.at(turned.revision + 1)
    print("corner pulled to the frame grip at 135 degrees, revision %d:" % state.revision)
    expect_near("corner (1, 0)", state.vertices_folded[corner], target)
    expect_near("corner (1, 1)", state.vertices_folded[far], (target[0], 1.0, target[2]))
    if abs(crease_angle(state) - angle) > 1e-8:
        fail("fold angle %g, expected 3 pi/4" % crease_angle(state))
    print("fold angle %.9f degrees" % math.degrees(crease_angle(state)))


if __name__ == "__main__":
    main()
