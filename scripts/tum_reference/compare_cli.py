#!/usr/bin/python3
"""Runs `dlslam eval` on every fixture in tests/fixtures/eval and prints how far
its JSON is from the reference results stored beside the fixtures (one row per
expected_*.json, then the maximum).

  scripts/tum_reference/compare_cli.py [--dlslam build/bin/dlslam]

Relative differences are taken over reference values >= 1e-6 only (a pair with
zero error has no meaningful relative difference).
"""
import argparse
import glob
import json
import os
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
KEYS = ["rmse", "mean", "median", "std", "min", "max"]


def numbers(result):
    """(name, value) of every statistic in an ATE or RPE result."""
    if "rotation_deg" in result:
        return [(f"{part}.{k}", result[part][k]) for part in ("translation", "rotation_deg")
                for k in KEYS]
    return [(k, result[k]) for k in KEYS]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--dlslam", default=os.path.join(ROOT, "build", "bin", "dlslam"))
    args = parser.parse_args(argv)
    worst_abs, worst_rel, rows = 0.0, 0.0, 0
    for path in sorted(glob.glob(os.path.join(ROOT, "tests", "fixtures", "eval", "*", "expected_*.json"))):
        doc = json.load(open(path))
        if doc["kind"] == "associate":
            continue
        case = os.path.dirname(path)
        p = doc["params"]
        cmd = [args.dlslam, "eval", doc["kind"], "--gt", os.path.join(case, "gt.txt"), "--est",
               os.path.join(case, "est.txt"), "--offset", repr(p["offset"]), "--scale", repr(p["scale"]),
               "--json"]
        if doc["kind"] == "ate":
            cmd += ["--max-diff", repr(p["max_diff"])]
        else:
            cmd += ["--delta", repr(p["delta"]), "--delta-unit", p["delta_unit"]]
        cpp = json.loads(subprocess.run(cmd, check=True, capture_output=True, text=True).stdout)
        ref = doc["result"]
        if cpp["pairs"] != ref["pairs"]:
            print(f"{path}: pairs {cpp['pairs']} != reference {ref['pairs']}")
            return 1
        ref_numbers = dict(numbers(ref))
        diffs = [(abs(v - ref_numbers[k]), k, ref_numbers[k]) for k, v in numbers(cpp)]
        max_abs = max(d for d, _, _ in diffs)
        max_rel = max((d / abs(r) for d, _, r in diffs if abs(r) >= 1e-6), default=0.0)
        worst_abs, worst_rel, rows = max(worst_abs, max_abs), max(worst_rel, max_rel), rows + 1
        name = os.path.relpath(path, os.path.join(ROOT, "tests", "fixtures", "eval"))
        print(f"| {name:<36} | {ref['pairs']:>5} | {max_abs:.1e} | {max_rel:.1e} |")
    print(f"max over {rows} runs: abs {worst_abs:.2e}, rel {worst_rel:.2e}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
