"""The code that studies share with the plot scripts under plots/ (one copy: the script's), e.g.
fig6_paper.py's data model of the BP paper's Fig. 6 or jdtvb_table.py's Table IV as printed."""

import importlib
import os
import sys

PLOTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "plots")


def load(name):
    """plots/<name>.py as a module (plots/ goes on sys.path first: the scripts import each other)."""
    if PLOTS not in sys.path:
        sys.path.insert(0, PLOTS)
    return importlib.import_module(name)
