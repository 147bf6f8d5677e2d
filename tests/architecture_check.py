"""The layout's rules, checked on the sources (docs/architecture.md):

1. A module's detail/ headers are its own: no file of lib/, apps/ or python/ outside lib/gyrokit/M includes
   <gyrokit/M/detail/...> (tests may: they exercise a module's internals).
2. The scene layer reads and writes files only: nothing in lib/gyrokit/io (or scene/) includes
   <gyrokit/analysis/...> or <gyrokit/solve/...>; and the layers under the analyses (core, eig, numerics,
   models, solve) include no analysis/ or study/ header.
3. No library file over 500 lines, no function over 100. A function is counted from the first line of its
   declaration to its closing brace: a brace block opened at namespace (or class) level by anything but
   namespace, struct, class, enum or union, with everything nested in it (lambdas included).
4. Every source of lib/gyrokit is in lib/CMakeLists.txt's explicit lists, and every listed file exists.
5. One of each: π is defined in lib/gyrokit/core/constants.hpp alone (no M_PI, acos(-1) or 3.14159 literal in lib/,
   apps/ or python/); std::thread is used by lib/gyrokit/core/parallel.cpp alone (the kept pool behind
   for_each_index; std::thread::hardware_concurrency aside); CSV fields are quoted by lib/gyrokit/io/csv.cpp alone.
6. The C++ tests mirror lib/gyrokit: tests/M/test_*.cpp for a module M (tests/bench/ for apps/bench), only
   test_main.cpp at the top, each listed in tests/CMakeLists.txt and every listed file present.

KNOWN lists what the layout work has not reached yet, each with its reason: the check fails for anything
else, and for an entry that no longer applies (so that the list only shrinks).

Usage: architecture_check.py SOURCE_DIR; prints each finding, exit 1 if any.
"""
import pathlib
import re
import sys

MAX_FILE_LINES = 500
MAX_FUNCTION_LINES = 100

# What a staged move has not reached yet: key -> why it is still here (empty: none).
KNOWN = {}


def code_only(line, in_block):
    """The line without comments and literals (their braces do not count); whether a /* */ stays open."""
    out, i = [], 0
    while i < len(line):
        if in_block:
            end = line.find("*/", i)
            if end < 0:
                return "".join(out), True
            i, in_block = end + 2, False
            continue
        c = line[i]
        if line.startswith("//", i):
            break
        if line.startswith("/*", i):
            in_block = True
            i += 2
            continue
        if line.startswith('R"', i):   # a raw string: to its closing )delim"
            m = re.match(r'R"([^(]*)\(', line[i:])
            if m:
                end = line.find(")" + m.group(1) + '"', i)
                i = len(line) if end < 0 else end + len(m.group(1)) + 2
                continue
        if c in "\"'":
            j = i + 1
            while j < len(line) and line[j] != c:
                j += 2 if line[j] == "\\" else 1
            i = j + 1
            continue
        out.append(c)
        i += 1
    return "".join(out), in_block


def functions(path_or_text):
    """(name, first line, last line) of each function body opened at namespace or class level."""
    text = path_or_text if isinstance(path_or_text, str) else path_or_text.read_text()
    lines = text.split("\n")
    stack = []            # kinds of the open blocks: ns, type, func, inner
    statement, start = "", None
    found = []
    in_block = False
    for n, raw in enumerate(lines, 1):
        code, in_block = code_only(raw, in_block)
        if code.strip().startswith("#"):
            continue
        for c in code:
            if start is None and not c.isspace():
                start = n
            if c == "{":
                outer = stack[-1][0] if stack else "ns"
                if outer in ("ns", "type"):
                    head = statement.strip()
                    if re.match(r"(?:inline\s+)?namespace\b|extern\s+\"", head) or head == "":
                        kind = "ns"
                    elif re.search(r"\b(struct|class|enum|union)\b[^()]*$", head):
                        kind = "type"
                    elif head.endswith("=") or re.search(r"=\s*$", head):
                        kind = "inner"   # an initializer
                    else:
                        kind = "func"
                else:
                    kind = "inner"
                name = ""
                if kind == "func":
                    m = re.findall(r"([A-Za-z_~][\w:~]*)\s*\(", statement)
                    name = m[0] if m else "?"
                stack.append((kind, start if start is not None else n, name))
                statement, start = "", None
            elif c == "}":
                if stack:
                    kind, first, name = stack.pop()
                    if kind == "func":
                        found.append((name.split("::")[-1], first, n))
                statement, start = "", None
            elif c == ";":
                statement, start = "", None
            else:
                statement += c
        statement += " "
    return found


SAMPLE = """namespace gyrokit {
namespace {
struct S {
    int f() const { return 1; }
};
const char* brace = "{";   // not a block
}  // namespace

double g(int a,
         int b) {
    auto h = [](int x) {
        return x;
    };
    /* } */
    return h(a) + b;
}
}  // namespace gyrokit
"""


def main(root):
    # The counter itself, on a sample: a method, a two-line signature with a lambda inside, literal braces.
    assert functions(SAMPLE) == [("f", 4, 4), ("g", 9, 16)], functions(SAMPLE)
    root = pathlib.Path(root)
    lib = root / "lib" / "gyrokit"
    findings = []
    include = re.compile(r'#\s*include\s*[<"]gyrokit/([a-z_]+)/(detail/)?([^>"]+)[>"]')
    for path in sorted(p for d in ("lib", "apps", "python") for p in (root / d).rglob("*.[ch]pp")):
        rel = path.relative_to(root).as_posix()
        parts = path.relative_to(root).parts
        own = parts[2] if rel.startswith("lib/gyrokit/") and len(parts) > 3 else None
        for m in include.finditer(path.read_text()):
            module, detail, rest = m.groups()
            if detail and module != own:
                findings.append(f"include {rel} -> gyrokit/{module}/detail/{rest}")
            if own in ("io", "scene") and module in ("analysis", "solve"):
                findings.append(f"include {rel} -> gyrokit/{module}/{rest}")
            if own in ("solve", "numerics", "models", "eig", "core") and module in ("analysis", "study"):
                findings.append(f"include {rel} -> gyrokit/{module}/{rest}")
    for path in sorted(lib.rglob("*.[ch]pp")):
        rel = path.relative_to(root).as_posix()
        count = len(path.read_text().rstrip("\n").split("\n"))
        if count > MAX_FILE_LINES:
            findings.append(f"length {rel}")
            print(f"note: {rel}: {count} lines (at most {MAX_FILE_LINES})")
        for name, first, last in functions(path):
            if last - first + 1 > MAX_FUNCTION_LINES:
                findings.append(f"function {rel} {name}")
                print(f"note: {rel}:{first}: {name} has {last - first + 1} lines (at most {MAX_FUNCTION_LINES})")
    # Rule 5: one of each, searched in the code (comments and literals aside).
    one_of = [("pi", re.compile(r"\bM_PI\b|3\.14159|acos\(-1"), "lib/gyrokit/core/constants.hpp", True),
              ("thread", re.compile(r"std::j?thread\b(?!::)"),
               "lib/gyrokit/core/parallel.cpp", False),
              ("csv quoting", re.compile(r'find_first_of\(",\\"'), "lib/gyrokit/io/csv.cpp", True)]
    for path in sorted(p for d in ("lib", "apps", "python") for p in (root / d).rglob("*.[ch]pp")):
        rel = path.relative_to(root).as_posix()
        in_block = False
        for number, raw in enumerate(path.read_text().split("\n"), 1):
            code, in_block = code_only(raw, in_block)
            for what, pattern, home, literal in one_of:
                if rel != home and pattern.search(raw if literal else code):
                    if literal and raw.lstrip().startswith("//"):
                        continue
                    findings.append(f"one {what}: {rel}:{number} (its one place: {home})")
    cmake = (root / "lib" / "CMakeLists.txt").read_text()
    listed = set(re.findall(r"\bgyrokit/[\w/]+\.cpp\b", cmake))
    present = {p.relative_to(root / "lib").as_posix() for p in lib.rglob("*.cpp")}
    findings += [f"unlisted lib/{p} (not in lib/CMakeLists.txt: it would not be built)" for p in sorted(present - listed)]
    findings += [f"missing lib/{p} (listed in lib/CMakeLists.txt)" for p in sorted(listed - present)]
    # Rule 6: the C++ tests mirror lib/gyrokit (bench/ mirrors apps/bench), each listed in tests/CMakeLists.txt.
    tests = root / "tests"
    mirrors = {d.name for d in lib.iterdir() if d.is_dir()} | {"bench"}
    test_cmake = (tests / "CMakeLists.txt").read_text()
    listed = set(re.findall(r"^\s+([\w/]*test_\w+\.cpp)\s*$", test_cmake, re.M))
    present = {p.relative_to(tests).as_posix() for p in tests.rglob("test_*.cpp")
               if p.relative_to(tests).parts[0] not in ("fuzz", "python")}
    findings += [f"unlisted tests/{p} (not in tests/CMakeLists.txt: it would not run)" for p in sorted(present - listed)]
    findings += [f"missing tests/{p} (listed in tests/CMakeLists.txt)" for p in sorted(listed - present)]
    for p in sorted(present):
        folder = p.split("/")[0] if "/" in p else ""
        if p.count("/") > 1:
            findings.append(f"test tests/{p} lies below tests/{folder}/: the tests of a module sit in its folder")
        elif folder and folder not in mirrors:
            findings.append(f"test folder tests/{folder} mirrors no module of lib/gyrokit")
        if not folder and p != "test_main.cpp":
            findings.append(f"test tests/{p} lies outside the folders that mirror lib/gyrokit")
    bad = [f for f in findings if f not in KNOWN]
    stale = [k for k in KNOWN if k not in findings]
    for f in bad:
        print(f"FAIL: {f}")
    for k in stale:
        print(f"FAIL: KNOWN lists '{k}', which no longer applies: take it off the list")
    known = len(findings) - len(bad)
    print(f"{len(findings)} findings, {known} of them known and pending ({len(KNOWN)} listed)")
    return 1 if bad or stale else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1] if len(sys.argv) > 1 else "."))
