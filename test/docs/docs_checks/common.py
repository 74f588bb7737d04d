"""What every part of the docs test shares: the problems, notes and counts of a run, reading files,
and Markdown (fenced code, code spans, headings and their GitHub anchors, pipe tables, sections)."""
import os
import re

problems = []
notes = []
counts = {}
option_sources = {}  # tool -> "source", "source+binary" or "source (no binary)"


def problem(text):
    problems.append(text)


def read(path):
    with open(path, encoding="utf-8") as f:
        return f.read()


def rel(root, path):
    return os.path.relpath(path, root)


# ---- Markdown ----------------------------------------------------------------------------------

FENCE = re.compile(r"^\s*(```|~~~)")


def split_fences(text):
    """[(line_number, line, in_fence)] of a Markdown text."""
    out = []
    fence = None
    for number, line in enumerate(text.split("\n"), 1):
        m = FENCE.match(line)
        if m:
            if fence is None:
                fence = m.group(1)
                out.append((number, line, True))
                continue
            if m.group(1) == fence:
                fence = None
                out.append((number, line, True))
                continue
        out.append((number, line, fence is not None))
    return out


def code_spans(line):
    """The inline code spans of a line (handles `` spans too)."""
    return [m.group(2) for m in re.finditer(r"(`+)(.+?)\1", line)]


def without_code_spans(line):
    return re.sub(r"(`+)(.+?)\1", " ", line)


def slug(heading):
    """GitHub's anchor for a heading's text."""
    text = re.sub(r"!\[([^\]]*)\]\([^)]*\)", r"\1", heading)
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", text)
    text = re.sub(r"<[^>]+>", "", text)
    text = text.replace("`", "")
    text = re.sub(r"(?<!\w)_(.+?)_(?!\w)", r"\1", text)
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def headings(text):
    """[(level, text)] of the ATX and setext headings outside fenced code."""
    out = []
    lines = split_fences(text)
    for i, (_, line, fenced) in enumerate(lines):
        if fenced:
            continue
        m = re.match(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m:
            out.append((len(m.group(1)), m.group(2)))
            continue
        if i + 1 < len(lines) and line.strip() and not lines[i + 1][2]:
            underline = lines[i + 1][1]
            if re.match(r"^ {0,3}=+\s*$", underline):
                out.append((1, line.strip()))
            elif re.match(r"^ {0,3}-+\s*$", underline) and not line.lstrip().startswith(("-", "*", "|")):
                out.append((2, line.strip()))
    return out


_anchor_cache = {}


def anchors(path):
    if path not in _anchor_cache:
        text = read(path)
        seen = {}
        result = set()
        for _, heading in headings(text):
            base = slug(heading)
            n = seen.get(base, 0)
            seen[base] = n + 1
            result.add(base if n == 0 else "%s-%d" % (base, n))
        for m in re.finditer(r"<a\s+[^>]*(?:name|id)\s*=\s*\"([^\"]+)\"", text):
            result.add(m.group(1))
        _anchor_cache[path] = result
    return _anchor_cache[path]


def markdown_files(root):
    out = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in ("node_modules", "build", "devel"))
        out += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    return out


def markdown_tables(lines):
    """[(header cells, [(line number, cells)])] of the pipe tables in (number, line, fenced) lines."""
    tables = []
    i = 0
    while i < len(lines):
        number, line, fenced = lines[i]
        if not fenced and line.lstrip().startswith("|") and i + 1 < len(lines) and \
                re.match(r"^\s*\|?\s*:?-{3,}", lines[i + 1][1]):
            header = cells(line)
            rows = []
            i += 2
            while i < len(lines) and lines[i][1].lstrip().startswith("|") and not lines[i][2]:
                rows.append((lines[i][0], cells(lines[i][1])))
                i += 1
            tables.append((header, rows))
            continue
        i += 1
    return tables


def cells(line):
    line = line.strip()
    if line.startswith("|"):
        line = line[1:]
    if line.endswith("|"):
        line = line[:-1]
    parts, current, code = [], "", False
    i = 0
    while i < len(line):
        c = line[i]
        if c == "`":
            code = not code
        if c == "\\" and i + 1 < len(line) and line[i + 1] == "|":
            current += "|"
            i += 2
            continue
        if c == "|" and not code:
            parts.append(current.strip())
            current = ""
        else:
            current += c
        i += 1
    parts.append(current.strip())
    return parts


def sections(text, level):
    """{heading text: [(number, line, fenced)]} of the sections at `level` (until the next heading of
    that level or higher)."""
    out = {}
    current = None
    for number, line, fenced in split_fences(text):
        m = None if fenced else re.match(r"^(#{1,6})\s+(.*?)\s*#*\s*$", line)
        if m and len(m.group(1)) <= level:
            current = m.group(2).strip() if len(m.group(1)) == level else None
            if current is not None:
                out[current] = []
            continue
        if current is not None:
            out[current].append((number, line, fenced))
    return out


def plain(cell):
    return re.sub(r"[*_]", "", cell).strip()
