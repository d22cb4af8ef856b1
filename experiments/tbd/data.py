"""The TBD study's committed files as its checks read them (TbdData: summaries, meta.json and the
digests of digest.py), the paired differences of run means between two trackers, and how the
checks print their numbers (signed, as millisecond times, as ranges of steps k)."""

import math
import os

from reports.core import data, markdown, stats


class TbdData:
    """The committed files of the study under root: summaries and meta.json (required), and the
    digests (None when a digest is not there: the claims that need it are "not run")."""

    def __init__(self, root):
        self.root = root
        self._files = {}

    def _read(self, folder, name, required):
        key = (folder, name)
        if key not in self._files:
            if not required and not os.path.exists(data.path(self.root, folder, name)):
                self._files[key] = None
            else:
                self._files[key] = data.read_rows(self.root, f"{folder}/{name}")
        return self._files[key]

    def summary(self, folder):
        return self._read(folder, "summary.csv", True)

    def summary_row(self, folder, algorithm, point=0):
        return data.one(self.summary(folder), f"{folder}/summary.csv", point=point, algorithm=algorithm)

    def summary_mean(self, folder, algorithm, column, point=0):
        row = self.summary_row(folder, algorithm, point)
        return data.num(row, f"{column}_mean"), data.num(row, f"{column}_se")

    def point_of(self, folder, **where):
        """The sweep point whose scenario parameters are `where` (e.g. sigma_s2=0.5)."""
        rows = data.select(self.summary(folder), **where)
        if not rows:
            raise data.DataError(f"{folder}/summary.csv: no point with {where}")
        return int(rows[0]["point"])

    def runs(self, folder, algorithm, column="gospa", point=0, below_trial=None):
        """{trial: the run's value of column} from runs.csv, or None without the digest."""
        rows = self._read(folder, "runs.csv", False)
        if rows is None:
            return None
        out = {}
        for r in rows:
            if r["algorithm"] == algorithm and int(r["point"]) == point:
                trial = int(r["trial"])
                if below_trial is None or trial < below_trial:
                    value = data.num(r, column)
                    out[trial] = math.nan if value is None else value
        return out

    def step_means(self, folder, algorithm, point=0):
        """{k: steps-mean.csv row} of one tracker, or None without the digest."""
        rows = self._read(folder, "steps-mean.csv", False)
        if rows is None:
            return None
        return {int(r["k"]): r for r in rows if r["algorithm"] == algorithm and int(r["point"]) == point}

    def step_diffs(self, folder, a, b, point=0, first=None):
        """[(k, mean, se)] of GOSPA(a) - GOSPA(b) per step over paired runs (from steps-paired.csv,
        which holds each pair once, in either order; over the first MATCHED_RUNS runs from
        steps-paired-100.csv when first is given), or None without the digest."""
        name = "steps-paired.csv" if first is None else f"steps-paired-{first}.csv"
        rows = self._read(folder, name, False)
        if rows is None:
            return None
        out = []
        for r in rows:
            if int(r["point"]) != point:
                continue
            if (r["a"], r["b"]) in ((a, b), (b, a)):
                sign = 1.0 if r["a"] == a else -1.0
                out.append((int(r["k"]), sign * data.num(r, "gospa_diff_mean"), data.num(r, "gospa_diff_se")))
        if not out:
            raise data.DataError(f"{folder}/{name}: no pair {a} / {b} at point {point}")
        return sorted(out)

    def beliefs(self, folder):
        """The rows of a toy run's beliefs-summary.csv, or None without the digest."""
        return self._read(folder, "beliefs-summary.csv", False)

    def meta(self, folder):
        return data.read_meta(self.root, folder)


NAN3 = (math.nan, math.nan, 0)


def paired_runs(d, folder_a, a, folder_b, b, column="gospa", point=0, below_trial=None):
    """(mean, se, n) over paired runs of the run means a - b (NaNs without the digest)."""
    ra = d.runs(folder_a, a, column, point, below_trial)
    rb = d.runs(folder_b, b, column, point, below_trial)
    if ra is None or rb is None:
        return NAN3
    return stats.paired(ra, rb)


# ============================================================================= formatting


def pm_signed(mean, se):
    """"+m ± se" / "−m ± se" (markdown.pm with the sign always shown)."""
    text = markdown.pm(abs(mean), se) if math.isfinite(mean) else "–"
    return text if text == "–" else ("−" if mean < 0 else "+") + text


def k_ranges(ks):
    """[1, 2, 3, 7, 9, 10] -> "1–3, 7, 9–10"."""
    ks = sorted(ks)
    if not ks:
        return "none"
    parts, start, prev = [], ks[0], ks[0]
    for k in ks[1:] + [None]:
        if k is not None and k == prev + 1:
            prev = k
            continue
        parts.append(str(start) if start == prev else f"{start}–{prev}")
        if k is not None:
            start = prev = k
    return ", ".join(parts)


def ms(seconds, se=None):
    """Milliseconds, "m ± se ms" (three significant digits without an SE)."""
    return markdown.pm(1e3 * seconds, None if se is None else 1e3 * se) + " ms"
