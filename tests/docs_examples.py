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
  - in a table column that measures rounding itself (backward_error, error_bound, *_bound,
    bound_*: they scale with the BLAS's rounding), numbers agree within a factor
    of 100;
  - every other part of a token must be equal, except a table's rule (a run of
    dashes), whose width follows the widths of the numbers;
  - a `...` line skips any number of output lines; a trailing `...` lets the
    output continue.

Pictures: every picture a page shows (`![...](img/NAME)`, a file of docs/img) is the
file an example writes under that name into its working directory (top level), e.g.
`$ gyrokit static ... --plot static.png` in the block above the picture. After the
examples run, each file of such a name that an example wrote must be a valid picture
of its extension (.png: the PNG signature, an IHDR of nonzero size and the closing
IEND chunk; .svg: UTF-8 text with `<svg` and `</svg>`) of at least MIN_IMAGE_BYTES,
and written by one block only (two would leave docs/img ambiguous). A picture that
a page shows and no example writes is a failure naming it, unless it is listed in
NOT_FROM_GYROKIT with the reason it cannot come from gyrokit; so is a picture a page
shows that docs/img lacks. The report says which pictures differ from docs/img
(gnuplot's version changes their bytes, so a difference alone is no failure).
`--update-images` copies every valid picture the examples wrote into docs/img (only
those whose bytes differ), so a maintainer regenerates the docs' pictures with one
command; review them with `git status docs/img` and an image viewer, then commit.

Usage: python3 tests/docs_examples.py --gyrokit BUILD/apps/gyrokit --root REPO [--min N]
                                      [--jobs J] [--update-images]
Exit 0 when every example passes, every picture of the docs is written by an
example and valid, and at least N `$ gyrokit` examples were found.
"""

import argparse
import concurrent.futures
import difflib
import glob
import os
import re
import shlex
import shutil
import struct
import subprocess
import sys
import tempfile

NUMBER = re.compile(r"[-+]?(?:\d+\.\d*|\.\d+|\d+)(?:[eE][-+]?\d+)?")
NOISE = 1e-9
TIMEOUT_S = 120

# A picture of the docs: `![alt](img/NAME)` in docs/*.md, `![alt](docs/img/NAME)` in README.md.
IMAGE_REFERENCE = re.compile(r"!\[[^\]]*\]\((?:docs/)?img/([^)\s]+)\)")
PNG_SIGNATURE = b"\x89PNG\r\n\x1a\n"
PNG_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"
# The smallest docs picture is a 900 x 380 PNG of about 20 kB; gnuplot's empty 900 x 380
# frame with its axes takes about 7 kB (PNG) or 8.5 kB (SVG), so a smaller file is a
# failed or truncated figure.
MIN_IMAGE_BYTES = 2000
# Pictures of docs/img that no gyrokit command can draw (photographs, hand-made
# diagrams), NAME -> the reason; they are exempt from "written by an example". None today:
# every picture of the docs is a gyrokit figure.
NOT_FROM_GYROKIT = {
    "report.png": "a browser's screenshot of the HTML report (tests/report_browser.py --screenshot)",
}


class Command:
    def __init__(self, path, line, text):
        self.path = path          # doc file, relative to the root
        self.line = line          # 1-based line of the `$ ` line
        self.text = text          # the command without `$ `
        self.expected = []

    @property
    def is_gyrokit(self):
        return re.match(r"gyrokit(\s|$)", self.text) is not None


def doc_files(root):
    return [os.path.join(root, "README.md")] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))


def extract(root):
    """Blocks (lists of Commands) of README.md and docs/*.md that hold a gyrokit command."""
    files = doc_files(root)
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


def referenced_images(root):
    """{NAME: ["doc:line", ...]} of the pictures the docs show (outside fenced blocks)."""
    refs = {}
    for path in doc_files(root):
        if not os.path.isfile(path):
            continue
        rel = os.path.relpath(path, root)
        in_fence = False
        with open(path, encoding="utf-8") as f:
            for number, line in enumerate(f, start=1):
                if line.lstrip().startswith("```"):
                    in_fence = not in_fence
                    continue
                if in_fence:
                    continue
                for m in IMAGE_REFERENCE.finditer(line):
                    refs.setdefault(m.group(1), []).append(f"{rel}:{number}")
    return refs


def image_problem(name, data):
    """None if data is a valid picture for the name's extension, else the reason."""
    ext = os.path.splitext(name)[1].lower()
    if len(data) < MIN_IMAGE_BYTES:
        return f"{len(data)} bytes, less than a picture ({MIN_IMAGE_BYTES})"
    if ext == ".png":
        if not data.startswith(PNG_SIGNATURE):
            return "not a PNG: no PNG signature"
        if data[12:16] != b"IHDR":
            return "not a PNG: no IHDR chunk first"
        width, height = struct.unpack(">II", data[16:24])
        if width == 0 or height == 0:
            return f"an empty PNG ({width} x {height})"
        if not data.endswith(PNG_IEND):
            return "a truncated PNG: no IEND chunk at its end"
        return None
    if ext == ".svg":
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError:
            return "not an SVG: not UTF-8 text"
        if "<svg" not in text:
            return "not an SVG: no <svg element"
        if "</svg>" not in text:
            return "a truncated SVG: no </svg>"
        return None
    return f"not a picture type the docs use ({ext or 'no extension'}; .png or .svg)"


def image_summary(name, data):
    if name.lower().endswith(".png"):
        width, height = struct.unpack(">II", data[16:24])
        return f"PNG {width}x{height}, {len(data)} bytes"
    return f"SVG, {len(data)} bytes"


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
MEASURE_COLUMN = re.compile(r"(backward_error|error_bound|^bound_|_bound$)")
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


def collect_images(work, block, names):
    """{NAME: (bytes, Command)} for the files of the working directory (top level, no
    links) that have the name of a docs picture; the Command is the first that names
    the file, else the block's first."""
    images = {}
    for name in sorted(os.listdir(work)):
        path = os.path.join(work, name)
        if name not in names or os.path.islink(path) or not os.path.isfile(path):
            continue
        with open(path, "rb") as f:
            data = f.read()
        writer = next((c for c in block if re.search(r"(^|[\s=/])" + re.escape(name) + r"(\s|$)", c.text)), block[0])
        images[name] = (data, writer)
    return images


def run_block(block, binary, root, env, image_names=frozenset()):
    """([(command, reason or None, output lines)], {picture NAME: (bytes, Command)})
    for the commands of one block."""
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
        images = collect_images(work, block, image_names)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    return results, images


def check_images(root, refs, produced, update):
    """Checks the pictures the examples wrote against the pictures the docs show (and,
    with update, copies them into docs/img). Prints a line per picture; returns the
    number of failures."""
    img_dir = os.path.join(root, "docs", "img")
    failures = differing = 0
    for name in sorted(produced):
        writers = produced[name]
        where = ", ".join(f"{cmd.path}:{cmd.line}" for _, cmd in writers)
        if len(writers) > 1:
            failures += 1
            print(f"FAIL img/{name}: written by {len(writers)} blocks ({where}); "
                  f"a docs picture must come from one example: give the others another name")
            continue
        data, cmd = writers[0]
        problem = image_problem(name, data)
        if problem:
            failures += 1
            print(f"FAIL img/{name} from {where}: {problem}")
            continue
        target = os.path.join(img_dir, name)
        old = None
        if os.path.isfile(target):
            with open(target, "rb") as f:
                old = f.read()
        state = "new, not in docs/img" if old is None else "same as docs/img" if old == data else "differs from docs/img"
        differing += old != data
        if update and old != data:
            os.makedirs(img_dir, exist_ok=True)
            with open(target, "wb") as f:
                f.write(data)
            state = "written to docs/img (new)" if old is None else "updated in docs/img"
        if name not in refs:
            state += "; shown by no page"
        print(f"PASS img/{name} from {where} {cmd.text}: {image_summary(name, data)}, {state}")

    missing = sorted(n for n in refs if n not in produced and n not in NOT_FROM_GYROKIT)
    if missing:
        failures += 1
        print(f"FAIL pictures shown by the docs but written by no example ({len(missing)}): "
              + ", ".join(f"{n} ({refs[n][0]})" for n in missing))
        print("  add a run example `$ gyrokit ... --plot NAME` to the page that shows the picture, "
              "or list it in NOT_FROM_GYROKIT with the reason")
    absent = sorted(n for n in refs if not os.path.isfile(os.path.join(img_dir, n)))
    if absent:
        failures += 1
        print("FAIL pictures shown by the docs that docs/img lacks: "
              + ", ".join(f"{n} ({refs[n][0]})" for n in absent)
              + ("" if update else " (--update-images writes those an example wrote)"))
    for name in sorted(NOT_FROM_GYROKIT):
        print(f"SKIP img/{name}: not from gyrokit: {NOT_FROM_GYROKIT[name]}")
    unused = sorted(n for n in (os.listdir(img_dir) if os.path.isdir(img_dir) else ()) if n not in refs)
    if unused:
        print("note: docs/img files shown by no page: " + ", ".join(unused))
    if differing:
        print(f"note: {differing} written pictures are new or differ from docs/img"
              + (" and were copied there" if update else " (--update-images copies them there)"))
    return failures


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--gyrokit", required=True, help="path of the gyrokit binary")
    parser.add_argument("--root", required=True, help="repository root (README.md, docs/, data/)")
    parser.add_argument("--min", type=int, default=1, help="fail if fewer gyrokit examples are found")
    parser.add_argument("--jobs", type=int, default=min(4, os.cpu_count() or 1),
                        help="blocks run at once (default: up to 4)")
    parser.add_argument("--update-images", action="store_true",
                        help="copy the valid pictures the examples wrote into docs/img")
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
    refs = referenced_images(root)
    img_dir = os.path.join(root, "docs", "img")
    image_names = frozenset(refs) | frozenset(os.listdir(img_dir) if os.path.isdir(img_dir) else ())
    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, args.jobs)) as pool:
        runs = list(pool.map(lambda b: run_block(b, binary, root, env, image_names), blocks))

    examples = failures = 0
    produced = {}
    for _, images in runs:
        for name, item in images.items():
            produced.setdefault(name, []).append(item)
    for block_results, _ in runs:
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

    image_failures = check_images(root, refs, produced, args.update_images)
    valid = sum(1 for n, w in produced.items() if len(w) == 1 and image_problem(n, w[0][0]) is None)
    print(f"{examples} gyrokit examples, {failures} failed; "
          f"{len(refs)} pictures shown, {valid} written valid, {image_failures} picture checks failed")
    failures += image_failures
    if examples < args.min:
        print(f"error: found {examples} gyrokit examples, expected at least {args.min}", file=sys.stderr)
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
