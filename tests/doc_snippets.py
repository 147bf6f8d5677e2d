"""Writes the ```cpp blocks of docs/*.md as one program against the installed gyrokit: the
blocks of each page, in order, are the body of one function (a page's snippets build on each
other), their #include lines at the top, after the context the snippets assume (`system` and
`speeds` of data/fe_rotor.toml, `use` for what they read); main runs every page's function and
names the page that fails. One program: one compile of the headers.
Usage: doc_snippets.py SOURCE_DIR OUT_FILE"""
import os
import re
import sys

HEAD = """#include <gyrokit/gyrokit.hpp>
#include <exception>
#include <iostream>
{includes}
// The context of the documentation's snippets.
template <class... T> void use(const T&...) {{}}
"""

PAGE = """
void page_{name}() {{
    const gyrokit::Scene doc_scene = gyrokit::load_scene("data/fe_rotor.toml");
    const gyrokit::GyroscopicSystem& system = doc_scene.system;
    const std::vector<double> speeds = doc_scene.speeds->points();
    (void)system;
    (void)speeds;
{body}
}}
"""

MAIN = """
int main() {{
    const char* page = "";
    try {{
{calls}
    }} catch (const std::exception& e) {{
        std::cerr << "docs/" << page << ".md: " << e.what() << "\\n";
        return 1;
    }}
    return 0;
}}
"""


def main():
    src, out = sys.argv[1], sys.argv[2]
    includes, pages = set(), []
    for name in sorted(os.listdir(os.path.join(src, "docs"))):
        if not name.endswith(".md"):
            continue
        blocks = re.findall(r"```cpp\n(.*?)```", open(os.path.join(src, "docs", name)).read(), re.S)
        if not blocks:
            continue
        lines = [x for b in blocks for x in b.splitlines()]
        includes.update(x for x in lines if x.startswith("#include"))
        pages.append((name[:-3], "\n".join("    " + x for x in lines if not x.startswith("#include"))))
    text = HEAD.format(includes="\n".join(sorted(includes)))
    text += "".join(PAGE.format(name=n, body=b) for n, b in pages)
    text += MAIN.format(calls="\n".join(f'        page = "{n}";\n        page_{n}();\n'
                                           f'        std::cout << "docs/{n}.md: its C++ ran\\n";' for n, _ in pages))
    open(out, "w").write(text)


if __name__ == "__main__":
    main()
