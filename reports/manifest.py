"""The committed data's manifest: results/SHA256SUMS holds the sha256 of every committed file
under results/ but the rendered REPORTs (which `--check` compares with what the data give) and
the READMEs, in `sha256sum` format with paths from the repository root
(`sha256sum -c results/SHA256SUMS` checks it without Python). `python3 -m reports.render --check` fails on a file that changed, is missing,
or is committed but not listed; a hand edit that moves no printed digit is caught too.

`python3 -m reports.manifest` rewrites it from the files as they are (reports.rerun does after a
rerun); its diff is what a reviewer reads."""

import hashlib
import os
import subprocess
import sys

from reports.core import data

MANIFEST = "results/SHA256SUMS"
NOT_LISTED = ("REPORT.md", "README.md")  # rendered from the data (compared by --check itself), and prose


def sha256(path):
    digest = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            digest.update(block)
    return digest.hexdigest()


def listed_name(relpath):
    return relpath != MANIFEST and os.path.basename(relpath) not in NOT_LISTED


def committed_files(root):
    """The files git tracks under root/results (sorted), or None where root is not a git work tree
    (a copy of the data: only the listed files are checked then)."""
    try:
        done = subprocess.run(["git", "-C", root, "ls-files", "-z", "--", "results"], capture_output=True, check=False)
    except OSError:
        return None
    if done.returncode != 0:
        return None
    return sorted(p for p in done.stdout.decode("utf-8").split("\0") if p and listed_name(p))


def read(root):
    """{path: sha256} of the manifest under root ({} when there is none)."""
    full = os.path.join(root, MANIFEST)
    if not os.path.exists(full):
        return {}
    entries = {}
    with open(full, encoding="utf-8") as f:
        for number, line in enumerate(f, start=1):
            digest, sep, path = line.rstrip("\n").partition("  ")
            if not sep or len(digest) != 64:
                raise ValueError(f"{MANIFEST}:{number}: not `<sha256>  <path>`")
            entries[path] = digest
    return entries


def problems(root):
    """Why the committed data under root are not what the manifest lists, one line each."""
    try:
        listed = read(root)
    except ValueError as error:
        return [str(error)]
    if not listed:
        return [f"{MANIFEST}: missing (python3 -m reports.manifest writes it)"]
    out = []
    for path, digest in listed.items():
        full = os.path.join(root, path)
        if not os.path.exists(full):
            out.append(f"{path}: listed in {MANIFEST} but missing")
        elif sha256(full) != digest:
            out.append(f"{path}: not the file {MANIFEST} lists (its sha256 differs): changed since the manifest "
                       "was written; restore it, or rerun what made it (python3 -m reports.rerun)")
    for path in committed_files(root) or []:
        if path not in listed:
            out.append(f"{path}: committed but not in {MANIFEST} (python3 -m reports.manifest adds it)")
    return out


def write(root):
    """Rewrite the manifest from the committed files as they are now; returns how many it lists."""
    files = committed_files(root)
    if files is None:
        raise ValueError(f"{root}: not a git work tree (the manifest lists the files git tracks under results/)")
    lines = [f"{sha256(os.path.join(root, p))}  {p}\n" for p in files if os.path.exists(os.path.join(root, p))]
    data.write_text(os.path.join(root, MANIFEST), "".join(lines))
    return len(lines)


def main():
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    try:
        count = write(root)
    except ValueError as error:
        print(f"manifest: {error}", file=sys.stderr)
        return 2
    print(f"{MANIFEST}: {count} files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
