#!/usr/bin/env python3
"""The five-minute tutorial of README.md, done exactly as it says, on a copy
of the repository.

  python3 tests/tutorial/tutorial.py ROOT

The tutorial is the part of README.md between `<!-- tutorial` and
`<!-- /tutorial -->`. Its steps are taken from there, in order, so the text
and the test cannot drift apart:

- `<!-- file: PATH -->` and the fenced block after it: the block is that
  file of the repository, byte for byte;
- a `sh` block: each line is a command run in the copy, which must succeed
  (`make` builds the copy from scratch: only the repository's files are
  copied, never build/ or ./s42); a `./s42 tui ...` line starts the terminal
  in a detached 100x30 tmux pane on a private socket instead (through
  tests/tmux.sh, the driver the terminal tests share);
- a `console` block: each `$ COMMAND` line is run (one sh session per
  block); the lines after it must be its stdout then its stderr (trailing
  spaces and trailing empty lines aside);
- a table whose header starts `| when | press |` drives that tmux pane, row
  by row: first wait until each `text` of the "when" column has appeared in
  the pane, in order; press the keys of the "press" column (`Enter`,
  `Backspace`, F-keys, or one character each); wait until each `text` of the
  last column is in the pane. Runs of spaces count as one space on both
  sides. After `q` the terminal must quit with status 0 and leave the tty
  settings as they were.

Then the man page must render with groff -ww (-Tutf8 and -Tascii) without a
warning. Prints FAIL lines and `tutorial: N passed, M failed`.
"""
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import transcript  # noqa: E402  (tests/transcript.py)

root = os.path.abspath(sys.argv[1])
passed = failed = 0
tmp = tempfile.mkdtemp(prefix="s42-tutorial.")
repo = os.path.join(tmp, "repo")
DRIVER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tmux.sh")


def ok():
    global passed
    passed += 1


def bad(msg):
    global failed
    failed += 1
    print("FAIL tutorial: " + msg)


def squeeze(s):
    return re.sub(r"[ \t]+", " ", s)


# The copy's make and commands must not inherit the make that runs this test
# (-j jobserver fds, BUILD=, S42=, CFLAGS= of make asan ...).
env = dict(os.environ)
# make exports its command-line variables to recipes, so make asan's BUILD=,
# S42=, CFLAGS= and LDFLAGS= arrive here as environment variables too.
for k in ("MAKEFLAGS", "MFLAGS", "MAKELEVEL", "MAKEOVERRIDES", "GNUMAKEFLAGS",
          "S42_PLUGIN_PATH", "BUILD", "S42", "CFLAGS", "LDFLAGS"):
    env.pop(k, None)
env.update(LC_ALL="C.UTF-8", MANPAGER="cat", PAGER="cat", MANWIDTH="80")


def copy_repository():
    """The repository's own files (tracked, and new ones not ignored), as a
    fresh clone would have them with the work in progress on top."""
    r = subprocess.run(["git", "-C", root, "ls-files", "-z", "--cached", "--others",
                        "--exclude-standard"], capture_output=True)
    if r.returncode == 0:
        names = [n for n in r.stdout.decode().split("\0") if n]
    else:                                   # not a git checkout: the tree minus build output
        names = []
        for d, subs, files in os.walk(root):
            subs[:] = [s for s in subs if s not in (".git", "build", "build-asan")]
            for f in files:
                n = os.path.relpath(os.path.join(d, f), root)
                if n != "s42" and not n.endswith(".state"):
                    names.append(n)
    for n in names:
        src = os.path.join(root, n)
        if not os.path.isfile(src):
            continue                        # deleted in the worktree
        dst = os.path.join(repo, n)
        os.makedirs(os.path.dirname(dst), exist_ok=True)
        shutil.copy2(src, dst)
    return len(names)


# ---- the terminal in tmux: tests/tmux.sh, one function a call ----
tm_env = None                               # TM_SOCK and TM_DIR once the server runs


def tm(*args, **kw):
    return subprocess.run(["sh", DRIVER] + list(args), env=tm_env or env, capture_output=True, text=True, **kw)


def tm_init():
    global tm_env
    r = tm("init", tmp)
    if r.returncode != 0:
        bad("tmux did not start: %s" % r.stderr.strip())
        return False
    tm_env = dict(env)
    for line in r.stdout.split("\n"):
        if "=" in line:
            k, v = line.split("=", 1)
            tm_env[k] = v
    return True


def pane():
    return tm("pane", "tut").stdout


def wait_for(text, seconds=30):
    # spacing is insignificant, except where the README writes a run of
    # spaces on purpose (the 7-digit field's right-aligned number): then the
    # pane must show it exactly so
    return tm("wait", "tut", "-F" if "  " in text else "-S", text, str(seconds)).returncode == 0


def show_pane():
    return "\n".join("    | " + l for l in pane().rstrip("\n").split("\n"))


def start_tui(cmd):
    # the driver's server has a session that outlives the cases: killing
    # "tut" never empties it (whose exit would race a new-session under load)
    if tm_env is None and not tm_init():
        return False
    r = tm("run", "tut", "100", "30", repo, "-e", "LC_ALL=C.UTF-8", "-e", "TERM=screen", *shlex.split(cmd))
    if r.returncode != 0:
        bad("tmux could not start `%s`: %s" % (cmd, r.stderr.strip()))
        return False
    ok()
    return True


KEYS = {"Enter": "Enter", "Backspace": "BSpace", "Tab": "Tab", "Esc": "Escape"}


def press(key):
    k = KEYS.get(key, key)
    if not re.fullmatch(r"F[0-9]{1,2}", k) and k not in KEYS.values() and len(k) != 1:
        bad("the tutorial names a key this test does not know: %r" % key)
        return
    tm(*(["type", "tut", k] if len(k) == 1 else ["keys", "tut", k]))


def tui_ended():
    r = tm("ended", "tut", "10")
    if r.returncode != 0:
        bad("s42 tui did not quit after q:\n" + show_pane())
        return
    st = r.stdout.strip()
    if st == "exit=0":
        ok()
    else:
        bad("s42 tui quit with %s, not exit=0" % st)
    if tm("stty_same").returncode == 0:
        ok()
    else:
        bad("the terminal settings changed after s42 tui")


def cells(row):
    return [c.strip() for c in row.strip().strip("|").split("|")]


def ticks(cell):
    return re.findall(r"`([^`]+)`", cell)


def run_table(rows, tui_running):
    for row in rows:
        when, keys, _what, shows = (cells(row) + ["", "", "", ""])[:4]
        if not tui_running:
            bad("a key table with no `./s42 tui` running: %s" % row)
            return False
        for t in ticks(when):
            if wait_for(t):
                ok()
            else:
                bad("waiting for '%s' (row: %s):\n%s" % (t, row, show_pane()))
        quit_ = False
        for k in ticks(keys):
            press(k)
            quit_ = quit_ or k == "q"
        for t in ticks(shows):
            if wait_for(t):
                ok()
            else:
                bad("'%s' did not appear after %s:\n%s" % (t, " ".join(ticks(keys)), show_pane()))
        if quit_:
            tui_ended()
            tui_running = False
    return tui_running


def run_console(ln, content):
    transcript.run("README.md:%d" % ln, content, repo, env, ok, bad)


def run_sh(cmd):
    word = shlex.split(cmd)[0]
    if word == "man" and shutil.which("man") is None:
        print("tutorial: man is not installed: `%s` skipped (the page is still rendered with groff below)" % cmd)
        return
    t0 = time.time()
    r = subprocess.run(["sh", "-c", cmd], cwd=repo, env=env, stdin=subprocess.DEVNULL,
                       capture_output=True, text=True, timeout=1800)
    if r.returncode == 0:
        ok()
        if word == "make":
            print("tutorial: `%s` built the copy in %.0f s" % (cmd, time.time() - t0))
    else:
        bad("`%s` failed with status %d:\n%s" % (cmd, r.returncode,
            "\n".join("    | " + l for l in (r.stdout + r.stderr).strip().split("\n")[-15:])))


def main():
    if shutil.which("tmux") is None:
        print("tutorial: tmux is not installed: the tutorial test was skipped (sh scripts/deps.sh installs it)")
        return 0
    n = copy_repository()
    readme = open(os.path.join(repo, "README.md"), encoding="utf-8").read()
    lines = readme.split("\n")
    try:
        a = next(i for i, l in enumerate(lines) if l.startswith("<!-- tutorial"))
        b = next(i for i, l in enumerate(lines) if l.strip() == "<!-- /tutorial -->")
    except StopIteration:
        bad("README.md has no <!-- tutorial --> ... <!-- /tutorial --> part")
        return 1
    if not 0 <= a < b:
        bad("README.md: the tutorial's end marker comes before its start")
        return 1
    print("tutorial: %d files of the repository copied; README.md lines %d-%d" % (n, a + 1, b + 1))
    tui_running = False
    marker = None
    i = a + 1
    while i < b:
        line = lines[i]
        m = re.match(r"^<!-- file: (\S+) -->$", line)
        if m:
            marker = m.group(1)
            i += 1
            continue
        if line.startswith("```"):
            info = line[3:].strip()
            j = i + 1
            while j < b and lines[j] != "```":
                j += 1
            if j >= b:
                bad("README.md:%d: a fenced block that does not end inside the tutorial" % (i + 1))
                return 1
            content = "\n".join(lines[i + 1:j]) + "\n" if j > i + 1 else ""
            if marker:
                path = os.path.join(repo, marker)
                if os.path.isfile(path) and open(path, encoding="utf-8").read() == content:
                    ok()
                else:
                    bad("README.md:%d: the block is not %s as it is in the repository" % (i + 1, marker))
                marker = None
            elif info == "sh":
                for c in content.split("\n"):
                    c = c.strip()
                    if not c or c.startswith("#"):
                        continue
                    if c.startswith("./s42 tui"):
                        tui_running = start_tui(c)
                    else:
                        run_sh(c)
            elif info == "console":
                run_console(i + 1, content)
            else:
                bad("README.md:%d: a %r block in the tutorial that this test cannot do" % (i + 1, info))
            i = j + 1
            continue
        if re.match(r"^\| *when *\| *press *\|", line):
            rows = []
            i += 2                          # the header and the |---| line
            while i < b and lines[i].startswith("|"):
                rows.append(lines[i])
                i += 1
            tui_running = run_table(rows, tui_running)
            continue
        i += 1
    if tui_running:
        bad("the tutorial leaves s42 tui running: it should end with q")

    # what step 3 said it made
    png = os.path.join(repo, "cycle.png")
    if os.path.isfile(png) and open(png, "rb").read(8) == b"\x89PNG\r\n\x1a\n":
        ok()
    else:
        bad("the tutorial's plot did not write cycle.png")

    # the man page renders without a warning
    if shutil.which("groff") is None:
        print("tutorial: groff is not installed: the man page was not rendered")
    else:
        for dev in ("utf8", "ascii"):
            r = subprocess.run(["groff", "-man", "-T" + dev, "-ww", "-z", "docs/s42.1"],
                               cwd=repo, capture_output=True, text=True)
            if r.returncode == 0 and not r.stderr:
                ok()
            else:
                bad("groff -man -T%s -ww docs/s42.1: status %d\n%s" % (dev, r.returncode, r.stderr))
    return 0


try:
    main()
except subprocess.TimeoutExpired as e:
    bad("timed out: %s" % e)
finally:
    if tm_env is not None:
        tm("end")
    shutil.rmtree(tmp, ignore_errors=True)
print("tutorial: %d passed, %d failed" % (passed, failed))
sys.exit(1 if failed else 0)
