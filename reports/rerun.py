#!/usr/bin/python3
"""Rerun a study: each of its runs (the commands its render.REPORT lists, from the repository root),
then its steps (digests, figures), then render its render.REPORT. Run it from a clean commit (the
provenance check refuses runs made from a modified tree) with a built ./build/dabench.

Usage: /usr/bin/python3 -m reports.rerun STUDY [--only FOLDER ...] [--steps-only] [--dry-run]"""

import argparse
import subprocess
import sys

from reports import render


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("name", metavar="STUDY")
    ap.add_argument("--only", nargs="+", metavar="FOLDER", help="rerun only these run folders")
    ap.add_argument("--steps-only", action="store_true", help="no runs: digests, figures and the render.REPORT")
    ap.add_argument("--dry-run", action="store_true", help="print the commands only")
    args = ap.parse_args(argv)
    known = {n: render.load(n) for n in render.STUDY_NAMES if n == args.name}
    if args.name not in known:
        print(f"rerun.py: unknown study {args.name!r} (known: {', '.join(render.STUDY_NAMES)})", file=sys.stderr)
        return 2
    s = known[args.name]
    runs = [] if args.steps_only else [r for r in s.runs if not args.only or r.folder in args.only]
    commands = [r.command for r in runs] + [step.command for step in s.steps]
    commands.append("/usr/bin/python3 -m reports.manifest")  # the rerun's files, listed for --check
    commands.append(f"/usr/bin/python3 -m reports.render {s.name}")
    for command in commands:
        print(f"rerun.py: {command}", flush=True)
        if not args.dry_run and subprocess.run(command, shell=True, cwd=render.REPO).returncode != 0:
            print(f"rerun.py: failed: {command}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
