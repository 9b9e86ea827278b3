#!/usr/bin/env python3
"""End-to-end: the whole crane by mouse and keyboard in real rviz, as docs/INTERACTION.md's
walkthrough ("Fold a crane") says.

Like interaction_e2e.py (whose helpers it uses: Xvfb on a free display, origami.launch with rviz
on a free master port, screen pixels from the camera rviz broadcasts as the tf frame
rviz_camera, the mouse and keys driven by xdotool), it folds the 21 steps of
test/data/crane_reference.json as a person would, with the Fold tool (key F) and, where only the
menu has an entry, the Interact tool's menu; each gesture is planned from the paper it sees
(`state`) and the highlight the interaction shows (`interaction_status`), as
test/ros/crane_by_mouse_rostest.cpp does with synthesized feedback:
  - crease (steps 1-4, 9-11, 14, 16): key 1, a drag along the line, its ends on the paper; the
    line snaps. The head's line (18) is on no snapping guide: "Snap the line" off in the menu for
    that drag and on again;
  - half turn (5-6): key 2, a press on the flap and a drag over its axis past the pressed point's
    mirror image;
  - the squash (7-8), petal (12-13) and reverse folds (15, 17, 19): key 5 (flap mode), Tab for a
    lower layer as the table says, and one drag of the flap from the point the table names to
    where the reference folding puts it;
  - the wings (20-21): key 3 (fold mode), clicks beside each hinge crease (Tab for the layer
    below: a click picks the top crease, clicks cycle valley, mountain, unfold; where the last
    crease picked lay in the lower half of its stack, the wheel turned towards the user instead,
    which picks the bottom crease and walks up), then under the Interact tool "Keep the face here"
    (and "Next layer down") and "Fold to a right angle".
Each step is checked on `state`: exactly one new revision, the crease pattern the reference
folding has after that step (fold_sequence runs the same steps in core), and every folded vertex
where that folding puts it, within 1e-6 m after a rigid fit (proper rotation and translation);
the creases a marked fold folds carry the angle it asks for. The head's line is drawn freely, so
from step 18 on the vertices of the head (within 0.14 of its corner on the sheet) are held to
where the reference puts them within HEAD_OFF (a pixel's reach), every other vertex to 1e-6. The
gestures of each row of the walkthrough's table are counted (key presses and the tool switches
included) and printed beside the table's number. Screenshots of every step in the output folder.

Usage: crane_e2e.py OUTPUT_DIR   (with the devel space's environment, e.g. devel/env.sh)
"""
import json
import math
import re
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import interaction_e2e as e2e  # noqa: E402  (its Xvfb, launch, camera and mouse helpers)
from interaction_e2e import Failure, add, dot, mul, norm, sub, wait_for, xdotool  # noqa: E402

import rosbag  # noqa: E402
import roslib.packages  # noqa: E402
import rospy  # noqa: E402
from virtual_origami.msg import ToolEvent  # noqa: E402
from visualization_msgs.msg import InteractiveMarkerFeedback, MarkerArray  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REFERENCE = os.path.join(HERE, '..', 'data', 'crane_reference.json')
WALKTHROUGH = os.path.join(HERE, '..', '..', 'docs', 'INTERACTION.md')
TIME_LIMIT = 220     # seconds for the whole test (about 80 on two cores)
EXACT = 1e-6         # metres: the mouse's paper against the reference folding, after a rigid fit
HEAD_CORNER, HEAD_REACH = (1.0, 0.0), 0.14  # the head's part of the sheet (its line lies 0.12 from the corner)
HEAD_OFF = 0.005     # metres: the head's vertices from the reference's, its line drawn by the pixel
SNAP_RADIUS = 0.03   # the interaction node's snap radius on a 1 m sheet (core::SnapSettings)
SHEET = 'paper'       # the interaction's interactive marker of the sheet (InteractionStyle::marker_name)
DOUBLE_CLICK = 0.5    # seconds: Qt's double-click interval (400 ms) and a little
MESSAGE_LIFETIME = 4.3  # seconds the interaction's message shows (its marker's lifetime, 4 s)
MOST_GESTURES = 100   # issue 39's target for the crane


class NoSnap(Failure):
    """A line no press and release snap onto."""


# The interaction node's menu as rviz shows it (interaction_menu.cpp), from 1.
CREASE_MODE, ROTATE_MODE, FOLD_MODE, FLAP_MODE = 1, 2, 11, 18
FOLD_ON_MARKED = 13  # a submenu: Fold flat, Fold to a right angle, Keep the face here, Clear the marks
FOLD_FLAT, RIGHT_ANGLE, KEEP_FACE = 1, 2, 3
NEXT_LAYER = 14
SNAP_THE_LINE = 16
MODES = {'crease': CREASE_MODE, 'rotate': ROTATE_MODE, 'fold': FOLD_MODE, 'flap': FLAP_MODE}
MODE_KEYS = {'crease': '1', 'rotate': '2', 'fold': '3', 'flap': '5'}  # the Fold tool's keys (tool_keys.cpp)


# ---------------------------------------------------------------------------------------------
# The paper as `state` gives it, and the geometry the plan needs.

class Paper:
    def __init__(self, msg):
        self.revision = msg.revision
        self.cp = [(p.x, p.y) for p in msg.vertices_crease_pattern]
        self.at = [(p.x, p.y, p.z) for p in msg.vertices_folded]
        self.edges = [(e.v0, e.v1, e.face_left, e.face_right, e.fold_angle) for e in msg.edges]
        self.faces = [list(f.vertices) for f in msg.faces]
        self.orders = [(o.face, o.other, o.above) for o in msg.face_orders]

    def is_crease(self, e):
        return self.edges[e][2] >= 0 and self.edges[e][3] >= 0

    def midpoint(self, e):
        return mul(0.5, add(self.at[self.edges[e][0]], self.at[self.edges[e][1]]))

    def centroid(self, f):
        return mul(1.0 / len(self.faces[f]), sum_points([self.at[v] for v in self.faces[f]]))

    def normal(self, f):
        vs = self.faces[f]
        n = (0.0, 0.0, 0.0)
        for i, v in enumerate(vs):
            n = add(n, cross(self.at[v], self.at[vs[(i + 1) % len(vs)]]))
        return mul(1.0 / norm(n), n) if norm(n) > 0 else (0.0, 0.0, 1.0)

    def vertex_at(self, q):
        for i, p in enumerate(self.cp):
            if math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-9:
                return i
        return -1

    def face_containing(self, q):
        """The face whose crease-pattern polygon holds q (core::faceContaining)."""
        for f, vs in enumerate(self.faces):
            pts = [self.cp[v] for v in vs]
            if all((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0]) >= -1e-12
                   for a, b in zip(pts, pts[1:] + pts[:1])):
                return f
        return -1

    def holds(self, f, p):
        """Whether face f covers the point p seen from above (inside, not on its outline)."""
        pts = [self.at[v] for v in self.faces[f]]
        sides = [(b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]) for a, b in zip(pts, pts[1:] + pts[:1])]
        return all(x > 1e-9 for x in sides) or all(x < -1e-9 for x in sides)

    def layers_over(self, f, p):
        """How many faces lie over face f at p, seen from above (the stacking order `state` holds)."""
        over = 0
        for a, b, above in self.orders:
            if a == f and self.holds(b, p) and above * self.normal(a)[2] > 0:
                over += 1  # b on f's side towards the eye
            elif b == f and self.holds(a, p) and above * self.normal(a)[2] < 0:
                over += 1  # f on a's side away from the eye
        return over

    def point_at(self, f, q):
        """Where face f puts the crease-pattern point q on the folded model (faces stay flat): the
        affine map of its widest corner triangle."""
        vs = self.faces[f]
        best, corners = -1.0, None
        for i in range(len(vs)):
            for j in range(i + 1, len(vs)):
                for k in range(j + 1, len(vs)):
                    a, b, c = (self.cp[vs[i]], self.cp[vs[j]], self.cp[vs[k]])
                    area = abs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
                    if area > best:
                        best, corners = area, (vs[i], vs[j], vs[k])
        a, b, c = [self.cp[v] for v in corners]
        det = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
        s = ((q[0] - a[0]) * (c[1] - a[1]) - (q[1] - a[1]) * (c[0] - a[0])) / det
        t = ((b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])) / det
        pa, pb, pc = [self.at[v] for v in corners]
        return add(pa, add(mul(s, sub(pb, pa)), mul(t, sub(pc, pa))))

    def creases_on(self, start, end):
        """The crease edges lying on a crease-pattern segment (as flat_fold names them)."""
        def on(v):
            return segment_distance(self.cp[v], start, end) < 1e-9
        return [e for e, (a, b, _, _, _) in enumerate(self.edges) if self.is_crease(e) and on(a) and on(b)]


def sum_points(points):
    s = (0.0, 0.0, 0.0)
    for p in points:
        s = add(s, p)
    return s


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    return mul(1.0 / norm(a), a)


def segment_distance(q, a, b):
    """Distance of 2D point q from the segment a-b."""
    d = (b[0] - a[0], b[1] - a[1])
    length2 = d[0] * d[0] + d[1] * d[1]
    t = 0.0 if length2 == 0 else max(0.0, min(1.0, ((q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1]) / length2))
    return math.hypot(q[0] - a[0] - t * d[0], q[1] - a[1] - t * d[1])


def pairs(a, b, tolerance=1e-7):
    """Vertices of paper a and b with the same crease-pattern position; None when the sets differ."""
    if len(a.cp) != len(b.cp):
        return None
    out = []
    for i, p in enumerate(a.cp):
        match = [j for j, q in enumerate(b.cp) if math.hypot(p[0] - q[0], p[1] - q[1]) < tolerance]
        if len(match) != 1:
            return None
        out.append((i, match[0]))
    return out


def jacobi_top_eigenvector(m):
    """The eigenvector of the symmetric matrix m (lists) with the largest eigenvalue."""
    n = len(m)
    a = [row[:] for row in m]
    v = [[float(i == j) for j in range(n)] for i in range(n)]
    for _ in range(100):
        off = sum(a[i][j] ** 2 for i in range(n) for j in range(n) if i != j)
        if off < 1e-30:
            break
        for p in range(n):
            for q in range(p + 1, n):
                if abs(a[p][q]) < 1e-300:
                    continue
                theta = (a[q][q] - a[p][p]) / (2 * a[p][q])
                t = (1.0 if theta >= 0 else -1.0) / (abs(theta) + math.sqrt(theta * theta + 1))
                c = 1 / math.sqrt(t * t + 1)
                s = t * c
                for k in range(n):  # a <- a J (columns p, q)
                    akp, akq = a[k][p], a[k][q]
                    a[k][p], a[k][q] = c * akp - s * akq, s * akp + c * akq
                for k in range(n):  # a <- J^T a (rows p, q)
                    apk, aqk = a[p][k], a[q][k]
                    a[p][k], a[q][k] = c * apk - s * aqk, s * apk + c * aqk
                for k in range(n):
                    vkp, vkq = v[k][p], v[k][q]
                    v[k][p], v[k][q] = c * vkp - s * vkq, s * vkp + c * vkq
    best = max(range(n), key=lambda i: a[i][i])
    return [v[k][best] for k in range(n)]


class Rigid:
    """x -> r x + t."""

    def __init__(self, r=((1, 0, 0), (0, 1, 0), (0, 0, 1)), t=(0.0, 0.0, 0.0)):
        self.r, self.t = r, t

    def __call__(self, p):
        return add(tuple(dot(row, p) for row in self.r), self.t)


def rigid_fit(src, dst):
    """The proper rigid motion that maps the points src onto dst best (Horn's quaternions), and
    the largest distance left."""
    cs, cd = mul(1.0 / len(src), sum_points(src)), mul(1.0 / len(dst), sum_points(dst))
    s = [[0.0] * 3 for _ in range(3)]
    for p, q in zip(src, dst):
        a, b = sub(p, cs), sub(q, cd)
        for i in range(3):
            for j in range(3):
                s[i][j] += a[i] * b[j]
    (xx, xy, xz), (yx, yy, yz), (zx, zy, zz) = s
    n = [[xx + yy + zz, yz - zy, zx - xz, xy - yx],
         [yz - zy, xx - yy - zz, xy + yx, zx + xz],
         [zx - xz, xy + yx, -xx + yy - zz, yz + zy],
         [xy - yx, zx + xz, yz + zy, -xx - yy + zz]]
    w, x, y, z = jacobi_top_eigenvector(n)
    r = ((w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)),
         (2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)),
         (2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z))
    motion = Rigid(r, (0.0, 0.0, 0.0))
    motion.t = sub(cd, motion(cs))
    return motion, max(norm(sub(motion(p), q)) for p, q in zip(src, dst))


def compare(paper, reference, head=False):
    """How far the paper's folded vertices lie from the reference's after the best rigid fit
    (infinity when their crease patterns differ), and that fit (reference -> paper). With `head`
    (the head's line drawn freely), the vertices of the head's part of the sheet are matched to the
    nearest (within 0.01) and left out of the fit; then also how far the farthest of them lies."""
    if not head:
        matched = pairs(reference, paper)
        if matched is None:
            return float('inf'), None
        return rigid_fit([reference.at[i] for i, _ in matched], [paper.at[j] for _, j in matched])[::-1]
    if len(reference.cp) != len(paper.cp):
        return float('inf'), None, float('inf')
    body, tip = [], []
    for i, p in enumerate(reference.cp):
        if math.hypot(p[0] - HEAD_CORNER[0], p[1] - HEAD_CORNER[1]) < HEAD_REACH:
            j = min(range(len(paper.cp)), key=lambda k: math.hypot(paper.cp[k][0] - p[0], paper.cp[k][1] - p[1]))
            if math.hypot(paper.cp[j][0] - p[0], paper.cp[j][1] - p[1]) > 0.01:
                return float('inf'), None, float('inf')
            tip.append((i, j))
        else:
            match = [j for j, q in enumerate(paper.cp) if math.hypot(p[0] - q[0], p[1] - q[1]) < 1e-7]
            if len(match) != 1:
                return float('inf'), None, float('inf')
            body.append((i, match[0]))
    fit, off = rigid_fit([reference.at[i] for i, _ in body], [paper.at[j] for _, j in body])
    return off, fit, max(norm(sub(fit(reference.at[i]), paper.at[j])) for i, j in tip)


# Snapping as the interaction node does it (core/snap.cpp), to plan lines that snap exactly.
def snap_point(paper, cursor, start_vertex=-1, radius=SNAP_RADIUS):
    """(point, kind, vertex) the node snaps the cursor to."""
    best, found = radius, None
    for v, p in enumerate(paper.at):
        d = norm(sub(p, cursor))
        if d <= best:
            best, found = d, (p, 'vertex', v)
    if found:
        return found
    best, edge, divisions = radius, -1, 0
    for e, (a, b, _, _, _) in enumerate(paper.edges):
        pa, pb = paper.at[a], paper.at[b]
        for n in (2, 4):
            for k in range(1, n):
                p = add(pa, mul(k / n, sub(pb, pa)))
                d = norm(sub(p, cursor))
                if d < best - 1e-12 or (edge == e and d <= best and n < divisions):
                    best, edge, divisions, found = d, e, n, (p, 'edge division', -1)
    if found or start_vertex < 0:
        return found or (cursor, 'none', -1)
    p = paper.at[start_vertex]
    if norm(sub(cursor, p)) <= radius:
        return cursor, 'none', -1
    best, face, divisions = radius, -1, 0
    # The faces of every vertex lying there, in any layer (as core/snap.cpp).
    here = [v for v, q in enumerate(paper.at) if norm(sub(q, p)) <= 1e-9]
    for corner, f in [(v, f) for v in here for f, vs in enumerate(paper.faces) if v in vs]:
        vs = paper.faces[f]
        i = vs.index(corner)
        to_next = unit(sub(paper.at[vs[(i + 1) % len(vs)]], p))
        to_prev = unit(sub(paper.at[vs[i - 1]], p))
        angle = math.acos(max(-1.0, min(1.0, dot(to_next, to_prev))))
        axis = unit(cross(to_next, to_prev))
        for n in (2, 4):
            for k in range(1, n):
                a = angle * k / n  # to_next turned by a about axis (Rodrigues; axis is normal to it)
                direction = add(mul(math.cos(a), to_next), mul(math.sin(a), cross(axis, to_next)))
                t = dot(sub(cursor, p), direction)
                if t <= 0:
                    continue
                d = norm(sub(add(p, mul(t, direction)), cursor))
                if d < best - 1e-12 or (face == f and d <= best and n < divisions):
                    best, face, divisions = d, f, n
                    found = (add(p, mul(max(t, exit_along(paper, f, p, direction)), direction)), 'angle division', -1)
    return found or (cursor, 'none', -1)


def exit_along(paper, f, p, direction):
    vs, n, out = paper.faces[f], paper.normal(f), 0.0
    for i, v in enumerate(vs):
        a, b = paper.at[v], paper.at[vs[(i + 1) % len(vs)]]
        across = dot(cross(direction, sub(b, a)), n)
        if abs(across) < 1e-12:
            continue
        t = dot(cross(sub(a, p), sub(b, a)), n) / across
        s = dot(sub(add(p, mul(t, direction)), a), sub(b, a)) / dot(sub(b, a), sub(b, a))
        if t > 1e-12 and -1e-9 <= s <= 1 + 1e-9:
            out = max(out, t)
    return out


MOUSE_OFF = 0.003  # metres: where a pixel of the default view lands, at worst, from where it is aimed


def plan_line(paper, a, b):
    """Where to press and where to release so that the line snaps to exactly a-b (or a longer
    piece of the same line), wherever within MOUSE_OFF of those points the mouse lands: the
    press points to try, best first, and the release point."""
    d = sub(b, a)

    def along(p):  # position along the line (0 at a, 1 at b), and distance from it
        t = dot(sub(p, a), d) / dot(d, d)
        return t, norm(sub(p, add(a, mul(t, d))))

    def steady(cursor, good, start_vertices=(-1,)):
        """Where the cursor snaps wherever within MOUSE_OFF the mouse lands: (point, the vertices
        there it may snap to), None unless always at the same point and `good`."""
        point, vertices = None, set()
        for v in start_vertices:
            for dx in (-MOUSE_OFF, 0.0, MOUSE_OFF):
                for dy in (-MOUSE_OFF, 0.0, MOUSE_OFF):
                    s = snap_point(paper, add(cursor, (dx, dy, 0.0)), v)
                    if s[1] == 'none' or not good(*along(s[0])) or (point and norm(sub(point, s[0])) > 1e-9):
                        return None
                    point = point or s[0]
                    if s[1] == 'vertex':
                        vertices.add(s[2])  # coincident vertices of the layers: any of them
        return point, vertices

    fractions = [0.0, 0.05, 0.1, 0.15, 0.2, 0.3]  # of the way in from the end
    presses = []
    for f in fractions:
        start = steady(add(a, mul(f, d)), lambda t, off: t <= 1e-9 and off < 1e-9)
        if start and (not presses or norm(sub(start[0], presses[0][1][0])) < 1e-9):
            presses.append((add(a, mul(f, d)), start))  # the same start whichever is pressed
    if not presses:
        raise NoSnap('no press point snaps the line (%.4f, %.4f)-(%.4f, %.4f) onto itself' % (a[:2] + b[:2]))
    # Where the layers' corners coincide, the press snaps to any of their vertices; the angle
    # divisions at it are those of its own faces. The release is planned for one of them; the
    # drag checks its guide (Folder.crease).
    vertices = set().union(*[s[1] for _, s in presses]) or {-1}
    presses = [p for p, _ in presses]
    for f in fractions:
        release = add(b, mul(-f, d))
        if any(steady(release, lambda t, off: t >= 1 - 1e-9 and off < 1e-9, (v,)) for v in sorted(vertices)):
            return presses, release
    raise NoSnap('no release point snaps the line (%.4f, %.4f)-(%.4f, %.4f) onto itself' % (a[:2] + b[:2]))


def on_paper(paper, start, end):
    """The part of the line start-end over the paper (the flat folded paper seen from above)."""
    d = sub(end, start)
    inside = []
    for f in range(len(paper.faces)):
        pts = [paper.at[v] for v in paper.faces[f]]
        lo, hi = -math.inf, math.inf
        sign = 1.0 if paper.normal(f)[2] >= 0 else -1.0
        for a, b in zip(pts, pts[1:] + pts[:1]):
            # inside: sign * cross2(b - a, x - a) >= 0, with x = start + s d
            c0 = sign * ((b[0] - a[0]) * (start[1] - a[1]) - (b[1] - a[1]) * (start[0] - a[0]))
            c1 = sign * ((b[0] - a[0]) * d[1] - (b[1] - a[1]) * d[0])
            if abs(c1) < 1e-15:
                if c0 < -1e-12:
                    lo, hi = 1, 0
            elif c1 > 0:
                lo = max(lo, -c0 / c1)
            else:
                hi = min(hi, -c0 / c1)
        if lo <= hi:
            inside.append((lo, hi))
    lo, hi = max(0.0, min(i[0] for i in inside)), min(1.0, max(i[1] for i in inside))
    return add(start, mul(lo, d)), add(start, mul(hi, d))


# ---------------------------------------------------------------------------------------------
# The reference folding: fold_sequence runs the same steps in core.

def reference_states(out):
    """The reference's steps, and its paper before its first step and after each step (Paper objects)."""
    folder = os.path.join(out, 'reference')
    os.makedirs(folder, exist_ok=True)
    tools = roslib.packages.find_node('virtual_origami', 'fold_sequence')
    if not tools:
        raise Failure('fold_sequence is not built (the reference folding)')
    subprocess.run([tools[0], REFERENCE, '--out', folder], check=True, capture_output=True)
    with open(REFERENCE) as f:
        steps = json.load(f)['steps']
    with rosbag.Bag(os.path.join(folder, 'crane_reference.bag')) as bag:
        states = [Paper(m) for _, m, _ in bag.read_messages(topics=['/origami/state'])]
    return steps, states[-(len(steps) + 1):]


class Row:
    """A row of the walkthrough's table: its steps, its gestures, and for each fold step made by a
    drag the point pressed, the layers down (Next layer down; negative: up, Next layer up) and the
    fold it names."""

    def __init__(self, first, last, gestures, how):
        self.first, self.last, self.gestures, self.how = first, last, gestures, how
        self.drags = {}
        numbers = list(re.finditer(r'\*\*([0-9]+)\*\*', how))
        for i, n in enumerate(numbers):
            said = how[n.end():numbers[i + 1].start() if i + 1 < len(numbers) else len(how)]
            press = re.search(r'press at \(([-0-9.]+), ([-0-9.]+)\)', said)
            kind = re.search(r'\*((?:squash|petal|inside reverse|outside reverse|reverse) fold)\*', said)
            if press and kind:
                walk = re.search(r'\*Next layer (down|up)\* (once|twice|([0-9]+) times)', said)
                layers = 0 if not walk else 1 if walk.group(2) == 'once' else 2 if walk.group(2) == 'twice' \
                    else int(walk.group(3))
                if walk and walk.group(1) == 'up':
                    layers = -layers
                self.drags[int(n.group(1))] = ((float(press.group(1)), float(press.group(2))), layers, kind.group(1))


def walkthrough():
    """docs/INTERACTION.md's crane walkthrough (as test/unit/crane_walkthrough.h reads it): its rows,
    and the total gestures it gives."""
    with open(WALKTHROUGH) as f:
        text = f.read()
    text = text[text.index('\n## Fold a crane'):]
    text = text[:text.index('\n## ', 1)]
    total = re.search(r'([0-9]+) steps,\s*\*\*([0-9]+) gestures\*\*', text)
    rows = [Row(int(m.group(1)), int(m.group(2) or m.group(1)), int(m.group(3)), m.group(4))
            for m in re.finditer(r'\n\|\s*([0-9]+)(?:–([0-9]+))?\s*\|[^|]*\|\s*([0-9]+)\s*\|([^\n]*)\|', text)]
    if not rows or not total:
        raise Failure('%s: no crane walkthrough table' % WALKTHROUGH)
    return rows, int(total.group(2))


# ---------------------------------------------------------------------------------------------
# The mouse, as a person folds: look, click, look at the highlight.

class Folder:
    """Gestures in rviz, and the operations of the crane made of them.

    rviz gives a press to what it draws nearest the eye under the pointer: where the
    interaction's guides (the picked crease's highlight, the marks, the message) lie over the
    sheet, a press there reaches no interactive marker (it goes to the view, which a press without
    a drag leaves as it is). So each gesture has places to try, best first, as a person moves the
    pointer beside a highlight: a click counts when rviz sends its press, a menu when it opens.
    The message of the last gesture floats over the paper near where it was made for 4 s: where
    it hides every place to try, the gesture waits for it to go, as a person would. Two clicks
    at one place within Qt's double-click interval make a double click, which rviz does not pass
    on: the second waits."""

    def __init__(self, check, mouse):
        self.check, self.mouse = check, mouse
        self.events = []  # feedback event types rviz sent, in order
        self.gestures = 0
        self.missed = {}  # presses rviz gave to something drawn over the sheet, by gesture
        self.waited = 0.0  # seconds waited for a message to go
        self.last_click = None  # (time, pixel)
        self.told = 0.0
        self.pick = None  # where the last crease pick was clicked
        self.from_below = False  # the last crease picked lay in the lower half of its stack
        self.sheet_presses = 0  # presses rviz gave to the sheet (not to the fold slider's handle)
        rospy.Subscriber('/origami/interaction/feedback', InteractiveMarkerFeedback, self._feedback)
        self.guide = None  # the crease drag's line as the interaction draws it (snapped)
        rospy.Subscriber('/origami/interaction_markers', MarkerArray, self._guides)
        self.tool = False  # the Fold tool is rviz's current tool (else the Interact tool)
        self.tool_events = []  # the kinds of the Fold tool's events, in order
        self.switches = 0  # tool switches (key F), among the gestures
        rospy.Subscriber('/origami/tool_events', ToolEvent, lambda e: self.tool_events.append(e.kind))
        self.unseen = 0  # events the node received before these subscriptions (calibrate())
        self.trace = []  # what each gesture was, in order

    def _feedback(self, msg):
        if msg.event_type == InteractiveMarkerFeedback.MOUSE_DOWN and msg.marker_name == SHEET:
            self.sheet_presses += 1
        self.events.append(msg.event_type)

    def _guides(self, msg):
        for m in msg.markers:
            if m.ns == 'line' and m.action == m.ADD and len(m.points) == 2:
                self.guide = tuple((p.x, p.y, p.z) for p in m.points)
            elif m.action == 3:  # DELETEALL
                self.guide = None

    # --- what the user sees
    def paper(self):
        return Paper(self.check.state)

    @property
    def status(self):
        return self.check.status

    def marked(self, edge):
        for e, a in zip(self.status.marked_edges, self.status.marked_angles):
            if e == edge:
                return a
        return None

    def on_table(self, pixel, z):
        """The point at height z under a pixel (the pixel's sight line onto that plane)."""
        eye, (right, down, forward) = self.check.camera()
        m = self.mouse
        ray = add(forward, add(mul((pixel[0] - m.cx) / m.focal, right), mul((pixel[1] - m.cy) / m.focal, down)))
        return add(eye, mul((z - eye[2]) / ray[2], ray))

    def beside(self, a, b, at, offsets):
        """Points on the paper's plane near `at` (on the line a-b), moved on the screen by
        (along, across) pixels of the line's image."""
        pa, pb, pm = self.mouse.pixel(a), self.mouse.pixel(b), self.mouse.pixel(at)
        length = math.hypot(pb[0] - pa[0], pb[1] - pa[1])
        t = ((pb[0] - pa[0]) / length, (pb[1] - pa[1]) / length)
        n = (-t[1], t[0]) if t[0] >= 0 else (t[1], -t[0])  # across, down the screen: away from the message
        return [self.on_table((pm[0] + u * t[0] + v * n[0], pm[1] + u * t[1] + v * n[1]), at[2]) for u, v in offsets]

    # --- gestures
    def sent(self):
        """The events rviz sent the interaction node (the sheet marker's feedback, the Fold tool's)."""
        return len(self.events) + len(self.tool_events)

    def calibrate(self):
        """Counts what the node received before this listened (it says once a second)."""
        time.sleep(1.2)
        self.unseen = self.status.feedback_received - self.sent()

    def handled(self, what):
        """The interaction node handled all rviz sent."""
        count = self.sent() + self.unseen
        wait_for(lambda: self.status.feedback_received >= count and self.status.pending == 0 and
                 not self.status.dragging, 30, what + ': the interaction node did not handle it')

    def settle(self, before, last_event, what):
        """The gesture's last event went out, and the interaction node handled all rviz sent.
        `before`: the events before the gesture, the sheet marker's (Interact) or the tool's."""
        sent = self.tool_events if self.tool else self.events
        try:
            wait_for(lambda: last_event in sent[before:], 10, '')
        except Failure:
            raise Failure('%s: rviz sent no event %d (it sent %s)' % (what, last_event, sent[before:]))
        self.handled(what)
        self.gestures += 1
        self.trace.append(what)
        self.told = time.time()  # the node's message about it shows for MESSAGE_LIFETIME

    def key(self, name, at, what):
        """A key of the Fold tool with the pointer at `at` (Tab, Enter and the number keys act
        where the pointer is)."""
        if not self.tool:
            raise Failure('%s: the key %s without the Fold tool' % (what, name))
        self.mouse.move(self.mouse.pixel(at))
        time.sleep(0.1)
        before = len(self.tool_events)
        xdotool('key', name)
        self.settle(before, ToolEvent.KEY, what)

    def wheel(self, at, away, what):
        """One notch of the Fold tool's wheel with the pointer at `at`: away from the user (the next
        layer down) or towards (the next layer up; with nothing picked there, the bottom layer)."""
        if not self.tool:
            raise Failure('%s: the wheel without the Fold tool' % what)
        self.mouse.move(self.mouse.pixel(at))
        time.sleep(0.1)
        before = len(self.tool_events)
        xdotool('click', 4 if away else 5)
        self.settle(before, ToolEvent.WHEEL, what)

    def use_tool(self, fold_tool):
        """Key F over the view: the Fold tool, or back to the Interact tool. Another key (x, which
        no tool and no action has) tells which is current: only the Fold tool sends it."""
        if self.tool == fold_tool:
            return
        self.mouse.away()
        time.sleep(0.1)
        xdotool('key', 'f')
        self.gestures += 1
        self.trace.append('key F: the %s tool' % ('Fold' if fold_tool else 'Interact'))
        self.switches += 1
        time.sleep(0.2)
        before = len(self.tool_events)
        xdotool('key', 'x')
        sent = False
        try:
            wait_for(lambda: ToolEvent.KEY in self.tool_events[before:], 0.6 if not fold_tool else 5, '')
            sent = True
        except Failure:
            pass
        if sent != fold_tool:
            raise Failure('key F did not %s' % ('select the Fold tool' if fold_tool else 'put the Fold tool away'))
        self.tool = fold_tool
        self.handled('the key x')

    def attempts(self, points, wait=True):
        """Each point, then the first once more after the message went (when one may be shown)."""
        for p in points:
            yield p
        left = self.told + MESSAGE_LIFETIME - time.time()
        if wait and left > 0:
            time.sleep(left)
            self.waited += left
            yield points[0]

    def miss(self, what):
        what = what.split(' (')[0].split(' beside')[0].split(' marking')[0]
        self.missed[what] = self.missed.get(what, 0) + 1

    def not_a_double_click(self, pixel):
        """Two clicks at one place within Qt's double-click interval make a double click, which
        rviz does not give to the marker: the second waits."""
        if self.last_click and math.hypot(pixel[0] - self.last_click[1][0], pixel[1] - self.last_click[1][1]) < 10:
            left = self.last_click[0] + DOUBLE_CLICK - time.time()
            if left > 0:
                time.sleep(left)
        self.last_click = (time.time(), pixel)

    def before(self):
        return (len(self.tool_events) if self.tool else len(self.events)), self.sheet_presses

    def pressed(self, before, sheet_presses, what, patience=1.0, hold=False):
        """rviz gave the press to the sheet marker (Interact) or the Fold tool sent it (the tool:
        and, for a drag, the node holds something there)."""
        if self.tool:
            try:
                wait_for(lambda: ToolEvent.PRESS in self.tool_events[before:], patience, '')
                if hold:
                    wait_for(lambda: self.status.dragging, patience, '')
            except Failure:
                self.miss(what)
                return False
            return True
        try:
            wait_for(lambda: InteractiveMarkerFeedback.MOUSE_DOWN in self.events[before:], patience, '')
        except Failure:
            self.miss(what)
            return False
        if self.sheet_presses == sheet_presses:
            raise Failure('a press meant for the sheet went to another interactive marker (the fold slider?)')
        return True

    @property
    def up(self):
        return ToolEvent.RELEASE if self.tool else InteractiveMarkerFeedback.MOUSE_UP

    def click(self, points, what, must=True):
        """A click at the first of `points` where rviz gives it to the sheet; that point (None,
        unless it `must`, when rviz gave it to none)."""
        for p in self.attempts(points, wait=not self.tool):
            self.mouse.move(self.mouse.pixel(p))
            time.sleep(0.12)
            self.not_a_double_click(self.mouse.pixel(p))
            before, sheet_presses = self.before()
            xdotool('click', 1)
            if self.pressed(before, sheet_presses, what):
                self.settle(before, self.up, what)
                return p
        if must:
            raise Failure('%s: rviz gave no click to the sheet at (%.3f, %.3f, %.3f) or %d places beside it' %
                          ((what,) + points[0] + (len(points) - 1,)))
        return None

    def press(self, points, what, must=True, wait=True, patience=1.0):
        """Holds the button down at the first of `points` where rviz gives the press to the sheet:
        (the events before it, the point); None, unless it `must`, where rviz gave it to none."""
        for p in self.attempts(points, wait and not self.tool):
            self.mouse.move(self.mouse.pixel(p))
            time.sleep(0.12)
            self.not_a_double_click(self.mouse.pixel(p))
            before, sheet_presses = self.before()
            xdotool('mousedown', 1)
            if self.pressed(before, sheet_presses, what, patience, hold=True):
                return before, p
            xdotool('mouseup', 1)  # the view took it: a press without a drag leaves it as it is
            time.sleep(0.1)
            if self.tool:
                self.handled(what + ' let go')  # a click: in crease and flap mode nothing
        if not must:
            return None
        raise Failure('%s: rviz gave no press to the sheet at (%.3f, %.3f, %.3f) or %d places beside it' %
                      ((what,) + points[0] + (len(points) - 1,)))

    def glide(self, pixels, pause=0.03):
        for p in pixels:
            self.mouse.move(p)
            time.sleep(pause)

    def release(self, before, what):
        time.sleep(0.15)
        xdotool('mouseup', 1)
        self.settle(before, self.up, what)

    @staticmethod
    def popups():
        r = subprocess.run(['xdotool', 'search', '--onlyvisible', '--class', 'rviz'], capture_output=True, text=True)
        return len(r.stdout.split())

    def menu(self, points, entry, sub_entry=None, what='menu', shot=None, must=True):
        """Right-click at the first of `points` where the menu opens; the `entry`-th item (from 1)
        with the keyboard, in a submenu the `sub_entry`-th (Right opens it on its first item).
        That point (None, unless it `must`, when the menu opened at none)."""
        for p in self.attempts(points):
            before, windows = len(self.events), self.popups()
            self.mouse.move(self.mouse.pixel(p))
            time.sleep(0.12)
            xdotool('click', 3)
            try:
                wait_for(lambda: self.popups() > windows, 1.0, '')
            except Failure:
                self.miss(what)
                continue
            xdotool('key', '--delay', 20, *(['Down'] * entry))
            if sub_entry:
                xdotool('key', 'Right')
                wait_for(lambda: self.popups() > windows + 1, 2.0, what + ': the submenu did not open')
                if sub_entry > 1:
                    xdotool('key', '--delay', 20, *(['Down'] * (sub_entry - 1)))
            if shot:
                time.sleep(0.3)
                shot()
            xdotool('key', 'Return')
            self.settle(before, InteractiveMarkerFeedback.MENU_SELECT, what)
            return p
        if must:
            raise Failure('%s: the menu did not open at (%.3f, %.3f, %.3f) or %d places beside it' %
                          ((what,) + points[0] + (len(points) - 1,)))
        return None

    def off_paper(self):
        """Points on the margin around the paper, off it: the corners of its box, pushed out."""
        at = self.paper().at
        lo, hi = [min(p[i] for p in at) for i in range(3)], [max(p[i] for p in at) for i in range(3)]
        corners = [(x, y, lo[2]) for x, y in ((lo[0] - 0.05, lo[1] - 0.05), (hi[0] + 0.05, lo[1] - 0.05),
                                              (lo[0] - 0.05, hi[1] + 0.05), (hi[0] + 0.05, hi[1] + 0.05))]
        px, py, w, h = e2e.PANEL
        x0, y0 = self.mouse.cx - w / 2.0, self.mouse.cy - h / 2.0

        def seen(p):  # in the render panel
            x, y = self.mouse.pixel(p)
            return x0 + 10 < x < x0 + w - 10 and y0 + 10 < y < y0 + h - 10
        return [p for p in corners if seen(p)]

    def mode(self, name):
        """The mode: its number key with the Fold tool, its menu entry with the Interact tool."""
        if self.status.mode != name:
            if self.tool:
                self.key(MODE_KEYS[name], self.off_paper()[0], name + ' mode')
            else:
                self.menu(self.off_paper(), MODES[name], what=name + ' mode')
            wait_for(lambda: self.status.mode == name, 5, 'no switch to %s mode' % name)

    def committed(self, revision, what):
        state = self.check.wait_revision(revision, what)
        time.sleep(0.3)  # rviz takes the sheet marker the node sent for it
        return Paper(state)

    # --- operations, planned from the paper now
    def crease(self, start, end, revision):
        """A drag along the line, from where it enters the paper to where it leaves it; the ends
        pressed where the line snaps onto itself (a vertex, an edge's division, the division of
        the angle at the start vertex), whichever pixel the mouse lands on. Released where the
        guide shows the line snapped onto itself; else taken back to the press (no crease) and
        pressed again a pixel aside."""
        self.mode('crease')
        now = self.paper()
        a, b = on_paper(now, start, end)
        presses, release = plan_line(now, a, b)
        d = sub(b, a)

        def on_line(p, ahead):
            t = dot(sub(p, a), d) / dot(d, d)
            return norm(sub(p, add(a, mul(t, d)))) < 1e-9 and (t >= 1 - 1e-9 if ahead else t <= 1e-9)

        shown = None
        # Pixels around the press point: where the corners of the layers coincide, the vertex it
        # snaps to (and so the angle divisions offered) depends on the side it is pressed from.
        ring = [(0, 0)] + [(round(r * math.cos(k * math.pi / 4)), round(r * math.sin(k * math.pi / 4)))
                           for r in (6, 10) for k in range(8)]
        for dx, dy in ring:
            aside = [self.on_table(add(self.mouse.pixel(p), (dx, dy)), p[2]) for p in presses]
            # (a press rviz gives late makes a click: in crease mode nothing)
            held = self.press(aside, 'the crease', must=False, wait=False, patience=0.5)
            if not held:
                continue
            before, pressed = held
            self.glide([self.mouse.pixel(add(pressed, mul(i / 8.0, sub(release, pressed)))) for i in range(1, 9)])
            time.sleep(0.3)  # the node draws the guide for the pointer's last place
            shown = self.guide
            if shown and on_line(shown[0], False) and on_line(shown[1], True):
                self.release(before, 'the crease')
                return self.committed(revision, 'the crease')
            self.glide([self.mouse.pixel(pressed)])  # back: too short a line creases nothing
            self.release(before, 'the crease taken back')
            self.miss('the crease, its guide off the line')
        raise Failure('the crease (%.4f, %.4f)-(%.4f, %.4f): the guide never snapped onto it (last %s)' %
                      (a[:2] + b[:2] + (shown,)))

    def half_turn(self, click, foot, revision, shot=None):
        """Rotate mode; press at `click` and drag over the axis (through `foot`) to past the
        pressed point's mirror image, on the half circle the pressed point goes."""
        self.mode('rotate')
        around = [add(click, (dx, dy, 0.0)) for dx, dy in ((0, 0), (0.01, 0), (-0.01, 0), (0, 0.01), (0, -0.01))]
        before, click = self.press(around, 'the half turn')
        out = sub(click, foot)
        radius = norm(out)
        # Across the line of sight the view turns for the drag (seed Fig. 11): the path on the turned view.
        camera = self.check.camera()
        for _ in range(20):
            time.sleep(0.1)
            turned = self.check.camera()
            if norm(sub(turned[0], camera[0])) < 1e-4:
                break
            camera = turned
        path = []
        for i in range(1, 19):
            angle = math.pi * 1.15 * i / 18  # past the mirror image (below the table there): a half turn
            path.append(add(foot, add(mul(math.cos(angle), out), (0.0, 0.0, radius * math.sin(angle)))))
        self.glide([self.mouse.pixel(p, camera) for p in path])
        if shot:
            time.sleep(0.3)
            shot()
        self.release(before, 'the half turn')
        return self.committed(revision, 'the half turn')

    def let_go(self):
        """A click on the margin off the paper lets go of the pick."""
        self.click(self.off_paper(), 'a click off the paper')
        self.pick = None

    def down_to(self, picked, spots, what):
        """'Next layer down' at the first of `spots` where the menu opens, until `picked()` or the
        bottom; False when the menu opened at none."""
        while not picked() and self.status.picked_layer < self.status.layers:
            if self.tool:
                layer = self.status.picked_layer
                self.key('Tab', spots[0], 'Tab (%s)' % what)
                wait_for(lambda: self.status.picked_layer != layer, 2, 'Tab (%s) picked no layer below' % what)
            elif not self.menu(spots, NEXT_LAYER, what='Next layer down (%s)' % what, must=False):
                return False
        return True

    def mark(self, edge, angle):
        """Picks the crease and clicks it until it carries the angle's mark (crane_by_mouse's
        mark): with the Fold tool on its middle (where the layers' creases lie on each other, so
        Tab walks down from the pick), else 8 pixels beside it (the Interact tool gives a press on
        its highlight to the view), at its middle, or where the interaction's message does not
        hide it, further along."""
        now = self.paper()
        a, b = [now.at[v] for v in now.edges[edge][:2]]
        wanted = math.pi if angle > 0 else -math.pi if angle < 0 else 0.0

        def picked():
            return self.status.picked_edge == edge

        def at_spot(spot):
            # the spot, and a few pixels along the crease from it: within the pick's reach
            spot = [spot] + self.beside(a, b, spot, [(5, 0), (-5, 0)])
            if self.marked(edge) == wanted:
                return True
            if self.tool and self.from_below and not (self.pick is not None and self.pick == spot[0]) and \
                    (self.pick is None or norm(sub(spot[0], self.pick)) > SNAP_RADIUS + 0.005):
                # The wing underneath: its creases lie low in their stacks, so the wheel turned
                # towards the user picks the bottom one there, and walks up to the crease.
                self.wheel(spot[0], False, 'the wheel towards you (crease %d)' % edge)
                while not picked() and self.status.picked_layer > 1:
                    layer = self.status.picked_layer
                    self.wheel(spot[0], False, 'the wheel towards you (crease %d)' % edge)
                    wait_for(lambda: self.status.picked_layer != layer, 2, 'the wheel picked no layer above')
                self.pick = spot[0]
                if not picked():
                    self.let_go()
            if not (self.pick is not None and self.pick == spot[0] and self.status.picked_edge >= 0):
                # A click near the pick would mark the crease picked there: let go of it first.
                if self.pick is not None and self.status.picked_edge >= 0 and \
                        norm(sub(spot[0], self.pick)) <= SNAP_RADIUS + 0.005:
                    self.let_go()
                if not self.click(spot, 'a click beside crease %d' % edge, must=False):
                    return False
                self.pick = spot[0]
            if not self.down_to(picked, spot, 'crease %d' % edge):
                return False
            if not picked():  # the pick went past it: from the top again
                self.let_go()
                if not self.click(spot, 'a click beside crease %d' % edge, must=False):
                    return False
                self.pick = spot[0]
                if not self.down_to(picked, spot, 'crease %d' % edge) or not picked():
                    raise Failure('crease %d is not among the creases under (%.3f, %.3f, %.3f): %s' %
                                  ((edge,) + spot[0] + (self.status.message,)))
            if self.tool:
                self.from_below = 2 * self.status.picked_layer > self.status.layers + 1
            for _ in range(4):
                if self.marked(edge) == wanted:
                    return True
                if not self.click(spot, 'a click marking crease %d' % edge, must=False):
                    return False
            return self.marked(edge) == wanted

        spots = [mul(0.5, add(a, b))] if self.tool else []  # the Fold tool: on it (its highlight takes no press)
        for f in (0.5, 0.35, 0.65, 0.2, 0.8):
            spots += self.beside(a, b, add(a, mul(f, sub(b, a))), [(0, 8), (0, -8)])
        if self.pick is not None and self.status.picked_edge == edge:
            spots.insert(0, self.pick)
        for spot in spots:
            if at_spot(spot):
                return
        raise Failure('crease %d does not carry the mark %.2f after clicks all along it: %s' %
                      (edge, wanted, self.status.message))

    def keep(self, now, face, staying=()):
        """'Keep the face here' inside the face (its centroid, or towards its corners), and
        'Next layer down' there until the face is the one picked. Where another face the fold
        leaves in place (`staying`) lies on top at its centre, there instead: the same fold."""
        on_top = [f for f in staying if now.layers_over(f, now.centroid(f)) == 0]
        if face not in on_top and on_top and now.layers_over(face, now.centroid(face)) > 0:
            c = now.centroid(on_top[0])
            if self.menu([c], FOLD_ON_MARKED, KEEP_FACE, what='Keep the face here', must=False) and \
                    self.status.picked_face in staying:
                return c
        c = now.centroid(face)
        for spot in [c] + [add(c, mul(0.4, sub(now.at[v], c))) for v in now.faces[face]]:
            if self.menu([spot], FOLD_ON_MARKED, KEEP_FACE, what='Keep the face here', must=False) and \
                    self.down_to(lambda: self.status.picked_face == face, [spot], 'the face that stays') and \
                    self.status.picked_face == face:
                return spot
        raise Failure('the face that stays (%d) was never picked: %s' % (face, self.status.message))

    def flat_fold(self, request, before, after, revision, shot=None):
        """Marks the fold's creases with the Fold tool (clicks, Tab), then under the Interact tool
        picks the face that stays and folds from the menu (crane_by_mouse's flatFold): "Fold to a
        right angle" is the menu's alone."""
        self.use_tool(True)
        self.mode('fold')
        right_angle = False
        for line in request['creases']:
            edges = self.paper().creases_on(line['start'], line['end'])
            if not edges:
                raise Failure('no crease on (%.3f, %.3f)-(%.3f, %.3f)' % tuple(line['start'] + line['end']))
            right_angle = abs(abs(line['angle_deg']) - 90) < 1e-9
            for e in edges:
                self.mark(e, math.radians(line['angle_deg']))
        now = self.paper()
        face = face_that_stays(now, request, before, after)
        if face < 0:
            raise Failure('no face seen from above stays in this fold')
        self.use_tool(False)
        at = self.keep(now, face, faces_that_stay(now, before, after))
        self.pick = None
        if shot:
            self.mouse.away()
            time.sleep(0.3)
            shot()
        self.menu([at] + self.off_paper(), FOLD_ON_MARKED, RIGHT_ANGLE if right_angle else FOLD_FLAT,
                  what='Fold to a right angle' if right_angle else 'Fold flat')
        return self.committed(revision, 'the fold on the marked creases')

    def flap(self, drag, now, after, revision, shot=None):
        """Flap mode (key 5): Tab (or Shift+Tab, from the bottom) at the point the walkthrough names as
        often as it says (and on down until that point's face is picked), then one drag of the flap from there to where the
        reference folding puts that point, the face the interaction keeps (compound_fold's
        farthest face) where it lies now (crane_by_mouse's flapFold)."""
        (x, y), layers, kind = drag
        self.use_tool(True)
        self.mode('flap')
        face = now.face_containing((x, y))
        if face < 0:
            raise Failure('no face at (%.2f, %.2f)' % (x, y))
        at = now.point_at(face, (x, y))
        for _ in range(layers):
            self.key('Tab', at, 'Tab (the flap below)')
        for _ in range(-layers):  # from the bottom up
            self.key('shift+Tab', at, 'Shift+Tab (the flap above)')
        if layers < 0 and self.status.picked_face != face:
            raise Failure('the layer of (%.2f, %.2f) was not picked from below: %s' % (x, y, self.status.message))
        if layers > 0:
            self.down_to(lambda: self.status.picked_face == face, [at], 'the flap below')
            if self.status.picked_face != face:
                raise Failure('the layer of (%.2f, %.2f) was never picked: %s' % (x, y, self.status.message))

        def centre(f):
            return mul(1.0 / len(now.faces[f]), sum_points([now.cp[v] + (0.0,) for v in now.faces[f]]))
        pressed = centre(face)
        fixed = max(range(len(now.faces)), key=lambda f: (norm(sub(centre(f), pressed)), -f))
        corners = now.faces[fixed]
        moved = rigid_fit([after.at[after.vertex_at(now.cp[v])] for v in corners], [now.at[v] for v in corners])[0]
        target = moved(after.point_at(after.face_containing((x, y)), (x, y)))
        target = (target[0], target[1], at[2])  # the pointer's sight line meets the paper's plane there
        held = self.press([at], 'the ' + kind)
        if not held:
            raise Failure('the %s: no press on the flap at (%.2f, %.2f)' % (kind, x, y))
        before, _ = held
        way = [self.mouse.pixel(add(at, mul(i / 10.0, sub(target, at)))) for i in range(1, 11)]
        self.glide(way[:6], pause=0.05)
        if shot:  # the preview follows the pointer: the fold part way
            time.sleep(0.4)
            shot()
        self.glide(way[6:], pause=0.05)
        self.release(before, 'the ' + kind)
        paper = self.committed(revision, 'the ' + kind)
        said = kind[0].upper() + kind[1:] + '.'
        if self.status.message != said:
            raise Failure('the drag made "%s", the walkthrough says "%s"' % (self.status.message, said))
        return paper

    def free_crease(self, start, end, revision):
        """A line on no snapping guide (the head's): "Snap the line" off in the Interact tool's menu,
        a drag along the line with the Fold tool from just before to just past the paper (the line
        is creased where it crosses the paper), and snapping on again in the menu."""
        a, b = on_paper(self.paper(), start, end)
        d = sub(b, a)
        self.use_tool(False)
        self.menu(self.off_paper(), SNAP_THE_LINE, what='Snap the line (off)')
        self.use_tool(True)
        self.mode('crease')
        held = self.press([add(a, mul(-0.3, d))], 'the free line')
        if not held:
            raise Failure('no press at the free line\'s start')
        before, pressed = held
        release = add(b, mul(0.3, d))
        self.glide([self.mouse.pixel(add(pressed, mul(i / 8.0, sub(release, pressed)))) for i in range(1, 9)])
        self.release(before, 'the free line')
        paper = self.committed(revision, 'the free line')
        self.use_tool(False)
        self.menu(self.off_paper(), SNAP_THE_LINE, what='Snap the line (on)')
        return paper


def faces_that_stay(now, before, after):
    """The faces seen from above that the reference's fold leaves in place."""
    def stays(f):
        for v in now.faces[f]:
            r = before.vertex_at(now.cp[v])
            if r < 0 or norm(sub(before.at[r], after.at[after.vertex_at(now.cp[v])])) > 1e-9:
                return False
        return True
    return [f for f in range(len(now.faces)) if abs(now.normal(f)[2]) > 0.5 and stays(f)]


def face_that_stays(now, request, before, after):
    """The script's face that stays, or, where that one stands edge-on to the view from above, a
    face seen from there that the script's fold leaves in place too (crane_by_mouse's faceThatStays)."""
    def stays(f):
        for v in now.faces[f]:
            r = before.vertex_at(now.cp[v])
            if r >= 0 and norm(sub(before.at[r], after.at[after.vertex_at(now.cp[v])])) > 1e-9:
                return False
        return True

    def seen(f):
        return abs(now.normal(f)[2]) > 0.5
    scripts = now.face_containing(request['fixed'])
    if scripts >= 0 and seen(scripts):
        return scripts
    return next((f for f in range(len(now.faces)) if seen(f) and stays(f)), -1)


def mirror_foot(before, after, click):
    """A half turn of a flat flap: its axis is where a moved vertex and its mirror image meet
    halfway; the foot of `click` on it."""
    moved = []
    for i, p in enumerate(before.cp):
        j = after.vertex_at(p)
        if j >= 0 and norm(sub(before.at[i], after.at[j])) > 1e-6:
            moved.append((before.at[i], after.at[j]))
    if not moved:
        raise Failure('the reference half turn moves nothing')
    a, b = max(moved, key=lambda m: norm(sub(m[0], m[1])))
    middle = mul(0.5, add(a, b))
    n = unit((b[0] - a[0], b[1] - a[1], 0.0))
    d = (-n[1], n[0], 0.0)
    return add(middle, mul(dot(sub(click, middle), d), d))


# ---------------------------------------------------------------------------------------------

def run(out):
    started = time.time()
    steps, reference = reference_states(out)
    shots = []
    window = []
    shot, view_shot = e2e.shooters(out, window, shots)

    check = e2e.Checker()
    wait_for(lambda: check.state is not None, 60, 'no state from paper_model')
    revision = check.revision()
    wait_for(lambda: check.status is not None and check.status.revision == revision, 30,
             'the interaction node is not up')

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
    trace = []
    try:
        run_steps(out, check, window, shot, view_shot, steps, reference, started, trace)
    except Failure:
        shot('failure.png')
        raise
    finally:
        with open(os.path.join(out, 'gestures.txt'), 'w') as f:
            f.write(''.join('%3d %s\n' % (i + 1, what) for i, what in enumerate(trace)))
    print('screenshots:\n  ' + '\n  '.join(shots))


def run_steps(out, check, window, shot, view_shot, steps, reference, started, trace):
    revision = check.revision()
    mouse = e2e.Mouse(window, check)
    try:
        check.camera()
    except Exception as e:
        raise Failure('rviz does not broadcast its camera (the ViewCamera display): %s' % e)
    folder = Folder(check, mouse)
    folder.trace = trace
    # rviz draws the sheet and takes the interactive marker: a click on it reaches the node.
    for _ in range(15):
        mouse.click((0.5, 0.5, 0.0))  # in crease mode a click creases nothing
        try:
            wait_for(lambda: check.presses, 2, '')
            break
        except Failure:
            pass
    if not check.presses:
        raise Failure('a click on the sheet does not reach the interaction node')
    mouse.away()
    first = Paper(check.state)
    if compare(first, reference[0])[0] > EXACT:
        raise Failure('the sheet at the start is not the reference\'s flat square')
    view_shot('00_flat.png')
    print('ready after %.0f s' % (time.time() - started))

    to_paper = compare(first, reference[0])[1]  # reference -> the mouse's paper
    rows, total = walkthrough()
    folder.calibrate()
    head = False  # the head's line drawn freely (from step 18 on)
    counts = []
    for i, step in enumerate(steps):
        number = i + 1
        row = next((r for r in rows if r.first <= number <= r.last), None)
        if row is None:
            raise Failure('the walkthrough has no row for step %d' % number)
        if number == row.first:
            row_began, row_gestures, row_switches = time.time(), folder.gestures, folder.switches
        began, gestures = time.time(), folder.gestures
        before, after = reference[i], reference[i + 1]
        revision += 1
        if 'crease' in step:
            start, end = [to_paper(tuple(step['crease'][k]) + (0.0,)) for k in ('start', 'end')]
            try:
                folder.use_tool(True)
                paper = folder.crease(start, end, revision)
            except NoSnap:  # on no snapping guide: drawn freely
                paper = folder.free_crease(start, end, revision)
                head = True
            kind = 'crease'
        elif 'rotate' in step:
            if abs(abs(step['rotate']['angle_deg']) - 180) > 1e-9:
                raise Failure('step %d: the crane turns by half turns' % number)
            folder.use_tool(True)
            click = tuple(step['rotate']['click']) + (0.0,)
            paper = folder.half_turn(to_paper(click), to_paper(mirror_foot(before, after, click)), revision,
                                     shot=(lambda: view_shot('half_turn_drag.png')) if number == 5 else None)
            kind = 'half turn'
        elif number in row.drags:
            drag = row.drags[number]
            kind = drag[2]
            paper = folder.flap(drag, folder.paper(), after, revision,
                                shot=(lambda: view_shot('%02d_%s_drag.png' % (number, kind.replace(' ', '_')))))
        else:
            request = step['flat_fold']
            paper = folder.flat_fold(request, before, after, revision,
                                     shot=lambda: view_shot('%02d_marks.png' % number))
            kind = 'wing' if number in (20, 21) else 'flat fold'
        # The step's state: one new revision, the reference's crease pattern and folded form.
        if check.revision() != revision:
            raise Failure('step %d made revision %s, expected %d' % (number, check.revision(), revision))
        compared = compare(paper, after, head)
        off, fit = compared[:2]
        if fit is None:
            raise Failure('step %d (%s): the crease pattern differs from the reference\'s (%d vertices, %d expected)'
                          % (number, step['note'], len(paper.cp), len(after.cp)))
        if off > EXACT:
            raise Failure('step %d (%s): a vertex lies %.2g m from where the reference folding puts it'
                          % (number, step['note'], off))
        head_off = ''
        if head:
            if compared[2] > HEAD_OFF:
                raise Failure('step %d (%s): a vertex of the head lies %.3f m from where the reference puts it'
                              % (number, step['note'], compared[2]))
            head_off = ', the head\'s vertices %.4f m' % compared[2]
        to_paper = fit
        folded = ''
        if 'flat_fold' in step:
            worst = 0.0
            for line in step['flat_fold']['creases']:
                for e in paper.creases_on(line['start'], line['end']):
                    worst = max(worst, abs(abs(paper.edges[e][4]) - abs(math.radians(line['angle_deg']))))
            if worst > 1e-6:
                raise Failure('step %d: a crease of the fold is %.2g rad off the angle asked for' % (number, worst))
            flat = max(abs(p[2] - paper.at[0][2]) for p in paper.at)
            if flat > 1e-6 and number not in (20, 21):
                raise Failure('step %d: the folded paper is not flat (%.2g m)' % (number, flat))
            folded = ', flat' if number not in (20, 21) else ''
        folder.mouse.away()
        time.sleep(0.2)
        view_shot('%02d_%s.png' % (number, kind.replace(' ', '_')))
        print('step %2d %-20s %3d gestures %5.1f s: revision %d, %d vertices, %.1g m from the reference%s%s  (%s)' %
              (number, kind, folder.gestures - gestures, time.time() - began, revision, len(paper.cp), off, head_off,
               folded, step['note']))
        if number == row.last:
            made = folder.gestures - row_gestures
            counts.append((row, made, folder.switches - row_switches, time.time() - row_began))
    print('\nthe walkthrough\'s rows: gestures in rviz (of them tool switches, key F) / the table\'s')
    for row, made, switches, seconds in counts:
        print('  steps %2d-%2d: %3d (%d) / %3d  %5.1f s' % (row.first, row.last, made, switches, row.gestures, seconds))
    print('the crane by mouse and keys: %d steps, %d gestures (%d tool switches; the table: %d), %.0f s' %
          (len(steps), folder.gestures, folder.switches, total, time.time() - started))
    print('made again where the press went to the view or to a guide, or after the message went (%.0f s waited): %s'
          % (folder.waited, ', '.join('%s %d' % m for m in sorted(folder.missed.items())) or 'none'))
    time.sleep(max(0.0, folder.told + MESSAGE_LIFETIME - time.time()))  # the crane without the last message
    view_shot('crane.png')
    if folder.gestures > MOST_GESTURES:
        raise Failure('the crane took %d gestures, more than %d' % (folder.gestures, MOST_GESTURES))


def main():
    e2e.run_system(run, 'e2e_crane_output', TIME_LIMIT)

if __name__ == '__main__':
    main()
