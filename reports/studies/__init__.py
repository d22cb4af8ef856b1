"""One module per study: its runs, its figures, and the checks that fill its REPORT template."""
