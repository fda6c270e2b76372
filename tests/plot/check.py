#!/usr/bin/env python3
"""Check the pictures of `s42 plot` (tests/plot/run.sh calls this).

check.py PNG SVG TRACE.jsonl DUMP.json [PDF [TITLE]]
check.py --tips PNG PANEL LEAST   (see tips())
check.py --same PNG PNG LEVELS    (see same())
  PNG: must be 1600 x 1000; its pixels are decoded here (zlib, no PIL) and
  each panel is checked against what the trace says moved:
    - a panel whose axes the program moves holds path pixels (the blue of
      programmed moves), and the path is fitted to the panel: the inked
      pixels span nearly the whole width or height of its inner area;
    - a panel whose axes nothing moves holds no path pixels;
    - without arcs and corrections, every block's start and end maps (by the
      documented fitting rule) to a pixel with ink next to it;
    - the A panel: a trace that spans the time axis, and at least half the
      panel's height when A moves by 1 degree or more; flat when A never moves.
  SVG: well-formed XML, an <svg> root of 1600pt x 1000pt.
  PDF (its text, read by pdftext.py): the header says what the dump says --
    the blocks the run counted, the simulated time, the end position.
  Tick labels (check_ticks): coordinates along both axes of every plane
    panel and along time and A, at a round step, where their values are
    (where the fit is known: the fit's scale and origin), one scale on both
    axes of a plane, not overlapping, inside the frame; the PNG has text and
    the SVG glyphs where the PDF has each label.
  A run that failed (the dump's status): the line under the title says how
    (TITLE, or "stopped: CODE at Nn" from the dump's error), the stop sign
    marks every panel -- where the run stopped, when the fit is known -- and
    the legend, and no end marker is drawn; a run that ended has neither.
Prints nothing and exits 0 when all is well; otherwise prints the failures
and exits 1.
"""
import json
import math
import re
import struct
import sys
import xml.etree.ElementTree as ET
import zlib

import pdftext

W, H = 1600, 1000
# The frames of src/host/plot.c: (name, u axis, v axis, x).  y 96..676, w 490.
PANELS = [("XY", 0, 1, 40), ("XZ", 0, 2, 555), ("YZ", 1, 2, 1070)]
PY, PW_, PH_ = 96, 490, 580
IN_L, IN_T, IN_R, IN_B = 62, 22, 18, 62      # inner area margins (left and bottom: the tick bands)
MINEXT = 0.02                                 # mm
A_FRAME = (90, 724, 1560, 924)                # x0, y0, x1, y1
A_TEND_X = 90 + 10 + (1470 - 20)              # where the A trace ends
LB, BB = 50, 50                               # the tick bands, left and bottom


def decode_png(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG (bad signature)")
    pos, idat, ihdr = 8, [], None
    while pos < len(data):
        ln, typ = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + ln]
        if typ == b"IHDR":
            ihdr = struct.unpack(">IIBBBBB", body)
        elif typ == b"IDAT":
            idat.append(body)
        elif typ == b"IEND":
            break
        pos += 12 + ln
    if ihdr is None:
        raise ValueError("no IHDR")
    w, h, depth, ctype, _, _, interlace = ihdr
    if depth != 8 or ctype not in (2, 6) or interlace:
        raise ValueError("unexpected PNG format: depth %d colour type %d" % (depth, ctype))
    bpp = 3 if ctype == 2 else 4
    raw = zlib.decompress(b"".join(idat))
    stride = w * bpp
    rows, prev = [], bytearray(stride)
    for y in range(h):
        f = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        if f == 1:
            for i in range(bpp, stride):
                line[i] = (line[i] + line[i - bpp]) & 255
        elif f == 2:
            line = bytearray((a + b) & 255 for a, b in zip(line, prev))
        elif f == 3:
            for i in range(stride):
                left = line[i - bpp] if i >= bpp else 0
                line[i] = (line[i] + ((left + prev[i]) >> 1)) & 255
        elif f == 4:
            for i in range(stride):
                a = line[i - bpp] if i >= bpp else 0
                b = prev[i]
                c = prev[i - bpp] if i >= bpp else 0
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pr = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pr) & 255
        elif f != 0:
            raise ValueError("bad filter %d" % f)
        rows.append(bytes(line))
        prev = line
    return w, h, bpp, rows


def classify(r, g, b):
    """'P' programmed path blue, 'M' manual orange, 'C' correction magenta,
    'S' start green, 'E' end red, 'X' the yellow stop sign, 'O' oscillation
    teal, None otherwise (white, grey, text)."""
    if r > 200 and g > 185 and b < 90:
        return "X"
    if g - r > 50 and b - r > 50 and abs(g - b) < 20 and g > 145:
        return "O"
    if b - r > 50 and b - g > 30:
        return "P"
    if r - b > 80 and r > 150 and 60 < g < 200 and r - g > 40:
        return "M"
    if r - g > 60 and b - g > 50:
        return "C"
    if g - r > 50 and g - b > 40:
        return "S"
    if r - g > 100 and r - b > 100 and g < 120:
        return "E"
    return None


class Img:
    def __init__(self, w, h, bpp, rows):
        self.w, self.h, self.bpp, self.rows = w, h, bpp, rows

    def px(self, x, y):
        o = x * self.bpp
        row = self.rows[y]
        return classify(row[o], row[o + 1], row[o + 2])

    def scan(self, x0, y0, x1, y1):
        """Classified pixels in [x0,x1) x [y0,y1): {kind: [count, bbox]}."""
        out = {}
        bpp = self.bpp
        for y in range(y0, y1):
            row = self.rows[y]
            for x in range(x0, x1):
                o = x * bpp
                r, g, b = row[o], row[o + 1], row[o + 2]
                if r == g == b:
                    continue
                k = classify(r, g, b)
                if k:
                    e = out.get(k)
                    if e is None:
                        out[k] = [1, [x, y, x, y]]
                    else:
                        e[0] += 1
                        bb = e[1]
                        if x < bb[0]: bb[0] = x
                        if x > bb[2]: bb[2] = x
                        if y < bb[1]: bb[1] = y
                        if y > bb[3]: bb[3] = y
        return out

    def ink_near(self, x, y, rad=3):
        for yy in range(max(0, y - rad), min(self.h, y + rad + 1)):
            for xx in range(max(0, x - rad), min(self.w, x + rad + 1)):
                if self.px(xx, yy):
                    return True
        return False


def fmt(v, dec):
    """plot.c's fmt_num: at most dec decimals, trailing zeros dropped."""
    if abs(v) < 0.5 * 10 ** -dec:
        v = 0.0
    t = "%.*f" % (dec, v)
    if "." in t:
        t = t.rstrip("0").rstrip(".")
    return t


def check_header(texts, d):
    """The summary line says what the run counted (the dump)."""
    hdr = [r.text for r in texts if re.search(r"\d+ blocks?, ", r.text)]
    if len(hdr) != 1:
        return ["PDF: %d header lines with 'blocks' in them, want 1" % len(hdr)]
    m = re.match(r"(\d+) blocks?, (\S+) s simulated; (?:end position|position at the stop) "
                 r"X (\S+)  Y (\S+)  Z (\S+) mm  A (\S+)°$", hdr[0])
    if not m:
        return ["PDF: header %r not understood" % hdr[0]]
    fails = []
    if int(m.group(1)) != d["blocks"]:
        fails.append("header: %s blocks, the run counted %d" % (m.group(1), d["blocks"]))
    t = fmt(d["time"], 3 if d["time"] < 1 else 1)
    if m.group(2) != t:
        fails.append("header: %s s, the run took %s" % (m.group(2), t))
    for i, a in enumerate("xyza"):
        v = d["pos"][a]
        want = ("+" if v > 0 else "") + fmt(v / 1000.0, 3)
        if m.group(3 + i) != want:
            fails.append("header: %s %s, the run ended at %s" % (a.upper(), m.group(3 + i), want))
    return fails


def check_stop(texts, d, want):
    """The line under the title and the legend say how the run ended."""
    fails = []
    line = [r.text for r in texts if 50 < r.y < 70 and r.x < 200]
    legend = [r.text for r in texts if r.y > 975]
    if d["status"] == "end":
        if line:
            fails.append("title: %r for a run that ended" % line[0])
        if "end" not in legend or "stopped here" in legend:
            fails.append("legend: %s, want 'end' and no 'stopped here'" % legend)
        return fails
    if want is None and d["status"] == "error" and d["error"]:
        e = d["error"]
        want = "stopped: %s%s" % (e["code"], " at N%d" % e["n"] if e["n"] is not None else "")
    if not line:
        fails.append("title: nothing says the run %s" % ("failed" if d["status"] == "error" else "stopped"))
    elif want is not None and line[0] != want:
        fails.append("title: %r, want %r" % (line[0], want))
    if "stopped here" not in legend or "end" in legend:
        fails.append("legend: %s, want 'stopped here' and no 'end'" % legend)
    return fails


def nice(step):
    """1, 2 or 5 times a power of ten"""
    e = 10 ** math.floor(math.log10(step) + 1e-9)
    return any(abs(step - m * e) <= 1e-6 * step for m in (1, 2, 5, 10))


def ticks_along(labs, pos, name, unit=""):
    """Labels [(position, Run)] along one axis: numbers at one round step,
    evenly placed.  Returns (fails, slope px per unit, position of 0)."""
    fails, vals = [], []
    for p, r in labs:
        t = r.text[:-len(unit)] if unit and r.text.endswith(unit) else r.text
        try:
            vals.append((p, float(t), r))
        except ValueError:
            fails.append("%s: a tick label %r is not a number%s" % (name, r.text, unit and " with " + unit))
    if len(vals) < 2:
        return fails + ["%s: %d tick labels, want 2 or more" % (name, len(vals))], None, None
    vals.sort(key=lambda q: q[0])
    step = abs(vals[1][1] - vals[0][1])
    for (p0, v0, _), (p1, v1, _) in zip(vals, vals[1:]):
        if abs(abs(v1 - v0) - step) > 1e-6 * max(step, 1e-9):
            fails.append("%s: tick labels %g and %g are not one step (%g) apart" % (name, v0, v1, step))
    if step <= 0 or not nice(step):
        fails.append("%s: the labelled step %g is not 1, 2 or 5 x 10^n" % (name, step))
    for _, v, _ in vals:
        if step > 0 and abs(v / step - round(v / step)) > 1e-6:
            fails.append("%s: %g is not a multiple of the step %g" % (name, v, step))
    slope = (vals[-1][0] - vals[0][0]) / (vals[-1][1] - vals[0][1]) if vals[-1][1] != vals[0][1] else 0
    for p, v, r in vals:
        if abs(vals[0][0] + slope * (v - vals[0][1]) - p) > 1.0:
            fails.append("%s: the label %r is not where its value is on the axis" % (name, r.text))
    return fails, slope, vals[0][0] - slope * vals[0][1]


def check_ticks(texts, img, uses, mappings):
    """Tick labels: on every plane panel along both axes, on the A panel along
    time and A: round steps, evenly placed at their values, one scale on
    both axes of a plane, apart, inside the frame -- and the same labels in
    the PNG's pixels and the SVG's glyphs.  mappings: {panel: (fit, 1)}
    where the fitting rule is known, to check the coordinates themselves."""
    fails = []
    drawn = []

    def apart(labs, name, along):
        for (_, a), (_, b) in zip(labs, labs[1:]):
            if (along == "x" and a.x + a.w + 2 > b.x) or (along == "y" and abs(a.y - b.y) < a.size + 1):
                fails.append("%s: the tick labels %r and %r overlap" % (name, a.text, b.text))

    for name, u, v, x in PANELS:
        base_u = PY + PH_ - BB + 16
        ul = sorted(((r.x + r.w / 2, r) for r in texts
                     if abs(r.y - base_u) < 0.6 and x <= r.x < x + PW_), key=lambda q: q[0])
        vl = sorted(((r.y - 0.35 * r.size, r) for r in texts
                     if x <= r.x and abs(r.x + r.w - (x + LB - 8)) < 0.6 and PY < r.y < PY + PH_ - BB + 10),
                    key=lambda q: q[0])
        f1, su, zu = ticks_along(ul, None, "%s %s ticks" % (name, "XYZA"[u]))
        f2, sv, zv = ticks_along(vl, None, "%s %s ticks" % (name, "XYZA"[v]))
        fails += f1 + f2
        apart(ul, name, "x")
        apart(vl, name, "y")
        for _, r in ul + vl:
            if r.x < x or r.x + r.w > x + PW_:
                fails.append("%s: the tick label %r leaves the frame" % (name, r.text))
        if su is not None and sv is not None:
            if su <= 0 or sv >= 0:
                fails.append("%s: the tick labels do not grow right and up" % name)
            elif abs(su + sv) > 0.01 * su:
                fails.append("%s: %.3f px a mm along %s, %.3f along %s: not one scale"
                             % (name, su, "XYZA"[u], -sv, "XYZA"[v]))
            if name in mappings:
                mp = mappings[name]
                x0, y0 = mp(0, 0)
                s_fit = mp(1000, 0)[0] - x0
                if abs(su - s_fit) > 0.005 * s_fit or abs(zu - (math.floor(x0) + 0.5)) > 1.2 \
                        or abs(zv - (math.floor(y0) + 0.5)) > 1.2:
                    fails.append("%s: the tick labels put 0 at (%.1f, %.1f) with %.3f px a mm; the fit says "
                                 "(%.1f, %.1f) with %.3f" % (name, zu, zv, su, x0, y0, s_fit))
        drawn += [r for _, r in ul + vl]

    x0, y0, x1, y1 = A_FRAME
    tl = sorted(((r.x + r.w / 2, r) for r in texts if abs(r.y - (y1 + 15)) < 0.6 and x0 - 30 < r.x < x1 + 30),
                key=lambda q: q[0])
    al = sorted(((r.y - 4, r) for r in texts if abs(r.x + r.w - (x0 - 6)) < 0.6 and y0 - 10 < r.y < y1 + 10),
                key=lambda q: q[0])
    f1, st, zt = ticks_along(tl, None, "A time ticks")
    f2, sa, za = ticks_along(al, None, "A degree ticks", "°")
    fails += f1 + f2
    apart(tl, "A", "x")
    apart(al, "A", "y")
    if zt is not None and abs(zt - (math.floor(x0 + 10) + 0.5)) > 1.2:
        fails.append("A: the time labels put 0 s at x=%.1f, the axis starts at %d" % (zt, x0 + 10))
    drawn += [r for _, r in tl + al]

    # the same labels in the other formats
    for r in drawn:
        ink = 0
        for yy in range(int(r.y - 0.7 * r.size), int(r.y) + 1):
            for xx in range(int(r.x), int(r.x + r.w) + 1):
                o = xx * img.bpp
                p = img.rows[yy][o:o + 3]
                if p[0] == p[1] == p[2] and p[0] < 140:
                    ink += 1
        if ink < 3:
            fails.append("PNG: no text where the tick label %r is (%.0f, %.0f)" % (r.text, r.x, r.y))
        if uses is not None and not any(abs(uy - r.y) < 0.6 and r.x - 0.6 <= ux <= r.x + r.w for ux, uy in uses):
            fails.append("SVG: no glyph where the tick label %r is (%.0f, %.0f)" % (r.text, r.x, r.y))
    return fails


def fit(pts, u, v, x):
    """The documented fitting rule: mm -> pixel in the panel at x."""
    ix0, iy0 = x + IN_L, PY + IN_T
    iw, ih = PW_ - IN_L - IN_R, PH_ - IN_T - IN_B
    lo_u = min(p[u] for p in pts) / 1000.0; hi_u = max(p[u] for p in pts) / 1000.0
    lo_v = min(p[v] for p in pts) / 1000.0; hi_v = max(p[v] for p in pts) / 1000.0
    du, dv = hi_u - lo_u, hi_v - lo_v
    s = min(iw / max(du, MINEXT), ih / max(dv, MINEXT))
    if du < MINEXT and dv < MINEXT:
        s = min(iw, ih) / 1.0
    u0, v0 = (lo_u + hi_u) / 2, (lo_v + hi_v) / 2
    return lambda pu, pv: (ix0 + iw / 2 + (pu / 1000.0 - u0) * s, iy0 + ih / 2 - (pv / 1000.0 - v0) * s)


def check(png, svg, trace, dump, pdf=None, title=None):
    fails = []
    data = open(png, "rb").read()
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        return ["PNG: bad signature or no IHDR first"]
    w, h = struct.unpack(">II", data[16:24])
    if (w, h) != (W, H):
        return ["PNG: size %dx%d, want %dx%d" % (w, h, W, H)]
    img = Img(*decode_png(data))

    rows = [json.loads(l) for l in open(trace) if l.strip()]
    dumped = json.load(open(dump))
    final = dumped["pos"]
    if pdf:
        texts = pdftext.runs(pdf)
        fails += check_header(texts, dumped)
        fails += check_stop(texts, dumped, title)
    stopped = dumped["status"] != "end"
    axes = "xyza"
    pos = [0, 0, 0, 0]
    pts = [tuple(pos)]
    moved = [False] * 4       # programmed moves
    manual = [False] * 4      # jogs
    arcs = False
    for r in rows:
        d = [r.get(a, 0) for a in axes]
        if r.get("motion") in ("G02", "G03", "G12", "G13") or \
           (r.get("motion") == "M19" and "jogs" in r):
            arcs = True
        for i in range(4):
            if d[i]:
                moved[i] = True
            pos[i] += d[i]
        pts.append(tuple(pos))
        j = r.get("jogs")
        if j:
            for i in range(4):
                if j[axes[i]]:
                    manual[i] = True
                pos[i] += j[axes[i]]
            pts.append(tuple(pos))
    corr = [pos[i] != final[axes[i]] for i in range(4)]
    osc = dumped.get("osc") or {}
    oa = osc.get("axis")
    osc_axis = axes.index(oa) if isinstance(oa, str) and len(oa) == 1 and oa in axes else -1
    osc_stroke = abs(osc.get("stroke", 0)) / 1000.0
    oscillated = any(r.get("osc") == "on" for r in rows)
    # (the strokes widen the fit beyond what the trace knows)
    exact = not arcs and not any(corr) and not oscillated and len(pts) < 4000

    mappings = {}
    for name, u, v, x in PANELS:
        if exact:
            mappings[name] = fit(pts, u, v, x)
        found = img.scan(x, PY, x + PW_, PY + PH_)
        ix0, iy0 = x + IN_L, PY + IN_T
        iw, ih = PW_ - IN_L - IN_R, PH_ - IN_T - IN_B
        blue = found.get("P", [0, None])[0]
        if "S" not in found:
            fails.append("%s: no start marker" % name)
        if moved[u] or moved[v]:
            if blue < 20:
                fails.append("%s: the program moves %s/%s but the panel has %d path pixels"
                             % (name, axes[u].upper(), axes[v].upper(), blue))
            lo_u = min(p[u] for p in pts); hi_u = max(p[u] for p in pts)
            lo_v = min(p[v] for p in pts); hi_v = max(p[v] for p in pts)
            if max(hi_u - lo_u, hi_v - lo_v) / 1000.0 >= MINEXT:
                bb = None
                for k, (n, b) in found.items():
                    bb = list(b) if bb is None else [min(bb[0], b[0]), min(bb[1], b[1]),
                                                     max(bb[2], b[2]), max(bb[3], b[3])]
                spanw, spanh = bb[2] - bb[0], bb[3] - bb[1]
                du, dv = (hi_u - lo_u) / 1000.0, (hi_v - lo_v) / 1000.0
                sc = min(iw / max(du, MINEXT), ih / max(dv, MINEXT))
                if spanw < 0.9 * du * sc and spanh < 0.9 * dv * sc:
                    fails.append("%s: the path is not fitted to the panel: it spans %dx%d px of %dx%d"
                                 % (name, spanw, spanh, iw, ih))
                if found.get("P") and not arcs:
                    b = found["P"][1]
                    if b[0] < ix0 - 3 or b[2] > ix0 + iw + 3 or b[1] < iy0 - 3 or b[3] > iy0 + ih + 3:
                        fails.append("%s: path pixels outside the fitted area: %s" % (name, b))
        elif not (manual[u] or manual[v] or corr[u] or corr[v] or arcs):
            if blue:
                fails.append("%s: nothing moves %s/%s but the panel has %d path pixels"
                             % (name, axes[u].upper(), axes[v].upper(), blue))
        # the oscillation's strokes fit the panel's scale like the rest
        if found.get("O", [0])[0] >= 5:   # a stray blend of two colours is not a stroke
            b = found["O"][1]
            if b[0] < ix0 - 3 or b[2] > ix0 + iw + 3 or b[1] < iy0 - 3 or b[3] > iy0 + ih + 3:
                fails.append("%s: oscillation strokes outside the fitted area: %s" % (name, b))
            if osc_axis in (u, v) and osc_stroke >= MINEXT:
                bb = None
                for k, (n, b) in found.items():
                    bb = list(b) if bb is None else [min(bb[0], b[0]), min(bb[1], b[1]),
                                                     max(bb[2], b[2]), max(bb[3], b[3])]
                if bb[2] - bb[0] < 0.9 * iw and bb[3] - bb[1] < 0.9 * ih:
                    fails.append("%s: the oscillation is not fitted to the panel: it spans %dx%d px of %dx%d"
                                 % (name, bb[2] - bb[0], bb[3] - bb[1], iw, ih))
        elif osc_axis in (u, v) and oscillated:
            fails.append("%s: %s oscillates but no stroke is drawn" % (name, axes[osc_axis].upper()))
        if stopped:
            if "X" not in found:
                fails.append("%s: the run stopped but no stop sign marks where" % name)
            elif exact:
                b = found["X"][1]
                cx, cy = (b[0] + b[2]) / 2.0, (b[1] + b[3]) / 2.0
                ex, ey = fit(pts, u, v, x)(final[axes[u]], final[axes[v]])
                if abs(cx - ex) > 2 or abs(cy - ey) > 2:
                    fails.append("%s: the stop sign is at (%.0f, %.0f), the run stopped at (%.0f, %.0f)"
                                 % (name, cx, cy, ex, ey))
            if "E" in found:
                fails.append("%s: an end marker for a run that stopped" % name)
        elif "X" in found:
            fails.append("%s: a stop sign for a run that ended" % name)
        if exact and (moved[u] or moved[v] or manual[u] or manual[v]):
            mapping = fit(pts, u, v, x)
            miss = 0
            for p in pts:
                px, py = mapping(p[u], p[v])
                px, py = int(round(px)), int(round(py))
                if py > PY + PH_ - 50:
                    continue   # in the tick band
                if not img.ink_near(px, py):
                    miss += 1
            if miss:
                fails.append("%s: %d block end points have no path drawn at their pixel" % (name, miss))

    x0, y0, x1, y1 = A_FRAME
    found = img.scan(x0, y0, x1, y1)
    if "O" in found and (found["O"][1][1] < y0 + 3 or found["O"][1][3] > y1 - 3):
        fails.append("A: oscillation strokes leave the panel's scale: %s" % found["O"][1])
    if stopped != ("X" in found):
        fails.append("A: %s" % ("no stop sign for a run that stopped" if stopped else "a stop sign for a run that ended"))
    if "P" not in found:
        fails.append("A: no trace")
    else:
        b = found["P"][1]
        right = max(b[2], found["X"][1][2] if "X" in found else 0)   # the stop sign covers its end
        if right < A_TEND_X - 2:
            fails.append("A: the trace ends at x=%d, not at the end of the time axis (%d)" % (b[2], A_TEND_X))
        ys = [found[k][1] for k in "PMC" if k in found]
        top, bot = min(q[1] for q in ys), max(q[3] for q in ys)
        a_ext = max(p[3] for p in pts) - min(p[3] for p in pts)
        if moved[3] and a_ext >= 1000 and bot - top < 0.5 * (y1 - y0):
            fails.append("A: A moves but the trace spans only %d px in height" % (bot - top))
        if not (moved[3] or manual[3] or corr[3]) and b[3] - b[1] > 4:
            fails.append("A: A never moves but the trace spans %d px in height" % (b[3] - b[1]))

    uses = None
    try:
        root = ET.parse(svg).getroot()
        if not root.tag.endswith("svg"):
            fails.append("SVG: root is <%s>" % root.tag)
        wa, ha = root.get("width", ""), root.get("height", "")
        if wa.replace("pt", "") not in ("1600", "1600.0") or ha.replace("pt", "") not in ("1000", "1000.0"):
            fails.append("SVG: size %s x %s, want 1600pt x 1000pt" % (wa, ha))
        # cairo writes text as glyphs, each a <use> at its origin
        uses = [(float(e.get("x", 0)), float(e.get("y", 0))) for e in root.iter() if e.tag.endswith("}use")]
    except ET.ParseError as e:
        fails.append("SVG: not well-formed XML: %s" % e)
    if pdf:
        fails += check_ticks(texts, img, uses, mappings)
    return fails


def tips(png, panel, least):
    """The oscillation's turning points on the far side (the top of the teal
    strokes in PANEL) are spread along the path: at least LEAST of them
    apart, not bunched where a block ends."""
    img = Img(*decode_png(open(png, "rb").read()))
    x = dict((p[0], p[3]) for p in PANELS)[panel]
    found = img.scan(x, PY, x + PW_, PY + PH_)
    if "O" not in found:
        return ["%s: no oscillation drawn" % panel]
    top = found["O"][1][1]
    cols = sorted(set(xx for xx in range(x, x + PW_) for yy in (top, top + 1) if img.px(xx, yy) == "O"))
    groups = sum(1 for i, c in enumerate(cols) if i == 0 or c - cols[i - 1] > 2)
    if groups < int(least):
        return ["%s: the strokes turn at %d places along the path, want %s or more" % (panel, groups, least)]
    return []


def same(png_a, png_b, levels):
    """Two pictures of one run differ by at most LEVELS in any channel of any
    pixel (the A panel's band against its plain stroke: the same picture but
    for how cairo samples a row here and there)."""
    a = decode_png(open(png_a, "rb").read())
    b = decode_png(open(png_b, "rb").read())
    if a[:3] != b[:3]:
        return ["%s and %s: not the same size or format" % (png_a, png_b)]
    worst, n, at = 0, 0, None
    for y, (ra, rb) in enumerate(zip(a[3], b[3])):
        if ra == rb:
            continue
        for i, (u, v) in enumerate(zip(ra, rb)):
            if u != v:
                n += 1
                if abs(u - v) > worst:
                    worst, at = abs(u - v), (i // a[2], y)
    if worst > int(levels):
        return ["%s and %s differ by up to %d levels (at %s; %d channel values differ), want %s or less"
                % (png_a, png_b, worst, at, n, levels)]
    return []


if __name__ == "__main__":
    try:
        if sys.argv[1] == "--tips":
            f = tips(*sys.argv[2:5])
        elif sys.argv[1] == "--same":
            f = same(*sys.argv[2:5])
        else:
            f = check(*sys.argv[1:7])
    except Exception as e:  # a broken file is a failure, not a crash
        f = ["%s: %s" % (type(e).__name__, e)]
    for m in f:
        print(m)
    sys.exit(1 if f else 0)
