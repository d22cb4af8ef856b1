"""What the tampered-data tests share: editing a copied CSV in place."""
import csv


def rewrite_csv(path, change):
    """Rewrite a CSV with change(row) applied to each row (a dict of strings; edit it in place)."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header, rows = reader.fieldnames, list(reader)
    for row in rows:
        change(row)
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, header, lineterminator="\n")
        writer.writeheader()
        writer.writerows(rows)
