#!/usr/bin/env python3
"""Checks a `qverify stress --candidate-cmd ...` report: in each named family the
candidate breaks (its geometric error exceeds the target, or a call fails) and
qverify's default double path never does.

    python3 check_report.py DIR [FAMILY ...]

DIR is the stress --out directory; FAMILY defaults to far-from-origin. Prints
every family's breaking points; exits 1 (saying why) when in a named family the
candidate never breaks or the default path breaks too, or when a listed
reproducer file is missing."""
import json
import os
import sys

out = sys.argv[1]
wanted = sys.argv[2:] or ["far-from-origin"]
doc = json.load(open(os.path.join(out, "report.json")))
cand = doc["candidate"]
problems = []
for fam in doc["families"]:
    at = fam["candidate"]["breakdown"]
    default = fam["breakdown"]["double/direct (default, robust)"]
    where = lambda x: "never" if x is None else f"at {fam['parameter']} = {x:g}"
    print(f"{fam['name']}: candidate {cand['name']} breaks {where(at)}; qverify's default double path breaks {where(default)}")
    if fam["name"] not in wanted:
        continue
    if at is None:
        problems.append(f"{fam['name']}: the candidate never breaks")
    if default is not None or not fam["default_meets_target"]:
        problems.append(f"{fam['name']}: qverify's default path breaks too")
for name in wanted:
    if name not in [f["name"] for f in doc["families"]]:
        problems.append(f"{name}: not in the report")
for rep in cand["reproducers"]:
    for key in ("scene", "log"):
        if not os.path.isfile(os.path.join(out, rep[key])):
            problems.append(f"reproducer file {rep[key]} is missing")
print(f"{len(cand['reproducers'])} reproducers in {os.path.join(out, 'failures')}")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
