"""(d) the source map names every file of src/ and include/; (e) the repository paths written in the
maintained docs exist; (f) the README keeps the commands CI runs; (g) the references to the docs
from the code, scripts and configs exist and have their anchors."""
import os
import re

from .common import anchors, code_spans, counts, markdown_files, problem, read, rel, split_fences

DOC_ARCHITECTURE = "doc/dev/architecture.md"
MAINTAINED_DOCS = ("README.md", "doc/guide", "doc/reference", "doc/dev")
# The docs test itself (its entry point and this package) names the docs it checks: not references.
PACKAGE_DIR = os.path.dirname(os.path.abspath(__file__))
ENTRY_POINT = os.path.join(os.path.dirname(PACKAGE_DIR), "check_docs.py")


def check_source_map(root):
    path = os.path.join(root, DOC_ARCHITECTURE)
    if not os.path.exists(path):
        problem("%s does not exist" % DOC_ARCHITECTURE)
        return
    text = read(path)
    n = 0
    for top in ("src", "include"):
        for folder, _, files in os.walk(os.path.join(root, top)):
            for f in sorted(files):
                if not f.endswith((".cpp", ".h", ".hpp")):
                    continue
                n += 1
                stem = os.path.splitext(f)[0]
                if not re.search(r"(?<![\w/])%s(?![\w])" % re.escape(stem), text):
                    problem("%s: %s is not named in the source map" % (DOC_ARCHITECTURE, rel(root, os.path.join(folder, f))))
    counts["source files mapped"] = n


def check_paths(root):
    tops = {e for e in os.listdir(root) if os.path.isdir(os.path.join(root, e)) and e != ".git"}
    checked = 0
    for path in markdown_files(root):
        relative = rel(root, path)
        if not any(relative == d or relative.startswith(d + os.sep) for d in MAINTAINED_DOCS):
            continue
        for number, line, fenced in split_fences(read(path)):
            if fenced:
                continue
            for span in code_spans(line):
                for word in span.split():
                    word = word.rstrip(".,;:)")
                    word = re.sub(r":\d+$", "", word)
                    first = word.split("/")[0]
                    if "/" not in word or first not in tops or re.search(r"[*<>{}$…]|\.\.\.", word):
                        continue
                    checked += 1
                    if not os.path.exists(os.path.join(root, word)):
                        problem("%s:%d: `%s` does not exist" % (relative, number, word))
    counts["file references"] = checked


DOC_REFERENCE = re.compile(r"(?<![\w/.-])((?:doc/[\w./-]+?\.md|README\.md)(?:#[\w-]*[\w])?)(?![\w/-])")


def check_doc_references(root):
    checked = 0
    for top in ("src", "include", "launch", "config", "rviz", "scripts", "test", "bench", ".ci", "cmake"):
        for folder, dirs, files in os.walk(os.path.join(root, top)):
            dirs[:] = [d for d in dirs if d != "__pycache__"]
            for f in sorted(files):
                path = os.path.join(folder, f)
                if f.endswith((".md", ".png", ".pyc")) or path == ENTRY_POINT \
                        or os.path.dirname(path) == PACKAGE_DIR:
                    continue
                try:
                    text = read(path)
                except (UnicodeDecodeError, OSError):
                    continue
                for number, line in enumerate(text.split("\n"), 1):
                    for m in DOC_REFERENCE.finditer(line):
                        target, _, anchor = m.group(1).partition("#")
                        if target == "README.md" and not anchor:
                            continue  # "the README" of some other tool, or ours without a place
                        checked += 1
                        where = "%s:%d: '%s'" % (rel(root, path), number, m.group(1))
                        resolved = os.path.join(root, target)
                        if not os.path.exists(resolved):
                            problem("%s: %s does not exist" % (where, target))
                        elif anchor and anchor not in anchors(resolved):
                            problem("%s: no heading with the anchor #%s in %s" % (where, anchor, target))
    counts["references from code"] = checked


def check_readme_commands(root):
    text = read(os.path.join(root, "README.md"))
    lines = [l.split("#")[0].strip() for _, l, fenced in split_fences(text) if fenced]
    for command in ("scripts/test", "scripts/test --sanitize"):
        if command not in lines:
            problem("README.md: no code line '%s' (the command CI runs, .ci/run)" % command)
