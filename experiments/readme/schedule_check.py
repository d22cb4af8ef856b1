"""`python3 -m experiments.readme.schedule_check`: the committed schedule predictions
(scheduling.SCHEDULE_DIGEST) against what the build's `dabench schedule` gives on the committed
runs now (ctest `readme_schedule_current`, after the build). Exit 0 equal, 1 different, 2 no
build or unreadable data."""

import argparse
import math
import sys

from experiments.readme.scheduling import DIGEST_HEADER, REPO, SCHEDULE_DIGEST, build_program, schedule_rows
from reports.core import data


def same_numbers(a, b):
    """Two digests' rows equal, numbers to 1e-9 relative (the simulator's sums in another order
    would move the last bits)."""
    if len(a) != len(b):
        return False
    for ra, rb in zip(a, b):
        if ra[:3] != rb[:3]:
            return False
        for x, y in zip(ra[3:], rb[3:]):
            if not math.isclose(float(x), float(y), rel_tol=1e-9, abs_tol=1e-12):
                return False
    return True


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", default=str(REPO), help="the tree whose data and build are checked")
    args = ap.parse_args(argv)
    try:
        committed = [[r[c] for c in DIGEST_HEADER] for r in data.read_rows(args.root, SCHEDULE_DIGEST)]
        fresh = schedule_rows(args.root, build_program(args.root))
    except data.DataError as error:
        print(f"schedule_check: {error}", file=sys.stderr)
        return 2
    if not same_numbers(committed, fresh):
        print(f"schedule_check: {SCHEDULE_DIGEST} is not what `dabench schedule` gives on the committed runs: "
              "run /usr/bin/python3 -m reports.digest readme, then python3 -m reports.render readme", file=sys.stderr)
        return 1
    print(f"schedule_check: {SCHEDULE_DIGEST}: {len(fresh)} predictions, as the build's dabench gives them")
    return 0


if __name__ == "__main__":
    sys.exit(main())
