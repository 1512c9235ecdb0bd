#!/usr/bin/env python3
"""The power of `sst-eval check`'s distribution tests (issue 15): renders SETS fresh seed sets of
configs/ci.json, disjoint from the baseline's seeds and from each other, checks each clean and with
injected faults (a uniform bias of 1%, 3% and 10% of the indirect estimate, a rise of 10% and 50% in
variance; sst-eval check --inject-*), and prints per method and per group how many sets fail.
Faults are injected into every group at once: groups are tested independently, so a group's outcome
is the one it would have with the fault in its method alone. A method counts as caught in a set when
any of its groups fails.

Usage: scripts/check_power.py [--sets 10] [--first-seed 2000] [--variant cpu] [--out DIR]
                              [--baseline results/ci] [--config configs/ci.json] [-- sst-eval args]
Extra arguments after -- go to every sst-eval check (e.g. --scene-dir ../shared/scenes).
"""
import argparse
import json
import os
import subprocess
import sys
from collections import defaultdict

FAULTS = [("bias 1%", ["--inject-bias", "0.01"]), ("bias 3%", ["--inject-bias", "0.03"]),
          ("bias 10%", ["--inject-bias", "0.1"]), ("variance +10%", ["--inject-variance", "0.1"]),
          ("variance +50%", ["--inject-variance", "0.5"])]


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--sets", type=int, default=10)
    ap.add_argument("--first-seed", type=int, default=2000)
    ap.add_argument("--variant", action="append", help="only this variant of the config (repeatable) [all]")
    ap.add_argument("--out", default=os.path.join(root, "build", "check-power"))
    ap.add_argument("--baseline", default=os.path.join(root, "results", "ci"))
    ap.add_argument("--config", default=os.path.join(root, "configs", "ci.json"))
    ap.add_argument("--sst-eval", default=os.path.join(root, "build", "sst-eval"))
    ap.add_argument("extra", nargs="*")
    a = ap.parse_args()
    config = json.load(open(a.config))
    if a.variant:
        config["variants"] = [v for v in config.get("variants", []) if v["name"] in a.variant]
        if not config["variants"]:
            sys.exit("error: no variant of %s is named %s" % (a.config, ", ".join(a.variant)))
    os.makedirs(a.out, exist_ok=True)
    config_path = os.path.join(a.out, "config.json")
    json.dump(config, open(config_path, "w"), indent=2)
    seeds = int(config.get("seeds", 1))

    clean = defaultdict(int)                       # group -> sets passed clean
    caught = defaultdict(lambda: defaultdict(int))  # fault -> group or method -> sets failed
    method_of, tested = {}, defaultdict(int)
    sets_all_clean = 0
    for k in range(a.sets):
        out = os.path.join(a.out, "set-%d" % k)
        for name, flags in [("clean", [])] + FAULTS:
            cmd = [a.sst_eval, "check", config_path, "--baseline", a.baseline, "-o", out, "--resume", "-q",
                   "--seed", str(a.first_seed + seeds * k)] + flags + a.extra
            subprocess.run(cmd, stdout=subprocess.DEVNULL, check=False)
            record = json.load(open(os.path.join(out, "check.json")))
            groups = [g for g in record["distribution"]["groups"] if g["status"] != "missing"]
            failed_methods = set()
            for g in groups:
                method_of[g["group"]] = g["method"]
                fails = g["status"] == "fails"
                if name == "clean":
                    tested[g["group"]] += 1
                    clean[g["group"]] += not fails
                else:
                    caught[name][g["group"]] += fails
                if fails:
                    failed_methods.add(g["method"])
            key = "clean" if name == "clean" else name
            for m in set(g["method"] for g in groups):
                caught[key]["method " + m] += m in failed_methods
            if name == "clean":
                sets_all_clean += not failed_methods
        print("set %d of %d done" % (k + 1, a.sets), file=sys.stderr)

    names = [n for n, _ in FAULTS]
    print("Clean: %d of %d sets pass in every group.\n" % (sets_all_clean, a.sets))
    print("| | clean passes | " + " | ".join(n + " caught" for n in names) + " |")
    print("|---|---|" + "---|" * len(names))
    for m in sorted(set(method_of.values())):
        print("| method %s | %d of %d | " % (m, a.sets - caught["clean"]["method " + m], a.sets) +
              " | ".join("%d of %d" % (caught[n]["method " + m], a.sets) for n in names) + " |")
    for g in sorted(method_of):
        print("| %s | %d of %d | " % (g, clean[g], tested[g]) +
              " | ".join("%d of %d" % (caught[n][g], tested[g]) for n in names) + " |")


if __name__ == "__main__":
    main()
