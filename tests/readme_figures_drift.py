#!/usr/bin/env python3
"""The test readme_figures_catches_drift: scripts/readme-figures.py --check must refuse a README whose figures differ
from bench/results by one digit. A copy of README.md with the last digit of the first figure between its markers
changed is checked against the committed bench/results; the check must exit 1 with a message naming the copy and
the changed line. (readme_figures checks the README itself; this checks that the check can fail.)

Usage: readme_figures_drift.py REPOSITORY_ROOT
"""
import os
import re
import subprocess
import sys
import tempfile

BEGIN = "<!-- figures:begin"
END = "<!-- figures:end -->"


def main():
    root = sys.argv[1]
    readme = open(os.path.join(root, "README.md")).read()
    start = readme.index(BEGIN)
    stop = readme.index(END)
    # The first "digits.digits" figure inside the markers (a decimal: not a date, not part of a commit hash).
    figure = re.compile(r"(?<![\w.])\d+\.(\d*)(\d)(?![\w.])").search(readme, start, stop)
    if figure is None:
        sys.exit("readme_figures_drift: README.md: figures: no decimal figure between the markers")
    changed_digit = str((int(figure.group(2)) + 1) % 10)
    drifted = readme[:figure.start(2)] + changed_digit + readme[figure.end(2):]
    line = readme.count("\n", 0, figure.start()) + 1
    with tempfile.TemporaryDirectory() as folder:
        copy = os.path.join(folder, "README.md")
        open(copy, "w").write(drifted)
        ran = subprocess.run([sys.executable, os.path.join(root, "scripts", "readme-figures.py"), "--check",
                              "--readme", copy, "--results", os.path.join(root, "bench", "results")],
                             capture_output=True, text=True)
    expected = f"{copy}: figures: line {line} "
    if ran.returncode != 1 or expected not in ran.stderr:
        sys.exit(f"readme_figures_drift: changing {figure.group(0)!r} on line {line} was not caught: exit status "
                 f"{ran.returncode}, stderr {ran.stderr.strip()!r} (wanted exit 1 and {expected!r})")
    print(f"readme_figures_drift: {figure.group(0)!r} -> ...{changed_digit} on line {line} refused: "
          + ran.stderr.strip())


if __name__ == "__main__":
    main()
