#!/usr/bin/env python3
"""Write programs that nest or chain expressions far past any real block,
to check that the parser and compiler refuse them instead of exhausting the
stack (each crashed s42 once).  Usage: deep.py DIR"""
import os, sys

d = sys.argv[1]
os.makedirs(d, exist_ok=True)
cases = {
    "deep-functions.kp": "SI(" * 200000 + "1" + ")" * 200000,
    "deep-signs.kp": "-" * 200000 + "1",
    "deep-powers.kp": "R1%%" * 100000 + "2",
    "long-sum.kp": "1+" * 300000 + "1",
    "long-params.kp": "R2+" * 300000 + "1",
}
for name, e in cases.items():
    with open(os.path.join(d, name), "w") as f:
        f.write("№1 R1+" + e + " ^\n№2 M02 ^\n")
with open(os.path.join(d, "deep-condition.kp"), "w") as f:
    f.write("№1 P" + "(" * 200000 + "R1:R:1" + ")" * 200000 + "2 ^\n№2 M02 ^\n")
with open(os.path.join(d, "long-condition.kp"), "w") as f:
    f.write("№1 P(" + "(R1:R:1)U" * 100000 + "(R1:R:1))2 ^\n№2 M02 ^\n")
