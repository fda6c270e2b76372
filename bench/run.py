#!/usr/bin/env python3
"""make bench: s42's figures, measured side by side in one run, with their
Lua 5.4 and LinuxCNC (rs274 -g) twins when those are installed.

Prints one line per figure, `bench NAME VALUE UNIT`, then a summary with the
ratios and the targets of issue 8.  Every timing is the wall time of a whole
process (spawn to exit), repeated; throughput figures take the best run (the
least disturbed by other load on the machine), start-up the median.  Loop
figures subtract the same program run for one iteration, so they are the
cost of an iteration, not of start-up and compilation.

usage: run.py [--s42 ./s42] [--reps N] [--quick] [--out DIR]
"""
import argparse
import os
import re
import shutil
import statistics
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))


def run(argv, stdout_path=None):
    """Spawn argv; return (wall seconds, peak RSS bytes, exit status, stdout)."""
    out_r = None
    if stdout_path is None:
        out_r, out_w = os.pipe()
    else:
        out_w = os.open(stdout_path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644)
    devnull = os.open(os.devnull, os.O_RDWR)
    fa = [(os.POSIX_SPAWN_DUP2, devnull, 0), (os.POSIX_SPAWN_DUP2, out_w, 1),
          (os.POSIX_SPAWN_DUP2, devnull, 2)]
    t0 = time.perf_counter()
    pid = os.posix_spawnp(argv[0], argv, os.environ, file_actions=fa)
    os.close(out_w)
    data = b""
    if out_r is not None:
        chunks = []
        while True:
            c = os.read(out_r, 1 << 16)
            if not c:
                break
            chunks.append(c)
        os.close(out_r)
        data = b"".join(chunks)
    _, status, ru = os.wait4(pid, 0)
    t1 = time.perf_counter()
    os.close(devnull)
    return t1 - t0, ru.ru_maxrss * 1024, os.waitstatus_to_exitcode(status), data


def best(argv, reps, expect=0):
    times, rss, out = [], 0, b""
    for _ in range(reps):
        t, m, st, out = run(argv)
        if st != expect:
            sys.exit("bench: %s exited with %d (expected %d)" % (" ".join(argv), st, expect))
        times.append(t)
        rss = max(rss, m)
    return min(times), rss, out, times


def with_count(src, dst, n):
    """Write the program src with its iteration count 1000000 replaced by n."""
    with open(src, encoding="utf-8") as f:
        text = f.read()
    assert "1000000" in text, src
    with open(dst, "w", encoding="utf-8") as f:
        f.write(text.replace("1000000", str(n)))
    return dst


figures = []


def fig(name, value, unit):
    figures.append((name, value, unit))
    if isinstance(value, float):
        v = ("%.3f" % value) if value < 100 else ("%.0f" % value)
    else:
        v = str(value)
    print("bench %s %s %s" % (name, v, unit), flush=True)


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
        f.write(chunk * body)
        f.write("".join(pat[i] + "\n" for i in range(left)))
        f.write("M02 ^\n")


def gen_motion(kp, ngc, rounds):
    """4 * rounds motion blocks: lines in XY, Z with A, a half circle in XY,
    a line back; the same moves in NGC (G91 incremental, mm and degrees)."""
    with open(kp, "w", encoding="utf-8") as f:
        f.write("№1 M03 ^\n")
        f.write(("G01 X+1000 Y+500 F2000 ^\nG01 Z-300 A+1500 ^\n"
                 "G02 G17 X+2000 Y+0 I+1000 J+0 ^\nG01 X-3000 Y-500 Z+300 A-1500 ^\n") * rounds)
        f.write("M05 M02 ^\n")
    with open(ngc, "w", encoding="utf-8") as f:
        f.write("G21 G91 G17 G94\nM3 S1000\n")
        f.write(("G1 X1.000 Y0.500 F2000\nG1 Z-0.300 A1.500\n"
                 "G2 X2.000 Y0 I1.000 J0\nG1 X-3.000 Y-0.500 Z0.300 A-1.500\n") * rounds)
        f.write("M5\nM2\n")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--s42", default="./s42")
    ap.add_argument("--reps", type=int, default=5)
    ap.add_argument("--quick", action="store_true", help="fewer repetitions, shorter rs274 runs")
    ap.add_argument("--out", default="build/bench")
    a = ap.parse_args()
    s42 = os.path.abspath(a.s42)
    reps = 2 if a.quick else a.reps
    os.makedirs(a.out, exist_ok=True)
    out = a.out
    lua = shutil.which("lua5.4")
    rs274 = shutil.which("rs274")
    if not lua:
        print("bench: lua5.4 is not installed: the Lua twins are skipped (apt-get install lua5.4)")
    if not rs274:
        print("bench: rs274 is not installed: the LinuxCNC twins are skipped (apt-get install linuxcnc-uspace)")
    N = 1000000

    # ---- loops: ns per iteration, start-up and compilation subtracted ----
    per = {}
    for name in ("loop", "trig"):
        kp1 = with_count(os.path.join(HERE, name + ".kp"), os.path.join(out, name + "-1.kp"), 1)
        kpn = os.path.join(HERE, name + ".kp")
        tn = best([s42, "run", kpn], reps)[0]
        t1 = best([s42, "run", kp1], reps)[0]
        per[(name, "s42")] = (tn - t1) / (N - 1) * 1e9
        fig(name + "_s42", per[(name, "s42")], "ns/iter")
        if lua:
            l1 = with_count(os.path.join(HERE, name + ".lua"), os.path.join(out, name + "-1.lua"), 1)
            tn = best([lua, os.path.join(HERE, name + ".lua")], reps)[0]
            t1 = best([lua, l1], reps)[0]
            per[(name, "lua")] = (tn - t1) / (N - 1) * 1e9
            fig(name + "_lua", per[(name, "lua")], "ns/iter")
        if rs274:
            # rs274 takes ~10 us an iteration: one run of a million (or of
            # 100,000 with --quick) against one of a single iteration
            n = 100000 if a.quick else N
            src = os.path.join(HERE, name + ".ngc")
            gn = with_count(src, os.path.join(out, "%s-%d.ngc" % (name, n)), n)
            g1 = with_count(src, os.path.join(out, name + "-1.ngc"), 1)
            tn = best([rs274, "-g", gn, os.devnull], 1)[0]
            t1 = best([rs274, "-g", g1, os.devnull], 3)[0]
            per[(name, "rs274")] = (tn - t1) / (n - 1) * 1e9
            fig(name + "_rs274", per[(name, "rs274")], "ns/iter")

    # ---- compile: blocks per second and peak memory per block ----
    nb = 1000000
    ck = os.path.join(out, "compile-1m.kp")
    gen_compile(ck, nb)
    t, rss, _, _ = best([s42, "check", ck], max(3, reps // 2 + 1))
    fig("compile_blocks_per_s", nb / t, "blocks/s")
    fig("compile_peak_bytes_per_block", rss / nb, "bytes/block")
    fig("compile_source_bytes_per_block", os.path.getsize(ck) / nb, "bytes/block")

    # ---- motion run: 100,000 motion blocks, headless, trace off ----
    rounds = 25000
    mk, mn = os.path.join(out, "motion.kp"), os.path.join(out, "motion.ngc")
    gen_motion(mk, mn, rounds)
    nmot = 4 * rounds
    t = best([s42, "run", mk], reps)[0]
    fig("motion_s42", nmot / t, "blocks/s")
    mot = {"s42": nmot / t}
    if rs274:
        t = best([rs274, "-g", mn, os.devnull], 1 if a.quick else 3)[0]
        mot["rs274"] = nmot / t
        fig("motion_rs274", mot["rs274"], "blocks/s")

    # ---- simulation: simulated seconds per wall second ----
    cyc = os.path.join(HERE, "cycle.kp")
    t, _, dump, _ = best([s42, "run", cyc, "--dump"], reps)
    m = re.search(rb'"time":([0-9.]+)', dump)
    sim = float(m.group(1))
    fig("sim_speed", sim / t, "sim-s/wall-s")

    # ---- start-up: a two-block program, median of many runs ----
    two = os.path.join(out, "two.kp")
    with open(two, "w", encoding="utf-8") as f:
        f.write("№1 R1+1 ^\n№2 M02 ^\n")
    nst = 50 if a.quick else 300
    ts = best([s42, "run", two], nst)[3]
    tt = best(["/bin/true"], nst)[3]
    fig("startup_s42", statistics.median(ts) * 1e3, "ms")
    fig("startup_bin_true", statistics.median(tt) * 1e3, "ms")

    # ---- summary ----
    print("\nsummary")
    ok = True

    def target(what, good, text):
        nonlocal ok
        ok = ok and good
        print("  %-5s %s" % ("PASS" if good else "MISS", text) if good is not None else "  skip  %s" % text)

    for name in ("loop", "trig"):
        s = per[(name, "s42")]
        for twin in ("lua", "rs274"):
            if (name, twin) in per:
                r = per[(name, twin)] / s
                line = "%s: s42 %.1f ns/iter, %s %.1f ns/iter: s42 is %.1fx faster" % (
                    name, s, "Lua 5.4" if twin == "lua" else "rs274", per[(name, twin)], r)
                if name == "loop":
                    need = 2 if twin == "lua" else 500
                    target(name, r >= need, line + " (target >= %dx)" % need)
                else:
                    print("  info  " + line)
    if "lua" not in [k[1] for k in per]:
        target("loop", None, "loop vs Lua 5.4: lua5.4 not installed")
    if "rs274" not in [k[1] for k in per]:
        target("loop", None, "loop vs rs274: linuxcnc-uspace not installed")
    cps = [v for n, v, u in figures if n == "compile_blocks_per_s"][0]
    bpb = [v for n, v, u in figures if n == "compile_peak_bytes_per_block"][0]
    target("compile", cps >= 5e6, "compile: %.2f million blocks/s (target >= 5)" % (cps / 1e6))
    target("memory", bpb <= 200, "compile: %.0f bytes of peak memory per block (target <= 200)" % bpb)
    if "rs274" in mot:
        print("  info  motion: s42 %.0f blocks/s, rs274 %.0f blocks/s: s42 is %.1fx faster"
              % (mot["s42"], mot["rs274"], mot["s42"] / mot["rs274"]))
    su = [v for n, v, u in figures if n == "startup_s42"][0]
    target("startup", su < 5, "start-up: %.2f ms median (target < 5 ms)" % su)
    print("  %s" % ("all measured targets met" if ok else "some targets missed"))
    return 0


if __name__ == "__main__":
    sys.exit(main())
