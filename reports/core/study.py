"""A study: its runs (the commands that made the committed data), the steps that turn runs into
figures and digests, and its checks, which fill the study's template.

A study module defines STUDY = Study(...) with a `checks(report)` function; render.py calls it
with a Report, which collects named values, tables and claims for the template."""

import dataclasses
import json
import os
import re
import shlex
import subprocess
from collections import Counter

from . import data, markdown, verdicts


@dataclasses.dataclass
class Run:
    """One committed run: the folder it wrote and the command that wrote it (from the repository
    root). rerun.py runs the command; the provenance check compares it with meta.json. A run of
    `dabench_bench` names its JSON file (`--benchmark_out`) instead of a folder; its provenance is
    the JSON's context (git_commit, source_modified, command_line: bench/bench_main.cpp)."""
    folder: str
    command: str
    note: str = ""  # what a reader should expect: its length, what it is for
    # A measurement that needs a quiet machine or hours (kernel benchmarks, Algorithm 2's cost):
    # while it is not recorded, its row says so and its checks say "not run"; once recorded, its
    # provenance is checked like any other run's.
    optional: bool = False


@dataclasses.dataclass
class Step:
    """A command run after the runs (a figure, a digest of a large file): rerun.py runs it."""
    command: str
    note: str = ""


@dataclasses.dataclass
class Claim:
    """A statement checked against the data.

    statement: the statement in words (the paper's, quoted or closely paraphrased, or ours);
    source: where the paper makes it (e.g. "Table IV", "Sec. V-B"), or "ours";
    paper / ours: the numbers on both sides as printed (text; "–" where there is none);
    verdict: one of verdicts.VERDICTS; rule: how the verdict was decided, in one line;
    details: the parts behind the verdict, listed under the rules (optional)."""
    id: str
    statement: str
    source: str
    paper: str
    ours: str
    verdict: str
    rule: str
    details: list = dataclasses.field(default_factory=list)


@dataclasses.dataclass
class Study:
    name: str  # e.g. "jdtvb"
    report: str  # the file rendered, e.g. "results/jdtvb/REPORT.md"
    template: str  # e.g. "experiments/jdtvb/template.md"
    runs: list
    steps: list
    checks: object  # function(Report) -> None
    digest: object = None  # function(root) -> [files written]: digests of large per-trial files
    lint: bool = True  # lint the template's prose for numbers (every study's, the README's and its pages')
    pages: tuple = ()  # more (template, file) pairs rendered from the same checks (the README's docs pages)
    needs: tuple = ()  # studies whose values the checks read (report.studies[name]): the README's headlines


class Report:
    """What a study's checks produce for its template: values by name, and the claims."""

    def __init__(self, study, root):
        self.study, self.root = study, root
        self.values = {}
        self.claims = []
        self.studies = {}  # the Reports of the studies this one needs (Study.needs), by name

    def value(self, name, text):
        if name in self.values:
            raise ValueError(f"{self.study.name}: value '{name}' set twice")
        self.values[name] = text
        return text

    def claim(self, claim):
        """Register a claim; its parts become values claim.ID.{verdict,paper,ours,statement}."""
        if claim.verdict not in verdicts.VERDICTS:
            raise ValueError(f"{claim.id}: unknown verdict {claim.verdict!r}")
        self.claims.append(claim)
        for part in ("verdict", "paper", "ours", "statement"):
            self.value(f"claim.{claim.id}.{part}", getattr(claim, part))
        return claim

    def claims_table(self, ids, statement_header="statement"):
        """The claims with these ids as a table: id, statement (source), paper, ours, verdict."""
        by_id = {c.id: c for c in self.claims}
        rows = []
        for i in ids:
            c = by_id[i]
            rows.append([c.id, f"{c.statement} ({c.source})" if c.source != "ours" else c.statement,
                         c.paper, c.ours, f"**{c.verdict}**"])
        return markdown.table(["#", statement_header, "paper", "ours", "verdict"], rows)

    def rules_list(self, ids):
        """Each claim's rule, and its details as sub-items."""
        by_id = {c.id: c for c in self.claims}
        lines = []
        for i in ids:
            lines.append(f"- **{i}**: {by_id[i].rule}")
            lines += [f"  - {d}" for d in by_id[i].details]
        return "\n".join(lines)

    def verdict_counts(self, ids=None):
        chosen = [c for c in self.claims if ids is None or c.id in ids]
        counts = Counter(c.verdict for c in chosen)
        return ", ".join(f"{counts[v]} {v}" for v in verdicts.VERDICTS if counts[v])

    def headline(self, what, ids=None):
        """The value "headline": the verdict counts of the claims a study leads with (ids; all by
        default), as the README's list of studies shows them: "N <what>: counts"."""
        n = len([c for c in self.claims if ids is None or c.id in ids])
        self.value("headline", f"{n} {what}: {self.verdict_counts(ids)}")


# ----------------------------------------------------------------------------- provenance

COMMENT_LINE = re.compile(r"^\s*[#;]")
MOVED = "experiments/moved.csv"  # experiment files that moved after a committed run recorded them


def moved_paths(root):
    """{old path: new path} of MOVED under root: a run made before a move names the old path in
    its meta.json (command_line, experiment_path and any file the experiment reads)."""
    if not os.path.exists(os.path.join(root, MOVED)):
        return {}
    return {r["old_path"]: r["new_path"] for r in data.read_rows(root, MOVED)}


def with_moves(text, moves):
    """text with every moved path, as a whole word, replaced by its new path."""
    for old, new in moves.items():
        text = re.sub(r"(?<![\w./-])" + re.escape(old) + r"(?![\w./-])", new, text)
    return text


def experiment_body(text):
    """An experiment file without comments and blank lines: what decides the run."""
    return [line.rstrip() for line in text.splitlines() if line.strip() and not COMMENT_LINE.match(line)]


def command_words(command):
    """The program's part of a command line as words: a launcher before it (`mpirun -np 2`,
    `taskset -c 0`) dropped, quotes resolved as the shell does, and `--resume` read as `--force`
    (a resumed run finishes the same trials with the same seeds: the files are bit-identical)."""
    words = shlex.split(command)
    for i, w in enumerate(words):
        if os.path.basename(w) in ("dabench", "dabench_bench"):
            words = words[i:]
            break
    return ["--force" if w == "--resume" else w for w in words]


def is_bench(run):
    return run.folder.endswith(".json")


def read_bench_context(root, relpath):
    """The context of a committed Google Benchmark JSON (its provenance), or a DataError."""
    try:
        with open(os.path.join(root, relpath), encoding="utf-8") as f:
            return json.load(f).get("context", {})
    except OSError as error:
        raise data.DataError(f"{relpath}: {error.strerror}") from None
    except json.JSONDecodeError as error:
        raise data.DataError(f"{relpath}: not JSON ({error.msg})") from None


def bench_provenance(root, run):
    """(context, problems) of a committed benchmark JSON, as provenance() for a run folder."""
    try:
        context = read_bench_context(root, run.folder)
    except data.DataError as error:
        return None, [str(error)]
    problems = []
    if context.get("source_modified") != "false":
        problems.append(f"{run.folder}: made from a modified or unknown source tree (git_commit "
                        f"{context.get('git_commit')}, source_modified {context.get('source_modified')}); "
                        "rerun it from a clean commit")
    if command_words(context.get("command_line", "")) != command_words(run.command):
        problems.append(f"{run.folder}: made by `{context.get('command_line')}`, the study lists `{run.command}`")
    problems += commit_problems(root, run.folder, context.get("git_commit", ""))
    return context, problems


def provenance(root, run):
    """(meta, problems) of a committed run: problems lists why the run cannot be traced to the
    committed code and experiment (modified source, another command, an edited experiment)."""
    if run.optional and not os.path.exists(os.path.join(root, run.folder)):
        return None, []
    if is_bench(run):
        return bench_provenance(root, run)
    problems = []
    try:
        meta = data.read_meta(root, run.folder)
    except data.DataError as error:
        return None, [str(error)]
    commit = meta.get("git_commit", "")
    modified = meta.get("source_modified")
    if commit.endswith("-dirty") or modified is not False:
        problems.append(f"{run.folder}: made from a modified source tree (git_commit {commit}, "
                        f"source_modified {modified}); rerun it from a clean commit")
    if meta.get("status") != "complete":
        problems.append(f"{run.folder}: run not complete ({meta.get('status')})")
    problems += commit_problems(root, run.folder, commit)
    moves = moved_paths(root)
    if command_words(with_moves(meta.get("command_line", ""), moves)) != command_words(run.command):
        problems.append(f"{run.folder}: made by `{meta.get('command_line')}`, the study lists `{run.command}`")
    experiment = moves.get(meta.get("experiment_path", ""), meta.get("experiment_path", ""))
    ini = os.path.join(root, experiment)
    if os.path.exists(ini):
        with open(ini, encoding="utf-8") as f:
            text = f.read()
        if experiment_body(text) != experiment_body(with_moves(meta.get("experiment", ""), moves)):
            problems.append(f"{run.folder}: {experiment} has changed since the run; rerun it")
        problems += settings_problems(run.folder, meta, run.command, text)
    else:
        problems.append(f"{run.folder}: its experiment {experiment} is not in the tree")
    return meta, problems


_HISTORY = {}  # root -> whether its whole git history is at hand


def git(root, *args):
    """The completed `git -C root ARGS`, or None where git cannot run there."""
    try:
        return subprocess.run(["git", "-C", root, *args], capture_output=True, text=True, check=False)
    except OSError:
        return None


def history_at_hand(root):
    """True where root is a git work tree with its whole history (not a shallow clone)."""
    if root not in _HISTORY:
        done = git(root, "rev-parse", "--is-shallow-repository")
        _HISTORY[root] = done is not None and done.returncode == 0 and done.stdout.strip() == "false"
    return _HISTORY[root]


def commit_problems(root, folder, commit):
    """Why a run's recorded commit cannot be traced in the repository under root: it is not there,
    or HEAD does not descend from it. Nothing where root is not a git work tree (a copy of the
    data) or is a shallow clone (its history is cut: a missing commit proves nothing)."""
    commit = commit.removesuffix("-dirty")
    if not history_at_hand(root):
        return []
    exists = git(root, "cat-file", "-e", f"{commit}^{{commit}}")
    if not re.fullmatch(r"[0-9a-f]{40}", commit) or exists.returncode != 0:
        return [f"{folder}: its git_commit {commit or '(none)'} is not a commit of this repository"]
    if git(root, "merge-base", "--is-ancestor", commit, "HEAD").returncode != 0:
        return [f"{folder}: its git_commit {commit} is not an ancestor of HEAD (made on another branch?)"]
    return []


def option(words, name):
    """The value of `--name VALUE` or `--name=VALUE` among a command's words, else None."""
    for i, w in enumerate(words):
        if w == name and i + 1 < len(words):
            return words[i + 1]
        if w.startswith(name + "="):
            return w.split("=", 1)[1]
    return None


def ini_value(text, key):
    """The value of a top-level `key = value` of an experiment file (before its first section;
    a trailing comment dropped), else None."""
    for line in text.splitlines():
        if line.lstrip().startswith("["):
            break
        name, sep, value = line.partition("=")
        if sep and name.strip() == key and not COMMENT_LINE.match(line):
            return re.split(r"\s[#;]", value, maxsplit=1)[0].strip()
    return None


def settings_problems(folder, meta, command, experiment_text):
    """Why a run's recorded seed and trial count are not what its command and experiment file
    ask for (a `--seed`/`--trials` of the command wins over the file's)."""
    words = command_words(command)
    out = []
    for recorded, flag, key in (("seed", "--seed", "seed"), ("trials_per_point", "--trials", "trials")):
        wanted = option(words, flag) or ini_value(experiment_text, key)
        if wanted is None:
            continue
        try:
            same = float(wanted) == float(meta.get(recorded))
        except (TypeError, ValueError):
            same = False
        if not same:
            out.append(f"{folder}: meta.json's {recorded} is {meta.get(recorded)}, its command and experiment ask "
                       f"for {wanted}")
    return out


def short_command(command):
    return command.replace("./build/dabench_bench ", "dabench_bench ").replace("./build/dabench ", "dabench ")


def runs_table(root, runs):
    """Markdown table of the study's runs from their meta.json (or benchmark context), and the
    provenance problems."""
    from reports import staleness  # the record of which runs' sources changed (reports/staleness.py)
    record = staleness.read_record(root)
    rows, problems = [], []
    for run in runs:
        meta, found = provenance(root, run)
        problems += found
        if meta is None:
            state = "not recorded" if run.optional and not found else "missing"
            rows.append([f"`{run.folder}`", f"`{short_command(run.command)}`", state, "", "", "", ""])
            continue
        sources = "–" if is_bench(run) else staleness.describe(record.get(run.folder))
        commit = meta.get("git_commit", "?")
        if is_bench(run):
            clean = meta.get("source_modified") == "false"
            size = f"{meta.get('num_cpus', '?')} CPUs, one benchmark at a time"
            finished, wall = (meta.get("date") or "")[:10], "–"
        else:
            clean = meta.get("source_modified") is False and not commit.endswith("-dirty")
            size = (f"{meta.get('items_total', '?')} items, {meta.get('threads', '?')} threads"
                    + (f" × {meta.get('processes')} processes" if meta.get("processes", 1) != 1 else ""))
            finished = (meta.get("end_time") or "")[:10]
            wall = markdown.duration(meta["wall_seconds"]) if meta.get("wall_seconds") is not None else "–"
            if meta.get("resumed"):
                wall += " (its last session: the run was resumed)"
        state = "clean" if clean else "**modified**"
        rows.append([f"`{run.folder}`", f"`{short_command(run.command)}`", size,
                     f"`{commit[:10]}` ({state})", finished, wall, sources])
    table = markdown.table(["folder", "command", "size", "commit", "finished", "wall time", "sources since"], rows)
    return table, problems
