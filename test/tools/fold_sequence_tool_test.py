#!/usr/bin/python3
"""fold_sequence turns a shipped sequence into a recording, a multi-frame FOLD file, an OBJ and a
PNG picture per step: every output exists, agrees with the others in its count of steps, and
reads back.

    fold_sequence_tool_test.py FOLD_SEQUENCE_BINARY SEQUENCE.json
"""
import json
import os
import subprocess
import sys
import tempfile

import rosbag


def main():
    tool, sequence = sys.argv[1], sys.argv[2]
    name = os.path.splitext(os.path.basename(sequence))[0]
    steps = sum(step.get("repeat", 1) for step in json.load(open(sequence))["steps"])
    failures = []

    def check(ok, what):
        print(("ok      " if ok else "FAILED  ") + what)
        if not ok:
            failures.append(what)

    with tempfile.TemporaryDirectory() as out:
        run = subprocess.run([tool, sequence, "--out", out], capture_output=True, text=True)
        print(run.stdout + run.stderr, end="")
        check(run.returncode == 0, f"fold_sequence {name} exits 0")
        if run.returncode != 0:
            return 1
        base = os.path.join(out, name)

        # FOLD: the key frame and one more per state; the first frame holds the crease pattern.
        fold = json.load(open(base + ".fold"))
        frames = 1 + len(fold.get("file_frames", []))
        check(frames == steps + 1, f"{name}.fold has a frame per state: the flat sheet and one per step "
                                   f"({frames} frames, {steps} steps)")
        check(len(fold.get("vertices_coords", [])) > 0 and len(fold.get("faces_vertices", [])) > 0,
              f"{name}.fold's key frame has vertices and faces")

        # The bag: the starting state, then each operation followed by the state it made.
        with rosbag.Bag(base + ".bag") as bag:
            operations = bag.get_message_count(topic_filters=["/origami/operations"])
            states = bag.get_message_count(topic_filters=["/origami/state"])
        check(operations == frames, f"{name}.bag has one operation per frame ({operations})")
        check(states == operations + 1, f"{name}.bag has the starting state and one per operation ({states})")

        # OBJ: the folded result, as vertices and faces.
        obj = open(base + ".obj").read().splitlines()
        check(any(l.startswith("v ") for l in obj) and any(l.startswith("f ") for l in obj),
              f"{name}.obj has vertices and faces")

        # Pictures: an SVG and a PNG per frame, the PNGs real PNG files.
        pictures = sorted(os.listdir(base + "_frames"))
        svgs = [p for p in pictures if p.endswith(".svg")]
        pngs = [p for p in pictures if p.endswith(".png")]
        check(len(svgs) == frames, f"an SVG per frame ({len(svgs)})")
        check(len(pngs) == frames, f"a PNG per frame ({len(pngs)})")
        check(all(open(os.path.join(base + "_frames", p), "rb").read(8) == b"\x89PNG\r\n\x1a\n" for p in pngs),
              "every PNG starts with the PNG signature")

        # A broken sequence file is refused with a message and writes nothing.
        broken = os.path.join(out, "broken.json")
        with open(broken, "w") as f:
            f.write('{"steps": [{"crease": ')
        run = subprocess.run([tool, broken, "--out", os.path.join(out, "never")], capture_output=True, text=True)
        check(run.returncode != 0 and "broken.json" in run.stderr, "a broken sequence file is refused, naming it")
        check(not os.path.exists(os.path.join(out, "never")), "and nothing is written for it")

    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
