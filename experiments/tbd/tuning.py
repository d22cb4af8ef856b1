"""TBD-BP's own settings against its defaults, on the same frames: 10 000 particles per PO against
2000 (P1), and merging POs closer than 1 m (M1, M2; G2-merge, G3-merge: the letter's every-k
statement for the merged trackers)."""

from reports.core import markdown, stats, verdicts
from reports.core.study import Claim
from experiments.tbd.data import ms, paired_runs, pm_signed
from experiments.tbd.gospa import every_step, steps_words
from experiments.tbd.runs import BP, BP1, GOSPA, IEMB, MANY_PARTICLES, MERGE, MERGE_TRIALS, MERGED, PARTICLES


def check_particles(report, d):
    """Ours: 2000 particles per PO lose nothing measurable against 10 000 (the notes' [K] value):
    per L, the paired run-mean difference G(2000) - G(10 000) is not above 0 beyond error."""
    parts, words, rows = [], [], []
    for L, spec in BP.items():
        m, se, n = paired_runs(d, PARTICLES, spec, PARTICLES, MANY_PARTICLES[L])
        parts.append(verdicts.compare_bound(m, se, 0.0, holds_below=True))
        t_few, t_few_se = d.summary_mean(PARTICLES, spec, "step_time_us")
        t_many, t_many_se = d.summary_mean(PARTICLES, MANY_PARTICLES[L], "step_time_us")
        g_few = markdown.pm(*d.summary_mean(PARTICLES, spec, "gospa"))
        g_many = markdown.pm(*d.summary_mean(PARTICLES, MANY_PARTICLES[L], "gospa"))
        rows.append([f"L = {L}", g_few, g_many, pm_signed(m, se), ms(1e-6 * t_few, 1e-6 * t_few_se),
                     ms(1e-6 * t_many, 1e-6 * t_many_se), markdown.fixed(t_many / t_few, 1)])
        words.append(f"L = {L}: {pm_signed(m, se)}")
    report.value("particles.runs", d.summary_row(PARTICLES, BP1)["ok"])
    report.value("particles.table", markdown.table(
        ["TBD-BP", "GOSPA, P = 2000", "GOSPA, P = 10 000", "2000 − 10 000 (paired)", "runtime, 2000",
         "runtime, 10 000", "runtime ratio"], rows, "lrrrrrr"))
    report.claim(Claim(
        "P1", "2000 particles per PO lose nothing measurable against 10 000", "ours", "–",
        "GOSPA(2000) − GOSPA(10 000): " + ", ".join(words), verdicts.worst(parts),
        "per L, paired run means G(2000) − G(10 000) not above 0 beyond 2 SE (compare_bound); the worse"))


def merge_effect_claim(d, L):
    """M1 (L = 2: merging improves) or M2 (L = 1: merging worsens): paired run means of the merged
    tracker minus the unmerged one on runs 0-199 of tbd/gospa.ini, compare_direction."""
    m, se, _ = paired_runs(d, MERGE, MERGED[L], GOSPA, BP[L], below_trial=MERGE_TRIALS)
    improves = L == 2
    return Claim(
        "M1" if improves else "M2",
        f"merging POs closer than 1 m {'improves' if improves else 'worsens'} TBD-BP with L = {L}", "ours", "–",
        f"merged minus unmerged {pm_signed(m, se)}", verdicts.compare_direction(m, se, -1 if improves else +1),
        f"paired run means (merged − unmerged, runs 0–{MERGE_TRIALS - 1}) {'< 0' if improves else '> 0'} "
        f"beyond 2 SE (compare_direction)")


def merge_every_step_claim(d, L):
    """G2-merge / G3-merge: the letter's every-k statement for the merged tracker against TBD-IEMB
    on the same runs (steps-paired.csv of the merge run)."""
    verdict, counts, _ = every_step(d.step_diffs(MERGE, IEMB, MERGED[L]))
    m, se, _ = paired_runs(d, MERGE, MERGED[L], GOSPA, IEMB, below_trial=MERGE_TRIALS)
    return Claim(
        f"G{L + 1}-merge", f"[merge_distance = 1 m] TBD-BP L = {L} outperforms TBD-IEMB for all time steps k",
        "letter Fig. 2, quoted in supplement Sec. 2", "–",
        steps_words(counts, MERGED[L], IEMB) + f"; mean over k: merged minus TBD-IEMB {pm_signed(m, se)}", verdict,
        f"per k, paired difference over runs 0–{MERGE_TRIALS - 1} (TBD-IEMB minus merged TBD-BP) > 0 beyond "
        f"2 SE (compare_direction); the worst over k")


def first_runs_mean(d, spec, column="gospa"):
    """(mean, se) over runs 0-199 of tbd/gospa.ini of one tracker's run means."""
    return stats.mean_se(list((d.runs(GOSPA, spec, column, below_trial=MERGE_TRIALS) or {}).values()))[:2]


def check_merge(report, d):
    """Ours: merging POs closer than 1 m (tbd/merge.ini, the first 200 runs of tbd/gospa.ini,
    paired): its effect on each L (M1, M2) and the letter's every-k statement for the merged
    trackers (G2-merge, G3-merge)."""
    for claim in [merge_effect_claim(d, 2), merge_effect_claim(d, 1),
                  merge_every_step_claim(d, 1), merge_every_step_claim(d, 2)]:
        report.claim(claim)
    rows = []
    for L in (1, 2):
        merged = MERGED[L]
        m, se, _ = paired_runs(d, MERGE, merged, GOSPA, BP[L], below_trial=MERGE_TRIALS)
        vs_iemb = paired_runs(d, MERGE, merged, GOSPA, IEMB, below_trial=MERGE_TRIALS)
        parts = lambda mean: " / ".join(markdown.pm(*mean(c)) for c in ("false", "missed"))  # noqa: E731
        rows.append([f"L = {L}", markdown.pm(*first_runs_mean(d, BP[L])), markdown.pm(*d.summary_mean(MERGE, merged, "gospa")),
                     pm_signed(m, se), parts(lambda c: first_runs_mean(d, BP[L], c)),
                     parts(lambda c: d.summary_mean(MERGE, merged, c)), pm_signed(vs_iemb[0], vs_iemb[1])])
    report.value("merge.iemb", markdown.pm(*first_runs_mean(d, IEMB)))
    report.value("merge.table", markdown.table(
        ["TBD-BP", "GOSPA without merging", "GOSPA, merge_distance = 1 m", "merged − unmerged (paired)",
         "false / missed per step without", "false / missed per step merged", "merged − TBD-IEMB (paired)"],
        rows, "lrrrrrr"))
    report.value("merge.claims", report.claims_table(["M1", "M2", "G2-merge", "G3-merge"]))
