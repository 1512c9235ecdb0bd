#!/usr/bin/env python3
"""The power of `sst-eval check`'s distribution tests (issue 15): renders SETS fresh seed sets of
configs/ci.json, disjoint from the baseline's seeds and from each other, checks each clean and with
injected faults (a uniform bias of 1%, 3% and 10% of the indirect estimate, a rise of 10% and 50% in
variance; sst-eval check --inject-*), and prints per method and per group how many sets fail.
Faults are injected into every group at once: groups are tested independently, so a group's outcome
is the one it would have with the fault in its method alone. A method counts as caught in a set when
any of its groups fails.

Three tables, from the same renders. "Other seeds" checks each set against the baseline as it
is, whose same-seed records are of other seeds, so only the two-sample tests run. "Same seeds"
checks against a copy of the baseline whose same-seed records are the set's own clean renders: the
power against a fault that leaves the random numbers as they were (a wrong factor, a lost term),
which is what a CI check of the baseline's seeds sees of such a fault. "Other random numbers"
pairs each set with the next set's clean renders under its own seeds' names: a change that gives
every seed other random numbers (clean: the same-seed tests must keep their level; faults: their
power then).

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


def check(a, config_path, baseline, out, seed, flags):
    """Runs one sst-eval check and returns its distribution groups (those tested)."""
    cmd = [a.sst_eval, "check", config_path, "--baseline", baseline, "-o", out, "--resume", "-q",
           "--seed", str(seed)] + flags + a.extra
    subprocess.run(cmd, stdout=subprocess.DEVNULL, check=False)
    record = json.load(open(os.path.join(out, "check.json")))
    return [g for g in record["distribution"]["groups"] if g["status"] != "missing"]


def same_seed_baseline(a, records_out, seeds_out, dest):
    """A copy of the baseline whose same-seed records are the clean renders in `records_out`,
    named by the seeds of the clean renders in `seeds_out` (in order)."""
    os.makedirs(dest, exist_ok=True)
    for name in ("results.json", "statistics"):
        link = os.path.join(dest, name)
        if not os.path.lexists(link):
            os.symlink(os.path.abspath(os.path.join(a.baseline, name)), link)
    statistics = json.load(open(os.path.join(a.baseline, "check_statistics.json")))
    records = json.load(open(os.path.join(records_out, "clean_same_seeds.json")))
    names = json.load(open(os.path.join(seeds_out, "clean_same_seeds.json")))
    for g in statistics["groups"]:
        pairs = zip(records.get(g["group"], []), names.get(g["group"], []))
        g["same_seeds"] = [dict(r, seed=n["seed"]) for r, n in pairs]
    json.dump(statistics, open(os.path.join(dest, "check_statistics.json"), "w"))


class Tally:
    def __init__(self):
        self.caught = defaultdict(lambda: defaultdict(int))  # row name -> group or method -> sets failed
        self.tested = defaultdict(int)
        self.method_of = {}

    def add(self, row, groups):
        failed_methods = set()
        for g in groups:
            self.method_of[g["group"]] = g["method"]
            fails = g["status"] == "fails"
            self.caught[row][g["group"]] += fails
            if row == "clean":
                self.tested[g["group"]] += 1
            if fails:
                failed_methods.add(g["method"])
        for m in set(g["method"] for g in groups):
            self.caught[row]["method " + m] += m in failed_methods
        return not failed_methods

    def table(self, rows, sets):
        print("| | " + " | ".join(r + (" fails" if r.startswith("clean") else " caught") for r in rows) + " |")
        print("|---|" + "---|" * len(rows))
        for m in sorted(set(self.method_of.values())):
            print("| method %s | " % m + " | ".join("%d of %d" % (self.caught[r]["method " + m], sets) for r in rows) + " |")
        for g in sorted(self.method_of):
            print("| %s | " % g + " | ".join("%d of %d" % (self.caught[r][g], self.tested[g]) for r in rows) + " |")


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

    tallies = {"other seeds": Tally(), "same seeds": Tally(), "other random numbers": Tally()}
    clean_sets = defaultdict(int)
    outs = [os.path.join(a.out, "set-%d" % k) for k in range(a.sets)]
    seed_of = [a.first_seed + seeds * k for k in range(a.sets)]
    for k in range(a.sets):  # renders each set and writes its same-seed records
        groups = check(a, config_path, a.baseline, outs[k], seed_of[k], [])
        clean_sets["other seeds"] += tallies["other seeds"].add("clean", groups)
        # Every check rewrites same_seeds.json, with its faults.
        os.replace(os.path.join(outs[k], "same_seeds.json"), os.path.join(outs[k], "clean_same_seeds.json"))
        print("set %d of %d rendered" % (k + 1, a.sets), file=sys.stderr)
    for k in range(a.sets):
        baselines = {"same seeds": os.path.join(a.out, "set-%d-same" % k),
                     "other random numbers": os.path.join(a.out, "set-%d-other" % k)}
        same_seed_baseline(a, outs[k], outs[k], baselines["same seeds"])
        same_seed_baseline(a, outs[(k + 1) % a.sets], outs[k], baselines["other random numbers"])
        for kind, baseline in baselines.items():
            clean_sets[kind] += tallies[kind].add("clean", check(a, config_path, baseline, outs[k], seed_of[k], []))
        for name, flags in FAULTS:
            tallies["other seeds"].add(name, check(a, config_path, a.baseline, outs[k], seed_of[k], flags))
            for kind, baseline in baselines.items():
                tallies[kind].add(name, check(a, config_path, baseline, outs[k], seed_of[k], flags))
        print("set %d of %d checked" % (k + 1, a.sets), file=sys.stderr)

    rows = ["clean"] + [n for n, _ in FAULTS]
    for kind, tally in tallies.items():
        print("## %s\n" % kind.capitalize())
        print("Clean: %d of %d sets pass in every group.\n" % (clean_sets[kind], a.sets))
        tally.table(rows, a.sets)
        print()


if __name__ == "__main__":
    main()
