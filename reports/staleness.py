"""Which committed runs are stale: a source file their numbers depend on has changed since the
commit that made them (or since a rerun last reproduced them).

A run's sources are the files of its algorithms and references (the file that defines each
registered name, `kName = "bp"`, and its .cpp), of its scenario, of its kind's execution
(harness/run/kinds/<kind>*.cpp) and of the summariser, each with everything it includes from this
repository (`#include "…"`, and each included header's .cpp), transitively. A source has changed
when its content, comments and whitespace aside, now differs from its content at the run's
`git_commit` (a file added since counts as changed); a run rerun by
`python3 -m reports.rerun` into a scratch folder and found identical (results/verified.csv) is
compared with the sources it was reproduced with instead. Content, not commit hashes, decides: the
answer does not change when the same tree is committed again.

The record results/staleness.csv (one row per run) is committed data: the REPORTs' runs tables
read it, so rendering needs neither git nor a build. `python3 -m reports.staleness` rewrites it;
`python3 -m reports.render --check` recomputes it where the history is at hand (not in a shallow
clone) and fails when it is not current, and `--check --strict` also fails on a stale run."""

import hashlib
import os
import re
import subprocess
import sys

from reports.core import data
from reports.core.study import git, history_at_hand

RECORD = "results/staleness.csv"
RECORD_HEADER = ["folder", "state", "changed", "examples", "since"]
VERIFIED = "results/verified.csv"  # written by reports.rerun: runs reproduced identically
VERIFIED_HEADER = ["folder", "sources", "commit", "date"]
INCLUDE = re.compile(r'^\s*#\s*include\s+"([^"]+)"', re.M)
ALWAYS = ["harness/core/summary.cpp", "harness/run/trial_draw.hpp"]


COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)


def code_id(content):
    """A hash of C++ source without its comments and whitespace: what compiles, not what explains."""
    text = COMMENT.sub(" ", content.decode("utf-8", errors="replace"))
    return hashlib.sha256(" ".join(text.split()).encode()).hexdigest()[:16]


def file_code_id(path):
    with open(path, "rb") as f:
        return code_id(f.read())


class Blobs:
    """code_id of git blobs, read in batches through one `git cat-file --batch`, cached."""

    def __init__(self, root):
        self.root, self.cache = root, {}

    def code_ids(self, blob_ids):
        missing = [b for b in dict.fromkeys(blob_ids) if b not in self.cache]
        if missing:
            done = subprocess.run(["git", "-C", self.root, "cat-file", "--batch"], input="\n".join(missing).encode() + b"\n",
                                  capture_output=True, check=True)
            out, pos = done.stdout, 0
            for blob in missing:
                end = out.index(b"\n", pos)
                header = out[pos:end].split()
                size = int(header[2])
                self.cache[blob] = code_id(out[end + 1:end + 1 + size])
                pos = end + 1 + size + 1
        return [self.cache[b] for b in blob_ids]


class Sources:
    """The repository's source files: which file defines each registered name, and includes."""

    def __init__(self, root):
        self.root = root
        self.defined_in = {}  # registered name -> file declaring its kName
        for top in ("algorithms", "scenarios"):
            for folder, _, names in os.walk(os.path.join(root, top)):
                for name in names:
                    if name.endswith(".hpp"):
                        path = os.path.relpath(os.path.join(folder, name), root)
                        with open(os.path.join(root, path), encoding="utf-8") as f:
                            for m in re.finditer(r'kName\s*=\s*"([^"]+)"', f.read()):
                                self.defined_in.setdefault(m.group(1), path)
        self._includes = {}

    def includes(self, path):
        if path not in self._includes:
            full = os.path.join(self.root, path)
            found = []
            if os.path.exists(full):
                with open(full, encoding="utf-8", errors="replace") as f:
                    found = [p for p in INCLUDE.findall(f.read()) if os.path.exists(os.path.join(self.root, p))]
            self._includes[path] = found
        return self._includes[path]

    def closure(self, start):
        """start and everything it includes, with each header's .cpp, transitively."""
        seen, todo = set(), list(start)
        while todo:
            path = todo.pop()
            if path in seen or not os.path.exists(os.path.join(self.root, path)):
                continue
            seen.add(path)
            todo += self.includes(path)
            if path.endswith(".hpp"):
                todo.append(path[:-4] + ".cpp")
        return sorted(seen)

    def of_run(self, meta):
        """The source files a run's numbers depend on (see the module's docstring)."""
        names = [spec.split(":")[0] for spec in list(meta.get("algorithms", [])) + list(meta.get("references", []))]
        names.append(meta.get("scenario", ""))
        start = list(ALWAYS)
        kind = None
        for name in names:
            path = self.defined_in.get(name)
            if path is None:  # a name no header declares: its kind's whole folder, conservatively
                continue
            start.append(path)
            if path.startswith("scenarios/"):
                kind = path.split("/")[1]  # scenarios/<kind>/
        unknown = [n for n in names if n and n not in self.defined_in]
        if kind:
            start += [f"harness/run/kinds/{kind}.cpp", f"harness/run/kinds/{kind}_execution.cpp"]
            if unknown:
                folder = os.path.join(self.root, "algorithms", kind)
                start += [os.path.join("algorithms", kind, f) for f in sorted(os.listdir(folder))]
        return self.closure(start)


def blobs_at(root, commit, paths):
    """{path: blob id} of paths at a commit (a path absent there is absent here)."""
    done = git(root, "ls-tree", "-r", commit, "--", *paths)
    if done is None or done.returncode != 0:
        return None
    out = {}
    for line in done.stdout.splitlines():
        meta, path = line.split("\t", 1)
        out[path] = meta.split()[2]
    return out


def fingerprint(blobs):
    return hashlib.sha256("\n".join(f"{p} {b}" for p, b in sorted(blobs.items())).encode()).hexdigest()[:16]


def run_folders():
    """The committed run folders of every study (benchmarks aside), in the studies' order."""
    from reports import render  # the studies, imported only when the record is computed
    from reports.core.study import is_bench
    return [r.folder for s in render.studies() for r in s.runs if not is_bench(r)]


def verified_sources(root):
    """{folder: {sources fingerprint: date}} of the runs reproduced identically (VERIFIED)."""
    if not os.path.exists(os.path.join(root, VERIFIED)):
        return {}
    out = {}
    for r in data.read_rows(root, VERIFIED):
        out.setdefault(r["folder"], {})[r["sources"]] = r["date"]
    return out


def current_sources(root, sources, meta):
    """{path: code_id} of a run's sources as they are in the tree now."""
    return {p: file_code_id(os.path.join(root, p)) for p in sources.of_run(meta)}


def record_rows(root):
    """The record's rows, computed from the history (None where it is not at hand)."""
    if not history_at_hand(root):
        return None
    sources = Sources(root)
    verified = verified_sources(root)
    blobs = Blobs(root)
    rows = []
    for folder in run_folders():
        if not os.path.exists(os.path.join(root, folder, "meta.json")):
            continue
        meta = data.read_meta(root, folder)
        now = current_sources(root, sources, meta)
        date = verified.get(folder, {}).get(fingerprint(now))
        if date:
            rows.append([folder, "reproduced", "0", "", date])
            continue
        commit = meta.get("git_commit", "")
        then = blobs_at(root, commit, sorted(now))
        if then is None:
            rows.append([folder, "unknown", "", "", commit[:7]])
            continue
        then = dict(zip(then, blobs.code_ids(list(then.values()))))
        changed = [p for p in sorted(now) if then.get(p) != now[p]]
        rows.append([folder, "stale" if changed else "current", str(len(changed)),
                     " ".join(changed[:3]), commit[:7]])
    return rows


def read_record(root):
    """{folder: row dict} of the committed record ({} without one)."""
    if not os.path.exists(os.path.join(root, RECORD)):
        return {}
    return {r["folder"]: r for r in data.read_rows(root, RECORD)}


def problems(root, strict=False):
    """Why the committed record is not what the history gives now (nothing where the history is
    not at hand); with strict, each stale run too."""
    rows = record_rows(root)
    if rows is None:
        return []
    committed = read_record(root)
    fresh = {r[0]: dict(zip(RECORD_HEADER, r)) for r in rows}
    out = []
    if committed != fresh:
        changed = sorted(f for f in set(committed) | set(fresh) if committed.get(f) != fresh.get(f))
        out.append(f"{RECORD}: not what the sources give now ({', '.join(changed[:3])}"
                   f"{', …' if len(changed) > 3 else ''}): run /usr/bin/python3 -m reports.staleness, then "
                   "python3 -m reports.render")
    if strict:
        out += [f"{r['folder']}: stale: {r['changed']} of its source files changed since {r['since']} "
                f"({r['examples']}); python3 -m reports.rerun reproduces it" for r in fresh.values()
                if r["state"] == "stale"]
    return out


def describe(row):
    """A run's sources state as the REPORTs' runs tables show it."""
    if row is None:
        return "–"
    if row["state"] == "current":
        return "current"
    if row["state"] == "reproduced":
        return f"reproduced {row['since'][:10]}"
    if row["state"] == "stale":
        first = row["examples"].split()[0] if row["examples"] else ""
        return f"**stale**: {row['changed']} source files changed (`{first}`{', …' if int(row['changed']) > 1 else ''})"
    return "unknown"


def record_verified(root, folder, date):
    """Append to VERIFIED that folder was reproduced identically from the sources as they are."""
    meta = data.read_meta(root, folder)
    sources = current_sources(root, Sources(root), meta)
    head = git(root, "rev-parse", "HEAD")
    rows = [[r[c] for c in VERIFIED_HEADER] for r in data.read_rows(root, VERIFIED)] \
        if os.path.exists(os.path.join(root, VERIFIED)) else []
    rows.append([folder, fingerprint(sources), head.stdout.strip() if head else "", date])
    data.write_csv(os.path.join(root, VERIFIED), VERIFIED_HEADER, rows)


def write(root):
    rows = record_rows(root)
    if rows is None:
        raise ValueError(f"{root}: not a git work tree with its whole history")
    data.write_csv(os.path.join(root, RECORD), RECORD_HEADER, rows)
    return rows


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        rows = write(root)
    except ValueError as error:
        print(f"staleness: {error}", file=sys.stderr)
        return 2
    counts = {}
    for r in rows:
        counts[r[1]] = counts.get(r[1], 0) + 1
    print(f"{RECORD}: {len(rows)} runs: " + ", ".join(f"{n} {state}" for state, n in sorted(counts.items())))
    for r in rows:
        if r[1] == "stale":
            print(f"  {r[0]}: {r[2]} changed since {r[4]} ({r[3]})")
    return 0


if __name__ == "__main__":
    sys.exit(main())
