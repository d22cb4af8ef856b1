#!/usr/bin/env bash
# The documentation site: `mkdocs build --strict` (mkdocs.yml; a link to a missing page or file is an
# error), then every internal link's anchor checked against the ids of the page it points to
# (MkDocs 1.4 checks files, not anchors), and every link from README.md into docs/ to an existing
# page. Builds into a temporary folder; fails loudly (stderr, exit status 1) on the first problem.
set -euo pipefail
cd "$(dirname "$0")/../.."
python=${PYTHON:-/usr/bin/python3}
work=$(mktemp -d "${TMPDIR:-/tmp}/dabench-docs-XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "docs_site: FAILED: $*" >&2; exit 1; }

"$python" -m mkdocs build --strict --quiet -f mkdocs.yml -d "$work/site" >"$work/build.txt" 2>&1 ||
  fail "mkdocs build --strict: $(cat "$work/build.txt")"
"$python" - "$work/site" <<'PY' || exit 1
import html.parser
import os
import re
import sys
from urllib.parse import unquote, urlsplit

site = sys.argv[1]


class Page(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.ids, self.links = set(), []

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if "id" in attrs:
            self.ids.add(attrs["id"])
        if tag == "a" and attrs.get("href"):
            self.links.append(attrs["href"])


pages = {}
for folder, _, files in os.walk(site):
    for name in files:
        if name.endswith(".html"):
            page = Page()
            with open(os.path.join(folder, name), encoding="utf-8") as f:
                page.feed(f.read())
            pages[os.path.normpath(os.path.join(folder, name))] = page
problems = []
for path, page in pages.items():
    if path.endswith("404.html"):
        continue
    for href in page.links:
        parts = urlsplit(href)
        if parts.scheme or parts.netloc or not parts.fragment:
            continue
        target = path if not parts.path else os.path.normpath(os.path.join(os.path.dirname(path), unquote(parts.path)))
        if os.path.isdir(target):
            target = os.path.join(target, "index.html")
        if target not in pages:
            continue  # not a page of the site (mkdocs --strict has judged the file)
        if unquote(parts.fragment) not in pages[target].ids:
            problems.append(f"{os.path.relpath(path, site)}: link {href}: no anchor '{parts.fragment}' there")
readme = open("README.md", encoding="utf-8").read()
for link in re.findall(r"\]\((docs/[^)#\s]+)(?:#[^)\s]*)?\)", readme):
    if not os.path.isfile(link):
        problems.append(f"README.md: link to {link}: no such page")
if problems:
    print("docs_site: FAILED:\n  " + "\n  ".join(problems), file=sys.stderr)
    sys.exit(1)
print(f"docs_site: {len(pages)} pages, every anchor found")
PY
