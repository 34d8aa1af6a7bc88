"""Reading the benchmark's JSON files (bench/results, what scripts/bench.sh writes) for the scripts that report
them, bench-goals.py and readme-figures.py: a missing file or field is one line naming the file and the field,
and exit status 1. Each script sets TOOL to its own name for that line."""
import json
import sys

SITES = ("sample", "shrine", "house")
TOOL = "bench-results"


def fail(message):
    print(TOOL + ": " + message, file=sys.stderr)
    sys.exit(1)


def load(path):
    try:
        with open(path) as stream:
            return json.load(stream)
    except FileNotFoundError:
        fail(path + ": not found (scripts/bench.sh writes it)")
    except json.JSONDecodeError as error:
        fail(path + ": invalid JSON: " + str(error))


def field(document, path, keys):
    """document[keys[0]][keys[1]]..., or fail naming path and the JSON pointer of what is missing."""
    value = document
    for key in keys:
        if not isinstance(value, dict) or key not in value:
            fail(path + ": /" + "/".join(keys) + ": missing")
        value = value[key]
    return value
