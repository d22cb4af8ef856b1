"""Claims as code: each study's paper statements checked against the committed data, and the
REPORTs (and the README's measured numbers) rendered from those checks. See reports/README.md."""
