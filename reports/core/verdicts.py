"""The verdict vocabulary and the rules that weigh a difference against its sampling error.

A check compares a statement (the paper's, or one of ours) with the committed data and says one of:

- AGREES: the statement holds beyond sampling error (a direction, ordering or bound that the
  data confirm at about 95 %: a z-score of at least Z, or at least 95 % of bootstrap resamples).
- WITHIN_ERROR ("agrees within error"): the data cannot tell the statement from ours — a
  value within Z combined standard errors (plus the paper's rounding) of the paper's, or a
  direction, ordering or bound that the data neither confirm nor contradict beyond error.
- DIRECTION_ONLY: a number that differs beyond error, while the direction it implies
  (an ordering, the sign of a trend) agrees.
- DIFFERS: the data contradict the statement beyond sampling error.
- NOT_RUN: the runs the statement needs are not in the committed data.

"differs" is said only beyond sampling error; otherwise "agrees within error".
"""

import math

AGREES = "agrees"
WITHIN_ERROR = "agrees within error"
DIRECTION_ONLY = "direction only"
DIFFERS = "differs"
NOT_RUN = "not run"
VERDICTS = (AGREES, WITHIN_ERROR, DIRECTION_ONLY, DIFFERS, NOT_RUN)

Z = 2.0  # standard errors that make a difference "beyond sampling error" (about 95 %, two-sided)
STABLE = 0.95  # share of bootstrap resamples that make a rule's outcome "beyond sampling error"


def half_unit(printed):
    """Half a unit in the last printed digit of a number as the paper prints it ("0.88" -> 0.005):
    the paper's rounding error, added to the error bound of a comparison with it."""
    text = str(printed).strip()
    if "e" in text.lower():
        mantissa, exponent = text.lower().split("e")
        return half_unit(mantissa) * 10 ** int(exponent)
    if "." not in text:
        return 0.5
    return 0.5 * 10 ** -len(text.split(".")[1])


def combined_se(*errors):
    """sqrt of the sum of squares of the standard errors that are known (None: not known)."""
    known = [e for e in errors if e is not None and math.isfinite(e)]
    return math.sqrt(sum(e * e for e in known)) if known else 0.0


def compare_value(ours, ours_se, paper, paper_se=None, paper_printed=None, z=Z):
    """A value against the paper's: WITHIN_ERROR when |ours - paper| <= z * combined SE plus the
    paper's rounding (half a unit of paper_printed's last digit, the printed text of the paper's
    number; str(paper) when not given), else DIFFERS. Returns (verdict, difference, bound)."""
    if ours is None or not math.isfinite(ours):
        return NOT_RUN, math.nan, math.nan
    rounding = half_unit(paper_printed if paper_printed is not None else repr(paper))
    bound = z * combined_se(ours_se, paper_se) + rounding
    diff = ours - paper
    return (WITHIN_ERROR if abs(diff) <= bound else DIFFERS), diff, bound


def compare_direction(difference, se, expected_sign, z=Z, slack=0.0):
    """A statement that a difference has a sign (A above B: expected_sign +1): AGREES when it
    does beyond z standard errors (plus slack, e.g. the paper's rounding), DIFFERS when the
    opposite sign does, else WITHIN_ERROR."""
    if difference is None or not math.isfinite(difference):
        return NOT_RUN
    signed = difference * expected_sign
    bound = z * (se if se is not None and math.isfinite(se) else 0.0) + slack
    if signed > bound:
        return AGREES
    if signed < -bound:
        return DIFFERS
    return WITHIN_ERROR


def compare_bound(value, se, bound, holds_below, z=Z, slack=0.0):
    """A statement that a value lies below (holds_below) or above a bound: AGREES beyond z standard
    errors (plus slack), DIFFERS beyond them on the wrong side, else WITHIN_ERROR."""
    return compare_direction(bound - value if holds_below else value - bound, se, +1, z, slack)


def value_and_direction(value_verdict, direction_verdict):
    """A number that differs from the paper's while the direction it implies agrees
    (or agrees within error) is DIRECTION_ONLY."""
    if value_verdict == DIFFERS and direction_verdict in (AGREES, WITHIN_ERROR):
        return DIRECTION_ONLY
    return value_verdict


def from_resamples(point_holds, share_holding):
    """A rule's outcome on the data (point_holds) and the share of bootstrap resamples in which it
    holds: AGREES / DIFFERS when at least STABLE of the resamples say the same as the data, else
    WITHIN_ERROR."""
    if point_holds and share_holding >= STABLE:
        return AGREES
    if not point_holds and 1.0 - share_holding >= STABLE:
        return DIFFERS
    return WITHIN_ERROR


def worst(verdicts):
    """The verdict of a statement made of several parts: DIFFERS if any part differs, then
    DIRECTION_ONLY, WITHIN_ERROR, AGREES; NOT_RUN only if every part is."""
    parts = [v for v in verdicts if v != NOT_RUN]
    if not parts:
        return NOT_RUN
    for v in (DIFFERS, DIRECTION_ONLY, WITHIN_ERROR):
        if v in parts:
            return v
    return AGREES
