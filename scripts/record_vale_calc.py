#!/usr/bin/env python3
"""Re-record the non-regression values (VALE_CALC) of a study from its own
run: `scripts/record_vale_calc.py STUDY.comm STUDY.resu`.

Each VALE_CALC of the command file, in order, is replaced by the value the
run computed (the NON_REGRESSION rows of the .resu, in the same order).
Only for a deliberate change of the numbers, after checking the reference
(ANALYTIQUE / SOURCE_EXTERNE) tests still pass; the commit message and
docs/studies.md must say why the values moved.
"""
import re
import sys

comm_path, resu_path = sys.argv[1], sys.argv[2]
computed = []
for line in open(resu_path, encoding="utf-8"):
    f = line.split()
    if len(f) >= 5 and f[1] == "NON_REGRESSION":
        computed.append(f[4])
lines = open(comm_path, encoding="utf-8").read().split("\n")
pattern = re.compile(r"VALE_CALC=([-+0-9.eE]+)")
code = [i for i, l in enumerate(lines) if not l.lstrip().startswith("#")]
found = sum(len(pattern.findall(lines[i])) for i in code)
if found != len(computed):
    sys.exit(f"{found} VALE_CALC in {comm_path}, {len(computed)} NON_REGRESSION rows in {resu_path}")
values = iter(computed)
for i in code:
    lines[i] = pattern.sub(lambda m: "VALE_CALC=" + next(values), lines[i])
open(comm_path, "w", encoding="utf-8").write("\n".join(lines))
print(f"{comm_path}: {len(computed)} VALE_CALC recorded")
