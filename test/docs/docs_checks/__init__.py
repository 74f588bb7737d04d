"""The parts of the docs test (test/docs/check_docs.py, the entry point), one job a module:

 common         the problems, notes and counts a run collects; reading files; Markdown (fenced code,
                code spans, headings and their anchors, pipe tables, sections)
 links          (a) relative links and #anchors of every *.md
 cpp            reading C++: comments stripped, brackets and arguments, string literals, the sources
                of src/ and include/, and the resolver of default-value expressions
 properties     (b) the rviz properties the displays' code creates
 property_docs  (b) those properties against the tables of doc/reference/displays.md
 tools          (c) options, node parameters and launch arguments against doc/reference/tools.md
 files          (d) the source map, (e) file references, (f) the README's CI commands,
                (g) references to the docs from everything else
"""
