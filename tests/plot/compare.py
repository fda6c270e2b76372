#!/usr/bin/env python3
"""Plot every program with two builds of s42 and compare the pictures.

compare.py REF_S42 NEW_S42 OUTDIR [--formats png,svg,pdf] [--also DIR]... [WORD...]

For a change to the plot that must not change how the pictures look (a
faster way of drawing the same): the programs the tests plot -- programs/
(with their .operator and .tool), programs/errors, docs/guide, the
tutorial's cycle (with its operators from tests/plot), tests/plot,
tests/canon, tests/restart, the conformance cases (with operator.txt and
tool.txt) -- and the .kp files in each --also DIR (with NAME.operator), only
those whose path holds one of the WORDs when any are given; each drawn by
both builds into OUTDIR as NAME.ref.EXT and NAME.new.EXT (kept when they
differ).
  PNG: decoded (pycairo when it is there, else check.py's own decoder, much
  slower) and compared pixel by pixel: how many differ, the largest
  difference in each of R, G, B, and the box they are in.
  SVG: the same bytes, or else both drawn by librsvg (gi's Rsvg, when it is
  there) and compared as PNGs.
  PDF: the same bytes but for the creation date.
The last line: how many pictures, how many differ, the largest difference.
Exit 0 when all are the same, 1 otherwise.  Not part of `make check`: it
needs a second build (e.g. `git worktree add /tmp/ref BASE && make -C
/tmp/ref`).
"""
import glob
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, HERE)

try:
    import cairo
except ImportError:
    cairo = None


def with_files(kp, pairs):
    """kp and the options for the files beside it that exist."""
    opts = []
    for opt, path in pairs:
        if os.path.exists(path):
            opts += [opt, path]
    return (kp, opts)


def programs(also):
    out = []
    for kp in sorted(glob.glob(ROOT + "/programs/*.kp")):
        b = kp[:-3]
        out.append(with_files(kp, [("--operator", b + ".operator"), ("--tool", b + ".tool")]))
    out += [(kp, []) for kp in sorted(glob.glob(ROOT + "/programs/errors/*.kp"))]
    for kp in sorted(glob.glob(ROOT + "/docs/guide/*.kp")):
        out.append(with_files(kp, [("--operator", kp[:-3] + ".operator")]))
    out.append(with_files(ROOT + "/docs/guide/14-restart.kp",
                          [("--operator", ROOT + "/docs/guide/14-restart-stop.operator")]))
    cycle = ROOT + "/docs/tutorial/cycle.kp"
    for op in (ROOT + "/docs/tutorial/cycle.operator", HERE + "/no-action.operator", HERE + "/stop-key.operator"):
        out.append(with_files(cycle, [("--operator", op)]))
    for d in ("tests/plot", "tests/canon", "tests/restart"):
        out += [(kp, []) for kp in sorted(glob.glob(ROOT + "/" + d + "/*.kp"))]
    for d in sorted(glob.glob(ROOT + "/tests/conformance/cases/*/")):
        if os.path.exists(d + "program.kp"):
            out.append(with_files(d + "program.kp", [("--operator", d + "operator.txt"), ("--tool", d + "tool.txt")]))
    for d in also:
        for kp in sorted(glob.glob(os.path.join(d, "*.kp"))):
            out.append(with_files(kp, [("--operator", kp[:-3] + ".operator")]))
    return out


def png_pixels(path):
    """(w, h, bytes per pixel, rows, where R, G and B are in a pixel)."""
    if cairo is None:
        import check
        return check.decode_png(open(path, "rb").read()) + ((0, 1, 2),)
    return surface_pixels(cairo.ImageSurface.create_from_png(path))


def surface_pixels(s):
    # cairo's RGB24/ARGB32: B, G, R, x in memory on a little-endian machine
    s.flush()
    w, h, st, d = s.get_width(), s.get_height(), s.get_stride(), bytes(s.get_data())
    rgb = (2, 1, 0) if sys.byteorder == "little" else (1, 2, 3)
    return w, h, 4, [d[y * st:y * st + 4 * w] for y in range(h)], rgb


def svg_pixels(path):
    import gi
    gi.require_version("Rsvg", "2.0")
    from gi.repository import Rsvg
    s = cairo.ImageSurface(cairo.FORMAT_RGB24, 1600, 1000)
    cr = cairo.Context(s)
    cr.set_source_rgb(1, 1, 1)
    cr.paint()
    Rsvg.Handle.new_from_file(path).render_cairo(cr)
    return surface_pixels(s)


def diff(a, b):
    """(pixels that differ, [largest R, G, B difference], box), or None
    when the sizes differ."""
    if a[:2] != b[:2]:
        return None
    n, mx, box = 0, [0, 0, 0], [a[0], a[1], -1, -1]
    (pa, oa), (pb, ob) = (a[2], a[4]), (b[2], b[4])
    for y, (ra, rb) in enumerate(zip(a[3], b[3])):
        if ra == rb:
            continue
        for x in range(a[0]):
            u = [ra[x * pa + o] for o in oa]
            v = [rb[x * pb + o] for o in ob]
            if u != v:
                n += 1
                for c in range(3):
                    mx[c] = max(mx[c], abs(u[c] - v[c]))
                box = [min(box[0], x), min(box[1], y), max(box[2], x), max(box[3], y)]
    return n, mx, box


def pdf_bytes(path):
    return re.sub(rb"/(CreationDate|ModDate) \([^)]*\)", b"", open(path, "rb").read())


def main(argv):
    if len(argv) < 3:
        sys.stderr.write(__doc__)
        return 2
    ref, new, out = argv[:3]
    formats, also, words, rest = ["png", "svg", "pdf"], [], [], argv[3:]
    while rest:
        a = rest.pop(0)
        if a == "--formats":
            formats = rest.pop(0).split(",")
        elif a == "--also":
            also.append(rest.pop(0))
        else:
            words.append(a)
    os.makedirs(out, exist_ok=True)
    def where(kp):
        return os.path.relpath(kp, ROOT) if kp.startswith(ROOT + "/") else kp

    progs = [p for p in programs(also) if not words or any(w in where(p[0]) for w in words)]
    total, ndiff, worst = 0, 0, (0, "")
    for kp, opts in progs:
        name = where(kp) + "".join(" " + os.path.basename(o) for o in opts[1::2])
        tag = re.sub(r"[^A-Za-z0-9]+", "_", name).strip("_")
        for ext in formats:
            files = []
            for which, exe in (("ref", ref), ("new", new)):
                f = os.path.join(out, "%s.%s.%s" % (tag, which, ext))
                if os.path.exists(f):
                    os.unlink(f)
                r = subprocess.run([exe, "plot", kp] + opts + ["-o", f, "--state", os.path.join(out, "state")],
                                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
                files.append((f, r.returncode, os.path.exists(f)))
            (fa, sa, ea), (fb, sb, eb) = files
            if (sa, ea) != (sb, eb):
                print("%s %s: exit %d vs %d, a picture %s vs %s" % (name, ext, sa, sb, ea, eb))
                total += 1
                ndiff += 1
                continue
            if not ea:
                continue   # both refused it alike (a usage error): nothing to compare
            total += 1
            if ext == "pdf":
                d = (0, [0, 0, 0], None) if pdf_bytes(fa) == pdf_bytes(fb) else "the bytes differ"
            elif ext == "svg" and open(fa, "rb").read() == open(fb, "rb").read():
                d = (0, [0, 0, 0], None)
            elif ext == "svg" and cairo is None:
                d = "the bytes differ (no pycairo to draw them)"
            else:
                read = svg_pixels if ext == "svg" else png_pixels
                d = diff(read(fa), read(fb)) or "the sizes differ"
            if isinstance(d, str) or d[0]:
                ndiff += 1
                if isinstance(d, str):
                    print("%s %s: %s" % (name, ext, d))
                    worst = (256, "%s %s" % (name, ext))
                else:
                    print("%s %s: %d px differ, largest R G B %s, in x %d..%d y %d..%d"
                          % (name, ext, d[0], d[1], d[2][0], d[2][2], d[2][1], d[2][3]))
                    if max(d[1]) > worst[0]:
                        worst = (max(d[1]), "%s %s" % (name, ext))
            else:
                os.unlink(fa)
                os.unlink(fb)
    print("%d pictures of %d programs, %d differ; the largest difference %d levels%s"
          % (total, len(progs), ndiff, worst[0], " (" + worst[1] + ")" if worst[1] else ""))
    return 1 if ndiff else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
