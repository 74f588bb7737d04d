"""(b) The display properties the code creates against the `| Property | Default | Meaning |` tables
of doc/reference/displays.md: every property has its row with the code's default and enum options,
and every row is a property the code creates."""
import os
import re

from .common import counts, markdown_tables, notes, plain, problem, read, sections
from .cpp import Resolver
from .properties import display_classes, find_properties

MIN_PROPERTIES = 40
DOC_DISPLAYS = "doc/reference/displays.md"


def describe(value):
    if value is Resolver.NONE:
        return "— (no value)"
    if isinstance(value, bool):
        return "on" if value else "off"
    if isinstance(value, tuple):
        return "%d; %d; %d" % value
    if isinstance(value, float):
        return "%g" % value
    if value == "":
        return "*(empty)*"
    return "`%s`" % value


def default_matches(value, cell):
    text = cell.strip()
    bare = plain(text.replace("`", ""))
    if value is Resolver.NONE:
        return bare in ("—", "-", "(none)", "")
    if isinstance(value, bool):
        word = (re.findall(r"[A-Za-z]+", bare) or [""])[0].lower()
        return (word in ("on", "true", "ticked", "yes")) if value else (word in ("off", "false", "unticked", "no"))
    if isinstance(value, tuple):
        m = re.search(r"(\d+)\s*;\s*(\d+)\s*;\s*(\d+)", bare)
        return bool(m) and tuple(int(g) for g in m.groups()) == value
    if isinstance(value, (int, float)):
        m = re.search(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?", bare)
        if not m:
            return False
        number = float(m.group(0))
        return abs(number - value) <= 1e-6 * max(1.0, abs(value))
    # a string
    if value == "":
        return bare.startswith("(empty)") or bare == ""
    m = re.match(r"^`([^`]*)`", text)
    if m:
        return m.group(1) == value
    return re.split(r"\s+\(|\s+—", bare)[0].strip() == value


def check_properties(root, sources):
    resolver = Resolver(sources)
    found = find_properties(root, sources, resolver)
    ours = counts.get("display properties in src/displays", 0)
    notes.append("display properties: %d created by the code of src/displays (+ %d from rviz's MessageFilterDisplay)"
                 % (ours, len(found) - ours))
    if ours < MIN_PROPERTIES:
        problem("only %d display properties found in src/displays (at least %d expected): the docs test's parser "
                "is broken, or the code changed its way of creating properties" % (ours, MIN_PROPERTIES))
    doc_path = os.path.join(root, DOC_DISPLAYS)
    if not os.path.exists(doc_path):
        problem("%s does not exist" % DOC_DISPLAYS)
        return
    doc_sections = sections(read(doc_path), 2)
    rows = {}  # (display, parent, name) -> (line, default cell, meaning cell)
    displays = sorted({f.display for f in found} | set(display_classes(root).values()))
    for display in displays:
        titles = [t for t in doc_sections if re.sub(r"[`*]", "", t).strip() == display]
        if not titles:
            problem("%s: no section '## %s'" % (DOC_DISPLAYS, display))
            continue
        for header, table_rows in markdown_tables(doc_sections[titles[0]]):
            if not header or plain(header[0]).lower() != "property":
                continue
            for number, row in table_rows:
                if len(row) < 3:
                    problem("%s:%d: a property row needs | Property | Default | Meaning |" % (DOC_DISPLAYS, number))
                    continue
                path = [plain(p) for p in row[0].split("→")]
                key = (display, path[-2] if len(path) > 1 else "", path[-1])
                if key in rows:
                    problem("%s:%d: '%s' is listed twice under %s" % (DOC_DISPLAYS, number, row[0], display))
                rows[key] = (number, row[1], row[2], row[0])
    used = set()
    for f in found:
        key = f.key()
        where = "%s:%d" % (f.path, f.line) if f.line else f.path
        entry = rows.get(key)
        if entry is None:
            label = ("%s → %s" % (f.parent, f.name)) if f.parent else f.name
            problem("%s property '%s' (%s, default %s) is missing from %s (a row | %s | default | meaning | under "
                    "## %s)" % (f.display, label, where, describe(f.default), DOC_DISPLAYS, label, f.display))
            continue
        used.add(key)
        number, default_cell, meaning, _ = entry
        if not default_matches(f.default, default_cell):
            problem("%s:%d: %s '%s': the default column says '%s', the code (%s) sets %s"
                    % (DOC_DISPLAYS, number, f.display, f.name, default_cell, where, describe(f.default)))
        for option in f.options:
            if isinstance(option, str) and not re.search(r"(?<!\w)%s(?!\w)" % re.escape(option), plain(meaning)):
                problem("%s:%d: %s '%s': option '%s' (%s) is not described in the row"
                        % (DOC_DISPLAYS, number, f.display, f.name, option, where))
    for key, (number, _, _, label) in sorted(rows.items(), key=lambda kv: kv[1][0]):
        if key not in used:
            problem("%s:%d: '%s' under %s is not a property the code creates (renamed or removed?)"
                    % (DOC_DISPLAYS, number, label, key[0]))
    counts["display properties checked"] = len(found)
