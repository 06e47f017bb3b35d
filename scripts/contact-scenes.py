#!/usr/bin/env python3
"""How the contact solve did on whole scenes: runs `weft simulate` on each scene named, one
thread, and prints a Markdown table of what its summary.json says (converged steps, steps split
by adaptive time stepping and the finest piece, the deepest node inside an obstacle's skin and its
step) with the CPU seconds the run took (user + system of the weft process).

  python3 scripts/contact-scenes.py [--weft build/app/weft] [--steps N] [--set KEY=VALUE ...]
                                    SCENE.json ...

docs/benchmarks.md's tables of converged contact scenes come from it. Standard library only.
Exit status 2 for a scene that does not exist, or a run that fails (its stderr is shown).
"""

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile


def child_cpu_seconds():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("scenes", nargs="+", metavar="SCENE.json")
    parser.add_argument("--weft", default=os.path.join("build", "app", "weft"))
    parser.add_argument("--steps", type=int, help="simulate only the first N steps")
    parser.add_argument("--set", action="append", default=[], metavar="KEY=VALUE",
                        help="passed on to weft simulate (repeatable)")
    args = parser.parse_args()
    for scene in args.scenes:
        if not os.path.isfile(scene):
            print(f"error: {scene}: no such scene file", file=sys.stderr)
            return 2
    rows = []
    with tempfile.TemporaryDirectory() as work:
        for i, scene in enumerate(args.scenes):
            out = os.path.join(work, str(i))
            command = [args.weft, "simulate", scene, "--threads", "1", "--quiet", "--out", out]
            if args.steps:
                command += ["--steps", str(args.steps)]
            for override in args.set:
                command += ["--set", override]
            before = child_cpu_seconds()
            run = subprocess.run(command, capture_output=True, text=True,
                                 env=dict(os.environ, OMP_NUM_THREADS="1"))
            cpu = child_cpu_seconds() - before
            if run.returncode != 0:
                print(f"error: {scene}: weft simulate exited {run.returncode}:\n{run.stderr}",
                      file=sys.stderr)
                return 2
            with open(os.path.join(out, "summary.json")) as f:
                summary = json.load(f)
            pd, contacts = summary["pd"], summary.get("contacts", {})
            steps = summary["steps"]
            split = pd.get("split_steps", 0)
            finest = f" (dt/{2 ** pd.get('deepest_halvings', 0)})" if split else ""
            depth = contacts.get("max_depth", 0.0)
            deepest = f"{1e3 * depth:.3f} mm (step {contacts['max_depth_step']})" if depth > 0 else "0"
            name = os.path.splitext(os.path.basename(scene))[0]
            rows.append(f"| {name} | {steps} | {pd['converged_steps']}/{steps} | {split}{finest} "
                        f"| {pd.get('worst_unconverged_residual', 0.0):.3g} | {deepest} | {cpu:.1f} |")
    print("| scene | steps | converged | split steps (finest) | worst unconverged residual "
          "| deepest node | CPU s |")
    print("|---|---:|---:|---:|---:|---:|---:|")
    print("\n".join(rows))
    return 0


if __name__ == "__main__":
    sys.exit(main())
