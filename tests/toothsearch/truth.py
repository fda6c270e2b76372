#!/usr/bin/env python3
"""What a tool model says, for tests/toothsearch/plugin.sh.

  truth.py diameter TOOL            the model's diameter, µm
  truth.py turn TOOL DX             the A turn (0.001°) that follows the flute
                                    over a table move of DX µm
  truth.py check TOOL DUMP G M10    compare s42's --dump with the model
  truth.py images DIR SIZE P1 P2    the --dump-images files of two revolutions

check prints the worst errors and exits 1 with the reasons when a value is
outside the accuracy of the search: circular steps ±0.03°, TK ±0.5 %,
UG ±0.03°, the tooth count exact, the hand exact.
"""
import json
import math
import os
import struct
import sys

STEP_TOL = 30.5      # 0.001°: ±0.03° and the rounding to whole discretes
TK_TOL = 0.005
UG_TOL = 30.5


def model(path):
    m = {"steps": "even", "lead": 0.0, "hand": "right"}
    with open(path, encoding="utf-8") as f:
        for line in f:
            line = line.split(";", 1)[0].strip()
            if not line:
                continue
            k, v = (s.strip() for s in line.split("=", 1))
            m[k] = v
    n = int(m["teeth"])
    if m["steps"] == "even":
        steps = [360.0 / n] * n
    else:
        steps = [float(s) for s in m["steps"].split(",")]
    return {"teeth": n, "steps": steps, "diameter": float(m["diameter"]), "lead": float(m["lead"]),
            "hand": 1 if m["hand"] == "right" else -1}


def turn(m, dx):
    """A right-hand flute is met earlier further along X: A turns back."""
    if m["lead"] == 0:
        return 0
    return round(-m["hand"] * 360000.0 * dx / m["lead"])


def check(m, dump, g, m10):
    d = json.load(open(dump, encoding="utf-8"))
    errs = []
    n = m["teeth"]
    if d.get("status") != "end":
        errs.append("status %r" % d.get("status"))
    r99 = d["r"][99]
    if r99 != n:
        errs.append("R99 = %s, the model has %d teeth" % (r99, n))
    a2 = d["arrays"][1]
    k = min(n, 15)
    if a2["ptr"] != 0 or a2["len"] != k:
        errs.append("array 2: ptr %s len %s, want 0 and %d" % (a2["ptr"], a2["len"], k))
    worst = 0.0
    for i in range(k):
        e = a2["cells"][i] - 1000.0 * m["steps"][i]
        worst = max(worst, abs(e))
        if abs(e) > STEP_TOL:
            errs.append("step %d: %s, the model %.3f°" % (i + 1, a2["cells"][i], m["steps"][i]))
        if a2["cells"][i] != round(a2["cells"][i]):
            errs.append("step %d: %s is not a whole number of discretes" % (i + 1, a2["cells"][i]))
    if n <= 15 and sum(a2["cells"][:n]) != 360000:
        errs.append("array 2 sums to %s, not 360000" % sum(a2["cells"][:n]))
    msg = "teeth %d, worst step %+.1f (0.001°)" % (n, worst)
    if m10 == "M10" and m["lead"] > 0:
        tk, ug = d["tk"], d["ug"]
        ug_true = math.degrees(math.atan(math.pi * m["diameter"] / m["lead"])) * 1000
        if abs(tk - m["lead"]) > TK_TOL * m["lead"]:
            errs.append("TK %s, the model's lead %.0f" % (tk, m["lead"]))
        if abs(ug - ug_true) > UG_TOL:
            errs.append("UG %s, the model's helix %.1f" % (ug, ug_true))
        s = d.get("search") or {}
        hand = {"right": 1, "left": -1}.get(s.get("hand"))
        if hand != m["hand"]:
            errs.append("hand %r, the model's %s" % (s.get("hand"), m["hand"]))
        if s.get("mismatch") != ((g == "G10") != (m["hand"] == 1)):
            errs.append("mismatch %r for %s on a %s-hand tool" % (s.get("mismatch"), g,
                                                                  "right" if m["hand"] == 1 else "left"))
        msg += ", TK %+.3f %%, UG %+.1f" % (100.0 * (tk - m["lead"]) / m["lead"], ug - ug_true)
    elif d["tk"] != 0 or d["ug"] != 0:
        errs.append("TK %s UG %s, want 0 (%s)" % (d["tk"], d["ug"], "no M10" if m10 != "M10" else "straight"))
    if errs:
        print("; ".join(errs))
        return 1
    print(msg)
    return 0


def png_size(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return struct.unpack(">II", head[16:24])


def images(folder, size, prefixes):
    errs = []
    want = set()
    for p in prefixes:
        for k in range(1, 5):
            for suffix in ("", "_annotated"):
                want.add("%s_shot%d%s.png" % (p, k, suffix))
    got = set(os.listdir(folder)) if os.path.isdir(folder) else set()
    if got != want:
        errs.append("files %s, want %s" % (sorted(got), sorted(want)))
    for name in sorted(want & got):
        wh = png_size(os.path.join(folder, name))
        if wh != (size, size):
            errs.append("%s: %s, not a %dx%d PNG" % (name, wh, size, size))
    if errs:
        print("; ".join(errs))
        return 1
    return 0


def main():
    cmd, rest = sys.argv[1], sys.argv[2:]
    if cmd == "diameter":
        print("%.0f" % model(rest[0])["diameter"])
    elif cmd == "turn":
        print(turn(model(rest[0]), float(rest[1])))
    elif cmd == "check":
        sys.exit(check(model(rest[0]), rest[1], rest[2], rest[3]))
    elif cmd == "images":
        sys.exit(images(rest[0], int(rest[1]), rest[2:]))
    else:
        sys.exit("truth.py: unknown command " + cmd)


if __name__ == "__main__":
    main()
