#!/usr/bin/env python3
"""Check a picture of the lathe's plot (tests/plot/lathe/run.sh calls this).

lcheck.py PNG [KIND@R,Z ...]       the PNG is 1000 x 600 and each point
    (radius R, Z mm, mapped by the driver's "xy R Z X Y" lines read from
    the file XY) shows KIND within 2 px: removed, part, feed, red, or !KIND
    for its absence within 4 px;  XY=FILE in the environment
lcheck.py --text PDF|SVG TEXT...   each TEXT is in the PDF's text (pdftext)
    or the SVG's <title>/<desc>
Prints the failures and exits 1, or nothing and 0.
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.dirname(HERE))
import check    # noqa: E402  (tests/plot/check.py: decode_png)
import pdftext  # noqa: E402

COLOURS = {     # src/host/lplot.c
    "removed": (0xf5, 0xa0, 0x4b),
    "part": (0x8f, 0xa8, 0xc2),
    "feed": (0x1f, 0x4d, 0xb3),
    "red": (0xd9, 0x1a, 0x1a),
}


def near(px, c, tol=40):
    return sum(abs(a - b) for a, b in zip(px, c)) <= tol


def main(argv):
    fails = []
    if argv[0] == "--text":
        path, want = argv[1], argv[2:]
        if path.endswith(".pdf"):
            text = "\n".join(r.text for r in pdftext.runs(path))
        else:
            import xml.etree.ElementTree as ET
            root = ET.parse(path).getroot()
            ns = "{http://www.w3.org/2000/svg}"
            if root.tag != ns + "svg" or root.get("width") != "1000pt" or root.get("height") != "600pt":
                fails.append("%s: not a 1000pt x 600pt SVG" % path)
            text = "\n".join((e.text or "") for e in root if e.tag in (ns + "title", ns + "desc"))
        for t in want:
            if t not in text:
                fails.append("%s: no %r in its text:\n  %s" % (path, t, text.replace("\n", "\n  ")))
    else:
        with open(argv[0], "rb") as f:
            w, h, bpp, rows = check.decode_png(f.read())
        if (w, h) != (1000, 600):
            fails.append("PNG is %d x %d, want 1000 x 600" % (w, h))
        xy = {}
        with open(os.environ["XY"]) as f:
            for line in f:
                p = line.split()
                if p and p[0] == "xy":
                    xy[(float(p[1]), float(p[2]))] = (float(p[3]), float(p[4]))
        for spec in argv[1:]:
            kind, at = spec.split("@")
            neg = kind.startswith("!")
            kind = kind.lstrip("!")
            r, z = (float(v) for v in at.split(","))
            x, y = xy[(r, z)]
            rad = 4 if neg else 2
            found = False
            for yy in range(int(round(y)) - rad, int(round(y)) + rad + 1):
                for xx in range(int(round(x)) - rad, int(round(x)) + rad + 1):
                    if 0 <= xx < w and 0 <= yy < h:
                        o = xx * bpp
                        if near(rows[yy][o:o + 3], COLOURS[kind]):
                            found = True
            if found == neg:
                fails.append("%s: %s at radius %g, Z %g (px %.0f, %.0f)" %
                             (argv[0], ("" if neg else "no ") + kind + (" where there should be none" if neg else ""),
                              r, z, x, y))
    if fails:
        print("\n".join(fails))
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
