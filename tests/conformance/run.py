#!/usr/bin/env python3
# The project's own copy of the shared conformance runner (shared/conformance/run.py),
# kept identical in behaviour so the repository works without ../shared.
"""Run s42 against conformance cases and report what differs.

Usage: run.py [--s42 PATH] CASE_DIR...   (a CASE_DIR holds case folders)

A case folder holds program.kp, optionally operator.txt and tool.txt, and
expect.json, whose keys are all optional:
  status      "end" | "error"
  error_code  e.g. "E-DIV0"            (the dump's error.code)
  error_n     block number of the error
  exit        expected exit status of `s42 run`
  blocks      block numbers in execution order (trace key n)
  moves       list of {"n":N, "x":.., "y":.., "z":.., "a":..} matched in order
              against the trace blocks with that n (only the keys given)
  motions     list of {"n":N, "motion":"G02"}  (same matching)
  feeds       list of {"n":N, "f":.., "feed":[lo,hi]}
  time        [lo, hi] seconds, the dump's time
  pos         {"x":..,...} final position
  r           {"0": value, ...} parameters; a value may be [lo, hi]
  d1, tk, ug  a value or [lo, hi]
  arrays      [{"ptr":..,"len":..,"cells":[...]}, ...] (keys given only)
  screen_has  strings that must each appear in the --screen output
  stderr_has  strings that must appear on stderr
For a case of another dialect (contracts.md sec. 8) the program is
program.EXT (any extension) and these keys apply too:
  dialect     e.g. "2u22": passed as --dialect
  at          list of {"n":N, "x":.., "z":..} matched in order against the
              trace rows with that n, comparing their "pos" (mm)
  dump        {"key": value, ...} other members of the dump, compared exactly
              (numbers with close(); a nested object by its given keys)
  canon_has   lines that must appear, in this order, in --trace=canon output
              (a second run); each is compared after collapsing spaces
Prints one line per case and ends with 'N passed, N failed'.
"""
import json, os, subprocess, sys

def close(got, want):
    if isinstance(want, list) and len(want) == 2 and all(isinstance(v, (int, float)) for v in want):
        return isinstance(got, (int, float)) and want[0] <= got <= want[1]
    if isinstance(want, (int, float)) and isinstance(got, (int, float)):
        return abs(got - want) <= 1e-6 * max(1.0, abs(want))
    return got == want

def match_seq(trace, wants, what):
    errs, used = [], {}
    for w in wants:
        n = w["n"]
        rows = [t for t in trace if t.get("n") == n]
        k = used.get(n, 0)
        if k >= len(rows):
            errs.append(f"{what}: no run #{k+1} of block N{n}")
            continue
        used[n] = k + 1
        row = rows[k]
        for key, val in w.items():
            if key == "n":
                continue
            if not close(row.get(key), val):
                errs.append(f"{what}: N{n} run #{k+1}: {key}={row.get(key)!r}, want {val!r}")
    return errs

def program_of(case):
    if os.path.exists(os.path.join(case, "program.kp")):
        return os.path.join(case, "program.kp")
    for f in sorted(os.listdir(case)):
        if f.startswith("program."):
            return os.path.join(case, f)
    return os.path.join(case, "program.kp")

def sub_match(got, want, where):
    errs = []
    if isinstance(want, dict):
        if not isinstance(got, dict):
            return [f"{where} = {got!r}, want an object"]
        for k, v in want.items():
            errs += sub_match(got.get(k), v, f"{where}.{k}")
    elif not close(got, want):
        errs.append(f"{where} = {got!r}, want {want!r}")
    return errs

def canon_lines(s42, cmd):
    c = [a for a in cmd if a not in ("--trace=json", "--dump")] + ["--trace=canon"]
    try:
        pr = subprocess.run(c, capture_output=True, text=True, timeout=60)
    except (subprocess.TimeoutExpired, OSError) as e:
        return None, str(e)
    return [" ".join(l.split()) for l in pr.stdout.splitlines()], None

def run_case(s42, case):
    exp = json.load(open(os.path.join(case, "expect.json")))
    cmd = [s42, "run", program_of(case), "--trace=json", "--dump"]
    if exp.get("dialect"):
        cmd += ["--dialect", exp["dialect"]]
    if exp.get("screen_has"):
        cmd.append("--screen")
    for opt, name in (("--operator", "operator.txt"), ("--tool", "tool.txt")):
        p = os.path.join(case, name)
        if os.path.exists(p):
            cmd += [opt, p]
    try:
        pr = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return ["timed out after 60 s"]
    except OSError as e:
        return [f"cannot run s42: {e}"]
    trace, dump, screen = [], None, []
    for line in pr.stdout.splitlines():
        s = line.strip()
        if s.startswith("{"):
            try:
                obj = json.loads(s)
            except ValueError:
                screen.append(line)
                continue
            if "seq" in obj:
                trace.append(obj)
            elif "status" in obj:
                dump = obj
            else:
                screen.append(line)
        else:
            screen.append(line)
    errs = []
    if "exit" in exp and pr.returncode != exp["exit"]:
        errs.append(f"exit {pr.returncode}, want {exp['exit']}")
    if dump is None:
        if set(exp) <= {"exit", "stderr_has"}:
            dump = {}
        else:
            return errs + ["no --dump object on stdout; stderr: " + pr.stderr.strip()[-300:]]
    if "status" in exp and dump.get("status") != exp["status"]:
        errs.append(f"status {dump.get('status')!r}, want {exp['status']!r} ({(dump.get('error') or {}).get('message')})")
    err = dump.get("error") or {}
    if "error_code" in exp and err.get("code") != exp["error_code"]:
        errs.append(f"error code {err.get('code')!r}, want {exp['error_code']!r}")
    if "error_n" in exp and err.get("n") != exp["error_n"]:
        errs.append(f"error block {err.get('n')!r}, want {exp['error_n']!r}")
    if "blocks" in exp:
        got = [t.get("n") for t in trace]
        if got != exp["blocks"]:
            errs.append(f"blocks {got[:40]}, want {exp['blocks'][:40]}")
    for key in ("moves", "motions", "feeds"):
        if key in exp:
            errs += match_seq(trace, exp[key], key)
    if "time" in exp and not close(dump.get("time"), exp["time"]):
        errs.append(f"time {dump.get('time')}, want {exp['time']}")
    for k, v in exp.get("pos", {}).items():
        if not close((dump.get("pos") or {}).get(k), v):
            errs.append(f"pos.{k} {(dump.get('pos') or {}).get(k)}, want {v}")
    r = dump.get("r") or []
    for k, v in exp.get("r", {}).items():
        got = r[int(k)] if int(k) < len(r) else None
        if not close(got, v):
            errs.append(f"R{k} = {got}, want {v}")
    for k in ("d1", "tk", "ug"):
        if k in exp and not close(dump.get(k), exp[k]):
            errs.append(f"{k} = {dump.get(k)}, want {exp[k]}")
    for i, want in enumerate(exp.get("arrays", [])):
        got = (dump.get("arrays") or [{}, {}])[i]
        for k, v in want.items():
            if got.get(k) != v:
                errs.append(f"array {i+1} {k} = {got.get(k)}, want {v}")
    seen = {}
    for w in exp.get("at", []):
        rows = [t for t in trace if t.get("n") == w["n"]]
        k = seen.get(w["n"], 0)
        seen[w["n"]] = k + 1
        if k >= len(rows):
            errs.append(f"at: no run #{k+1} of block N{w['n']}")
            continue
        for key, val in w.items():
            if key != "n":
                errs += sub_match((rows[k].get("pos") or {}).get(key), val, f"at N{w['n']} run #{k+1} {key}")
    for k, v in exp.get("dump", {}).items():
        errs += sub_match(dump.get(k), v, k)
    if exp.get("canon_has"):
        lines, why = canon_lines(s42, cmd)
        if lines is None:
            errs.append(f"--trace=canon failed: {why}")
        else:
            i = 0
            for want in exp["canon_has"]:
                want = " ".join(want.split())
                while i < len(lines) and lines[i] != want:
                    i += 1
                if i == len(lines):
                    errs.append(f"canon lacks (in order) {want!r}")
                    break
                i += 1
    scr = "\n".join(screen)
    for s in exp.get("screen_has", []):
        if s not in scr:
            errs.append(f"screen lacks {s!r}")
    for s in exp.get("stderr_has", []):  # noqa: shadowing is fine here
        if s not in pr.stderr:
            errs.append(f"stderr lacks {s!r}")
    return errs

def main():
    args = sys.argv[1:]
    s42 = "./s42"
    if args[:1] == ["--s42"]:
        s42, args = args[1], args[2:]
    cases = []
    for d in args:
        cases += sorted(os.path.join(d, c) for c in os.listdir(d) if os.path.exists(os.path.join(d, c, "expect.json")))
    passed = failed = 0
    for case in cases:
        errs = run_case(s42, case)
        name = os.path.basename(case)
        if errs:
            failed += 1
            print(f"FAIL {name}: " + "; ".join(errs[:4]))
        else:
            passed += 1
            print(f"ok   {name}")
    print(f"{passed} passed, {failed} failed")
    sys.exit(1 if failed else 0)

if __name__ == "__main__":
    main()
