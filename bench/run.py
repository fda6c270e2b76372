#!/usr/bin/env python3
"""make bench: the figures of issue 18, each beside its target.

How it measures (bench/README.md):
- every run is a whole process, spawned with posix_spawn and waited for with
  wait4; its time is the CPU time wait4 reports (user + sys, all its
  threads), except where a figure is about waiting for the disk (M15) and
  says so;
- the programs of one figure run in interleaved rounds: A B C A B C ..., the
  same number of rounds for every program (engine) of the figure, and the
  figure is the median over the rounds;
- a loop's cost per iteration is (run of N iterations - run of 1) / (N - 1),
  so start-up and compilation are not in it; every engine gets its own
  1-iteration run in the same rounds;
- ratios are taken between figures of the same run: the median of the
  rounds' own ratios (a round's two runs are neighbours in time), with the
  ratio of the two medians beside it;
- before the rounds, every program is run once and its result checked (the
  loop really ran N times, the twin printed N, rs274 reached PROGRAM_END),
  so a program that stops early cannot pass for a fast one.

A twin (lua5.4, luajit, rs274, strace) that is not installed is skipped with
a notice; nothing here fails the build because of one.  A program of s42's
that fails is an error (exit 1): its figure would be a lie.

usage: run.py [--s42 ./s42] [--quick] [--out DIR] [--reps N]
"""
import argparse
import math
import os
import re
import shutil
import signal
import statistics
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
TIMEOUT = 180.0  # seconds: a run that takes longer is killed (the bench must end)


class Run:
    __slots__ = ("cpu", "wall", "rss", "status", "out", "err")


def spawn(argv, env=None, capture=False):
    """Run argv to its end; return a Run: cpu (user + sys seconds, wait4),
    wall seconds, peak RSS bytes, exit status, and stdout/stderr when
    capture is set (else both go to /dev/null)."""
    devnull = os.open(os.devnull, os.O_RDWR)
    tmp_out = tmp_err = None
    if capture:
        tmp_out = tempfile.TemporaryFile()
        tmp_err = tempfile.TemporaryFile()
        fo, fe = tmp_out.fileno(), tmp_err.fileno()
    else:
        fo = fe = devnull
    fa = [(os.POSIX_SPAWN_DUP2, devnull, 0), (os.POSIX_SPAWN_DUP2, fo, 1),
          (os.POSIX_SPAWN_DUP2, fe, 2)]
    e = dict(os.environ)
    if env:
        e.update(env)
    t0 = time.perf_counter()
    pid = os.posix_spawnp(argv[0], argv, e, file_actions=fa)
    killer = threading.Timer(TIMEOUT, lambda: os.kill(pid, signal.SIGKILL))
    killer.start()
    _, status, ru = os.wait4(pid, 0)
    t1 = time.perf_counter()
    killer.cancel()
    os.close(devnull)
    r = Run()
    r.cpu = ru.ru_utime + ru.ru_stime
    r.wall = t1 - t0
    r.rss = ru.ru_maxrss * 1024
    r.status = os.waitstatus_to_exitcode(status)
    r.out = r.err = b""
    if capture:
        tmp_out.seek(0)
        tmp_err.seek(0)
        r.out, r.err = tmp_out.read(), tmp_err.read()
        tmp_out.close()
        tmp_err.close()
    return r


class Job:
    """One program of a figure: a name, its argv, the status it must end
    with, and a check of its captured output (run once, before timing)."""

    def __init__(self, name, argv, expect=0, check=None, env=None):
        self.name, self.argv, self.expect, self.check, self.env = name, argv, expect, check, env


def fail(msg):
    print("bench: " + msg, flush=True)
    sys.exit(1)


def validate(job):
    r = spawn(job.argv, job.env, capture=True)
    if r.status != job.expect:
        fail("%s: %s exited with %d (expected %d)\n%s" % (
            job.name, " ".join(job.argv), r.status, job.expect, r.err.decode(errors="replace")[-2000:]))
    if job.check:
        why = job.check(r)
        if why:
            fail("%s: %s: %s" % (job.name, " ".join(job.argv), why))
    return r


def rounds(jobs, reps):
    """Validate each job, then run reps interleaved rounds (every job once a
    round, in order).  Returns {name: [Run, ...]}."""
    for j in jobs:
        validate(j)
    res = {j.name: [] for j in jobs}
    for _ in range(reps):
        for j in jobs:
            r = spawn(j.argv, j.env)
            if r.status != j.expect:
                fail("%s: %s exited with %d (expected %d)" % (j.name, " ".join(j.argv), r.status, j.expect))
            res[j.name].append(r)
    return res


def med(xs):
    return statistics.median(xs)


def paired(num, den):
    """The ratio of two figures of the same rounds: the median of the
    rounds' own ratios (each round's num over its den), the ratio of the
    two medians, and the rounds' ratios.  A round's two runs are
    neighbours in time; two medians can come from different rounds, so on
    a host whose speed jumps from one second to the next they can pair a
    fast run with a slow one (bench/README.md)."""
    rr = [a / b for a, b in zip(num, den) if b > 0]
    return (med(rr) if rr else float("nan")), med(num) / med(den), rr


def spread(xs, scale=1.0, fmt="%.1f"):
    return "[" + (fmt % (min(xs) * scale)) + "-" + (fmt % (max(xs) * scale)) + "]"


figures = []


def fig(name, value, unit, note=""):
    figures.append((name, value, unit))
    if isinstance(value, float):
        v = ("%.3f" % value) if abs(value) < 100 else ("%.0f" % value)
    else:
        v = str(value)
    print("bench %s %s %s%s" % (name, v, unit, ("  " + note) if note else ""), flush=True)


def with_count(src, dst, n):
    """Write the program src with its iteration count 1000000 replaced by n."""
    with open(src, encoding="utf-8") as f:
        text = f.read()
    assert text.count("1000000") == 1, src
    with open(dst, "w", encoding="utf-8") as f:
        f.write(text.replace("1000000", str(n)))
    return dst


def dump_blocks(n):
    """A check of `s42 run --dump` output: the run ended and executed n blocks."""
    def check(r):
        m = re.search(rb'"status":"([a-z]+)".*?"blocks":([0-9]+)', r.out)
        if not m:
            return "no dump in its output"
        if m.group(1) != b"end" or int(m.group(2)) != n:
            return "ended %s after %s blocks, expected end after %d" % (
                m.group(1).decode(), m.group(2).decode(), n)
        return None
    return check


def prints_count(n):
    def check(r):
        words = r.out.split()
        if not words or float(words[0]) != n:
            return "printed %r, expected %d first" % (r.out[:80], n)
        return None
    return check


def rs274_ends(path):
    def check(r):
        with open(path, "rb") as f:
            if b"PROGRAM_END" not in f.read():
                return "its output %s has no PROGRAM_END" % path
        return None
    return check


# ---------------------------------------------------------------- programs

def gen_compile(path, nblocks):
    """A program of nblocks blocks of mixed words that compiles cleanly:
    motions with expressions, arcs, assignments with functions, arrays,
    conditional jumps, sub calls, M functions."""
    pat = [
        "G01 X+1000 Y-500 F2000 ^",
        "R3+R1%2+SI(30000) R4+R3/7-1 ^",
        "G02 G17 X+2000 Y+0 I+1000 J+0 F1500 ^",
        "R1+R1+1 Z-R1/10 A+R2%3 ^",
        "T11+R2 T01 ^",
        "G04 X+5 ^",
        "G01 G09 X+R5 A-45000 F+R6 ^",
        "R7+(R1+R2)%(R3-4)/2 P(R7:B:100)3 ^",
        "L10 H+R8 M03 ^",
        "G03 G19 X-2000 Z+0 I-1000 K+0 ^",
    ]
    with open(path, "w", encoding="utf-8") as f:
        f.write("№10 G01 X+1 F100 M17 ^\n№1 R1+0 R2+5 R5+100 R6+1000 R8+1 ^\n№2 R3+1 ^\n№3 R9+1 ^\n")
        body = (nblocks - 5) // len(pat)
        chunk = "\n".join(pat) + "\n"
        left = nblocks - 5 - body * len(pat)
        step = 100000 // len(pat)
        for i in range(0, body, step):
            f.write(chunk * min(step, body - i))
        f.write("".join(pat[i] + "\n" for i in range(left)))
        f.write("M02 ^\n")


def gen_chain(path, nsubs):
    """nsubs chained subs (10 calls 11, 11 calls 12, ...), called once from
    the main program: nsubs + 2 lines."""
    with open(path, "w", encoding="utf-8") as f:
        for i in range(10, 10 + nsubs):
            f.write("№%d L%d M17 ^\n" % (i, i + 1) if i < 9 + nsubs else "№%d M17 ^\n" % i)
        f.write("№1 L10 ^\n№2 M02 ^\n")


PLOT_ROUND = ("G01 X+1000 Y+500 F2000 ^\n"
              "G01 Z-300 A+1500 ^\n"
              "G02 G17 X+2000 Y+0 I+1000 J+0 ^\n"
              "G03 G19 X-2000 Z+0 I-1000 K+0 ^\n"
              "G02 G18 Y+2000 Z+0 J+1000 K+0 ^\n"
              "G01 X-1000 Y-2500 Z+300 A-1500 ^\n")
PLOT_PER_ROUND = 6


def gen_plot(path, rounds_):
    """PLOT_PER_ROUND * rounds_ + 2 blocks: lines in XY, Z with A, half
    circles in XY, XZ and YZ (each a line in the other panels), a line
    back to the start."""
    with open(path, "w", encoding="utf-8") as f:
        f.write("№1 M03 ^\n")
        f.write(PLOT_ROUND * rounds_)
        f.write("M05 M02 ^\n")
    return PLOT_PER_ROUND * rounds_ + 2


def libraries(argv):
    """The shared objects the dynamic loader maps for argv (LD_DEBUG=files):
    the libraries linked and those opened with dlopen."""
    r = spawn(argv, {"LD_DEBUG": "files"}, capture=True)
    names = re.findall(rb"file=(\S+) \[\d+\];  generating link map", r.err)
    return [n.decode() for n in dict.fromkeys(names)]


def strace_syncs(argv, out):
    """How many fsync-like calls argv makes (strace -f -c), or None."""
    st = shutil.which("strace")
    if not st:
        return None
    log = os.path.join(out, "strace.txt")
    r = spawn([st, "-f", "-c", "-o", log, "-e",
               "trace=fsync,fdatasync,sync_file_range,syncfs,sync,msync"] + argv)
    if r.status != 0 or not os.path.exists(log):
        return None
    n = 0
    with open(log, encoding="utf-8", errors="replace") as f:
        for line in f:
            w = line.split()
            # % time, seconds, usecs/call, calls, [errors,] syscall
            if len(w) >= 5 and w[-1] in ("fsync", "fdatasync", "sync_file_range", "syncfs", "sync", "msync"):
                n += int(w[3])
    return n


# ---------------------------------------------------------------- main

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--s42", default="./s42")
    ap.add_argument("--quick", action="store_true", help="fewer rounds, shorter loops (about a minute)")
    ap.add_argument("--reps", type=int, default=0, help="rounds of the loop figures (default 9, quick 3)")
    ap.add_argument("--out", default="build/bench")
    a = ap.parse_args()
    s42 = os.path.abspath(a.s42)
    os.makedirs(a.out, exist_ok=True)
    out = os.path.abspath(a.out)
    q = a.quick
    P = {  # what each figure runs: (quick, full)
        "reps":      3 if q else 9,          # rounds of the loop figures
        "reps_slow": 3 if q else 5,          # rounds of compile, check, endmill, plot, M15
        "loop_n":    1000000 if q else 5000000,
        "trig_n":    300000 if q else 1000000,
        "rs_loop_n": 20000 if q else 100000,  # rs274 takes ~5 us an iteration
        "rs_trig_n": 10000 if q else 50000,
        "compile_n": 1000000,
        "plot_rounds": 16667,                # 100,004 blocks
        "m15_n":     100 if q else 300,
        "startup":   60 if q else 200,
    }
    if a.reps:
        P["reps"] = a.reps
    reps, reps_slow = P["reps"], P["reps_slow"]
    t_start = time.perf_counter()
    print("bench: %s mode, %d rounds (%d for the slow figures); CPU time = user + sys from wait4"
          % ("quick" if q else "full", reps, reps_slow), flush=True)

    tw = {}
    for key, exe, pkg in (("lua", "lua5.4", "lua5.4"), ("luajit", "luajit", "luajit"),
                          ("rs274", "rs274", "linuxcnc-uspace")):
        tw[key] = shutil.which(exe)
        if not tw[key]:
            print("bench: %s is not installed: its twins are skipped (apt-get install %s)" % (exe, pkg))
    label = {"s42": "s42", "lua": "Lua 5.4", "luajit": "LuaJIT -joff", "rs274": "rs274"}

    def engine_jobs(engine, base, n, blocks_per_iter=1):
        """Jobs for a loop program: N iterations and 1 iteration."""
        jobs = []
        for k in (n, 1):
            tag = "%s:%s:%d" % (engine, base, k)
            if engine in ("s42", "mblock", "subcall"):
                src = os.path.join(HERE, base + ".kp")
                path = with_count(src, os.path.join(out, "%s-%d.kp" % (base, k)), k)
                jobs.append(Job(tag, [s42, "run", path]))
                jobs[-1].check_argv = [s42, "run", path, "--dump"]
                jobs[-1].check_n = blocks_per_iter * k + 2
            elif engine in ("lua", "luajit"):
                path = with_count(os.path.join(HERE, base + ".lua"),
                                  os.path.join(out, "%s-%d.lua" % (base, k)), k)
                argv = [tw["lua"], path] if engine == "lua" else [tw["luajit"], "-joff", path]
                jobs.append(Job(tag, argv, check=prints_count(k)))
            else:
                path = with_count(os.path.join(HERE, base + ".ngc"),
                                  os.path.join(out, "%s-%d.ngc" % (base, k)), k)
                canon = os.path.join(out, "%s-%d.canon" % (base, k))
                jobs.append(Job(tag, [tw["rs274"], "-g", path, os.devnull]))
                jobs[-1].check_argv = [tw["rs274"], "-g", path, canon]
                jobs[-1].check_file = canon
        return jobs

    def loop_group(specs, nreps):
        """specs: [(key, engine, base, n, blocks_per_iter)]; returns
        {key: [ns per iteration, one a round]}."""
        jobs, meta = [], {}
        for key, engine, base, n, bpi in specs:
            jn, j1 = engine_jobs(engine, base, n, bpi)
            meta[key] = (jn.name, j1.name, n)
            jobs += [jn, j1]
        for j in jobs:  # the check runs of s42 (with --dump) and rs274 (canon to a file)
            if hasattr(j, "check_n"):
                validate(Job(j.name, j.check_argv, check=dump_blocks(j.check_n)))
            elif hasattr(j, "check_file"):
                validate(Job(j.name, j.check_argv, check=rs274_ends(j.check_file)))
        res = rounds(jobs, nreps)
        per = {}
        for key, (nn, n1, n) in meta.items():
            per[key] = [(rn.cpu - r1.cpu) / (n - 1) * 1e9 for rn, r1 in zip(res[nn], res[n1])]
        return per

    results = {}  # key -> median value

    def report_loop(prefix, per, unit="ns/iter"):
        for key, xs in per.items():
            results[prefix + key] = med(xs)
            fig(prefix + key, med(xs), unit, "rounds " + spread(xs))

    # ---- 1. the VM loop, a block with an M word, a sub call; the twins ----
    specs = [("s42", "s42", "loop", P["loop_n"], 1),
             # the M-word and sub-call loops as many times as the plain one,
             # which their ratios divide by: runs of one length, alike noise
             ("mblock", "mblock", "mblock", P["loop_n"], 1),
             ("subcall", "subcall", "subcall", P["loop_n"], 2)]
    for e in ("lua", "luajit", "rs274"):
        if tw[e]:
            specs.append((e, e, "loop", P["rs_loop_n"] if e == "rs274" else P["loop_n"], 1))
    print("\n# loop: %d iterations (rs274 %d), the M-word and sub-call loops as many; %d rounds of %s"
          % (P["loop_n"], P["rs_loop_n"], reps, " ".join(s[0] for s in specs)), flush=True)
    per_loop = loop_group(specs, reps)
    report_loop("loop_", per_loop)

    # ---- 2. the trig loop ----
    specs = [("s42", "s42", "trig", P["trig_n"], 1)]
    for e in ("lua", "luajit", "rs274"):
        if tw[e]:
            specs.append((e, e, "trig", P["rs_trig_n"] if e == "rs274" else P["trig_n"], 1))
    print("\n# trig: %d iterations (rs274 %d); %d rounds of %s"
          % (P["trig_n"], P["rs_trig_n"], reps, " ".join(s[0] for s in specs)), flush=True)
    per_trig = loop_group(specs, reps)
    report_loop("trig_", per_trig)

    # ---- 3. compile: blocks/s and peak RSS per block ----
    nb = P["compile_n"]
    ck = os.path.join(out, "compile-1m.kp")
    gen_compile(ck, nb)
    print("\n# compile: s42 check of a %d-block program; %d rounds" % (nb, reps_slow), flush=True)
    res = rounds([Job("check", [s42, "check", ck])], reps_slow)["check"]
    cps = nb / med([r.cpu for r in res])
    bpb = med([r.rss for r in res]) / nb
    results["compile_bps"], results["compile_bpb"] = cps, bpb
    fig("compile_blocks_per_s", cps, "blocks/s", "rounds " + spread([nb / r.cpu / 1e6 for r in res], fmt="%.2f") + " M")
    fig("compile_peak_bytes_per_block", bpb, "bytes/block")
    fig("compile_source_bytes_per_block", os.path.getsize(ck) / nb, "bytes/block")

    # ---- 4. compile limits: a 10-million-block program (full mode) ----
    results["limit"] = None
    if q:
        print("bench: the 10-million-block compile runs in full mode only")
    else:
        big = os.path.join(out, "compile-10m.kp")
        n10 = 10000000
        gen_compile(big, n10)
        print("\n# compile limits: s42 check of a %d-block program (%d MB), once"
              % (n10, os.path.getsize(big) // 1000000), flush=True)
        r = spawn([s42, "check", big], capture=True)
        os.unlink(big)
        first = r.err.decode(errors="replace").strip().splitlines()
        first = first[0] if first else ""
        # "s42: PATH: message" or "PATH:1:1: error: message": the message
        first = re.sub(r"^(s42: )?" + re.escape(big) + r"(:\d+:\d+)?: (error: )?", "", first)
        results["limit"] = (r.status, first, n10 / r.cpu, r.rss / n10)
        fig("compile_10m_status", r.status, "(exit status)", first[:160])
        if r.status == 0:
            fig("compile_10m_blocks_per_s", n10 / r.cpu, "blocks/s")
            fig("compile_10m_peak_bytes_per_block", r.rss / n10, "bytes/block")

    # ---- 5. the sub recursion check: 990 chained subs ----
    base2 = os.path.join(out, "two.kp")
    with open(base2, "w", encoding="utf-8") as f:
        f.write("№1 R1+1 ^\n№2 M02 ^\n")
    c990, c330 = os.path.join(out, "chain990.kp"), os.path.join(out, "chain330.kp")
    gen_chain(c990, 990)
    gen_chain(c330, 330)
    print("\n# sub recursion check: s42 check of 990 and 330 chained subs, and of a two-block program; %d rounds"
          % reps_slow, flush=True)
    res = rounds([Job("c990", [s42, "check", c990]), Job("c330", [s42, "check", c330]),
                  Job("c2", [s42, "check", base2])], reps_slow)
    t990 = med([r.cpu for r in res["c990"]])
    t330 = med([r.cpu for r in res["c330"]])
    t2 = med([r.cpu for r in res["c2"]])
    x990, x330 = max(t990 - t2, 0.0), max(t330 - t2, 0.0)
    expo = math.log(x990 / x330) / math.log(3) if x330 > 0 and x990 > 0 else float("nan")
    results["chain"] = (t990, x990, expo)
    fig("subcheck_990_ms", t990 * 1e3, "ms", "(the check of the 992-line program; %.1f ms over a two-block one)" % (x990 * 1e3))
    fig("subcheck_330_ms", t330 * 1e3, "ms")
    fig("subcheck_growth_exponent", expo, "", "(time over the two-block check ~ subs^k, from 330 to 990 subs: 1 linear, 3 cubic)")

    # ---- 6. programs/endmill_search.kp ----
    sd = tempfile.mkdtemp(prefix="state-", dir=out)
    em = [s42, "run", os.path.join(ROOT, "programs/endmill_search.kp"),
          "--tool", os.path.join(ROOT, "programs/endmill_search.tool"),
          "--operator", os.path.join(ROOT, "programs/endmill_search.operator"),
          "--state", os.path.join(sd, "endmill.state")]
    print("\n# endmill_search.kp: s42 run with its tool and operator files; %d rounds" % reps_slow, flush=True)
    validate(Job("endmill", em + ["--dump"], check=lambda r: None if b'"status":"end"' in r.out else "did not end"))
    res = rounds([Job("endmill", em)], reps_slow)["endmill"]
    results["endmill"] = med([r.cpu for r in res]) * 1e3
    fig("endmill_search_ms", results["endmill"], "ms CPU", "rounds " + spread([r.cpu for r in res], 1e3, "%.0f"))
    fig("endmill_search_wall_ms", med([r.wall for r in res]) * 1e3, "ms wall")
    libs = [os.path.basename(x) for x in libraries(em)]
    results["endmill_libs"] = libs
    cv = [x for x in libs if x.startswith("libopencv_")]
    fig("endmill_search_libraries", len(libs), "shared objects mapped", "OpenCV: " + " ".join(cv))

    # ---- 7. plot: us per block ----
    pk, p1 = os.path.join(out, "plot.kp"), os.path.join(out, "plot-1.kp")
    npb = gen_plot(pk, P["plot_rounds"])
    np1 = gen_plot(p1, 1)
    png, png1 = os.path.join(out, "plot.png"), os.path.join(out, "plot-1.png")
    print("\n# plot: s42 plot of a %d-block program (lines, arcs in XY, XZ, YZ) and of a %d-block one; %d rounds"
          % (npb, np1, reps_slow), flush=True)
    validate(Job("plotrun", [s42, "run", pk, "--dump"], check=dump_blocks(npb)))
    res = rounds([Job("plot", [s42, "plot", pk, "-o", png]), Job("plot1", [s42, "plot", p1, "-o", png1]),
                  Job("run", [s42, "run", pk])], reps_slow)
    per = [(rn.cpu - r1.cpu) / (npb - np1) * 1e6 for rn, r1 in zip(res["plot"], res["plot1"])]
    results["plot"] = med(per)
    fig("plot_us_per_block", med(per), "us/block", "rounds " + spread(per, fmt="%.2f"))
    fig("plot_total_s", med([r.cpu for r in res["plot"]]), "s CPU", "(%d blocks, the picture included)" % npb)
    fig("plot_run_only_us_per_block", med([r.cpu for r in res["run"]]) / npb * 1e6, "us/block",
        "(s42 run of the same program, nothing drawn)")

    # ---- 8. M15: saves per second ----
    n15 = P["m15_n"]
    mk = with_count(os.path.join(HERE, "m15.kp"), os.path.join(out, "m15-%d.kp" % n15), n15)
    mk1 = with_count(os.path.join(HERE, "m15.kp"), os.path.join(out, "m15-1.kp"), 1)
    print("\n# M15: a loop of %d blocks with M15, --state in a temporary directory under %s; %d rounds (wall clock: a save waits for the disk)"
          % (n15, out, reps_slow), flush=True)
    argv15 = [s42, "run", mk, "--state", os.path.join(sd, "m15.state")]
    argv1 = [s42, "run", mk1, "--state", os.path.join(sd, "m15-1.state")]
    validate(Job("m15", argv15 + ["--dump"], check=dump_blocks(n15 + 2)))
    res = rounds([Job("m15", argv15), Job("m15-1", argv1)], reps_slow)
    wall = [(rn.wall - r1.wall) / (n15 - 1) for rn, r1 in zip(res["m15"], res["m15-1"])]
    cpu = [(rn.cpu - r1.cpu) / (n15 - 1) for rn, r1 in zip(res["m15"], res["m15-1"])]
    results["m15"] = 1 / med(wall)
    fig("m15_saves_per_s", 1 / med(wall), "saves/s", "(wall; rounds %s ms a save)" % spread(wall, 1e3, "%.2f"))
    fig("m15_cpu_us_per_save", med(cpu) * 1e6, "us CPU/save")
    fresh = tempfile.mkdtemp(prefix="state-", dir=out)
    ns = 50
    m50 = with_count(os.path.join(HERE, "m15.kp"), os.path.join(out, "m15-%d.kp" % ns), ns)
    syncs = strace_syncs([s42, "run", m50, "--state", os.path.join(fresh, "m15.state")], out)
    shutil.rmtree(fresh, ignore_errors=True)
    results["m15_syncs"] = None
    if syncs is None:
        print("bench: strace is not installed (or failed): the fsyncs a save are not counted")
    else:
        results["m15_syncs"] = (syncs, ns)
        fig("m15_fsyncs_per_save", syncs / ns, "fsyncs/save", "(%d in %d saves, the first creates the file; strace -f -c)" % (syncs, ns))
    shutil.rmtree(sd, ignore_errors=True)

    # ---- 9. start-up ----
    nst = P["startup"]
    print("\n# start-up: s42 run of a two-block program, lua5.4 -e '', /bin/true; %d rounds" % nst, flush=True)
    jobs = [Job("s42", [s42, "run", base2])]
    if tw["lua"]:
        jobs.append(Job("lua", [tw["lua"], "-e", ""]))
    jobs.append(Job("true", ["/bin/true"]))
    res = rounds(jobs, nst)
    st = {k: med([r.cpu for r in v]) * 1e3 for k, v in res.items()}
    stw = {k: med([r.wall for r in v]) * 1e3 for k, v in res.items()}
    results["startup"] = st
    results["startup_ratio"] = paired([r.cpu for r in res["s42"]], [r.cpu for r in res["lua"]]) if "lua" in res else None
    for k in res:
        fig("startup_" + k + "_ms", st[k], "ms CPU", "(%.2f ms wall)" % stw[k])
    libs = [os.path.basename(x) for x in libraries([s42, "run", base2])]
    results["startup_libs"] = libs
    fig("startup_s42_libraries", len(libs), "shared objects mapped", " ".join(libs))

    # ---- summary ----
    print("\nsummary (issue 18; ratios from this run; took %.0f s)" % (time.perf_counter() - t_start))
    rows = []

    def row(what, issue_now, value, target, met):
        rows.append((what, issue_now, value, target,
                     "skipped" if met is None else ("met" if met else "MISSED")))

    def ratio_row(group, per, twin, what, issue_now, need):
        if twin not in per:
            row(what, issue_now, "— (%s not installed)" % label[twin], ">= %gx" % need if need else "", None)
            return
        r, rm, rr = paired(per[twin], per["s42"])
        f = "%.0f" if r >= 100 else "%.2f"
        v = (f + "x (rounds %s; medians %.1f / %.1f ns = " + f + "x)") % (
            r, spread(rr, fmt=f), med(per[twin]), med(per["s42"]), rm)
        if need:
            row(what, issue_now, v, ">= %gx" % need, r >= need)
        else:
            rows.append((what, issue_now, v, "", "info"))

    ratio_row("loop", per_loop, "lua", "VM loop, Lua 5.4 / s42", "1.48–1.64x", 2.0)
    ratio_row("loop", per_loop, "luajit", "VM loop, LuaJIT -joff / s42", "0.83–0.90x", 1.1)
    ratio_row("loop", per_loop, "rs274", "VM loop, rs274 / s42", "427–438x", 600)
    ratio_row("trig", per_trig, "lua", "trig loop, Lua 5.4 / s42", "1.8–2.1x", 2.5)
    ratio_row("trig", per_trig, "luajit", "trig loop, LuaJIT -joff / s42", "", 0)
    ratio_row("trig", per_trig, "rs274", "trig loop, rs274 / s42", "", 0)
    for key, what, issue_now in (("mblock", "a block with an M word (M23) / a plain block", "~7.8x"),
                                 ("subcall", "a sub call (L10, sub 10 is M17) / a plain block", "~8.5x")):
        r, rm, rr = paired(per_loop[key], per_loop["s42"])
        row(what, issue_now, "%.2fx (rounds %s; medians %.1f / %.1f ns = %.2fx)" % (
            r, spread(rr, fmt="%.2f"), med(per_loop[key]), med(per_loop["s42"]), rm), "<= 2x", r <= 2.0)
    row("compile", "0.56–0.61 M blocks/s", "%.2f M blocks/s" % (cps / 1e6), ">= 2 M blocks/s", cps >= 2e6)
    row("compile, peak memory", "", "%.0f bytes/block" % bpb, "<= 200 bytes/block", bpb <= 200)
    lim = results["limit"]
    if lim is None:
        row("compile limits: a 10 M-block program", "2,097,152 blocks", "— (full mode only)", "compiles", None)
    else:
        st_, first, _, _ = lim
        v = "compiles (%.2f M blocks/s, %.0f bytes/block)" % (lim[2] / 1e6, lim[3]) if st_ == 0 else \
            "refused, status %d: %s" % (st_, first[:80])
        row("compile limits: a 10 M-block program", "2,097,152 blocks", v, "compiles", st_ == 0)
    t990, x990, expo = results["chain"]
    ok = x990 < 0.001 or (expo == expo and expo <= 1.5)
    row("sub recursion check, 990 chained subs", "0.65 s, cubic",
        "%.1f ms; growth ~subs^%.1f" % (t990 * 1e3, expo), "linear (exponent <= 1.5)", ok)
    row("endmill_search.kp run", "0.43–0.58 s", "%.0f ms CPU" % results["endmill"], "<= 150 ms", results["endmill"] <= 150)
    ic = [x for x in results["endmill_libs"] if x.startswith("libopencv_imgcodecs")]
    row("endmill_search.kp run: libopencv_imgcodecs", "loaded (139 libraries)",
        "%s; %d shared objects" % ("loaded" if ic else "not loaded", len(results["endmill_libs"])),
        "not loaded without --dump-images", not ic)
    row("plot", "~40 us/block", "%.2f us/block" % results["plot"], "<= 4 us/block", results["plot"] <= 4)
    if results["m15_syncs"] is None:
        row("M15 save: fsyncs", "two a save", "— (no strace)", "one a save", None)
    else:
        sy, n = results["m15_syncs"]
        row("M15 save: fsyncs", "two a save", "%.2f a save (%d in %d)" % (sy / n, sy, n),
            "one a save (+1 for the file's creation)", sy <= n + 1)
    rows.append(("M15 saves per second (wall)", "~180/s", "%.0f/s" % results["m15"], "", "info"))
    st = results["startup"]
    if results["startup_ratio"]:
        r, rm, rr = results["startup_ratio"]
        row("start-up, s42 run / lua5.4 -e ''", "", "%.2fx (medians %.2f / %.2f ms = %.2fx)" % (r, st["s42"], st["lua"], rm),
            "<= 1.5x", r <= 1.5)
    else:
        row("start-up, s42 run / lua5.4 -e ''", "", "—", "<= 1.5x", None)
    extra = [x for x in results["startup_libs"] if not re.match(r"(libc|libm|libdl|libpthread|librt|ld-linux.*)\.so", x)]
    row("start-up: libraries s42 run maps beyond libc and libm", "ncurses, modbus",
        " ".join(extra) if extra else "none", "none", not extra)
    rows.append(("start-up, s42 run / /bin/true", "~2.5x", "%.2fx (%.2f / %.2f ms)" % (
        st["s42"] / st["true"], st["s42"], st["true"]), "", "info"))

    w0 = max(len(r[0]) for r in rows)
    w1 = max(len(r[1]) for r in rows)
    w2 = max(len(r[2]) for r in rows)
    w3 = max(len(r[3]) for r in rows)
    print("  %-*s  %-*s  %-*s  %-*s  %s" % (w0, "figure", w1, "issue", w2, "now", w3, "target", ""))
    for r in rows:
        print("  %-*s  %-*s  %-*s  %-*s  %s" % (w0, r[0], w1, r[1], w2, r[2], w3, r[3], r[4]))
    nmet = sum(1 for r in rows if r[4] == "met")
    nmiss = sum(1 for r in rows if r[4] == "MISSED")
    nskip = sum(1 for r in rows if r[4] == "skipped")
    print("  targets: %d met, %d missed, %d skipped" % (nmet, nmiss, nskip))
    return 0


if __name__ == "__main__":
    sys.exit(main())
