#!/usr/bin/env python3
"""Runs docs/site-team.md's walkthrough as written (ctest docs_site_team_walkthrough).

Every ```sh block of the page is run in order, one command a line, in a fresh folder that stands for the
repository's root: `gusuku-bake` and `gusuku-render` are the built tools, a `python3` line runs the script of
that name from the repository's scripts folder (--scripts), an `export` line is skipped (the tools are given by path). A ```json block after the line
`<!-- walkthrough writes FILE -->` is written to FILE when the walk reaches it. To keep the test short the bake
gets `--samples 2 --quiet` and the render `--size 160x90 --samples 2`; nothing else is changed. Each command must
exit 0, check and preview must print `warnings: 0`, and georef's fitted fields must be the numbers the page's site.json holds (so the page cannot drift from
the fit).

usage: check_site_team_walkthrough.py --doc docs/site-team.md --bake GUSUKU_BAKE --render GUSUKU_RENDER
                                      --scripts SCRIPTS_DIR --work DIR
Exit 0 when the walk passes; 1 naming the page's line, the command and its output otherwise.
"""
import argparse
import json
import math
import pathlib
import re
import shlex
import shutil
import subprocess
import sys

WRITES = re.compile(r"^<!-- walkthrough writes (\S+) -->$")


def steps(doc):
    """(line number, kind, text): kind 'sh' (one command) or ('write', FILE) with the JSON block's text."""
    lines = doc.read_text().splitlines()
    found, i, pending_file = [], 0, None
    while i < len(lines):
        line = lines[i]
        match = WRITES.match(line.strip())
        if match:
            pending_file = match.group(1)
        elif line.startswith("```"):
            language, start = line[3:].strip(), i + 1
            i += 1
            block = []
            while i < len(lines) and not lines[i].startswith("```"):
                block.append(lines[i])
                i += 1
            if language == "sh":
                for offset, command in enumerate(block):
                    if command.strip() and not command.strip().startswith("#"):
                        found.append((start + offset + 1, "sh", command.strip()))
            elif language == "json" and pending_file:
                found.append((start, ("write", pending_file), "\n".join(block) + "\n"))
            pending_file = None
        i += 1
    return found


def argv_for(command, tools):
    words = shlex.split(command)
    if words[0] == "gusuku-bake":
        words[0] = tools.bake
        if len(words) > 1 and words[1] == "bake" and "--samples" not in words:
            words += ["--samples", "2", "--quiet"]
    elif words[0] == "gusuku-render":
        words[0] = tools.render
        for option, value in (("--size", "160x90"), ("--samples", "2")):
            if option in words:
                words[words.index(option) + 1] = value
            else:
                words += [option, value]
    elif words[0] == "python3" and words[1].startswith("scripts/"):
        words[1] = str(pathlib.Path(tools.scripts) / words[1][len("scripts/"):])
    return words


def close(a, b):
    return math.isclose(a, b, rel_tol=1e-6, abs_tol=1e-9)


def check_fit(output, site_json, where):
    """georef's printed fields against the page's site.json sfm_mesh."""
    fitted = json.loads(output[output.index("{"):output.rindex("}") + 1])
    given = json.loads(site_json)["sfm_mesh"]
    for field in ("scale", "rotation_wxyz", "translation_enu_m"):
        a, b = fitted[field], given[field]
        a, b = (a, b) if isinstance(a, list) else ([a], [b])
        if len(a) != len(b) or not all(close(x, y) for x, y in zip(a, b)):
            sys.exit(f"{where}: sfm_mesh.{field}: the page says {given[field]}, georef fits {fitted[field]}")


def main():
    parser = argparse.ArgumentParser()
    for option in ("--doc", "--bake", "--render", "--scripts", "--work"):
        parser.add_argument(option, required=True)
    tools = parser.parse_args()
    for name in ("bake", "render", "scripts"):  # the commands run in the work folder
        setattr(tools, name, str(pathlib.Path(getattr(tools, name)).resolve()))
    work = pathlib.Path(tools.work)
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    walk = steps(pathlib.Path(tools.doc))
    site_json = next((text for _, kind, text in walk if isinstance(kind, tuple)), None)
    georef_output = None
    for line, kind, text in walk:
        where = f"{tools.doc}:{line}"
        if isinstance(kind, tuple):
            (work / kind[1]).write_text(text)
            continue
        if text.startswith("export "):
            continue
        result = subprocess.run(argv_for(text, tools), cwd=work, capture_output=True, text=True, timeout=300)
        if result.returncode != 0:
            sys.exit(f"{where}: `{text}` exited {result.returncode}:\n{result.stdout}{result.stderr}")
        # The page says the walkthrough's site passes both: a placement warning here is the page gone wrong.
        if re.match(r"gusuku-bake (check|preview) ", text) and "warnings: 0" not in result.stdout:
            sys.exit(f"{where}: `{text}` warns, where the page says it passes:\n{result.stdout}")
        if " georef " in f" {text} ":
            georef_output = result.stdout
        print(f"{where}: ok: {text}")
    if georef_output is None or site_json is None:
        sys.exit(f"{tools.doc}: the walk has no georef command or no site.json block")
    check_fit(georef_output, site_json, tools.doc)
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
