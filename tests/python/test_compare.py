"""`dabench compare`: the paired statistics against Debian's scipy on the same pairs (exact and
normal Wilcoxon, ties, zero differences, the t interval), Holm's adjustment, and the refusal of
runs that are not of the same plan."""
import csv
import io
import json
import subprocess

import numpy as np
import pytest
from scipy import special, stats

HEADER = "point,spacing,trial,seed,algorithm,status,max_error,time_us\n"


def write_run(folder, pairs, fingerprint="f00d", seed=7):
    """A run folder whose trials.csv holds, per point, algorithms a and b with the given values."""
    folder.mkdir()
    rows = [HEADER]
    for point, (a, b) in enumerate(pairs):
        for trial, (x, y) in enumerate(zip(a, b)):
            rows.append(f"{point},{point / 2},{trial},{seed},a,ok,{x!r},1\n")
            rows.append(f"{point},{point / 2},{trial},{seed},\"b:k=1,m=2\",ok,{y!r},2\n")
    (folder / "trials.csv").write_text("".join(rows))
    (folder / "meta.json").write_text(json.dumps({"scenario": "grid", "fingerprint": fingerprint, "seed": seed}))
    return folder


def compare(program, *args):
    done = subprocess.run([program, "compare", *map(str, args), "--format", "csv"], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return list(csv.DictReader(io.StringIO(done.stdout)))


def test_statistics_equal_scipy(tmp_path, dabench_program):
    rng = np.random.default_rng(5)
    untied = (rng.normal(0.3, 1, 20), rng.normal(0, 1, 20))             # exact distribution
    x = np.round(rng.normal(0.2, 1, 40), 1)
    tied = (x, np.round(x + rng.choice([-0.2, -0.1, 0.0, 0.1, 0.3], 40), 1))  # ties and zero differences
    large = (rng.normal(0.1, 1, 120), rng.normal(0, 1, 120))            # normal approximation
    run = write_run(tmp_path / "run", [untied, tied, large])
    rows = compare(dabench_program, run, "--algorithms", "a,b:k=1,m=2", "--metric", "max_error")
    assert [r["point"] for r in rows] == ["0", "1", "2"]
    methods = ["exact", "approx", "approx"]
    p = []
    for row, (a, b), method in zip(rows, [untied, tied, large], methods):
        d = a - b
        assert int(row["n"]) == len(d)
        expected = stats.wilcoxon(a, b, zero_method="wilcox", correction=False, method=method).pvalue
        assert float(row["wilcoxon_p"]) == pytest.approx(expected, rel=1e-10)
        # scipy 1.10's t.ppf(0.975, 39) is 4e-9 below the quantile (its t.cdf there is 0.9749999996,
        # by scipy's own betainc); dabench's (Boost.Math) gives 0.975 to 1e-16: hence rel=1e-7.
        low, high = stats.t.interval(0.95, len(d) - 1, loc=d.mean(), scale=stats.sem(d))
        assert float(row["mean_diff"]) == pytest.approx(d.mean(), rel=1e-12, abs=1e-15)
        assert float(row["ci_low"]) == pytest.approx(low, rel=1e-7)
        assert float(row["ci_high"]) == pytest.approx(high, rel=1e-7)
        half = float(row["ci_high"]) - d.mean()
        t_quantile = half / stats.sem(d)
        assert 1 - 0.5 * special.betainc((len(d) - 1) / 2, 0.5, (len(d) - 1) / (len(d) - 1 + t_quantile ** 2)) == \
            pytest.approx(0.975, abs=1e-12)
        assert float(row["a_better"]) == pytest.approx(np.mean(d < 0))
        assert float(row["ties"]) == pytest.approx(np.mean(d == 0))
        p.append(expected)
    assert np.mean(tied[0] - tied[1] == 0) > 0  # the tied point has zero differences indeed
    # Holm over the three points.
    order = np.argsort(p)
    holm, running = np.empty(3), 0.0
    for rank, k in enumerate(order):
        running = max(running, min(1.0, (3 - rank) * p[k]))
        holm[k] = running
    assert [float(r["holm_p"]) for r in rows] == pytest.approx(list(holm), rel=1e-10)


def test_two_runs_of_one_plan_and_refusals(tmp_path, dabench_program):
    rng = np.random.default_rng(6)
    a = rng.normal(0, 1, 15)
    first = write_run(tmp_path / "first", [(a, a + 1)])
    second = write_run(tmp_path / "second", [(a + 0.5, a + 1)])
    rows = compare(dabench_program, first, second, "--algorithms", "a", "--metric", "max_error")
    assert float(rows[0]["mean_diff"]) == pytest.approx(-0.5)
    assert float(rows[0]["a_better"]) == 1.0
    other = write_run(tmp_path / "other", [(a, a)], fingerprint="beef")
    broken = write_run(tmp_path / "broken", [(a, a)])
    text = (broken / "trials.csv").read_text().split("\n")
    (broken / "trials.csv").write_text("\n".join([text[0], "x" + text[1][1:]] + text[2:]))
    for args, message in [
        ((first, other, "--algorithms", "a"), "are not runs of the same plan (their fingerprint differ)"),
        ((first, "--algorithms", "a"), "one run compares two algorithms"),
        ((first, "--algorithms", "a,zz"), "no rows of algorithm 'zz'"),
        ((first, "--algorithms", "a,b:k=1,m=2", "--metric", "nope"), "no metric column 'nope'"),
        ((tmp_path / "none", "--algorithms", "a,b"), "no trials.csv"),
        ((broken, "--algorithms", "a,b:k=1,m=2"), "'x' is not a point or trial index"),
    ]:
        done = subprocess.run([dabench_program, "compare", *map(str, args)], capture_output=True, text=True)
        assert done.returncode == 2 and message in done.stderr and done.stderr.count("\n") == 1, done.stderr
