#!/usr/bin/env python3
"""The table of docs/BENCHMARKS.md's "Real crease patterns" from pattern_bench's CSV:
   pattern_table.py docs/bench/patterns.csv > table.md
   pattern_table.py --summary docs/bench/patterns.csv: the CPU time of the calls, against issue 35's
   targets (every call within 5 s up to 5,000 vertices; under 1,000 vertices well under a second)"""
import csv
import sys
from collections import OrderedDict

STEPS = ["step_25", "step_50", "step_75", "step_100", "one_call_100"]


def number(text):
    try:
        return float(text)
    except ValueError:
        return None


def main(path):
    patterns = OrderedDict()
    with open(path, encoding='utf-8', errors='replace') as f:
        for row in csv.DictReader(f):
            patterns.setdefault(row["pattern"], []).append(row)
    print("| pattern | vertices | CPU s at 25 / 50 / 75 / 100 % | one call to 100 % | largest strain (steps) "
          "| 100 %: strain, against, crossings, flat | one call: strain, against, crossings, flat | answer at 100 % (steps / one call) |")
    print("|---|---|---|---|---|---|---|---|")
    for name, rows in patterns.items():
        done = {}
        vertices = ""
        note = ""
        for row in rows:
            if row["vertices"]:
                vertices = row["vertices"]
            if row["answer"].startswith("did not finish") or row["answer"].startswith("refused at load"):
                if row["answer"].startswith("refused at load"):
                    note = "refused at load: " + row["answer"][len("refused at load: "):][:80]
                else:  # the row names the call that did not finish (or the load)
                    note = "%s did not finish in %s s" % (row["path"].replace("_", " "), row["cpu_seconds"])
                continue
            done[row["path"]] = row

        def seconds(step):
            r = done.get(step)
            return "%.2g" % float(r["cpu_seconds"]) if r else "—"

        def figures(step):
            r = done.get(step)
            if not r:
                return "—"
            return "%.1e, %s, %s, %s" % (float(r["max_strain"]), r["against_target"], r["crossings"],
                                         "flat" if r["flat"] == "1" else "3D")

        def verdict(step):
            r = done.get(step)
            if not r:
                return "—"
            return "success" if r["answer"] == "success" else "refused"

        strains = [number(done[s]["max_strain"]) for s in STEPS[:4] if s in done]
        strains = [s for s in strains if s is not None]
        largest = "%.1e" % max(strains) if strains else "—"
        answer = "%s / %s" % (verdict("step_100"), verdict("one_call_100"))
        if note:
            answer += "; " + note
        print("| %s | %s | %s | %s | %s | %s | %s | %s |" % (
            name, vertices, " / ".join(seconds(s) for s in STEPS[:4]), seconds("one_call_100"), largest,
            figures("step_100"), figures("one_call_100"), answer))


def summary(path):
    calls = []  # (vertices, seconds, finished)
    vertices_of = {}
    with open(path, encoding='utf-8', errors='replace') as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        if row["vertices"]:
            vertices_of[row["pattern"]] = int(row["vertices"])
    for row in rows:
        if row["answer"].startswith("refused at load") or row["path"] == "load":
            continue
        finished = not row["answer"].startswith("did not finish")
        calls.append((vertices_of.get(row["pattern"]), float(row["cpu_seconds"]), finished))
    done = sorted(s for _, s, f in calls if f)
    median = done[len(done) // 2] if done else float("nan")
    print("%d calls finished, %d stopped; median %.2g s of CPU" % (len(done), len(calls) - len(done), median))
    for label, keep in (("under 1,000 vertices", lambda v: v is not None and v < 1000),
                        ("1,000 to 5,000 vertices", lambda v: v is not None and 1000 <= v <= 5000),
                        ("over 5,000 vertices or unknown", lambda v: v is None or v > 5000)):
        group = [(s, f) for v, s, f in calls if keep(v)]
        if not group:
            continue
        within = lambda t: sum(1 for s, f in group if f and s <= t)
        print("%s: %d calls; within 0.5 s %d, 1 s %d, 5 s %d; over 5 s or stopped %d" % (
            label, len(group), within(0.5), within(1.0), within(5.0), len(group) - within(5.0)))


if __name__ == "__main__":
    if sys.argv[1] == "--summary":
        summary(sys.argv[2])
    else:
        main(sys.argv[1])
