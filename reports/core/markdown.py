"""Formatting numbers and tables for the REPORTs: one convention everywhere.

A mean with its standard error is printed as "m ± se" with the standard error rounded to one
significant digit (two when that digit is 1) and the mean to the same decimal place."""

import math


def sig(value, digits=3):
    """value to `digits` significant digits, without exponent for 1e-4 <= |value| < 1e6."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    if value == 0:
        return "0"
    a = abs(value)
    if 1e-4 <= a < 1e6:
        decimals = max(0, digits - 1 - int(math.floor(math.log10(a))))
        text = f"{value:.{decimals}f}"
        return text
    return f"{value:.{digits - 1}e}"


def fixed(value, decimals):
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "–"
    return f"{value:.{decimals}f}"


def se_decimals(se):
    """Decimal places that show a standard error to one significant digit (two if it starts with 1)."""
    if se is None or not math.isfinite(se) or se <= 0:
        return None
    exponent = int(math.floor(math.log10(se)))
    leading = se / 10 ** exponent
    digits = 2 if leading < 2 else 1
    return max(0, digits - 1 - exponent)


def pm(mean, se, decimals=None):
    """"mean ± se" (see the module comment); "mean" alone when se is unknown or zero
    (then `decimals`, or 3 significant digits)."""
    if mean is None or (isinstance(mean, float) and not math.isfinite(mean)):
        return "–"
    d = se_decimals(se)
    if d is None:
        return fixed(mean, decimals) if decimals is not None else sig(mean)
    return f"{mean:.{d}f} ± {se:.{d}f}"


def percent(value, decimals=1):
    if value is None or not math.isfinite(value):
        return "–"
    return f"{100 * value:.{decimals}f} %"


def signed(value, decimals):
    if value is None or not math.isfinite(value):
        return "–"
    return f"{value:+.{decimals}f}".replace("-", "−")


def cell(text):
    return str(text).replace("|", "\\|").replace("\n", " ")


def table(header, rows, align=None):
    """A Markdown table; align: a string of 'l'/'r' per column (default all left)."""
    marks = {"l": "---", "r": "---:", "c": ":---:"}
    align = align or "l" * len(header)
    out = ["| " + " | ".join(cell(h) for h in header) + " |",
           "|" + "|".join(marks[a] for a in align) + "|"]
    for r in rows:
        out.append("| " + " | ".join(cell(c) for c in r) + " |")
    return "\n".join(out)


def bullets(lines):
    return "\n".join(f"- {line}" for line in lines)


def duration(seconds):
    """"42 s", "12.7 min", "1.6 h"."""
    if seconds < 100:
        return f"{seconds:.0f} s" if seconds >= 10 else f"{seconds:.1f} s"
    if seconds < 6000:
        return f"{seconds / 60:.1f} min"
    return f"{seconds / 3600:.1f} h"


def interval(lo, hi, se):
    """"[lo, hi]" to the decimals that show se (se_decimals; 3 significant digits without one)."""
    d = se_decimals(se)
    if d is None:
        return f"[{sig(lo)}, {sig(hi)}]"
    return f"[{lo:.{d}f}, {hi:.{d}f}]"


def thousands(value, digits=3):
    """value to `digits` significant digits with thin groups: 185626 -> "186 000"."""
    return f"{float(f'{value:.{digits}g}'):,.0f}".replace(",", " ")
