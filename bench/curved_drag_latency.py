#!/usr/bin/python3
"""Pointer event to `curved_mesh` message through curved_mesh_solver (issue 37).

    roslaunch virtual_origami curved_drag_latency.launch spacing:=0.025 frames:=true [moves:=90] [csv:=...]

Pins three corners of the square, drags the fourth on `curved_drag` as the interaction does (in
towards the middle and up, one move every 1/30 s, each stamped when sent), and times each
`curved_mesh` message against the move whose stamp it carries (the node stamps the sheet with
the drag it shows). The messages are taken raw (rospy.AnyMsg) and only their first header read,
so this side adds no deserialisation. Then the pointer stands still: the time to the settled
sheet (the last sheet of the last move, none coming for 10 s after it). Appends one row per move to the CSV.
"""
import csv
import math
import os
import struct
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Point
from visualization_msgs.msg import MarkerArray
from virtual_origami.msg import PaperState, VertexTarget
from virtual_origami.srv import PinVertex


def percentile(values, p):
    values = sorted(values)
    if not values:
        return float("nan")
    return values[min(len(values) - 1, max(0, math.ceil(p * len(values)) - 1))]


class Sheets:
    """Every curved_mesh message: its stamp (from the raw bytes) and when it arrived."""

    def __init__(self):
        self.lock = threading.Lock()
        self.arrivals = []  # (stamp in ns, arrival wall time, bytes)
        self.last_raw = None
        self.sub = rospy.Subscriber("/origami/curved_mesh", rospy.AnyMsg, self.take, queue_size=1000)

    def take(self, raw):
        arrived = time.time()
        # MarkerArray: uint32 count, then the first Marker's Header: uint32 seq, uint32 secs, uint32 nsecs.
        _, _, secs, nsecs = struct.unpack_from("<IIII", raw._buff, 0)
        with self.lock:
            self.arrivals.append((secs * 10**9 + nsecs, arrived, len(raw._buff)))
            self.last_raw = raw._buff

    def since(self, index):
        with self.lock:
            return list(self.arrivals[index:])


def main():
    rospy.init_node("curved_drag_latency")
    moves = rospy.get_param("~moves", 90)
    out = rospy.get_param("~csv", "curved_drag_latency.csv")
    frames = rospy.get_param("~frames", True)
    sheets = Sheets()
    state = rospy.wait_for_message("/origami/state", PaperState, timeout=60)
    corner_of = {}
    for v, p in enumerate(state.vertices_crease_pattern):
        corner_of[(round(p.x, 9), round(p.y, 9))] = v
    pin = rospy.ServiceProxy("/origami/pin", PinVertex)
    rospy.wait_for_service("/origami/pin", timeout=60)
    for xy in ((1.0, 0.0), (1.0, 1.0), (0.0, 1.0)):
        if not pin(vertex=corner_of[xy], frame_id="", release=False).success:
            sys.exit("curved_drag_latency: cannot pin corner %s" % (xy,))
    # The sheet of the pinned state (meshing and its first solve), its vertex count once.
    pinned = rospy.wait_for_message("/origami/state", PaperState, timeout=60)
    while len(pinned.pins) < 3:
        pinned = rospy.wait_for_message("/origami/state", PaperState, timeout=60)
    t0 = time.time()
    while not any(s == pinned.header.stamp.to_nsec() for s, _, _ in sheets.since(0)):
        if time.time() - t0 > 600:
            sys.exit("curved_drag_latency: no sheet of the pinned state within 600 s")
        time.sleep(0.05)
    time.sleep(0.5)
    with sheets.lock:
        first = MarkerArray().deserialize(sheets.last_raw)
    vertices = len({(p.x, p.y, p.z) for p in first.markers[0].points})
    rospy.loginfo("curved_drag_latency: %d vertices, sheet of the pinned state after %.1f s", vertices, time.time() - t0)
    drag = rospy.Publisher("/origami/curved_drag", VertexTarget, queue_size=10)
    while drag.get_num_connections() < 2 and not rospy.is_shutdown():
        time.sleep(0.05)
    time.sleep(0.5)
    start_index = len(sheets.since(0))
    sent = {}  # stamp ns -> (move, wall time sent)
    corner = corner_of[(0.0, 0.0)]
    next_at = time.time()
    for k in range(1, moves + 1):
        t = k / moves
        target = VertexTarget()
        target.header.frame_id = state.header.frame_id
        target.header.stamp = rospy.Time.now()
        target.vertex = corner
        target.position = Point(0.15 * t, 0.15 * t, 0.25 * t)
        sent[target.header.stamp.to_nsec()] = (k, time.time())
        drag.publish(target)
        next_at += 1.0 / 30
        time.sleep(max(0.0, next_at - time.time()))
    last = max(sent)
    first_sent, last_sent = sent[min(sent)][1], sent[last][1]
    # Standing still: the settled sheet is the last one of the last move (frames that lagged the
    # pointer catch up with its stamp first) once no sheet has come for 10 s.
    deadline = time.time() + 180
    while time.time() < deadline:
        arrived = sheets.since(start_index)
        if arrived and arrived[-1][0] == last and time.time() - arrived[-1][1] > 10.0:
            break
        time.sleep(0.05)
    arrivals = sheets.since(start_index)
    of_last = [a for s, a, _ in arrivals if s == last]
    settled = (of_last[-1] - last_sent) if of_last else float("nan")
    let_go = VertexTarget()
    let_go.header.frame_id = state.header.frame_id
    let_go.header.stamp = rospy.Time.now()
    let_go.vertex = -1
    drag.publish(let_go)

    shown = {}
    for stamp, arrived, size in arrivals:
        if stamp in sent and stamp not in shown:
            shown[stamp] = (arrived, size)
    latencies = [(shown[s][0] - sent[s][1]) * 1e3 for s in shown]
    times = sorted(a for _, a, _ in arrivals if a <= (shown[last][0] if last in shown else float("inf")))
    gaps = [(b - a) * 1e3 for a, b in zip(times, times[1:])]
    new = not os.path.exists(out)
    with open(out, "a", newline="") as f:
        w = csv.writer(f)
        if new:
            w.writerow(["vertices", "mode", "move", "sent_after_first_s", "latency_ms", "message_bytes"])
        for stamp, (k, at) in sorted(sent.items()):
            row = shown.get(stamp)
            w.writerow([vertices, "frames" if frames else "full_solve", k, "%.4f" % (at - first_sent),
                        "%.2f" % ((row[0] - at) * 1e3) if row else "", row[1] if row else ""])
        w.writerow([vertices, ("frames" if frames else "full_solve") + "_settled", moves, "%.4f" % (last_sent - first_sent), "%.2f" % (settled * 1e3), ""])
    rospy.loginfo(
        "curved_drag_latency: %d vertices, %s: %d of %d moves shown; pointer event -> curved_mesh p50 %.1f / p95 %.1f / "
        "max %.1f ms; between sheets p50 %.1f / p95 %.1f ms; message %.1f MB; last move -> settled sheet %.0f ms",
        vertices, "anytime frames" if frames else "full solves", len(shown), moves, percentile(latencies, 0.5),
        percentile(latencies, 0.95), percentile(latencies, 1.0), percentile(gaps, 0.5), percentile(gaps, 0.95),
        (arrivals[-1][2] if arrivals else 0) / 1e6, settled * 1e3)


if __name__ == "__main__":
    main()
