#!/usr/bin/env bash
# The Python package as a pip user installs it (docs/python.md): a virtual environment on the
# system's numpy, `pip install --no-build-isolation --no-index .` (offline), then, from another
# directory, `import dabench` at the project's version solving a problem as the build's package
# does; `pip uninstall dabench` removes it. The extension comes from BUILD (default ./build,
# already built) through DABENCH_BUILD_DIR, so nothing is compiled twice (setup.py).
# Fails loudly (message on stderr, exit status 1) on the first problem; removes its files.
set -euo pipefail
cd "$(dirname "$0")/../.."
source=$(pwd)
build=$(realpath "${1:-build}")
python=${PYTHON:-/usr/bin/python3}
work=$(mktemp -d "${TMPDIR:-/tmp}/dabench-pip-XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "pip_install: FAILED: $*" >&2; exit 1; }

"$python" -m venv --system-site-packages "$work/venv" || fail "python3 -m venv (apt-get install python3-venv)"
DABENCH_BUILD_DIR="$build" "$work/venv/bin/pip" install --no-build-isolation --no-index --quiet "$source" \
  >"$work/pip.txt" 2>&1 || fail "pip install: $(tail -5 "$work/pip.txt")"
version=$(sed -nE 's/^project\(dabench VERSION ([0-9.]+).*/\1/p' CMakeLists.txt)

cd "$work"
cat >check.py <<'PY'
import sys
import numpy as np
import dabench
version, site = sys.argv[1], sys.argv[2]
assert dabench.__version__ == version, (dabench.__version__, version)
assert dabench.__file__.startswith(site), dabench.__file__  # the installed package, not the build's
psi = np.array([[2.0, 0.5, 0.0], [1.0, 3.0, 0.2]])
exact = dabench.marginals(psi, "exact")
# By hand: the events' weights (target 1's choice, target 2's choice), ψ_i(0) = 1.
events = {(0, 0): 1.0, (0, 1): 1.0, (0, 2): 3.0, (0, 3): 0.2, (1, 0): 2.0, (1, 2): 6.0, (1, 3): 0.4,
          (2, 0): 0.5, (2, 1): 0.5, (2, 3): 0.1}
total = sum(events.values())
by_hand = np.zeros((2, 4))
for (a, b), w in events.items():
    by_hand[0, a] += w / total
    by_hand[1, b] += w / total
np.testing.assert_allclose(exact, by_hand, rtol=1e-13, atol=1e-15)
assert any(a["name"] == "bp" for a in dabench.algorithms("single_scan"))
print(dabench.__version__, dabench.__file__)
PY
site=$("$work/venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
"$work/venv/bin/python" check.py "$version" "$site" >check.txt 2>&1 || fail "import dabench: $(cat check.txt)"
"$work/venv/bin/pip" uninstall --yes --quiet dabench >/dev/null 2>&1 || fail "pip uninstall dabench"
if "$work/venv/bin/python" -c 'import dabench' >/dev/null 2>&1; then fail "dabench still imports after pip uninstall"; fi
[ -z "$(ls "$site" | grep -i '^dabench')" ] || fail "pip uninstall left $(ls "$site" | grep -i '^dabench')"
echo "pip_install: passed ($(cat check.txt))"
