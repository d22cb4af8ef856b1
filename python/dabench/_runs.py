"""dabench.run() and dabench.load(): experiment files run from Python, results as DataFrames."""
import json
import os
import sys
import time
from pathlib import Path

from . import _core


def _read_csv(path):
    """A result file as a DataFrame (numbers exactly as written; an empty field is NaN), or None."""
    import pandas
    if not path.is_file():
        return None
    return pandas.read_csv(path, keep_default_na=False, na_values=[""], float_precision="round_trip")


class Run:
    """A run folder: `trials` and `summary` (pandas DataFrames of trials.csv and summary.csv; summary
    is None until the run is complete, trials None in a committed folder that keeps only the
    summary), `meta` (meta.json as a dict), `folder`, and table(name) for the kind's per-trial files
    (e.g. "targets.csv", "tracks.csv", "steps.csv")."""

    def __init__(self, folder):
        self.folder = Path(folder)
        meta_path = self.folder / "meta.json"
        if not meta_path.is_file():
            raise ValueError(f"{folder}: not a dabench run folder (no meta.json)")
        with open(meta_path, encoding="utf-8") as file:
            self.meta = json.load(file)
        self.trials = _read_csv(self.folder / "trials.csv")
        self.summary = _read_csv(self.folder / "summary.csv")
        if self.trials is None and self.summary is None:
            raise ValueError(f"{folder}: not a dabench run folder (neither trials.csv nor summary.csv)")

    def table(self, name):
        """A per-trial file of the run (e.g. "targets.csv") as a DataFrame."""
        table = _read_csv(self.folder / name)
        if table is None:
            raise ValueError(f"{self.folder}: no {name}")
        return table

    def __repr__(self):
        rows = "no trials.csv" if self.trials is None else f"{len(self.trials)} rows"
        return f"<dabench.Run {str(self.folder)!r}: {rows}, {self.meta.get('status', '?')}>"


def load(folder):
    """The run in `folder` (written by `dabench run` or dabench.run()) as a Run."""
    return Run(folder)


def _progress_wanted():
    if os.environ.get("DABENCH_PROGRESS") is not None:
        return os.environ["DABENCH_PROGRESS"] != "0"
    return sys.stderr.isatty() or "ipykernel" in sys.modules


class _ProgressBar:
    """One line on stderr, redrawn in place: "[######----]  1200/6000 trials  20% | 850/s | ETA 0:05"."""

    def __init__(self):
        self.start = time.monotonic()
        self.first_done = None
        self.width = 0

    def draw(self, done, total):
        if total <= 0:
            return
        if self.first_done is None:
            self.first_done = done
        elapsed = time.monotonic() - self.start
        rate = (done - self.first_done) / elapsed if elapsed > 0 else 0.0
        filled = int(20 * done / total)
        text = f"[{'#' * filled}{'-' * (20 - filled)}] {done}/{total} trials {100 * done // total:3d}%"
        if rate > 0:
            text += f" | {rate:.0f}/s | ETA {_duration((total - done) / rate)}"
        sys.stderr.write("\r" + text.ljust(self.width))
        sys.stderr.flush()
        self.width = len(text)

    def finish(self):
        sys.stderr.write("\r" + " " * self.width + "\r")
        sys.stderr.flush()


def _duration(seconds):
    seconds = int(seconds)
    hours, rest = divmod(seconds, 3600)
    return f"{hours}:{rest // 60:02d}:{rest % 60:02d}" if hours else f"{rest // 60}:{rest % 60:02d}"


def _call_text(experiment, options):
    words = [repr(str(experiment))] + [f"{key}={value!r}" for key, value in options.items() if value not in (None, False)]
    return f"dabench.run({', '.join(words)})"


def run(experiment, trials=None, threads=None, seed=None, out=None, resume=False, force=False, progress=None):
    """Runs an experiment file as `dabench run` does and returns the Run of its output folder.

    trials, threads, seed and out override the file (threads: default all cores); resume finishes
    the run in the output folder, force discards it. A progress bar is drawn on stderr when it is
    a terminal or a notebook (progress=True/False decides instead). Ctrl-C stops after the trials
    in flight and raises KeyboardInterrupt; run(..., resume=True) finishes it.
    """
    options = dict(trials=trials, threads=threads, seed=seed, out=None if out is None else str(out),
                   resume=resume, force=force)
    handle = _core.start_run(str(experiment), command_line=_call_text(experiment, options), **options)
    bar = _ProgressBar() if (progress if progress is not None else _progress_wanted()) else None
    try:
        while not handle.wait(0.2):
            if bar:
                bar.draw(*handle.progress())
    except KeyboardInterrupt:  # Ctrl-C before the run took over SIGINT
        while not handle.wait(0.05):
            handle.interrupt()
    finally:
        if bar:
            bar.finish()
    outcome = handle.result()
    resume_hint = f"finish with {_call_text(experiment, dict(options, resume=True, force=False))}"
    if outcome["write_error"]:
        raise OSError(f"{outcome['write_error']} after {outcome['items_written']} of {outcome['items_total']} "
                      f"trials (whole rows kept); free space, then {resume_hint}")
    if outcome["interrupted"]:
        raise KeyboardInterrupt(f"interrupted after {outcome['items_written']} of {outcome['items_total']} trials; "
                                f"{resume_hint}")
    return Run(outcome["output"])
