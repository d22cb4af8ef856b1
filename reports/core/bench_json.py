"""A study's committed Google Benchmark JSON (e.g. results/bp-paper/bench.json): read when it is
committed, and the provenance its context records (commit, clean or modified tree, date, CPUs)."""

import json
import os

from reports.core import data


def read(root, relpath):
    """The JSON document at relpath under root, or None when it is not committed."""
    full = data.path(root, relpath)
    if not os.path.exists(full):
        return None
    try:
        with open(full, encoding="utf-8") as f:
            return json.load(f)
    except (OSError, json.JSONDecodeError) as error:
        raise data.DataError(f"{relpath}: {error}") from None


def provenance(context, unknown, no_date):
    """"commit `0123456789` (clean), 2026-12-04, 2 CPUs" of a benchmark's context: `unknown` in
    place of clean or modified when it does not say, `no_date` when it records no date."""
    state = {"false": "clean", "true": "**modified**"}.get(str(context.get("source_modified")), unknown)
    return (f"commit `{str(context.get('git_commit', '?'))[:10]}` ({state}), "
            f"{str(context.get('date', no_date))[:10]}, {context.get('num_cpus', '?')} CPUs")
