"""Reproduce a study: rerun its runs into a scratch folder and compare each with the committed
run (scripts/same_results.py: every CSV both hold, identical but for timings), or, with
--in-place, replace the committed data and then run the study's steps (digests, figures), the
manifest and its REPORT.

Usage (from the repository root, with a built ./build/dabench):
  /usr/bin/python3 -m reports.rerun STUDY [--only FOLDER ...] [--scratch DIR] [--record] [--dry-run]
  /usr/bin/python3 -m reports.rerun --all [--scratch DIR] [--dry-run]
  /usr/bin/python3 -m reports.rerun STUDY --in-place [--only FOLDER ...] [--steps] [--dry-run]

STUDY is a study of `python3 -m reports.render --list`, or `quickstart` (the quick start's run,
which the readme study holds). Before running, the predicted wall time of what is named is
printed (`dabench schedule` on the committed runs' unit times, on this machine's cores: a lower
estimate). --record: an identical rerun made from a clean commit is recorded in
results/verified.csv, so that the run's sources count as current again (reports/staleness.py).
--in-place with --only runs the study's steps only with --steps (a step may rewrite
another run's figure or a benchmark). Exit status: 0 every rerun identical (or done, in place),
1 a difference or a failed command, 2 bad arguments."""

import argparse
import csv
import io
import os
import shlex
import subprocess
import sys
import tempfile

from reports import render, staleness
from reports.core import data, markdown, study as study_core

ALIASES = {"quickstart": ("readme", ["results/quickstart"])}  # a name that is one run of a study
DABENCH = os.path.join(render.REPO, "build", "dabench")


def selected(args):
    """[(study, [runs])] that the arguments name, or an error message."""
    names = render.STUDY_NAMES if args.all else [args.name]
    out = []
    for name in names:
        only = args.only
        if name in ALIASES:
            name, only = ALIASES[name][0], (only or ALIASES[name][1])
        if name not in render.STUDY_NAMES:
            return None, (f"unknown study {name!r} (known: {', '.join(render.STUDY_NAMES)}, "
                          f"and {', '.join(ALIASES)})")
        s = render.load(name)
        runs = [r for r in s.runs if not only or r.folder in only]
        if only and not args.all:
            unknown = sorted(set(only) - {r.folder for r in s.runs})
            if unknown:
                return None, f"{unknown[0]}: not a run of {name} (its runs: {', '.join(r.folder for r in s.runs)})"
        out.append((s, runs))
    return out, None


def workers(command):
    """The workers a run command uses: --threads (else this machine's cores) × mpirun's -np."""
    words = shlex.split(command)
    threads = study_core.option(words, "--threads")
    ranks = study_core.option(words, "-np") if words and words[0] == "mpirun" else None
    return int(threads or os.cpu_count() or 1) * int(ranks or 1)


def predicted_seconds(run):
    """`dabench schedule` of a committed run at the command's worker count, or None (a benchmark,
    a run not committed, or no build)."""
    if study_core.is_bench(run) or not os.path.exists(os.path.join(render.REPO, run.folder, "meta.json")):
        return None
    args = [DABENCH, "schedule", run.folder, "--format", "csv", "--workers", str(workers(run.command))]
    trials = study_core.option(shlex.split(run.command), "--trials")
    if trials:
        args += ["--trials", trials]
    try:
        done = subprocess.run(args, cwd=render.REPO, capture_output=True, text=True, check=False)
    except OSError:
        return None
    if done.returncode != 0:
        return None
    return float(next(csv.DictReader(io.StringIO(done.stdout)))["wall_s"])


def print_prediction(chosen):
    total, unknown = 0.0, []
    for s, runs in chosen:
        for r in runs:
            seconds = predicted_seconds(r)
            if seconds is None:
                unknown.append(r.folder)
                continue
            total += seconds
            print(f"rerun: {r.folder}: predicted {markdown.duration(seconds)} on {workers(r.command)} workers")
    print(f"rerun: predicted in all {markdown.duration(total)} of wall time (algorithm time only: a lower estimate)"
          + (f"; not predicted: {', '.join(unknown)}" if unknown else ""), flush=True)


def scratch_command(run, scratch):
    """The run's command with its output in the scratch folder (--out replaced or added)."""
    words = shlex.split(run.command)
    out = os.path.join(scratch, run.folder)
    if "--out" in words:
        words[words.index("--out") + 1] = out
    else:
        words += ["--out", out]
    return shlex.join(words)


def shell(command, dry_run):
    print(f"rerun: {command}", flush=True)
    return dry_run or subprocess.run(command, shell=True, cwd=render.REPO).returncode == 0


def reproduce(chosen, scratch, dry_run, record):
    """Each run into scratch, then compared with the committed folder: (all identical, the folders
    recorded as reproduced)."""
    same, verified = True, []
    for s, runs in chosen:
        for r in runs:
            if study_core.is_bench(r):
                print(f"rerun: {r.folder}: a benchmark (timings only): not compared")
                continue
            if not shell(scratch_command(r, scratch), dry_run):
                print(f"rerun: failed: {r.folder}", file=sys.stderr)
                return False, verified
            if dry_run:
                continue
            done = subprocess.run([sys.executable, os.path.join(render.REPO, "scripts", "same_results.py"), "--shared",
                                   r.folder, os.path.join(scratch, r.folder)],
                                  cwd=render.REPO, capture_output=True, text=True, check=False)
            verdict = done.stdout.strip().splitlines()[-1] if done.stdout.strip() else done.stderr.strip()
            print(f"rerun: {r.folder}: {verdict}")
            if done.returncode != 0:
                print(done.stdout, end="")
                same = False
            elif record and record_verified(r.folder, os.path.join(scratch, r.folder)):
                verified.append(r.folder)
    return same, verified


def record_verified(folder, rerun_folder):
    """Record in results/verified.csv that folder was reproduced, if the rerun was made from a
    clean commit (its meta.json says so): its sources then count as current (reports/staleness.py)."""
    meta = data.read_meta(rerun_folder, "")
    if meta.get("source_modified") is not False or meta.get("git_commit", "").endswith("-dirty"):
        print(f"rerun: {folder}: not recorded as reproduced (the rerun was made from a modified tree)")
        return False
    staleness.record_verified(render.REPO, folder, meta.get("end_time", ""))
    return True


def in_place(chosen, args):
    for s, runs in chosen:
        steps = s.steps if (args.steps or not args.only) else []
        commands = [r.command for r in runs] + [step.command for step in steps]
        commands += ["/usr/bin/python3 -m reports.staleness", "/usr/bin/python3 -m reports.manifest",
                     f"/usr/bin/python3 -m reports.render {s.name}"]
        for command in commands:
            if not shell(command, args.dry_run):
                print(f"rerun: failed: {command}", file=sys.stderr)
                return False
    return True


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("name", metavar="STUDY", nargs="?")
    ap.add_argument("--all", action="store_true", help="every study")
    ap.add_argument("--only", nargs="+", metavar="FOLDER", help="only these run folders")
    ap.add_argument("--scratch", metavar="DIR", help="where the reruns go (default: a new temporary folder)")
    ap.add_argument("--in-place", action="store_true", help="replace the committed data, then steps, manifest, REPORT")
    ap.add_argument("--steps", action="store_true", help="with --in-place --only: run the study's steps too")
    ap.add_argument("--record", action="store_true",
                    help="record each identical rerun made from a clean commit in results/verified.csv, and rewrite "
                         "results/staleness.csv (its sources count as current again)")
    ap.add_argument("--dry-run", action="store_true", help="print the commands only")
    args = ap.parse_args(argv)
    if bool(args.name) == args.all:
        print("rerun: name one STUDY, or --all", file=sys.stderr)
        return 2
    chosen, error = selected(args)
    if error:
        print(f"rerun: {error}", file=sys.stderr)
        return 2
    print_prediction(chosen)
    if args.in_place:
        return 0 if in_place(chosen, args) else 1
    scratch = args.scratch or ("SCRATCH" if args.dry_run else tempfile.mkdtemp(prefix="dabench-rerun-"))
    print(f"rerun: reruns go to {scratch}; the committed data stay as they are", flush=True)
    same, verified = reproduce(chosen, scratch, args.dry_run, args.record)
    if verified:
        staleness.write(render.REPO)
        print(f"rerun: {len(verified)} runs recorded as reproduced in {staleness.VERIFIED}; {staleness.RECORD} "
              "rewritten: git add them, then /usr/bin/python3 -m reports.manifest and /usr/bin/python3 -m reports.render")
    return 0 if same else 1


if __name__ == "__main__":
    sys.exit(main())
