#!/usr/bin/python3
"""Write a study's digests: small committed files computed from large per-trial files that are
not committed (e.g. TBD's steps.csv), so that the render.REPORT's checks read committed data only.

Usage: /usr/bin/python3 -m reports.digest STUDY [--root DIR]"""

import argparse
import sys

from reports import render
from reports.core import data


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("name", metavar="STUDY")
    ap.add_argument("--root", default=render.REPO)
    args = ap.parse_args(argv)
    known = {n: render.load(n) for n in render.STUDY_NAMES if n == args.name}
    s = known.get(args.name)
    if s is None or s.digest is None:
        with_digests = [n for n in render.STUDY_NAMES if render.load(n).digest]
        print(f"digest.py: {args.name!r} has no digests (studies with digests: {', '.join(with_digests)})",
              file=sys.stderr)
        return 2
    try:
        for written in s.digest(args.root):
            print(written)
    except data.DataError as error:
        print(f"digest.py: {s.name}: {error}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
