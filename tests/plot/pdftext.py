#!/usr/bin/env python3
"""The text of a PDF that cairo wrote (`s42 plot -o FILE.pdf`), with where it is.

pdftext.py FILE.pdf      prints one line per text run: x y size width text
From Python: runs(path) -> [Run(x, y, size, w, text)], x/y the start of the
baseline in the drawing's coordinates (cairo's: y down, as the PNG's
pixels), w the advance width from the fonts' /Widths.

Only what cairo's PDF surface writes is understood: one page, Flate
streams, simple TrueType fonts (/Widths, /ToUnicode) and Type0 Identity-H
fonts (/W, /ToUnicode), the text operators Tm Td TD T* Tf Tj TJ ' and cm
(q/Q).  Poppler is not needed, so the test runs wherever s42 builds.
"""
import re
import sys
import zlib
from collections import namedtuple

Run = namedtuple("Run", "x y size w text")


def _objects(data):
    """{number: (dict text, stream bytes or None)}"""
    objs = {}
    for m in re.finditer(rb"(\d+) 0 obj\b", data):
        num = int(m.group(1))
        end = data.find(b"endobj", m.end())
        body = data[m.end():end]
        st = None
        k = body.find(b"stream")
        if k >= 0 and b">>" in body[:k]:
            head = body[:k]
            raw = body[k + 6:]
            raw = raw[2:] if raw[:2] == b"\r\n" else raw[1:]
            raw = raw[:raw.rfind(b"endstream")]
            st = zlib.decompress(raw) if b"/FlateDecode" in head else raw
            body = head
        objs[num] = (body.decode("latin1"), st)
    return objs


def _ref(d, key):
    m = re.search(r"/%s\s+(\d+)\s+0\s+R" % key, d)
    return int(m.group(1)) if m else None


def _cmap(text):
    """ToUnicode CMap -> {code: str}"""
    out = {}
    for blk in re.findall(r"beginbfchar(.*?)endbfchar", text, re.S):
        for a, b in re.findall(r"<([0-9a-fA-F]+)>\s*<([0-9a-fA-F]+)>", blk):
            out[int(a, 16)] = bytes.fromhex(b).decode("utf-16-be")
    for blk in re.findall(r"beginbfrange(.*?)endbfrange", text, re.S):
        for a, b, c in re.findall(r"<([0-9a-fA-F]+)>\s*<([0-9a-fA-F]+)>\s*<([0-9a-fA-F]+)>", blk):
            base = int(c, 16)
            for i, code in enumerate(range(int(a, 16), int(b, 16) + 1)):
                out[code] = chr(base + i)
    return out


class Font:
    def __init__(self, objs, num):
        d = objs[num][0]
        self.two = "/Type0" in d
        tu = _ref(d, "ToUnicode")
        self.uni = _cmap(objs[tu][1].decode("latin1")) if tu else {}
        self.widths = {}
        if self.two:
            desc = int(re.search(r"/DescendantFonts\s*\[\s*(\d+)\s+0\s+R", d).group(1))
            w = re.search(r"/W\s*\[(.*)\]", objs[desc][0], re.S)
            if w:
                toks = re.findall(r"\[[^\]]*\]|\S+", w.group(1))
                i = 0
                while i + 1 < len(toks):
                    first = int(toks[i])
                    if toks[i + 1].startswith("["):
                        for k, v in enumerate(toks[i + 1][1:-1].split()):
                            self.widths[first + k] = float(v)
                        i += 2
                    else:
                        for c in range(first, int(toks[i + 1]) + 1):
                            self.widths[c] = float(toks[i + 2])
                        i += 3
        else:
            fc = int(re.search(r"/FirstChar\s+(\d+)", d).group(1))
            ws = re.search(r"/Widths\s*\[([^\]]*)\]", d).group(1).split()
            for k, v in enumerate(ws):
                self.widths[fc + k] = float(v)

    def decode(self, s):
        codes = [s[i] << 8 | s[i + 1] for i in range(0, len(s) - 1, 2)] if self.two else list(s)
        return "".join(self.uni.get(c, "?") for c in codes), sum(self.widths.get(c, 0) for c in codes) / 1000.0


_TOK = re.compile(rb"\s*(?:(\()|(<<|>>)|<([0-9a-fA-F\s]*)>|(/[^\s/\[\]()<>]*)|([-+]?\d*\.?\d+)|(\[|\])|([A-Za-z'\"*]+))")


def _tokens(c):
    i, n = 0, len(c)
    while i < n:
        m = _TOK.match(c, i)
        if not m:
            i += 1
            continue
        if m.group(1):          # a literal string, with nesting and escapes
            depth, j, out = 1, m.end(), bytearray()
            while j < n and depth:
                ch = c[j]
                if ch == 0x5C:  # backslash
                    nx = c[j + 1]
                    esc = {0x6E: 10, 0x72: 13, 0x74: 9, 0x62: 8, 0x66: 12}
                    if nx in esc:
                        out.append(esc[nx]); j += 2
                    elif 0x30 <= nx <= 0x37:
                        k = j + 1
                        while k < j + 4 and 0x30 <= c[k] <= 0x37:
                            k += 1
                        out.append(int(c[j + 1:k], 8) & 255); j = k
                    elif nx in (10, 13):
                        j += 2
                    else:
                        out.append(nx); j += 2
                    continue
                if ch == 0x28:
                    depth += 1
                elif ch == 0x29:
                    depth -= 1
                    if not depth:
                        break
                out.append(ch)
                j += 1
            yield ("s", bytes(out))
            i = j + 1
            continue
        i = m.end()
        if m.group(3) is not None:
            yield ("s", bytes.fromhex(re.sub(rb"\s", b"", m.group(3)).decode()))
        elif m.group(4):
            yield ("n", m.group(4).decode("latin1"))
        elif m.group(5):
            yield ("f", float(m.group(5)))
        elif m.group(6):
            yield ("a", m.group(6).decode())
        elif m.group(7):
            yield ("o", m.group(7).decode())


def _mul(a, b):
    """a x b, PDF matrices [a b c d e f]"""
    return [a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3],
            a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3],
            a[4] * b[0] + a[5] * b[2] + b[4], a[4] * b[1] + a[5] * b[3] + b[5]]


def runs(path):
    data = open(path, "rb").read()
    objs = _objects(data)
    page = next(k for k, (d, _) in objs.items() if re.search(r"/Type\s*/Page\b", d))
    pd = objs[page][0]
    res = _ref(pd, "Resources")
    rd = objs[res][0] if res else pd
    fonts = {}
    fm = re.search(r"/Font\s*<<(.*?)>>", rd, re.S)
    if fm:
        for name, num in re.findall(r"/(\S+)\s+(\d+)\s+0\s+R", fm.group(1)):
            fonts[name] = Font(objs, int(num))
    height = float(re.search(r"/MediaBox\s*\[\s*\S+\s+\S+\s+\S+\s+(\S+)", pd).group(1))
    content = objs[_ref(pd, "Contents")][1]
    out = []
    ctm, stack, args = [1, 0, 0, 1, 0, 0], [], []
    tm = lm = [1, 0, 0, 1, 0, 0]
    font, size, lead = None, 1.0, 0.0

    def show(b):
        nonlocal tm
        text, w = font.decode(b)
        m = _mul(tm, ctm)
        # cairo's page matrix flips y: back to the drawing's coordinates
        x, y = m[4], height - m[5]
        sz = size * abs(m[3])
        out.append(Run(x, y, sz, w * sz, text))
        tm = _mul([1, 0, 0, 1, w * size, 0], tm)

    for kind, v in _tokens(content):
        if kind != "o":
            args.append(v)
            continue
        if v == "q":
            stack.append(ctm)
        elif v == "Q":
            ctm = stack.pop() if stack else ctm
        elif v == "cm":
            ctm = _mul(args[-6:], ctm)
        elif v == "BT":
            tm = lm = [1, 0, 0, 1, 0, 0]
        elif v == "Tm":
            tm = lm = list(args[-6:])
        elif v in ("Td", "TD"):
            if v == "TD":
                lead = -args[-1]
            lm = _mul([1, 0, 0, 1, args[-2], args[-1]], lm)
            tm = lm
        elif v == "T*":
            lm = _mul([1, 0, 0, 1, 0, -lead], lm)
            tm = lm
        elif v == "TL":
            lead = args[-1]
        elif v == "Tf":
            font, size = fonts.get(args[-2][1:]), args[-1]
        elif v == "Tj" or v == "'":
            if v == "'":
                lm = _mul([1, 0, 0, 1, 0, -lead], lm)
                tm = lm
            if font and args and isinstance(args[-1], bytes):
                show(args[-1])
        elif v == "TJ":
            # the array's strings and kerning numbers, since the last '['
            k = len(args) - 1
            while k >= 0 and args[k] != "[":
                k -= 1
            for it in args[k + 1:]:
                if isinstance(it, bytes) and font:
                    show(it)
                elif isinstance(it, float):
                    tm = _mul([1, 0, 0, 1, -it / 1000.0 * size, 0], tm)
        args = []
    return _merge(out)


def _merge(rs):
    """Runs that continue one another on the same baseline (cairo splits a
    string where the font changes) become one."""
    out = []
    for r in rs:
        if out:
            p = out[-1]
            if abs(p.y - r.y) < 0.01 and abs(p.size - r.size) < 0.01 and abs(p.x + p.w - r.x) < 0.05:
                out[-1] = Run(p.x, p.y, p.size, p.w + r.w, p.text + r.text)
                continue
        out.append(r)
    return out


if __name__ == "__main__":
    for r in runs(sys.argv[1]):
        print("%.2f %.2f %.2f %.2f %s" % (r.x, r.y, r.size, r.w, r.text))
