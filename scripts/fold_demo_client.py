#!/usr/bin/env python3
"""Folds a short demo through the paper_model services (SPEC §8) and saves the result.

Usage: fold_demo_client.py OUTPUT_DIR [NAMESPACE]
"""
import math
import sys

import rospy
from geometry_msgs.msg import Point
from std_srvs.srv import Trigger
from virtual_origami.srv import Crease, Rotate, Save


def main():
    out = sys.argv[1]
    ns = sys.argv[2] if len(sys.argv) > 2 else "/origami"
    rospy.init_node("fold_demo_client", anonymous=True)
    for name in ("crease", "rotate", "reset", "save"):
        rospy.wait_for_service(ns + "/" + name, timeout=60)
    crease = rospy.ServiceProxy(ns + "/crease", Crease)
    rotate = rospy.ServiceProxy(ns + "/rotate", Rotate)
    save = rospy.ServiceProxy(ns + "/save", Save)
    rospy.ServiceProxy(ns + "/reset", Trigger)()

    def turn(what, angle, click=(0, 0, 0), face=-1, axis=-1):
        # Previews first, so that rviz shows the motion; then one committed turn.
        steps = 20
        for i in range(1, steps):
            rotate(face=face, axis_edge=axis, click=Point(*click), angle=angle * i / steps, commit=False)
            rospy.sleep(0.04)
        turned = rotate(face=face, axis_edge=axis, click=Point(*click), angle=angle, commit=True)
        if not turned.success:
            raise SystemExit("%s: rotate failed: %s" % (what, turned.message))
        print("%-40s revision %d" % (what, turned.revision))
        return turned

    def fold(what, start, end, click, angle):
        made = crease(start=Point(*start), end=Point(*end), has_eye=False, eye=Point(), snap=True)
        if not made.success:
            raise SystemExit("%s: crease failed: %s" % (what, made.message))
        return turn(what, angle, click=click)

    fold("fold the square along its diagonal", (0, 0, 0), (1, 1, 0), (0.2, 0.8, 0), math.pi)
    last = fold("fold the triangle in half", (1, 0, 0), (0.5, 0.5, 0), (0.3, 0.1, 0), math.pi)
    turn("open the last fold to 90 degrees", -math.pi / 2, face=last.face, axis=last.axis_edge)
    for path in (out + "/result.fold", out + "/result.obj"):
        saved = save(path=path)
        print(saved.message if saved.success else "save failed: " + saved.message)


if __name__ == "__main__":
    main()
