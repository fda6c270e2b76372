#!/usr/bin/env python3
"""Check docs/guide.md against docs/guide/ and the s42 under test.

  python3 tests/guide/check.py S42 ROOT

1. Every fenced block of guide.md has an info string; a `kp` or `operator`
   block must follow an `<!-- example: docs/guide/FILE -->` marker, and its
   text must be that file's, byte for byte.
2. Every file in docs/guide/ is shown exactly once.
3. Every example program compiles (`s42 check`) and runs to M2 (`s42 run
   --dump`, exit 0, status "end"), with docs/guide/NN-name.operator when
   there is one — or, when its marker says `error E-CODE`, fails with that
   code (exit 1, dump status "error").
4. Every `console` block is run, in order, in a scratch folder that holds
   docs/guide/ and ./s42: each `$ COMMAND` line runs in one sh session, and
   what follows it up to the next `$` line must be the command's stdout then
   its stderr (trailing spaces of a line and trailing empty lines aside).
5. Every docs/guide/ path named anywhere in guide.md exists.
Prints one FAIL line per failure and `guide: N passed, M failed`.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import transcript  # noqa: E402  (tests/transcript.py)

s42 = os.path.abspath(sys.argv[1])
root = os.path.abspath(sys.argv[2])
guide_md = os.path.join(root, "docs", "guide.md")
guide_dir = os.path.join(root, "docs", "guide")
passed = failed = 0


def ok():
    global passed
    passed += 1


def bad(msg):
    global failed
    failed += 1
    print("FAIL guide: " + msg)


text = open(guide_md, encoding="utf-8").read()
lines = text.split("\n")

# ---- the fenced blocks and the markers before them ----
blocks = []          # (line number, info, content, marker or None)
marker = None
i = 0
while i < len(lines):
    line = lines[i]
    m = re.match(r"^<!-- example: (\S+)(?: error (E-[A-Z0-9+-]+))? -->$", line)
    if m:
        marker = (m.group(1), m.group(2), i + 1)
        i += 1
        continue
    if line.startswith("```"):
        info = line[3:].strip()
        start = i + 1
        j = start
        while j < len(lines) and lines[j] != "```":
            j += 1
        if j == len(lines):
            bad("guide.md:%d: a fenced block that never ends" % (i + 1))
            break
        content = "\n".join(lines[start:j]) + "\n" if j > start else ""
        blocks.append((i + 1, info, content, marker))
        marker = None
        i = j + 1
        continue
    if line.strip() and marker is not None:
        bad("guide.md:%d: the example marker of line %d is not followed by a block" % (i + 1, marker[2]))
        marker = None
    i += 1

shown = {}
examples = []        # (path, expected error code or None)
for ln, info, content, mk in blocks:
    if not info:
        bad("guide.md:%d: a fenced block without an info string (kp, operator, console, sh, text)" % ln)
        continue
    if info in ("kp", "operator"):
        if mk is None:
            bad("guide.md:%d: a %s block without an <!-- example: --> marker" % (ln, info))
            continue
        path = mk[0]
        full = os.path.join(root, path)
        if not os.path.isfile(full):
            bad("guide.md:%d: %s does not exist" % (ln, path))
            continue
        want = open(full, encoding="utf-8").read()
        if content == want:
            ok()
        else:
            bad("guide.md:%d: the block is not %s as it is on disk" % (ln, path))
        shown[path] = shown.get(path, 0) + 1
        if path.endswith(".kp"):
            examples.append((path, mk[1]))
    elif mk is not None:
        bad("guide.md:%d: an example marker before a %s block" % (ln, info))

for name in sorted(os.listdir(guide_dir)):
    path = "docs/guide/" + name
    if name.endswith(".state") or ".state.tmp" in name:
        continue   # an M15 restart state s42 saved beside an example that ran: not the guide's
    n = shown.get(path, 0)
    if n == 1:
        ok()
    else:
        bad("%s is shown %d times in guide.md (once is right)" % (path, n))

for path in sorted(set(re.findall(r"docs/guide/[A-Za-z0-9._-]+", text))):
    if not os.path.exists(os.path.join(root, path)):
        bad("guide.md names %s, which does not exist" % path)

env = dict(os.environ, LC_ALL="C.UTF-8")
env.pop("S42_PLUGIN_PATH", None)
tmp = tempfile.mkdtemp(prefix="dg-guide.")
try:
    # ---- every example runs to M2, or fails as documented ----
    run_dir = os.path.join(tmp, "run")
    shutil.copytree(guide_dir, run_dir)
    for path, code in examples:
        name = os.path.basename(path)
        op = os.path.join(run_dir, name[:-3] + ".operator")
        chk = subprocess.run([s42, "check", name], cwd=run_dir, env=env,
                             capture_output=True, text=True)
        cmd = [s42, "run", name, "--dump", "--max-blocks", "1000000"]
        if os.path.exists(op):
            cmd += ["--operator", os.path.basename(op)]
        r = subprocess.run(cmd, cwd=run_dir, env=env, capture_output=True, text=True)
        try:
            d = json.loads(r.stdout)
        except ValueError:
            bad("%s: the dump is not JSON: %r" % (path, r.stdout[:200]))
            continue
        got = (d.get("error") or {}).get("code")
        if code is None:
            if chk.returncode == 0 and r.returncode == 0 and d.get("status") == "end":
                ok()
            else:
                bad("%s: check exit %d, run exit %d, status %s %s: %s"
                    % (path, chk.returncode, r.returncode, d.get("status"), got or "",
                       (chk.stderr + r.stderr).strip()))
        else:
            if r.returncode == 1 and d.get("status") == "error" and got == code:
                ok()
            else:
                bad("%s: expected %s, got run exit %d, status %s %s"
                    % (path, code, r.returncode, d.get("status"), got))

    # ---- the console transcripts, in order, in one scratch folder ----
    con = os.path.join(tmp, "console")
    os.makedirs(os.path.join(con, "docs"))
    shutil.copytree(guide_dir, os.path.join(con, "docs", "guide"))
    os.symlink(s42, os.path.join(con, "s42"))
    for ln, info, content, mk in blocks:
        if info != "console":
            continue
        transcript.run("guide.md:%d" % ln, content, con, env, ok, bad)
finally:
    shutil.rmtree(tmp, ignore_errors=True)

print("guide: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
