#!/usr/bin/env python3
"""Checks that the documentation and the code have not drifted apart (issue 23).

Usage: /usr/bin/python3 test/docs/check_docs.py [REPO_ROOT]
Standard library only; nothing needs to be built. Exit 0 and a one-line summary when everything
checks out; exit 1 and one line per problem otherwise.

What it checks:
 (a) links: every relative link and image in every *.md of the repository (README.md, doc/**,
     fuzz/...; hidden folders are skipped) resolves to a file or folder inside the repository, and
     every #anchor (same file or another .md) is the GitHub slug of a heading there (or an explicit
     <a name/id>).
 (b) display properties: every rviz property the code creates (src/displays/*.cpp and
     include/rviz_projector/displays/*.h: `new rviz::XxxProperty("Name", default, ...)`, helper
     functions that wrap it, DisplayGroupVisibilityProperty, and the properties rviz's
     MessageFilterDisplay adds) appears in doc/reference/displays.md under its display, as a row
     `| Parent → Name | default | meaning |`, with the default the code sets (symbolic defaults such
     as `defaults.arrow.shaft_length` or `path_style::kDefaultAlpha` are resolved from the headers);
     enum options are named in the row; and every row of those tables is a property the code
     creates. Fewer than 40 properties found is a failure (a broken parser must not pass).
 (c) tools: every executable of the CMake files and every launch file has a section in
     doc/reference/tools.md; every option a tool's --help prints and every option its parser accepts
     is in the first column of the section's `| Option | ... |` table. The options come from the help
     text in the source (the function holding the usage text, in the source files with "--help") and,
     when RP_TOOL_BIN_DIR names a folder holding the built tool, also from running `<tool> --help`
     (the summary says which). Every private parameter (~name) a node reads is in a `| Parameter |`
     table, every argument a user can set in a launch file in an `| Argument |` table.
 (d) the source map: every file of src/ and include/ is named in doc/dev/architecture.md.
 (e) file references: every repository path written as inline code (`src/...`, `config/...`, ...)
     in README.md, doc/guide, doc/reference and doc/dev exists.
 (f) the README keeps the commands CI runs: `scripts/test` and `scripts/test --sanitize`.
 (g) references to the docs from everything else (comments and help texts in src/, include/,
     launch/, config/, rviz/, scripts/, test/, bench/, .ci/): every `doc/....md` or `README.md`
     named with a #anchor, or `doc/....md` alone, exists and has that heading.

Layout: this file is the entry point; the checks live beside it in docs_checks/ (one module a job:
common, links, cpp, properties, property_docs, tools, files; see docs_checks/__init__.py).
"""
import os
import sys
import traceback

sys.dont_write_bytecode = True  # run from the source tree: leave no __pycache__ in it
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from docs_checks.common import counts, notes, option_sources, problem, problems  # noqa: E402
from docs_checks.cpp import Sources  # noqa: E402
from docs_checks.files import check_doc_references, check_paths, check_readme_commands, check_source_map  # noqa: E402
from docs_checks.links import check_links  # noqa: E402
from docs_checks.property_docs import check_properties  # noqa: E402
from docs_checks.tools import check_tools  # noqa: E402


def main():
    root = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
    sources = Sources(root)
    for part in (lambda: check_links(root), lambda: check_properties(root, sources), lambda: check_tools(root, sources),
                 lambda: check_source_map(root), lambda: check_paths(root), lambda: check_readme_commands(root),
                 lambda: check_doc_references(root)):
        try:
            part()
        except Exception as e:  # a crash of the checker is a failure with its reason, never a pass
            problem("the docs test crashed: %s: %s\n%s" % (type(e).__name__, e, traceback.format_exc()))
    summary = ", ".join("%d %s" % (v, k) for k, v in counts.items())
    summary += "; tool options from: " + (", ".join("%s %s" % kv for kv in sorted(option_sources.items())) or "none")
    if problems:
        for note in notes:
            print("  " + note)
        for p in problems:
            print("PROBLEM " + p)
        print("docs check: %d problems (%s)" % (len(problems), summary))
        return 1
    print("docs check: ok (%s)" % summary)
    return 0


if __name__ == "__main__":
    sys.exit(main())
