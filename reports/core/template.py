"""Templates: hand-written Markdown with {{name}} placeholders filled by a study's checks.

- `{{name}}` is replaced by the text the checks produced under that name (a number, a verdict,
  a sentence, a table); a name no check produced is an error.
- `{{=text}}` is literal text: a configuration constant or a paper's equation label that the
  number lint below would otherwise take for a measurement.

The lint keeps numbers out of the prose: outside placeholders, code, link targets and references
(Sec., eq, Fig., Table, §, issue N), a template may not contain a decimal, a percentage (in
digits or words), "±", a count ("N of M", "N out of M", "87 iterations", "200 trials"), or a
factor ("a factor of ten", "3×", "4-fold") — such a number must come from a check, or be marked
a constant of the design or the paper with {{=…}}."""

import re

PLACEHOLDER = re.compile(r"\{\{(.*?)\}\}", re.S)
FENCE = re.compile(r"^```.*?^```[^\n]*$", re.S | re.M)
INLINE_CODE = re.compile(r"`[^`\n]*`")
LINK_TARGET = re.compile(r"\]\([^)]*\)")
COMMENT = re.compile(r"<!--.*?-->", re.S)
# Where a paper or this project is cited by number, not a measurement: "Sec. 1.3", "eqs 138–141".
REFERENCE = re.compile(r"(?:§|\b(?:Sec|Secs|Section|Sections|eq|eqs|Eq|Eqs|Fig|Figs|Figure|Table|Tables|Theorem|"
                       r"Algorithm|Appendix|issue|issues|stop|step)\.?)\s*\(?[\d.]+(?:\)?\s*(?:[–,-]|and|or)\s*\(?[\d.]+)*\)?")
NUMBER = r"\d(?:[\d\u2009\u202f ]*\d)?"  # 12, 10 000 (groups of digits)
WORD_NUMBER = (r"(?:one|two|three|four|five|six|seven|eight|nine|ten|eleven|twelve|thirteen|fourteen|fifteen|"
               r"sixteen|twenty|thirty|forty|fifty|sixty|seventy|eighty|ninety|hundred|thousand)")
COUNTED = (r"(?:iterations?|trials?|runs?|sweeps?|particles?|seconds?|ms|µs|minutes?|min|hours?|cases?|claims?|"
           r"statements?|resamples?|points?|draws?)")
NUMBER_CLAIMS = [
    (re.compile(r"(?<![\w.])\d+\.\d+(?![\w.]*\d)"), "a decimal"),
    (re.compile(r"(?<![\w.])\d+(?:\.\d+)?\s?%"), "a percentage"),
    (re.compile(rf"\b{WORD_NUMBER}[ -]?(?:percent|per cent)\b", re.I), "a percentage in words"),
    (re.compile(r"±"), "a ± interval"),
    (re.compile(rf"\b{NUMBER} (?:out )?of {NUMBER}\b"), "a count 'N of M'"),
    (re.compile(rf"(?<![\w.^/×-]){NUMBER} {COUNTED}\b"), "a count"),
    (re.compile(rf"\bfactor of (?:{WORD_NUMBER}|{NUMBER})\b|\b{NUMBER}(?:×(?!\s?[\dnNmk])|-fold)", re.I), "a factor"),
]


class TemplateError(Exception):
    pass


def render(text, values, template_name):
    """The template with every placeholder replaced (TemplateError naming the first unknown one)."""
    def replace(match):
        key = match.group(1).strip()
        if key.startswith("="):
            return key[1:]
        if key not in values:
            line = text.count("\n", 0, match.start()) + 1
            raise TemplateError(f"{template_name}:{line}: no check produced '{{{{{key}}}}}'")
        return str(values[key])
    return PLACEHOLDER.sub(replace, text)


def _blank(match):
    """The match replaced by spaces, newlines kept (so line numbers stay right)."""
    return re.sub(r"[^\n]", " ", match.group(0))


def lint(text, template_name):
    """Lines of prose that state a number no check produced: ["file:line: ... 'token'"]."""
    stripped = text
    for pattern in (FENCE, COMMENT, PLACEHOLDER, INLINE_CODE, LINK_TARGET, REFERENCE):
        stripped = pattern.sub(_blank, stripped)
    problems = []
    for number, line in enumerate(stripped.split("\n"), start=1):
        for pattern, what in NUMBER_CLAIMS:
            for m in pattern.finditer(line):
                problems.append(f"{template_name}:{number}: {what} in prose ('{m.group(0)}'): "
                                f"take it from a check ({{{{name}}}}), or mark a constant {{{{=…}}}}")
    return problems
