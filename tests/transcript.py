"""Console transcripts in documentation: a block of `$ command` lines, each
followed by what it prints (stdout, then stderr).  Used by the guide's and
the tutorial's tests (tests/guide/check.py, tests/tutorial/tutorial.py)."""
import os
import subprocess


def _norm(lines):
    lines = [x.rstrip() for x in lines]
    while lines and not lines[-1]:
        lines.pop()
    return lines


def run(where, content, cwd, env, ok, bad):
    """Run the block's commands in order in one shell in cwd (a failing
    command does not stop the next) and compare each one's output with the
    lines the block shows.  `where` names the block in messages
    ("guide.md:12"); ok() / bad(message) count the results."""
    cmds = []        # (command, expected output lines)
    for line in content.rstrip("\n").split("\n"):
        if line.startswith("$ "):
            cmds.append((line[2:], []))
        elif cmds:
            cmds[-1][1].append(line)
        else:
            bad("%s: a console block must start with a $ line" % where)
            return
    script = ["(%s) >.o%d 2>.e%d; __st=$?; cat .o%d .e%d > .out%d; rm -f .o%d .e%d; (exit $__st)"
              % (c, k, k, k, k, k, k, k) for k, (c, _) in enumerate(cmds)]
    subprocess.run(["sh", "-c", "\n".join(script)], cwd=cwd, env=env, stdin=subprocess.DEVNULL)
    for k, (c, want) in enumerate(cmds):
        outf = os.path.join(cwd, ".out%d" % k)
        got = ["(not run)"]
        if os.path.exists(outf):
            with open(outf, encoding="utf-8", errors="replace") as f:
                got = f.read().split("\n")
            os.unlink(outf)
        if _norm(got) == _norm(want):
            ok()
        else:
            bad("%s: `%s` printed (the block shows other lines):\n%s"
                % (where, c, "\n".join("    | " + x for x in _norm(got))))
