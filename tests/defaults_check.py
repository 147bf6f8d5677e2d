#!/usr/bin/env python3
"""One table of defaults (lib/gyrokit/study/defaults.hpp), shown alike everywhere.

`gyrokit defaults --format json` is the table. It must equal, row for row:
- docs/defaults.md's table (name, value, meaning, option, keyword);
- gyrokit.defaults() in Python;
and each value it gives (not a rule) must be
- the default the CLI's help shows for its option, in every command that has the option
  (or in its one command), and in at least one;
- the default of its keyword in every public Python call that has it (or in its one
  call), and in at least one.
Usage: defaults_check.py GYROKIT ROOT (PYTHONPATH holds the built module)."""
import inspect
import json
import re
import subprocess
import sys


def fail(msg):
    print("FAIL:", msg)
    sys.exit(1)


def run(cli, *args):
    r = subprocess.run([cli, *args], capture_output=True, text=True)
    if r.returncode != 0:
        fail(f"gyrokit {' '.join(args)} exited {r.returncode}: {r.stderr}")
    return r.stdout


def docs_rows(root):
    """The rows of the first table in docs/defaults.md whose header starts | name | value | meaning |."""
    text = open(f"{root}/docs/defaults.md", encoding="utf-8").read().splitlines()
    rows, inside = [], False
    for line in text:
        cells = [c.strip() for c in line.strip().strip("|").split("|")] if line.startswith("|") else None
        if cells and cells[:3] == ["name", "value", "meaning"]:
            inside = True
            continue
        if inside:
            if not cells:
                break
            if set(cells[0]) <= set("-: "):
                continue
            rows.append([c.replace("\\|", "|").strip("`") for c in cells[:5]])
    return rows


def commands(cli):
    """The command names `gyrokit --help` lists."""
    names, inside = [], False
    for line in run(cli, "--help").splitlines():
        if line.strip().upper().startswith("SUBCOMMANDS"):
            inside = True
            continue
        if inside and line.startswith("  ") and line.strip():
            names.append(line.split()[0])
    if not names:
        fail("gyrokit --help lists no commands")
    return names


def shown_default(help_text, option):
    """The default the help shows for `option` ("--units TEXT=rad/s"): the text after '=', None if the option is
    there without a default, False if it is not there."""
    for line in help_text.splitlines():
        m = re.match(r"\s+(?:-\w,\s*)?(--[\w-]+)(.*)$", line)
        if m and m.group(1) == option:
            # The type and default up to the description (two spaces or more): "INT:INT in [1 - 1000]=3".
            typed = re.split(r"\s{2,}", m.group(2).strip())[0] if m.group(2).startswith(" ") else ""
            return typed.split("=", 1)[1] if "=" in typed else None
    return False


def same(value, default):
    """A table value (as text) against a default (a Python value or the CLI's text)."""
    if isinstance(default, str):
        if default == value:
            return True
        try:
            return float(default) == float(value)
        except ValueError:
            return False
    if isinstance(default, bool) or default is None:
        return False
    try:
        return float(default) == float(value)
    except (TypeError, ValueError):
        return False


def rule_shown(r, table, helps, calls):
    """A rule (no value): no command's help shows a default for its option, every Python keyword's default is
    None, so that the library applies the rule (a command or call another row names for the same option or
    keyword is that row's). The count of options and keywords checked."""
    own_commands = {x["command"] for x in table if x is not r and x["option"] == r["option"] and x["command"]}
    own_calls = {x["function"] for x in table if x is not r and x["keyword"] == r["keyword"] and x["function"]}
    seen = 0
    if r["option"]:
        for name, text in helps.items():
            if (r["command"] and name != r["command"]) or name in own_commands:
                continue
            shown = shown_default(text, r["option"])
            if shown is False:
                continue
            if shown is not None:
                fail(f"gyrokit {name} --help: {r['option']} shows {shown!r}; the table's rule: {r['meaning']!r}")
            seen += 1
    if r["keyword"]:
        for name, f in calls.items():
            if (r["function"] and name != r["function"]) or name in own_calls:
                continue
            p = inspect.signature(f).parameters.get(r["keyword"])
            if p is None:
                continue
            if p.default is not None:
                fail(f"gyrokit.{name}({r['keyword']}={p.default!r}): the table's rule is {r['meaning']!r}, "
                     "so the default must be None")
            seen += 1
    return seen


def main():
    cli, root = sys.argv[1], sys.argv[2]
    table = json.loads(run(cli, "defaults", "--format", "json"))
    if not table:
        fail("the table of defaults is empty")

    import gyrokit as gk
    if gk.defaults() != table:
        fail("gyrokit.defaults() differs from `gyrokit defaults`")

    docs = docs_rows(root)
    want = [[r["name"], r["value"], r["meaning"], r["option"], r["keyword"]] for r in table]
    if docs != want:
        for d, w in zip(docs + [None] * len(want), want + [None] * len(docs)):
            if d != w:
                fail(f"docs/defaults.md row {d} != the table's {w}")

    helps = {c: run(cli, c, "--help") for c in commands(cli)}
    calls = {n: getattr(gk, n) for n in gk.__all__
             if inspect.isfunction(getattr(gk, n)) and not n[0].isupper()}
    checked = 0
    for r in table:
        if not r["value"]:
            checked += rule_shown(r, table, helps, calls)
            continue
        if r["option"]:
            seen = 0
            for name, text in helps.items():
                if r["command"] and name != r["command"]:
                    continue
                shown = shown_default(text, r["option"])
                if shown is False:
                    if r["command"]:
                        fail(f"gyrokit {name} has no {r['option']} (table row {r['name']!r})")
                    continue
                if shown is None or not same(r["value"], shown):
                    fail(f"gyrokit {name} --help: {r['option']} shows {shown!r}; the table says {r['value']!r}")
                seen += 1
            if not seen:
                fail(f"no command shows {r['option']} (table row {r['name']!r})")
            checked += seen
        if r["keyword"]:
            seen = 0
            for name, f in calls.items():
                if r["function"] and name != r["function"]:
                    continue
                p = inspect.signature(f).parameters.get(r["keyword"])
                if p is None:
                    if r["function"]:
                        fail(f"gyrokit.{name} has no keyword {r['keyword']} (table row {r['name']!r})")
                    continue
                if not same(r["value"], p.default):
                    fail(f"gyrokit.{name}({r['keyword']}={p.default!r}): the table says {r['value']!r}")
                seen += 1
            if not seen:
                fail(f"no Python call takes {r['keyword']} (table row {r['name']!r})")
            checked += seen
    print(f"ok: {len(table)} defaults; {checked} options and keywords show their table value")


if __name__ == "__main__":
    main()
