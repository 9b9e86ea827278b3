#!/usr/bin/env python3
"""End-to-end: fold in real rviz with the Fold tool (virtual_origami/Fold), mouse and keyboard.

Starts Xvfb and the whole system (origami.launch with rviz and rviz/origami.rviz) as
interaction_e2e.py does, selects the Fold tool with its shortcut key F, and drives it with
xdotool (presses, drags, a double click, `click 4/5` for the wheel, key presses), checking the
paper on `state` and the interaction on `interaction_status`:
  1. F selects the tool: a click on the paper reaches the interaction node as a ToolEvent, not as
     the sheet marker's feedback; the number keys choose the mode (3 fold, 1 crease);
  2. crease mode: a drag along the diagonal creases it corner to corner;
  3. fold mode: a click marks the crease valley, a click picks the face that stays, Enter folds;
  4. Ctrl+Z undoes the fold, Ctrl+Y redoes it, Ctrl+Z again;
  5. a click marks the crease again and a double click on the other half folds with that half
     staying;
  6. Esc during a drag cancels it: nothing committed, the tool still the current one;
  7. the fold slider's handle (at 100 % for the folded diagonal) dragged by the tool to 50 %
     folds the diagonal to 90°;
  8. on a quarter fold (four layers, folded through the services) in rotate mode (key 2) the
     wheel turned away from the user (`click 4`) and Tab walk the layers under the pointer down to
     the fourth, and say when there is none below; the wheel towards the user (`click 5`) and
     Shift+Tab walk them back up to the first, and say when there is none above;
  9. a right click on the paper opens the sheet's menu from the Fold tool itself: *Next layer
     down* chosen with the keyboard reaches the node as the Interact tool's MENU_SELECT (the
     entry's id, the point under the mouse) and picks the second layer there; a right drag over
     the paper moves the view and opens no menu; elsewhere on the stack, with nothing picked
     there, the wheel towards the user picks the bottom layer;
  10. a drag beside the paper turns the view and sends the node nothing;
  11. F again puts the tool away: a click reaches the sheet marker as before (the interactive
     marker path unchanged).
Screenshots of every step (the status line shows what a click does) go to the output folder.

Usage: tool_e2e.py OUTPUT_DIR   (with the devel space's environment, e.g. devel/env.sh)
"""
import math
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import interaction_e2e as e2e  # noqa: E402  (its Xvfb, launch, camera and mouse helpers)
from interaction_e2e import Failure, wait_for, xdotool  # noqa: E402

import rospy  # noqa: E402
from virtual_origami.msg import ToolEvent  # noqa: E402
from visualization_msgs.msg import InteractiveMarkerFeedback, InteractiveMarkerInit, MarkerArray  # noqa: E402

TIME_LIMIT = 280  # seconds for the whole test


class ToolChecker(e2e.Checker):
    """The product's topics, and the Fold tool's events."""

    def __init__(self):
        super().__init__()
        self.tool_events = []
        self.slider = {}  # the fold slider's plain markers by namespace
        self.menu_selections = []  # MENU_SELECT feedback, from any client
        self.menu = []  # the sheet marker's menu entries
        rospy.Subscriber('/origami/tool_events', ToolEvent, self._tool_event)
        rospy.Subscriber('/origami/fold_slider_markers', MarkerArray, self._slider)
        rospy.Subscriber('/origami/interaction/feedback', InteractiveMarkerFeedback, self._menu_selected)
        rospy.Subscriber('/origami/interaction/update_full', InteractiveMarkerInit, self._init)

    def _menu_selected(self, msg):
        if msg.event_type == InteractiveMarkerFeedback.MENU_SELECT:
            self.menu_selections.append(msg)

    def _init(self, msg):
        for m in msg.markers:
            if m.name == 'paper':
                self.menu = m.menu_entries

    def _slider(self, msg):
        for m in msg.markers:
            self.slider[m.ns] = m

    def _tool_event(self, msg):
        self.tool_events.append(msg)

    def kinds(self, since):
        return [e.kind for e in self.tool_events[since:]]


def key(*names):
    for name in names:
        xdotool('key', name)
        time.sleep(0.4)


def run(out):
    shots = []
    window = []
    shot, view_shot = e2e.shooters(out, window, shots)

    check = ToolChecker()
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
    mouse = e2e.Mouse(window, check)
    try:
        check.camera()
    except Exception as e:
        raise Failure('rviz does not broadcast its camera (the ViewCamera display): %s' % e)
    time.sleep(5)  # rviz draws the sheet and takes the interactive marker
    mouse.away()
    shot('00_start.png')

    def status_says(what, part):
        wait_for(lambda: part in check.status.message, 10, '%s: the interaction said "%s"' %
                 (what, check.status.message))

    # 1. F over the view selects the Fold tool; a click goes to the node as a ToolEvent.
    mouse.move(mouse.pixel((0.5, 0.5, 0.0)))
    time.sleep(0.3)
    key('f')
    mouse.away()
    time.sleep(0.5)
    shot('01_fold_tool.png')
    presses, events = len(check.presses), len(check.tool_events)
    mouse.click((0.3, 0.6, 0.0))
    wait_for(lambda: ToolEvent.PRESS in check.kinds(events) and ToolEvent.RELEASE in check.kinds(events), 10,
             'F did not select the Fold tool: a click sent no ToolEvent')
    if len(check.presses) != presses:
        raise Failure('with the Fold tool a click still reached the sheet marker')
    if check.revision() != base:
        raise Failure('a click in crease mode changed the paper')
    print('tool: F selected it; a click came as ToolEvent %s' % check.kinds(events))
    mouse.move(mouse.pixel((0.5, 0.5, 0.0)))
    key('3')
    wait_for(lambda: check.status.mode == 'fold', 10, 'key 3 did not choose fold mode')
    shot('02_fold_mode.png')  # the status line: what a click does in fold mode
    key('1')
    wait_for(lambda: check.status.mode == 'crease', 10, 'key 1 did not choose crease mode')
    print('keys: 3 chose fold mode, 1 crease mode; the hint: %s' % check.status.hint)

    # 2. A drag along the diagonal creases it.
    mouse.drag((0.012, 0.015, 0.0), (0.99, 0.985, 0.0), during=lambda: shot('03_crease_drag.png'))
    creased = check.wait_revision(base + 1, 'the crease dragged with the Fold tool')
    a, b = e2e.vertex_at(creased, 0, 0), e2e.vertex_at(creased, 1, 1)
    diagonal = e2e.edge_between(creased, a, b)
    if diagonal < 0 or len(creased.faces) != 2:
        raise Failure('the drag did not crease the diagonal corner to corner (%d faces)' % len(creased.faces))
    shot('04_creased.png')
    print('crease: edge %d joins (0, 0) and (1, 1)' % diagonal)
    revision = base + 1

    # 3. Fold mode: mark, pick the face that stays, Enter.
    mouse.move(mouse.pixel((0.5, 0.5, 0.0)))
    key('3')
    wait_for(lambda: check.status.mode == 'fold', 10, 'key 3 did not choose fold mode')
    mouse.click((0.5, 0.5, 0.0))
    wait_for(lambda: list(check.status.marked_edges) == [diagonal], 10, 'the click did not mark the diagonal')
    mouse.click((0.8, 0.2, 0.0))
    wait_for(lambda: check.status.picked_face >= 0, 10, 'the click did not pick the face that stays')
    shot('05_marked.png')
    mouse.move(mouse.pixel((0.8, 0.2, 0.0)))
    key('Return')
    folded = check.wait_revision(revision + 1, 'Enter on the marked crease')
    revision += 1
    if abs(folded.edges[diagonal].fold_angle - math.pi) > 1e-6:
        raise Failure('Enter folded the diagonal to %.3f rad, not flat' % folded.edges[diagonal].fold_angle)
    moved = folded.vertices_folded[e2e.vertex_at(folded, 0, 1)]
    if math.hypot(moved.x - 1, moved.y) > 1e-6:
        raise Failure('the corner (0, 1) lies at (%.3f, %.3f), not on (1, 0)' % (moved.x, moved.y))
    time.sleep(1.0)
    shot('06_folded_by_enter.png')
    print('Enter: folded flat on the diagonal, (0, 1) onto (1, 0)')

    # 4. Ctrl+Z, Ctrl+Y, Ctrl+Z.
    key('ctrl+z')
    undone = check.wait_revision(revision + 1, 'Ctrl+Z')
    if abs(undone.edges[diagonal].fold_angle) > 1e-6:
        raise Failure('Ctrl+Z left the diagonal at %.3f rad' % undone.edges[diagonal].fold_angle)
    key('ctrl+y')
    redone = check.wait_revision(revision + 2, 'Ctrl+Y')
    if abs(redone.edges[diagonal].fold_angle - math.pi) > 1e-6:
        raise Failure('Ctrl+Y left the diagonal at %.3f rad' % redone.edges[diagonal].fold_angle)
    key('ctrl+z')
    check.wait_revision(revision + 3, 'Ctrl+Z again')
    revision += 3
    print('Ctrl+Z undid the fold, Ctrl+Y redid it, Ctrl+Z undid it again')

    # 5. Mark again; a double click on the other half folds with that half staying.
    mouse.click((0.5, 0.5, 0.0))
    wait_for(lambda: list(check.status.marked_edges) == [diagonal], 10, 'the click did not mark the diagonal again')
    mouse.move(mouse.pixel((0.2, 0.8, 0.0)))
    time.sleep(0.3)
    xdotool('click', '--repeat', 2, '--delay', 120, 1)
    doubled = check.wait_revision(revision + 1, 'the double click on the face that stays')
    revision += 1
    moved = doubled.vertices_folded[e2e.vertex_at(doubled, 1, 0)]
    if math.hypot(moved.x, moved.y - 1) > 1e-6:
        raise Failure('after the double click the corner (1, 0) lies at (%.3f, %.3f), not on (0, 1)' %
                      (moved.x, moved.y))
    mouse.away()
    time.sleep(1.0)
    shot('07_folded_by_double_click.png')
    print('double click: folded with the upper-left half staying')

    # 6. Esc during a drag: nothing committed, and the Fold tool stays.
    key('1')
    wait_for(lambda: check.status.mode == 'crease', 10, 'key 1 did not choose crease mode')
    mouse.press((0.3, 0.9, 0.0))
    mouse.glide(mouse.pixel((0.3, 0.9, 0.0)), mouse.pixel((0.05, 0.4, 0.0)))
    wait_for(lambda: check.status.dragging, 10, 'the press did not start a drag')
    shot('08_dragging.png')
    key('Escape')
    wait_for(lambda: not check.status.dragging, 10, 'Esc did not cancel the drag')
    status_says('Esc', 'Cancelled')
    xdotool('mouseup', 1)
    time.sleep(1.0)
    if check.revision() != revision:
        raise Failure('the cancelled drag changed the paper')
    events = len(check.tool_events)
    mouse.click((0.3, 0.9, 0.0))
    wait_for(lambda: ToolEvent.PRESS in check.kinds(events), 10, 'after Esc the Fold tool is no longer the current one')
    shot('09_cancelled.png')
    print('Esc: the drag cancelled, nothing committed, the tool still on')

    # 7. The fold slider's handle, at 100 % for the folded diagonal, dragged by the tool to 50 %.
    wait_for(lambda: 'fold_slider_track' in check.slider and 'fold_slider_percent' in check.slider and
             check.slider['fold_slider_percent'].text == 'fold 100 %', 10, 'no fold slider at 100 %')
    track = check.slider['fold_slider_track'].points
    minus, plus = (track[0].x, track[0].y, track[0].z), (track[1].x, track[1].y, track[1].z)
    zero = e2e.mul(0.5, e2e.add(minus, plus))
    half = e2e.add(zero, e2e.mul(0.5, e2e.sub(plus, zero)))
    mouse.drag(plus, half, during=lambda: shot('10_slider_drag.png'))
    slid = check.wait_revision(revision + 1, 'the slider dragged by the Fold tool')
    revision += 1
    angle = slid.edges[diagonal].fold_angle
    if abs(abs(angle) - math.pi / 2) > 0.05:
        raise Failure('the slider at 50 %% left the diagonal at %.1f°, not 90°' % math.degrees(angle))
    time.sleep(1.0)
    shot('11_slider_half.png')
    print('slider: dragged from 100 %% to 50 %%, the diagonal at %.1f°' % math.degrees(angle))

    # 8. The wheel and Tab on a quarter fold (four layers), in rotate mode.
    check.reset()
    check.crease(start=e2e.rospy_point(0.5, 0), end=e2e.rospy_point(0.5, 1))
    check.rotate(face=-1, axis_edge=-1, click=e2e.rospy_point(0.75, 0.5), angle=math.pi, commit=True)
    check.crease(start=e2e.rospy_point(0, 0.5), end=e2e.rospy_point(0.5, 0.5))
    quarter = check.rotate(face=-1, axis_edge=-1, click=e2e.rospy_point(0.25, 0.9), angle=math.pi,
                           commit=True).revision
    check.wait_revision(quarter, 'the quarter fold')
    time.sleep(1.0)
    at = (0.25, 0.2, 0.0)
    mouse.move(mouse.pixel(at))
    key('2')
    wait_for(lambda: check.status.mode == 'rotate', 10, 'key 2 did not choose rotate mode')
    walked = []

    def walk(action, layer):
        mouse.move(mouse.pixel(at))
        time.sleep(0.3)
        xdotool(*action.split())
        wait_for(lambda: check.status.picked_layer == layer, 10, '%s did not pick layer %d (%d of %d picked)' %
                 (action, layer, check.status.picked_layer, check.status.layers))
        walked.append((action, check.status.picked_layer, check.status.layers))
        time.sleep(0.5)  # rviz draws the pick

    # Down: button 4 is the wheel turned away from the user (Qt's positive delta).
    for layer, action in zip([2, 3, 4], ['click 4', 'key Tab', 'click 4']):
        walk(action, layer)
        shot('12_layer_%d.png' % layer)
    if check.status.layers != 4:
        raise Failure('%d layers under the pointer, expected 4' % check.status.layers)
    xdotool('click', 4)
    status_says('the wheel at the bottom', 'No layer below')
    bottom = check.status.message
    # Up: the wheel towards the user, Shift+Tab.
    for layer, action in zip([3, 2, 1], ['click 5', 'key shift+Tab', 'click 5']):
        walk(action, layer)
    if 'Layer 1 of 4' not in check.status.hint:
        raise Failure('at the top the status line says "%s"' % check.status.hint)
    shot('12_layer_1_again.png')
    xdotool('click', 5)
    status_says('the wheel at the top', 'No layer above')
    if check.revision() != quarter:
        raise Failure('walking the layers changed the paper')
    print('layers: %s; "%s" at the bottom, "%s" at the top' %
          (', '.join('%s -> %d of %d' % w for w in walked), bottom, check.status.message))

    # 9. A right click on the paper: the sheet's menu from the Fold tool; Next layer down in it.
    titles = [(e.id, e.title) for e in check.menu if e.parent_id == 0]
    place = [i for i, (_, title) in enumerate(titles) if title.endswith('Next layer down')]
    if not place:
        raise Failure('no entry Next layer down in the sheet marker\'s menu: %s' % [t for _, t in titles])
    entry = titles[place[0]][0]
    mouse.move(mouse.pixel((0.3, 0.3, 0.0)))
    time.sleep(0.3)
    events, selections = len(check.tool_events), len(check.menu_selections)
    xdotool('click', 3)
    time.sleep(1.0)
    shot('13_menu.png')
    key(*(['Down'] * (place[0] + 1)))  # the menu's entries from the top, the submenus' heads included
    key('Return')
    wait_for(lambda: len(check.menu_selections) > selections, 10, 'the right click\'s menu sent no choice')
    chosen = check.menu_selections[-1]
    if chosen.menu_entry_id != entry or chosen.marker_name != 'paper' or not chosen.mouse_point_valid:
        raise Failure('the menu sent entry %d of %s (point valid: %s), not Next layer down (%d) of paper' %
                      (chosen.menu_entry_id, chosen.marker_name, chosen.mouse_point_valid, entry))
    p = chosen.mouse_point
    if math.hypot(p.x - 0.3, p.y - 0.3) > 0.02:
        raise Failure('the menu\'s point (%.3f, %.3f, %.3f) is not under the mouse at (0.3, 0.3)' % (p.x, p.y, p.z))
    wait_for(lambda: check.status.picked_layer == 2 and check.status.layers == 4, 10,
             'Next layer down from the Fold tool\'s menu picked layer %d of %d' %
             (check.status.picked_layer, check.status.layers))
    if len(check.tool_events) != events:
        raise Failure('the right click sent ToolEvents %s' % check.kinds(events))
    time.sleep(0.5)
    shot('14_menu_chosen.png')
    print('right click: the menu from the Fold tool, Next layer down (id %d) at (%.3f, %.3f) sent by %s: layer 2 of 4'
          % (entry, p.x, p.y, chosen.client_id))
    # A right drag over the paper moves the view (rviz zooms) and opens no menu.
    eye = check.camera()[0]
    start = mouse.pixel((0.3, 0.3, 0.0))
    mouse.move(start)
    time.sleep(0.3)
    xdotool('mousedown', 3)
    mouse.glide(start, (start[0], start[1] + 60), steps=12)
    xdotool('mouseup', 3)
    time.sleep(1.0)
    moved = e2e.norm(e2e.sub(check.camera()[0], eye))
    if moved < 0.01:
        raise Failure('a right drag over the paper did not move the view (the eye moved %.4f m)' % moved)
    key('Return')  # were a menu open, this would choose its first entry (Crease mode)
    time.sleep(1.0)
    if len(check.menu_selections) != selections + 1 or check.status.mode != 'rotate':
        raise Failure('a right drag opened the menu (%d choices since, mode %s)' %
                      (len(check.menu_selections) - selections - 1, check.status.mode))
    shot('15_right_drag.png')
    print('right drag: the view moved (the eye %.2f m), no menu' % moved)
    # Elsewhere on the stack, with nothing picked there, the wheel towards the user starts at the bottom.
    mouse.move(mouse.pixel((0.2, 0.4, 0.0)))
    time.sleep(0.3)
    xdotool('click', 5)
    wait_for(lambda: check.status.picked_layer == 4 and check.status.layers == 4, 10,
             'the wheel towards the user with nothing picked picked layer %d of %d, not the bottom' %
             (check.status.picked_layer, check.status.layers))
    print('the wheel towards the user elsewhere: "%s"' % check.status.message)

    # 10. A drag beside the paper turns the view (rviz's own gesture) and sends the node nothing.
    events, eye = len(check.tool_events), check.camera()[0]
    corner = (mouse.cx - e2e.PANEL[2] / 2.0 + 60, mouse.cy - e2e.PANEL[3] / 2.0 + 60)
    mouse.move(corner)
    time.sleep(0.3)
    xdotool('mousedown', 1)
    mouse.glide(corner, (corner[0] + 120, corner[1] + 40), steps=12)
    xdotool('mouseup', 1)
    time.sleep(1.0)
    moved = e2e.norm(e2e.sub(check.camera()[0], eye))
    if moved < 0.01:
        raise Failure('a drag beside the paper did not turn the view (the eye moved %.4f m)' % moved)
    if len(check.tool_events) != events:
        raise Failure('a drag beside the paper sent the node %s' % check.kinds(events))
    shot('16_view_turned.png')
    print('beside the paper: the drag turned the view (the eye moved %.2f m), no ToolEvent' % moved)

    # 11. F puts the tool away: the sheet marker takes the clicks again.
    key('f')
    mouse.away()
    time.sleep(0.5)
    presses, events = len(check.presses), len(check.tool_events)
    mouse.click((0.3, 0.3, 0.0))  # on the quarter fold
    wait_for(lambda: len(check.presses) > presses, 10, 'with the Fold tool put away a click did not reach the '
             'sheet marker')
    if len(check.tool_events) != events:
        raise Failure('with the Fold tool put away it still sent events')
    shot('17_interact_again.png')
    print('F again: the Interact tool, the sheet marker takes the click')
    print('screenshots:\n  ' + '\n  '.join(shots))


def main():
    e2e.run_system(run, 'tool_e2e_output', TIME_LIMIT)


if __name__ == '__main__':
    main()
