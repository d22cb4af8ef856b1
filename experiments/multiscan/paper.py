"""The multi-scan paper's statements (Sec. IV, Figs 3-5) beside ours: MSBP (P1-P4), JPDA-BP (P5-P7),
CV and CVS (P8-P14), the heuristic and single-sweep variants of Fig. 5 (P15, P16), and each
figure's table; the rules that decide them on paired trial resamples, and a percentage against the
paper's printed one."""

import math

import numpy as np

from reports.core import markdown, verdicts
from reports.core.study import Claim
from experiments.multiscan.targets import CALIBRATED_P80, TAIL, label

CVS = ["cvs:gamma=0.55", "cvs:gamma=0.75", "cvs:gamma=0.95"]  # increasing γ

# The paper's numbers as printed (Sec. IV): p80 is "20 % of targets are at a true location less
# likely than X of the belief". JPDA-BP's is the twelve-scan case; the paper does not say which
# figure CV's and CVS's are read from (compared with Fig. 4, the twelve-scan case, see P10).
PAPER_P80 = {"jpda-bp": "89%", "cv": "72%", "cvs:gamma=0.95": "84%", "cvs:gamma=0.75": "80%",
             "cvs:gamma=0.55": "77%"}
PAPER_P80_WHERE = "Sec. IV, p80 at twelve scans"
PAPER_MSBP_TAIL = "12%"  # Sec. IV and footnote 9 (Fig. 4): HPD >= 0.9999 "in 12 % of cases"


# ----------------------------------------------------------------------------- rules


def side_of_calibration(figure, method):
    """Which side of x = y the HPD CDF lies on, judged by p80 against 0.80 (compare_direction:
    beyond two bootstrap SE above is non-conservative, below conservative)."""
    verdict = verdicts.compare_direction(figure.value("p80", method) - CALIBRATED_P80, figure.se("p80", method), +1)
    return {verdicts.AGREES: "non-conservative", verdicts.DIFFERS: "conservative"}.get(verdict,
                                                                                        "calibrated within error")


def extreme(statistic, method, largest):
    """Rule: method's statistic is the largest (or smallest) of the figure's methods."""
    def rule(figure, values):
        v = values[statistic] if largest else -values[statistic]
        i = figure.index(method)
        return np.all(np.delete(v, i, axis=1) < v[:, i:i + 1], axis=1)
    return rule


def above_all(statistic, method, others):
    """Rule: method's statistic exceeds each of the others'."""
    def rule(figure, values):
        v = values[statistic]
        return np.all([v[:, figure.index(method)] > v[:, figure.index(o)] for o in others], axis=0)
    return rule


def monotone_in_gamma(figure, values):
    """Rule (CVS tunable): p80 rises and median entropy falls with γ = 0.55 → 0.75 → 0.95."""
    i = [figure.index(m) for m in CVS]
    p, e = values["p80"], values["entropy"]
    return (p[:, i[0]] < p[:, i[1]]) & (p[:, i[1]] < p[:, i[2]]) & (e[:, i[0]] > e[:, i[1]]) & (e[:, i[1]] > e[:, i[2]])


def closer_than_gap(pairs, reference):
    """Rule ("slight difference", Fig. 5): for each pair (a, b), |p80_a - p80_b| and |median
    entropy_a - median entropy_b| are below the reference pair's (CV against CVS(0.95): the change
    that the paper's tuning by γ makes)."""
    def rule(figure, values):
        ok = np.ones(values["p80"].shape[0], dtype=bool)
        for statistic in ("p80", "entropy"):
            v = values[statistic]
            gap = np.abs(v[:, figure.index(reference[0])] - v[:, figure.index(reference[1])])
            for a, b in pairs:
                ok &= np.abs(v[:, figure.index(a)] - v[:, figure.index(b)]) < gap
        return ok
    return rule


def resampled_verdict(figures, rule):
    """from_resamples on each figure, the worst over figures."""
    return verdicts.worst(verdicts.from_resamples(*f.holds(rule)) for f in figures)


def percent_text(printed):
    return printed.rstrip("%").strip()


def vs_paper_percent(ours, se, printed):
    """compare_value in the paper's printed unit (percent): the paper's standard error is ours
    (same 200-trial design), its rounding half a unit of its last printed digit."""
    verdict, _, _ = verdicts.compare_value(100 * ours, 100 * se, float(percent_text(printed)), 100 * se,
                                           percent_text(printed))
    return verdict



# ----------------------------------------------------------------------------- the paper's statements


def figure_table(figure):
    """Per method: p80 ± SE [95 % interval] and its side of x = y (and the likelihood-ranked p80
    where the run recorded it), KS distance, shares of HPD >= 0.99 and >= 0.9999, median entropy ± SE."""
    likelihood = figure.targets.has_likelihood()
    rows = []
    for m in figure.methods:
        row = [label(m), figure.pm_interval("p80", m), side_of_calibration(figure, m), markdown.fixed(figure.ks(m), 3),
               figure.pm_percent("ge_near", m), figure.pm_percent("ge_tail", m), figure.pm("entropy", m)]
        rows.append(row[:2] + [figure.pm_interval("p80_likelihood", m)] + row[2:] if likelihood else row)
    header = ["method", "p80 [95 % interval]", "side of x = y", "KS distance", "HPD ≥ 0.99", "HPD ≥ 0.9999",
              "median entropy (nats)"]
    if likelihood:
        header.insert(2, "p80, likelihood ranking")
    return markdown.table(header, rows, "lr" + ("r" if likelihood else "") + "lrrrr")


def next_smallest(figure, statistic, method):
    """"value (METHOD)" of the smallest statistic among the other methods."""
    value, other = min((figure.value(statistic, m), m) for m in figure.methods if m != method)
    return f"{markdown.sig(value)} ({label(other)})"


def per_figure(figures, text):
    return "; ".join(f"{f.label}: {text(f)}" for f in figures)


def claims_msbp(report, fig3, fig4):
    """Sec. IV: MSBP "significantly non-conservative", entropies "significantly smaller", and
    HPD >= 0.9999 in 12 % of cases (footnote 9: Fig. 4)."""
    both = [fig3, fig4]
    report.claim(Claim(
        "P1", "MSBP produces significantly non-conservative results (p80 above 0.80)", "Sec. IV, Figs 3–4",
        "qualitative", per_figure(both, lambda f: f.pm("p80", "msbp")),
        verdicts.worst(verdicts.compare_bound(f.value("p80", "msbp"), f.se("p80", "msbp"), CALIBRATED_P80, False)
                       for f in both),
        "compare_bound: p80 above 0.80 beyond two bootstrap SE in each figure"))
    rule = extreme("p80", "msbp", largest=True)
    report.claim(Claim(
        "P2", "MSBP is the most non-conservative method: the largest p80", "Sec. IV, Figs 3–4", "qualitative",
        per_figure(both, lambda f: f"{f.pm('p80', 'msbp')}, largest in {markdown.percent(f.holds(rule)[1], 0)} "
                   f"of resamples"),
        resampled_verdict(both, rule), "from_resamples on paired trial resamples: MSBP's p80 above every other method's"))
    rule = extreme("entropy", "msbp", largest=False)
    report.claim(Claim(
        "P3", "The entropies of the MSBP beliefs are significantly smaller than the other methods' (median)",
        "Sec. IV, Figs 3–4", "qualitative",
        per_figure(both, lambda f: f"{f.pm('entropy', 'msbp')} nats, next smallest " + next_smallest(f, "entropy", "msbp")),
        resampled_verdict(both, rule),
        "from_resamples on paired trial resamples: MSBP's median entropy below every other method's"))
    share, se = fig4.value("ge_tail", "msbp"), fig4.se("ge_tail", "msbp")
    value = vs_paper_percent(share, se, PAPER_MSBP_TAIL)
    direction = verdicts.compare_bound(share, se, 1 - TAIL, holds_below=False)
    report.claim(Claim(
        "P4", "MSBP: the true location is less likely than 99.99 % of the belief (HPD ≥ 0.9999) in 12 % of cases",
        "Sec. IV, footnote 9 (Fig. 4)", PAPER_MSBP_TAIL.replace("%", " %"),
        f"{fig4.pm_percent('ge_tail', 'msbp')} (HPD ≥ 0.99: {fig4.pm_percent('ge_near', 'msbp')})",
        verdicts.value_and_direction(value, direction),
        "compare_value in percent (our bootstrap SE; the paper's estimated as ours; its rounding), "
        "direction: the share above a calibrated belief's 0.01 % (compare_bound)"))


def claims_jpda(report, fig3, fig4):
    """Sec. IV: JPDA-BP non-conservative (CDF below x = y), more so with twelve scans, p80 = 0.89 there."""
    p3, se3 = fig3.value("p80", "jpda-bp"), fig3.se("p80", "jpda-bp")
    report.claim(Claim(
        "P5", "JPDA-BP produces non-conservative results: its HPD CDF lies below x = y (four scans)", "Sec. IV, Fig. 3",
        "qualitative", f"{fig3.pm_interval('p80', 'jpda-bp')}: {side_of_calibration(fig3, 'jpda-bp')}; "
        f"KS {fig3.ks('jpda-bp'):.3f}",
        verdicts.compare_bound(p3, se3, CALIBRATED_P80, holds_below=False),
        "compare_bound: p80 above 0.80 beyond two bootstrap SE"))
    p4, se4 = fig4.value("p80", "jpda-bp"), fig4.se("p80", "jpda-bp")
    report.claim(Claim(
        "P6", "JPDA-BP: the effect is more noticeable in the twelve-scan case", "Sec. IV, Figs 3–4", "qualitative",
        f"p80 {fig3.pm('p80', 'jpda-bp')} → {fig4.pm('p80', 'jpda-bp')}",
        verdicts.compare_direction(p4 - p3, verdicts.combined_se(se3, se4), +1),
        "compare_direction: Fig. 4's p80 above Fig. 3's (independent trials: SE combined)"))
    claim_p80_value(report, "P7", fig4, fig3, "jpda-bp", "JPDA-BP: 20 % of targets are at a true location less likely "
                    "than 89 % of the belief (twelve scans)")


def claim_p80_value(report, claim_id, figure, other, method, statement):
    """A p80 the paper prints, against figure's (Fig. 4's): compare_value (paper SE = ours), and the
    side of 0.80 that the paper's number implies (compare_bound) for value_and_direction; the other
    figure's p80 is shown beside it."""
    printed = PAPER_P80[method]
    paper = float(percent_text(printed)) / 100
    p, se = figure.value("p80", method), figure.se("p80", method)
    value = vs_paper_percent(p, se, printed)
    if math.isclose(paper, CALIBRATED_P80):
        verdict, direction_rule = value, ""
    else:
        direction = verdicts.compare_bound(p, se, CALIBRATED_P80, holds_below=paper < CALIBRATED_P80)
        verdict = verdicts.value_and_direction(value, direction)
        direction_rule = f"; direction: p80 {'below' if paper < CALIBRATED_P80 else 'above'} 0.80 (compare_bound)"
    report.claim(Claim(
        claim_id, statement, PAPER_P80_WHERE, f"{paper:.2f}",
        f"{figure.pm('p80', method)} ({figure.label}; {other.label}: {other.pm('p80', method)})", verdict,
        f"compare_value on {figure.label}'s p80 in percent (bootstrap SE; the paper's estimated as ours; "
        f"its rounding){direction_rule}"))


def claims_cv_cvs(report, fig3, fig4):
    """Sec. IV: CV conservative with higher entropy, p80 0.72; CVS 0.84 / 0.80 / 0.77, tunable by γ."""
    both = [fig3, fig4]
    report.claim(Claim(
        "P8", "CV produces conservative beliefs: its HPD CDF lies above x = y (p80 below 0.80)", "Sec. IV, Figs 3–4",
        "qualitative", per_figure(both, lambda f: f.pm("p80", "cv")),
        verdicts.worst(verdicts.compare_bound(f.value("p80", "cv"), f.se("p80", "cv"), CALIBRATED_P80, True)
                       for f in both),
        "compare_bound: p80 below 0.80 beyond two bootstrap SE in each figure"))
    rule = above_all("entropy", "cv", ["jpda-bp", "msbp"])
    report.claim(Claim(
        "P9", "The cost of CV's conservatism is beliefs with higher entropy (than the non-conservative JPDA-BP "
        "and MSBP; median)", "Sec. IV, Figs 3–4", "qualitative",
        per_figure(both, lambda f: f"{f.pm('entropy', 'cv')} against {markdown.sig(f.value('entropy', 'jpda-bp'))} "
                   f"and {markdown.sig(f.value('entropy', 'msbp'))}"),
        resampled_verdict(both, rule),
        "from_resamples on paired trial resamples: CV's median entropy above JPDA-BP's and MSBP's"))
    claim_p80_value(report, "P10", fig4, fig3, "cv", "CV: 20 % of targets are at a true location less likely than 72 % "
                    "of the belief")
    for claim_id, method in zip(("P11", "P12", "P13"), reversed(CVS)):
        gamma = method.split("=")[1]
        claim_p80_value(report, claim_id, fig4, fig3, method, f"CVS(γ = {gamma}): the equivalent value is "
                        f"{PAPER_P80[method].replace('%', ' %')}")
    report.claim(Claim(
        "P14", "CVS can be tuned between conservatism and entropy: with γ = 0.55 → 0.75 → 0.95 p80 rises and the "
        "median entropy falls", "Sec. IV, Figs 3–4", "qualitative",
        per_figure(both, lambda f: "p80 " + " → ".join(markdown.sig(f.value("p80", m)) for m in CVS)
                   + ", entropy " + " → ".join(markdown.sig(f.value("entropy", m)) for m in CVS)),
        resampled_verdict(both, monotone_in_gamma),
        "from_resamples on paired trial resamples: both orderings strict in γ"))


def claims_fig5(report, fig5):
    """Sec. IV, Fig. 5: the heuristic variants differ slightly from the guaranteed ones; almost the
    same performance with a single sweep. "Slight" is judged against the change that tuning γ
    makes (CV against CVS(0.95)), on paired resamples."""
    reference = ("cv", "cvs:gamma=0.95")

    def gaps(pairs):
        return "; ".join(f"{label(a)} − {label(b)}: p80 {markdown.signed(fig5.value('p80', a) - fig5.value('p80', b), 3)}, "
                         f"entropy {markdown.signed(fig5.value('entropy', a) - fig5.value('entropy', b), 2)}"
                         for a, b in pairs + [reference])
    heuristic = [("cvh", "cv"), ("cvsh:gamma=0.95", "cvs:gamma=0.95")]
    report.claim(Claim(
        "P15", "The heuristic methods CVH and CVSH(0.95) differ slightly from the guaranteed CV and CVS(0.95)",
        "Sec. IV, Fig. 5", "qualitative", gaps(heuristic),
        verdicts.from_resamples(*fig5.holds(closer_than_gap(heuristic, reference))),
        "from_resamples on paired trial resamples: each pair's |Δp80| and |Δ median entropy| below CV − CVS(0.95)'s"))
    single = [("cvsh1:gamma=0.95", "cvsh:gamma=0.95")]
    report.claim(Claim(
        "P16", "Almost the same performance is obtained with a single sweep: CVSH1(0.95) beside CVSH(0.95)",
        "Sec. IV, Fig. 5", "qualitative", gaps(single),
        verdicts.from_resamples(*fig5.holds(closer_than_gap(single, reference))),
        "from_resamples on paired trial resamples: |Δp80| and |Δ median entropy| below CV − CVS(0.95)'s"))


def figure_readings(report, figures):
    """Per figure: which methods lie on which side of x = y (the figure table's column)."""
    for name, figure in figures.items():
        sides = {}
        for m in figure.methods:
            sides.setdefault(side_of_calibration(figure, m), []).append(label(m))
        report.value(f"{name}.sides", "; ".join(f"{side}: {', '.join(sides[side])}" for side in
                                                ("non-conservative", "calibrated within error", "conservative")
                                                if side in sides))
        report.value(f"{name}.table", figure_table(figure))
        report.value(f"{name}.targets", str(len(figure.targets.trial)))
        report.value(f"{name}.trials", str(figure.trials()))
        if "jpda-bp" in figure.methods:
            side = side_of_calibration(figure, "jpda-bp")
            report.value(f"{name}.jpda_side", side)
            report.value(f"{name}.jpda_reading", {  # what that side says of the paper's "non-conservative"
                "non-conservative": "as the paper says", "conservative": "against the paper's statement beyond error"}.get(
                side, "so the data neither confirm the paper's statement nor contradict it beyond error"))
