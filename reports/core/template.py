"""Templates: hand-written Markdown with {{name}} placeholders filled by a study's checks.

- `{{name}}` is replaced by the text the checks produced under that name (a number, a verdict,
  a sentence, a table); a name no check produced is an error.
- `{{=text}}` is literal text: a configuration constant or a paper's equation label that the
  number lint below would otherwise take for a measurement.

The lint keeps numbers out of the prose: outside placeholders, code and link targets, a template
may not contain a decimal with two or more fractional digits, a percentage, "±", or a count of
the form "N of M" — such a number must come from a check."""

import re

PLACEHOLDER = re.compile(r"\{\{(.*?)\}\}", re.S)
FENCE = re.compile(r"^```.*?^```[^\n]*$", re.S | re.M)
INLINE_CODE = re.compile(r"`[^`\n]*`")
LINK_TARGET = re.compile(r"\]\([^)]*\)")
COMMENT = re.compile(r"<!--.*?-->", re.S)
NUMBER_CLAIMS = [
    (re.compile(r"(?<![\w.])\d+\.\d{2,}(?![\w])"), "a decimal with two or more fractional digits"),
    (re.compile(r"\d\s?%"), "a percentage"),
    (re.compile(r"±"), "a ± interval"),
    (re.compile(r"\b\d+ of \d+\b"), "a count 'N of M'"),
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
    for pattern in (FENCE, COMMENT, PLACEHOLDER, INLINE_CODE, LINK_TARGET):
        stripped = pattern.sub(_blank, stripped)
    problems = []
    for number, line in enumerate(stripped.split("\n"), start=1):
        for pattern, what in NUMBER_CLAIMS:
            for m in pattern.finditer(line):
                problems.append(f"{template_name}:{number}: {what} in prose ('{m.group(0)}'): "
                                f"take it from a check ({{{{name}}}}), or mark a constant {{{{=…}}}}")
    return problems
