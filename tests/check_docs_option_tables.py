#!/usr/bin/env python3
"""The docs' option tables against the tools' --help (ctest docs_option_tables).

Every command of gusuku-bake (as `gusuku-bake --help` lists them), gusuku-render and gusuku-bench prints its
options from one option table (engine/include/gusuku/tools/option_table.h): an option block starts "  --name" or
"  -o, --name" and ends, where the option has a default, with a line "default: VALUE". The docs hold the same
tables in Markdown, `| option | default | meaning |`, under a heading that names the command in backticks
(`gusuku-bake bake`, `gusuku-render`). For every command this checks that the two list the same options and the
same default for each (the meaning column is prose and is not compared). A doc default of '' or '-' means none.

usage: check_docs_option_tables.py --docs DOCS_DIR --bake GUSUKU_BAKE --render GUSUKU_RENDER --bench GUSUKU_BENCH
                                   [--view GUSUKU_VIEW]
(gusuku-view is built only where GLFW is; without --view its docs table is left unchecked.)
Exit 0 when every table agrees, 1 with one line per disagreement.
"""
import argparse
import pathlib
import re
import subprocess
import sys

OPTION_LINE = re.compile(r"^  (?:-\w, )?(--[a-z0-9-]+)")
HEADING = re.compile(r"^#+\s+(.*)$")
NO_DEFAULT = {"", "-", "\u2014", "none"}


def normalised(text):
    """Compares text as a reader sees it: no Markdown backticks or escapes, single spaces."""
    text = text.replace("\\|", "|").replace("`", "")
    return " ".join(text.split())


def help_text(command):
    result = subprocess.run(command + ["--help"], capture_output=True, text=True, timeout=60)
    if result.returncode != 0:
        sys.exit(f"{' '.join(command)} --help: exit {result.returncode}: {result.stderr.strip()}")
    return result.stdout + result.stderr


def help_options(text):
    """{long name: default} of the help's options: section."""
    options, current, in_options = {}, None, False
    for line in text.splitlines():
        if line == "options:":
            in_options = True
            continue
        if not in_options:
            continue
        if not line.strip():
            break  # the options end at the first blank line
        match = OPTION_LINE.match(line)
        if match:
            current = match.group(1)
            options[current] = ""
        elif current and line.strip().startswith("default: "):
            options[current] = normalised(line.strip()[len("default: "):])
    return options


def bake_commands(bake):
    text = help_text([bake])
    commands, in_commands = [], False
    for line in text.splitlines():
        if line == "commands:":
            in_commands = True
        elif in_commands and re.match(r"^  [a-z]+ ", line):
            commands.append(line.split()[0])
        elif in_commands and not line.strip() and commands:
            break
    return commands


def table_cells(row):
    cells = re.split(r"(?<!\\)\|", row.strip())
    return [cell.strip() for cell in cells[1:-1]]


def doc_tables(docs):
    """{command: (file:line, {long name: default})} of every option table under docs/."""
    tables, problems = {}, []
    for path in sorted(pathlib.Path(docs).glob("*.md")):
        lines = path.read_text(encoding="utf-8").splitlines()
        heading = ""
        index = 0
        while index < len(lines):
            line = lines[index]
            heading_match = HEADING.match(line)
            if heading_match:
                heading = heading_match.group(1)
            if line.startswith("|") and [c.lower() for c in table_cells(line)] == ["option", "default", "meaning"]:
                where = f"{path.name}:{index + 1}"
                named = re.search(r"`(gusuku-[a-z]+(?: [a-z]+)?)`", heading)
                if not named:
                    problems.append(f"{where}: an option table under a heading that names no command in backticks")
                command = named.group(1) if named else "?"
                options = {}
                index += 2  # the header and its | --- | row
                while index < len(lines) and lines[index].startswith("|"):
                    cells = table_cells(lines[index])
                    option = re.search(r"--[a-z0-9-]+", cells[0]) if cells else None
                    if len(cells) != 3 or not option:
                        problems.append(f"{path.name}:{index + 1}: not a row of option, default, meaning")
                    else:
                        default = normalised(cells[1])
                        options[option.group(0)] = "" if default.lower() in NO_DEFAULT else default
                    index += 1
                if command in tables:
                    problems.append(f"{where}: a second option table of `{command}` (the first: {tables[command][0]})")
                tables[command] = (where, options)
                continue
            index += 1
    return tables, problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--docs", required=True)
    parser.add_argument("--bake", required=True)
    parser.add_argument("--render", required=True)
    parser.add_argument("--bench", required=True)
    parser.add_argument("--view")
    arguments = parser.parse_args()

    commands = {f"gusuku-bake {name}": [arguments.bake, name] for name in bake_commands(arguments.bake)}
    if len(commands) < 8:
        sys.exit(f"gusuku-bake --help lists {len(commands)} commands; expected its 8 or more")
    commands["gusuku-render"] = [arguments.render]
    commands["gusuku-bench"] = [arguments.bench]
    if arguments.view:
        commands["gusuku-view"] = [arguments.view]

    tables, problems = doc_tables(arguments.docs)
    compared = 0
    for command, invocation in commands.items():
        in_help = help_options(help_text(invocation))
        where, in_docs = tables.pop(command, ("", {}))
        if in_help and not where:
            problems.append(f"{command}: --help lists {len(in_help)} options; no docs table "
                            "(| option | default | meaning | under a heading naming it)")
            continue
        for option in sorted(in_help.keys() - in_docs.keys()):
            problems.append(f"{where}: {command}: {option} is in --help but not in the docs' table")
        for option in sorted(in_docs.keys() - in_help.keys()):
            problems.append(f"{where}: {command}: {option} is in the docs' table but not in --help")
        for option in sorted(in_help.keys() & in_docs.keys()):
            compared += 1
            if in_help[option] != in_docs[option]:
                problems.append(f"{where}: {command}: {option}: the docs say default '{in_docs[option]}', "
                                f"--help says '{in_help[option]}'")
    for command, (where, _) in tables.items():
        if command == "gusuku-view" and not arguments.view:
            continue  # not built here (no GLFW)
        problems.append(f"{where}: an option table of `{command}`, which is no command of the tools")
    for problem in problems:
        print(problem)
    if problems:
        return 1
    print(f"docs option tables: {len(commands)} commands, {compared} options, every default as --help prints it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
