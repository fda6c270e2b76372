#!/usr/bin/env python3
"""Generate the helix golden cases (tests/conformance/cases/helix-*): every
plane with each axis that can rise along it, both directions, quarter turns
and full turns.  Expected values are worked out here independently of s42:
end point, path length, the speed limit of language.md sec. 16 rule 4 (rule
1 with the arc length H in place of the in-plane increments; an arc with Y
in its plane weighs H by its rule 2/3 factor), and the time.
Run: python3 tests/conformance/gen/helix_cases.py tests/conformance/cases"""
import json, math, os, sys

PLANES = {17: ("X", "Y"), 18: ("Y", "Z"), 19: ("X", "Z")}
CENTRE = {"X": "I", "Y": "J", "Z": "K"}
R = 10000          # radius, discretes
F = 1000

def ys_max(p, q, th0, sweep):
    if "Y" not in (p, q):
        return 0.0
    share = (lambda t: abs(math.sin(t))) if p == "Y" else (lambda t: abs(math.cos(t)))
    # sample densely: the largest Y share of the tangent along the arc
    return max(share(th0 + sweep * i / 20000) for i in range(20001))

def case(plane, h, g, turn, rise):
    p, q = PLANES[plane]
    ccw = g == 13
    # centre at -R on the first axis: the start angle is 0
    cp, cq = -R, 0
    th0 = 0.0
    if turn == "full":
        sweep = 2 * math.pi * (1 if ccw else -1)
        ep = eq = 0
    else:
        sweep = math.pi / 2 * (1 if ccw else -1)
        ep = round(cp + R * math.cos(th0 + sweep))
        eq = round(cq + R * math.sin(th0 + sweep))
    H = R * abs(sweep) / 1000.0
    hm = rise / 1000.0
    L = math.hypot(H, hm)
    ys = ys_max(p, q, th0, sweep)
    k2 = (1 - ys * ys) + 1296 * ys * ys
    w2 = 1296 if h == "Y" else 1
    lim = 6000 * math.sqrt((H * H + hm * hm) / (H * H * k2 + w2 * hm * hm))
    feed = min(F, lim)
    t = L / feed * 60
    words = f"{p}{ep:+d} {q}{eq:+d} {CENTRE[p]}{cp:+d} {CENTRE[q]}{cq:+d} {h}{rise:+d}"
    prog = (f"; helix: G{g} in G{plane} ({p}{q}), rising along {h}, {turn} turn "
            f"(expected values from tests/conformance/gen/helix_cases.py)\n"
            f"№1 G{g} G{plane} G09 {words} F{F} ^\n№2 M02 ^\n")
    pos = {a.lower(): 0 for a in "XYZA"}
    pos[p.lower()] = ep
    pos[q.lower()] = eq
    pos[h.lower()] = rise
    mv = {"n": 1, p.lower(): ep, q.lower(): eq, h.lower(): rise}
    exp = {"status": "end", "exit": 0, "blocks": [1, 2],
           "motions": [{"n": 1, "motion": f"G{g}"}],
           "moves": [mv],
           "feeds": [{"n": 1, "f": F, "feed": [round(feed * 0.9995 - 0.001, 3), round(feed * 1.0005 + 0.001, 3)]}],
           "time": [round(t * 0.9995, 4), round(t * 1.0005, 4)],
           "pos": pos}
    return prog, exp

def main():
    out = sys.argv[1]
    n = 0
    for plane, (p, q) in PLANES.items():
        for h in [a for a in "XYZA" if a not in (p, q)]:
            for g in (12, 13):
                for turn in ("quarter", "full"):
                    rise = 20000 if h != "A" else 90000
                    if g == 12:
                        rise = -rise // 2
                    prog, exp = case(plane, h, g, turn, rise)
                    d = os.path.join(out, f"helix-g{g}-g{plane}-{h.lower()}-{turn}")
                    os.makedirs(d, exist_ok=True)
                    open(os.path.join(d, "program.kp"), "w").write(prog)
                    open(os.path.join(d, "expect.json"), "w").write(json.dumps(exp, indent=1) + "\n")
                    n += 1
    print(f"{n} helix cases in {out}")

main()
