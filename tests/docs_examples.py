#!/usr/bin/env python3
"""Runs every `$ gyrokit ...` example of README.md and docs/*.md and compares its
output with the lines the doc shows, so that the docs cannot drift from the tool.

A fenced block (```) may hold commands, lines starting with `$ `, each followed by
its expected output (stdout and stderr merged, as in a terminal) up to the next
`$ ` line or the closing fence. Blocks without a `$ gyrokit` line are skipped. The
other `$ ` lines of a block (`ls`, `head` on what gyrokit wrote) are run and
checked as well; the commands of one block share a fresh temporary working
directory in which `data` and `docs` link to the repository's folders, so relative
output paths never land in the repository.

Comparison, line by line, whitespace-separated tokens (column alignment follows
the width of the numbers, so it is not compared):
  - numbers agree to the digits the doc prints: within half a unit of the doc
    number's last digit; numbers below 1e-9 in magnitude on both sides match each
    other (rounding noise: backward errors, real parts of neutral modes, which
    depend on the BLAS);
  - in a table column that measures rounding itself (backward_error, error_bound,
    bound_*: they scale with the BLAS's rounding), numbers agree within a factor
    of 100;
  - every other part of a token must be equal, except a table's rule (a run of
    dashes), whose width follows the widths of the numbers;
  - a `...` line skips any number of output lines; a trailing `...` lets the
    output continue.

Usage: python3 tests/docs_examples.py --gyrokit BUILD/apps/gyrokit --root REPO [--min N]
Exit 0 when every example passes and at least N `$ gyrokit` examples were found.
"""

import argparse
import concurrent.futures
import difflib
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
NOISE = 1e-9
TIMEOUT_S = 120


class Command:
    def __init__(self, path, line, text):
        self.path = path          # doc file, relative to the root
        self.line = line          # 1-based line of the `$ ` line
        self.text = text          # the command without `$ `
        self.expected = []

    @property
    def is_gyrokit(self):
        return re.match(r"gyrokit(\s|$)", self.text) is not None


def extract(root):
    """Blocks (lists of Commands) of README.md and docs/*.md that hold a gyrokit command."""
    files = [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    blocks = []
    for path in files:
        if not os.path.isfile(path):
            continue
        rel = os.path.relpath(path, root)
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
        in_fence = False
        block = []
        for number, line in enumerate(lines, start=1):
            if line.lstrip().startswith("```"):
                if in_fence and any(c.is_gyrokit for c in block):
                    blocks.append(block)
                in_fence = not in_fence
                block = []
                continue
            if not in_fence:
                continue
            if line.startswith("$ "):
                block.append(Command(rel, number, line[2:].strip()))
            elif block:
                block[-1].expected.append(line.rstrip())
    return blocks


def substitute(command, binary):
    """The command with `gyrokit` in command position replaced by the binary."""
    return re.sub(r"(^|[;&|(]\s*)gyrokit(?=\s|$)",
                  lambda m: m.group(1) + shlex.quote(binary), command)


def pieces(token):
    """A token split into ('n', number) and ('t', text) parts."""
    out, pos = [], 0
    for m in NUMBER.finditer(token):
        if m.start() > pos:
            out.append(("t", token[pos:m.start()]))
        out.append(("n", m.group()))
        pos = m.end()
    if pos < len(token):
        out.append(("t", token[pos:]))
    return out


def half_unit(text):
    """Half a unit of the last printed digit of a number as written."""
    m = re.fullmatch(r"[-+]?\d*(?:\.(\d*))?(?:[eE]([-+]?\d+))?", text)
    decimals = len(m.group(1) or "")
    exponent = int(m.group(2) or 0)
    return 0.5 * 10.0 ** (exponent - decimals)


def numbers_agree(doc, out):
    a, b = float(doc), float(out)
    if abs(a) < NOISE and abs(b) < NOISE:
        return True
    # The slack absorbs the binary representation of both decimals.
    return abs(a - b) <= half_unit(doc) * (1 + 1e-9) + 1e-12 * abs(a)


# Columns that measure rounding itself (backward errors, error bounds, the bounds
# derived from them): they scale with the rounding of the machine's BLAS, so a doc
# value and an output value agree when within a factor of MEASURE_FACTOR.
MEASURE_COLUMN = re.compile(r"(backward_error|error_bound|^bound_)")
MEASURE_FACTOR = 100.0


def measures_agree(doc, out):
    try:
        a, b = abs(float(doc.rstrip(","))), abs(float(out.rstrip(",")))
    except ValueError:
        return False
    if a < NOISE and b < NOISE:
        return True
    same_sign = doc.lstrip().startswith("-") == out.lstrip().startswith("-")
    return same_sign and a > 0 and b > 0 and max(a, b) <= MEASURE_FACTOR * min(a, b)


def line_matches(doc, out, header=None):
    csv = "," in doc and " " not in doc.strip()
    doc_tokens, out_tokens = (doc.split(",") if csv else doc.split()), (out.split(",") if csv else out.split())
    if len(doc_tokens) != len(out_tokens):
        return False
    columns = header if header is not None and len(header) == len(doc_tokens) else [None] * len(doc_tokens)
    if len(doc_tokens) == 2 and doc_tokens[0].startswith('"') and doc_tokens[0] == out_tokens[0]:
        columns = [None, doc_tokens[0].strip('":')]   # a JSON "key": value line
    for dt, ot, column in zip(doc_tokens, out_tokens, columns):
        if dt == ot:
            continue
        if column is not None and MEASURE_COLUMN.search(column) and measures_agree(dt, ot):
            continue
        if set(dt) == {"-"} and set(ot) == {"-"}:
            continue   # a table's rule: its width follows the numbers' widths
        dp, op = pieces(dt), pieces(ot)
        if len(dp) != len(op):
            return False
        for (dk, dv), (ok, ov) in zip(dp, op):
            if dk != ok:
                return False
            if dk == "t" and dv != ov:
                return False
            if dk == "n" and not numbers_agree(dv, ov):
                return False
    return True


def headers(lines):
    """For each doc line, the column names of the table it belongs to (or None): a
    text table's header is the line above its rule of dashes; a CSV table's is its
    first line of comma-separated names."""
    out, current = [], None
    for i, line in enumerate(lines):
        nxt = lines[i + 1] if i + 1 < len(lines) else ""
        if nxt.strip() and set(nxt.replace(" ", "")) == {"-"}:
            current = line.split()
        elif "," in line and " " not in line.strip() and re.fullmatch(r"[a-z_0-9,]+", line.strip()):
            current = line.strip().split(",")
        elif not line.strip() or line.strip() == "...":
            current = None   # a table ends at a blank line; after '...' rows may be of any table
        out.append(current)
    return out


def segment_at(segment, actual, start, heads=None):
    heads = heads or [None] * len(segment)
    return start + len(segment) <= len(actual) and all(
        line_matches(d, actual[start + i], heads[i]) for i, d in enumerate(segment))


def matching_prefix(segment, actual, start, heads=None):
    heads = heads or [None] * len(segment)
    n = 0
    while n < len(segment) and start + n < len(actual) and line_matches(segment[n], actual[start + n], heads[n]):
        n += 1
    return n


def missing_segment(segment, actual, pos):
    """Why the lines after a '...' are not found: the nearest partial match."""
    best = max(range(pos, len(actual)), key=lambda j: matching_prefix(segment, actual, j), default=None)
    if best is None or matching_prefix(segment, actual, best) == 0:
        return f"after '...' no output line from line {pos + 1} on matches: {segment[0]}"
    n = matching_prefix(segment, actual, best)
    if best + n >= len(actual):
        return f"after '...' output ends before: {segment[n]}"
    return f"after '...' output line {best + n + 1} differs:\n    doc: {segment[n]}\n    out: {actual[best + n]}"


def compare(expected, actual):
    """None if the output matches the doc, else a reason."""
    expected = list(expected)
    while expected and not expected[-1].strip():
        expected.pop()
    actual = [line.rstrip() for line in actual]
    while actual and not actual[-1]:
        actual.pop()
    heads = headers(expected)
    segments, current, seg_heads, current_heads = [], [], [], []
    for line, head in zip(expected, heads):
        if line.strip() == "...":
            segments.append(current)
            seg_heads.append(current_heads)
            current, current_heads = [], []
        else:
            current.append(line)
            current_heads.append(head)
    open_end = bool(expected) and expected[-1].strip() == "..."
    segments.append(current)
    seg_heads.append(current_heads)

    pos = 0
    for index, segment in enumerate(segments):
        if index == 0:
            for i, d in enumerate(segment):
                if i >= len(actual):
                    return f"output ends before doc line {i + 1}: {d!r}"
                if not line_matches(d, actual[i], seg_heads[index][i]):
                    return f"output line {i + 1} differs:\n    doc: {d}\n    out: {actual[i]}"
            pos = len(segment)
            continue
        if not segment:
            continue
        found = next((j for j in range(pos, len(actual)) if segment_at(segment, actual, j, seg_heads[index])), None)
        if found is None:
            return missing_segment(segment, actual, pos)
        pos = found + len(segment)
    if not open_end and pos < len(actual):
        return f"output continues after the doc's last line: {actual[pos]!r} (end the doc with '...' if meant)"
    return None


def make_workdir(root):
    work = tempfile.mkdtemp(prefix="gyrokit-docs-")
    for name in ("data", "docs"):
        os.symlink(os.path.join(root, name), os.path.join(work, name))
    return work


def run_block(block, binary, root, env):
    """[(command, reason or None, output lines)] for the commands of one block."""
    work = make_workdir(root)
    results = []
    try:
        for cmd in block:
            try:
                proc = subprocess.run(["bash", "-c", substitute(cmd.text, binary)], cwd=work, env=env,
                                      stdin=subprocess.DEVNULL, stdout=subprocess.PIPE,
                                      stderr=subprocess.STDOUT, timeout=TIMEOUT_S)
                output = proc.stdout.decode("utf-8", errors="replace").splitlines()
                reason = compare(cmd.expected, output)
            except subprocess.TimeoutExpired:
                output, reason = [], f"no result within {TIMEOUT_S} s"
            results.append((cmd, reason, output))
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return results


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--gyrokit", required=True, help="path of the gyrokit binary")
    parser.add_argument("--root", required=True, help="repository root (README.md, docs/, data/)")
    parser.add_argument("--min", type=int, default=1, help="fail if fewer gyrokit examples are found")
    parser.add_argument("--jobs", type=int, default=min(4, os.cpu_count() or 1),
                        help="blocks run at once (default: up to 4)")
    args = parser.parse_args()

    binary = os.path.abspath(args.gyrokit)
    root = os.path.abspath(args.root)
    if not os.access(binary, os.X_OK):
        print(f"error: {binary} is not an executable", file=sys.stderr)
        return 2

    env = dict(os.environ)
    env["LC_ALL"] = "C"
    env.pop("COLUMNS", None)
    env.pop("LINES", None)

    blocks = extract(root)
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        results = list(pool.map(lambda b: run_block(b, binary, root, env), blocks))

    examples = failures = 0
    for block_results in results:
        for cmd, reason, output in block_results:
            examples += cmd.is_gyrokit
            status = "PASS" if reason is None else "FAIL"
            print(f"{status} {cmd.path}:{cmd.line} {cmd.text}")
            if reason is None:
                continue
            failures += 1
            print(f"  {reason}")
            diff = list(difflib.unified_diff(cmd.expected, output, "doc", "output", lineterm="", n=1))
            for line in diff[:40]:
                print(f"  | {line}")
            if len(diff) > 40:
                print(f"  | ... ({len(diff) - 40} more diff lines)")

    print(f"{examples} gyrokit examples, {failures} failed")
    if examples < args.min:
        print(f"error: found {examples} gyrokit examples, expected at least {args.min}", file=sys.stderr)
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
