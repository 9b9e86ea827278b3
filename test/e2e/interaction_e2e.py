#!/usr/bin/env python3
"""End-to-end: fold in real rviz with the mouse, as a person would.

Starts Xvfb on a free display and the whole system (origami.launch with rviz and a fixed
view, test/e2e/e2e.rviz) on a free master port, drives the mouse with xdotool, and checks the
paper on the `state` topic:
  1. a drag along the diagonal, pressed and released near (not on) two corners, makes one new
     crease joining exactly those corners (snapping);
  2. the menu's "Rotate mode", then a drag from one half across the crease turns that half
     about the crease by about the dragged angle, and the other half stays;
  3. the menu's "Undo" brings back the state before the turn.
Screenshots of every step go to the output folder. Exits non-zero on any failure.

Usage: interaction_e2e.py OUTPUT_DIR   (with the devel space's environment, e.g. devel/env.sh)
"""
import math
import os
import signal
import socket
import subprocess
import sys
import time

import rosgraph
import rospy
from virtual_origami.msg import InteractionStatus, PaperState
from visualization_msgs.msg import InteractiveMarkerFeedback

HERE = os.path.dirname(os.path.abspath(__file__))
# The view of e2e.rviz, an rviz/Orbit camera: 1.9 m from the focal point (0.5, 0.45, 0), pitched
# 1.1 rad down, from the -y side (yaw -90°), vertical field of view 0.7 rad, in an 800 x 600
# window at the screen's corner.
FOCAL, DISTANCE, PITCH, YAW, FOV = (0.5, 0.45, 0.0), 1.9, 1.1, -math.pi / 2, 0.7
TIME_LIMIT = 240  # seconds for the whole test


class Failure(Exception):
    pass


def free_display():
    for n in range(90, 400):
        if not os.path.exists('/tmp/.X11-unix/X%d' % n) and not os.path.exists('/tmp/.X%d-lock' % n):
            return n
    raise Failure('no free X display number')


def free_port():
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


class System:
    """Xvfb, the launch with rviz, and the processes to stop at the end."""

    def __init__(self, out):
        self.out = out
        self.procs = []
        self.display = ':%d' % free_display()
        self.port = free_port()
        os.environ['DISPLAY'] = self.display
        os.environ['ROS_MASTER_URI'] = 'http://localhost:%d' % self.port
        os.environ['ROS_HOME'] = os.path.join(out, 'ros')

    def start(self):
        def log(name):
            return open(os.path.join(self.out, name), 'w')
        # Each in a process group of its own: stopping it stops what it started, nothing else.
        self.procs.append(subprocess.Popen(['Xvfb', self.display, '-screen', '0', '1024x768x24', '-nolisten', 'tcp'],
                                           stdout=log('xvfb.log'), stderr=subprocess.STDOUT,
                                           start_new_session=True))
        wait_for(lambda: os.path.exists('/tmp/.X11-unix/X' + self.display[1:]), 20, 'Xvfb did not start')
        self.procs.append(subprocess.Popen(
            ['roslaunch', '-p', str(self.port), 'virtual_origami', 'origami.launch',
             'rviz_config:=' + os.path.join(HERE, 'e2e.rviz'),
             'data_dir:=' + self.out, 'journal:=session.jsonl', 'resume:=false'],
            stdout=log('roslaunch.log'), stderr=subprocess.STDOUT, start_new_session=True))

    def stop(self):
        for p in reversed(self.procs):  # roslaunch first: it stops its nodes on SIGINT
            if p.poll() is None:
                os.killpg(p.pid, signal.SIGINT)
            try:
                p.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()


def wait_for(done, seconds, what):
    until = time.time() + seconds
    while time.time() < until:
        if done():
            return
        time.sleep(0.05)
    if not done():
        raise Failure(what)


def xdotool(*args):
    subprocess.run(['xdotool'] + [str(a) for a in args], check=True)


def _answers(master):
    try:
        master.getPid()
        return True
    except Exception:  # not up yet
        return False


class Checker:
    """What the product shows on its topics."""

    def __init__(self):
        master = rosgraph.Master('/interaction_e2e')
        wait_for(lambda: _answers(master), 60, 'no ROS master')
        rospy.init_node('interaction_e2e', anonymous=True, disable_signals=True)
        self.state = None
        self.status = None
        self.presses = []
        rospy.Subscriber('/origami/state', PaperState, self._state)
        rospy.Subscriber('/origami/interaction_status', InteractionStatus, self._status)
        rospy.Subscriber('/origami/interaction/feedback', InteractiveMarkerFeedback, self._feedback)

    def _state(self, msg):
        self.state = msg

    def _status(self, msg):
        self.status = msg

    def _feedback(self, msg):
        if msg.event_type == InteractiveMarkerFeedback.MOUSE_DOWN and msg.mouse_point_valid:
            self.presses.append((msg.mouse_point.x, msg.mouse_point.y, msg.mouse_point.z))

    def revision(self):
        return self.state.revision if self.state else None

    def wait_revision(self, revision, what):
        wait_for(lambda: self.revision() == revision, 30, '%s: the state stayed at revision %s, expected %d' %
                 (what, self.revision(), revision))
        # ... and the interaction node shows it, so the next press lands on the new sheet.
        wait_for(lambda: self.status and self.status.revision == revision, 10, what + ': interaction lags')
        return self.state


def dot(a, b):
    return sum(i * j for i, j in zip(a, b))


class Mouse:
    """Points on the sheet (the `paper` frame, z = 0) to screen pixels, through the camera."""

    def __init__(self, window):
        x, y, width, height = window
        # The render panel fills the window below the menu and tool bars, above the status bar,
        # between the collapsed docks (rviz's layout at this window size): 768 x 509 at (16, 62).
        self.cx, self.cy = x + 16 + 768 / 2.0, y + 62 + 509 / 2.0
        self.focal = (509 / 2.0) / math.tan(FOV / 2)  # pixels
        cp, sp = math.cos(PITCH), math.sin(PITCH)
        self.eye = tuple(f + DISTANCE * d for f, d in zip(FOCAL, (cp * math.cos(YAW), cp * math.sin(YAW), sp)))
        self.forward = tuple((f - e) / DISTANCE for f, e in zip(FOCAL, self.eye))
        self.right = (-math.sin(YAW), math.cos(YAW), 0.0)  # forward x up (z), normalised
        f, r = self.forward, self.right
        self.up = (r[1] * f[2] - r[2] * f[1], r[2] * f[0] - r[0] * f[2], r[0] * f[1] - r[1] * f[0])

    def pixel(self, p):
        v = [c - e for c, e in zip((p[0], p[1], 0.0), self.eye)]
        depth = dot(v, self.forward)
        return (int(round(self.cx + self.focal * dot(v, self.right) / depth)),
                int(round(self.cy - self.focal * dot(v, self.up) / depth)))

    def drag(self, start, end, steps=24, during=None):
        xdotool('mousemove', *self.pixel(start))
        time.sleep(0.3)
        xdotool('mousedown', 1)
        time.sleep(0.3)
        for i in range(1, steps + 1):
            t = i / steps
            xdotool('mousemove', *self.pixel((start[0] + t * (end[0] - start[0]), start[1] + t * (end[1] - start[1]))))
            time.sleep(0.05)
        time.sleep(0.5)
        if during:
            during()
        xdotool('mouseup', 1)
        time.sleep(0.3)
        self.away()

    def menu(self, at, entry, shot=None):
        """Right-click at `at`, then pick the `entry`-th item (from 1) with the keyboard."""
        xdotool('mousemove', *self.pixel(at))
        time.sleep(0.3)
        xdotool('click', 3)
        time.sleep(1.0)
        if shot:
            shot()
        for _ in range(entry):
            xdotool('key', 'Down')
            time.sleep(0.1)
        xdotool('key', 'Return')
        time.sleep(0.3)
        self.away()

    def away(self):
        xdotool('mousemove', *self.pixel((1.3, -0.1)))  # off the sheet and its margin, in the view


def vertex_at(state, x, y):
    for i, p in enumerate(state.vertices_crease_pattern):
        if abs(p.x - x) < 1e-9 and abs(p.y - y) < 1e-9:
            return i
    return -1


def edge_between(state, a, b):
    for i, e in enumerate(state.edges):
        if {e.v0, e.v1} == {a, b}:
            return i
    return -1


def run(out):
    shots = []

    def shot(name):
        path = os.path.join(out, name)
        crop = '%dx%d+%d+%d' % (window[2], window[3], window[0], window[1]) if window else '1024x768+0+0'
        subprocess.run(['import', '-window', 'root', '-crop', crop, '+repage', path], check=True)
        shots.append(path)

    window = []
    check = Checker()
    wait_for(lambda: check.state is not None, 60, 'no state from paper_model')
    base = check.revision()
    wait_for(lambda: check.status is not None and check.status.revision == base, 30, 'the interaction node is not up')

    def find_window():
        r = subprocess.run(['xdotool', 'search', '--name', 'RViz'], capture_output=True, text=True)
        for wid in r.stdout.split():
            g = subprocess.run(['xdotool', 'getwindowgeometry', '--shell', wid], capture_output=True, text=True)
            values = dict(line.split('=') for line in g.stdout.split() if '=' in line)
            if int(values.get('WIDTH', 0)) >= 800:
                window[:] = [int(values['X']), int(values['Y']), int(values['WIDTH']), int(values['HEIGHT'])]
                return True
        return False

    wait_for(find_window, 60, 'no rviz window')
    mouse = Mouse(window)
    time.sleep(5)  # rviz draws the sheet and takes the interactive marker
    mouse.away()
    shot('00_start.png')

    # The view is as assumed when a click lands where it should (a click creases nothing).
    xdotool('mousemove', *mouse.pixel((0.5, 0.5)))
    time.sleep(0.3)
    xdotool('click', 1)
    wait_for(lambda: check.presses, 10, 'a click on the sheet did not reach the interaction node')
    px, py, pz = check.presses[-1]
    print('view check: clicked (0.5, 0.5), rviz reports (%.4f, %.4f, %.4f)' % (px, py, pz))
    if math.hypot(px - 0.5, py - 0.5) > 0.015:
        raise Failure('the view is not as assumed: clicked (0.5, 0.5), rviz reports (%.4f, %.4f)' % (px, py))
    time.sleep(0.5)
    if check.revision() != base:
        raise Failure('a click changed the paper')

    # 1. Crease: a drag along the diagonal, from near corner (0, 0) to near corner (1, 1).
    mouse.drag((0.008, 0.012), (0.992, 0.99), during=lambda: shot('01_crease_drag.png'))
    creased = check.wait_revision(base + 1, 'crease')
    shot('02_creased.png')
    a, b = vertex_at(creased, 0, 0), vertex_at(creased, 1, 1)
    diagonal = edge_between(creased, a, b)
    if diagonal < 0 or len(creased.faces) != 2 or len(creased.vertices_crease_pattern) != 4:
        raise Failure('the crease does not join exactly corners (0, 0) and (1, 1): %d vertices, %d faces' %
                      (len(creased.vertices_crease_pattern), len(creased.faces)))
    print('crease: edge %d joins corners (0, 0) and (1, 1)' % diagonal)

    # 2. Rotate: the menu's rotate mode, then a drag from the lower-right half across the crease.
    mouse.menu((0.7, 0.6), 2, shot=lambda: shot('03_menu.png'))
    wait_for(lambda: check.status.mode == 'rotate', 10, 'the menu did not switch to rotate mode')
    press, release = (0.8, 0.3), (0.5, 0.6)
    mouse.drag(press, release, during=lambda: shot('04_rotate_drag.png'))
    turned = check.wait_revision(base + 2, 'rotate')
    shot('05_turned.png')
    # Seen from above, the pointer's distance from the crease sets the angle: the press point
    # 0°, over the crease 90°, at its mirror image 180°.
    r = (press[0] - press[1]) / math.sqrt(2)
    s = (release[0] - release[1]) / math.sqrt(2)
    dragged = 90.0 * (1 - s / r)
    angle = math.degrees(turned.edges[diagonal].fold_angle)
    moving, staying = vertex_at(turned, 1, 0), vertex_at(turned, 0, 1)
    lifted = turned.vertices_folded[moving]
    print('rotate: dragged %.1f°, the crease turned to %.1f°, corner (1, 0) now at (%.3f, %.3f, %.3f)' %
          (dragged, angle, lifted.x, lifted.y, lifted.z))
    if abs(angle - dragged) > 10:
        raise Failure('the crease turned to %.1f°, the drag asked for %.1f°' % (angle, dragged))
    if lifted.z < 0.2:
        raise Failure('the pressed half did not turn up towards the eye')
    if turned.vertices_folded[staying] != creased.vertices_folded[staying] or \
       turned.vertices_folded[a] != creased.vertices_folded[a]:
        raise Failure('the other half moved')

    # 3. Undo from the menu.
    mouse.menu((0.2, 0.75), 4)
    undone = check.wait_revision(base + 3, 'undo')
    shot('06_undone.png')
    if undone.vertices_folded != creased.vertices_folded or \
       [e.fold_angle for e in undone.edges] != [e.fold_angle for e in creased.edges]:
        raise Failure('undo did not restore the creased, unfolded state')
    print('undo: the state before the turn is back')
    print('screenshots:\n  ' + '\n  '.join(shots))


def main():
    out = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else 'e2e_output')
    os.makedirs(out, exist_ok=True)
    system = System(out)
    def out_of_time(*_):
        raise Failure('over the time limit of %d s' % TIME_LIMIT)

    signal.signal(signal.SIGALRM, out_of_time)
    signal.alarm(TIME_LIMIT)
    status = 0
    try:
        system.start()
        run(out)
        print('PASSED')
    except Failure as e:
        print('FAILED: %s (logs and screenshots in %s)' % (e, out))
        status = 1
    finally:
        signal.alarm(0)
        rospy.signal_shutdown('done')
        system.stop()
    sys.exit(status)


if __name__ == '__main__':
    main()
