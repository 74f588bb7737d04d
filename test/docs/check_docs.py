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
"""
import ast
import os
import re
import subprocess
import sys
import traceback
import urllib.parse

MIN_PROPERTIES = 40
DOC_DISPLAYS = "doc/reference/displays.md"
DOC_TOOLS = "doc/reference/tools.md"
DOC_ARCHITECTURE = "doc/dev/architecture.md"
MAINTAINED_DOCS = ("README.md", "doc/guide", "doc/reference", "doc/dev")

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


LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")


def markdown_files(root):
    out = []
    for folder, dirs, files in os.walk(root):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in ("node_modules", "build", "devel"))
        out += [os.path.join(folder, f) for f in sorted(files) if f.endswith(".md")]
    return out


def check_links(root):
    links = anchored = 0
    for path in markdown_files(root):
        for number, line, fenced in split_fences(read(path)):
            if fenced:
                continue
            plain = without_code_spans(line)
            targets = [m.group(1) for m in LINK.finditer(plain)]
            m = REFERENCE.match(plain)
            if m:
                targets.append(m.group(1))
            for target in targets:
                target = target.strip("<>")
                if re.match(r"^[A-Za-z][A-Za-z0-9+.-]*:", target):
                    continue  # http:, https:, mailto:, ...
                links += 1
                where = "%s:%d: link '%s'" % (rel(root, path), number, target)
                file_part, _, anchor = target.partition("#")
                file_part = urllib.parse.unquote(file_part)
                if file_part:
                    base = root if file_part.startswith("/") else os.path.dirname(path)
                    resolved = os.path.normpath(os.path.join(base, file_part.lstrip("/")))
                else:
                    resolved = path
                if not (resolved + os.sep).startswith(os.path.abspath(root) + os.sep) and resolved != os.path.abspath(root):
                    problem("%s leaves the repository" % where)
                    continue
                if not os.path.exists(resolved):
                    problem("%s: %s does not exist" % (where, rel(root, resolved)))
                    continue
                if anchor and resolved.endswith(".md"):
                    anchored += 1
                    if anchor not in anchors(resolved):
                        problem("%s: no heading with the anchor #%s in %s" % (where, anchor, rel(root, resolved)))
    counts["links"] = links
    counts["anchors"] = anchored


# ---- C++ ---------------------------------------------------------------------------------------


def strip_comments(code):
    """`code` with comments blanked out (string and character literals kept, line numbers kept)."""
    out = []
    i, n = 0, len(code)
    while i < n:
        c = code[i]
        if c == "/" and code.startswith("//", i):
            j = code.find("\n", i)
            j = n if j < 0 else j
            out.append(" " * (j - i))
            i = j
        elif c == "/" and code.startswith("/*", i):
            j = code.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(re.sub(r"[^\n]", " ", code[i:j]))
            i = j
        elif c in "\"'":
            if c == '"' and i > 0 and code[i - 1] == "R":  # raw string R"(...)"
                m = re.match(r'"([^(\s]*)\(', code[i:])
                if m:
                    end = code.find(")" + m.group(1) + '"', i)
                    end = n if end < 0 else end + len(m.group(1)) + 2
                    out.append(code[i:end])
                    i = end
                    continue
            j = i + 1
            while j < n and code[j] != c:
                j += 2 if code[j] == "\\" else 1
            out.append(code[i:j + 1])
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out)


def after_string(text, i):
    """Index just past the string or character literal that opens at text[i] (escapes skipped)."""
    quote = text[i]
    j = i + 1
    while j < len(text) and text[j] != quote:
        j += 2 if text[j] == "\\" else 1
    return j + 1


def matching(code, open_index, open_char="(", close_char=")"):
    """Index of the bracket closing the one at open_index (strings skipped)."""
    depth = 0
    i = open_index
    while i < len(code):
        c = code[i]
        if c in "\"'":
            i = after_string(code, i)
            continue
        if c == open_char:
            depth += 1
        elif c == close_char:
            depth -= 1
            if depth == 0:
                return i
        i += 1
    return -1


def split_args(text):
    """Top-level comma-separated arguments of an argument list's inside."""
    args, depth, start, i = [], 0, 0, 0
    while i < len(text):
        c = text[i]
        if c in "\"'":
            i = after_string(text, i)
            continue
        if c in "([{<":
            # '<' only opens a template argument list right after a name (static_cast<float>)
            if c != "<" or re.search(r"[A-Za-z_]\s*$", text[:i]) and re.match(r"<\s*[\w:]+\s*[>,*&]", text[i:]):
                depth += 1
        elif c in ")]}>":
            if c != ">" or depth > 0 and re.search(r"<\s*[\w:]+\s*$", text[:i]):
                depth -= 1
        elif c == "," and depth == 0:
            args.append(text[start:i].strip())
            start = i + 1
        i += 1
    last = text[start:].strip()
    if last or args:
        args.append(last)
    return args


STRING_LITERALS = re.compile(r'"((?:[^"\\]|\\.)*)"')


def literal_string(expr):
    """The value of a (possibly concatenated) string literal expression, else None."""
    expr = expr.strip()
    if not expr.startswith('"'):
        return None
    rest = STRING_LITERALS.sub("", expr)
    if rest.strip():
        return None
    return "".join(bytes(s, "utf-8").decode("unicode_escape") if "\\" in s else s for s in STRING_LITERALS.findall(expr))


def line_of(code, index):
    return code.count("\n", 0, index) + 1


class Sources:
    """The package's C++ sources, comment-free, and what can be looked up in them."""

    def __init__(self, root):
        self.root = root
        self.files = {}
        for top in ("src", "include"):
            for folder, _, files in os.walk(os.path.join(root, top)):
                for f in sorted(files):
                    if f.endswith((".cpp", ".h", ".hpp")):
                        path = os.path.join(folder, f)
                        self.files[path] = strip_comments(read(path))

    def scope_body(self, name):
        """Bodies of the class/struct/namespace `name` (possibly several)."""
        out = []
        for path, code in self.files.items():
            for m in re.finditer(r"\b(?:class|struct|namespace)\s+%s\b[^;{]*\{" % re.escape(name), code):
                end = matching(code, m.end() - 1, "{", "}")
                if end > 0:
                    out.append((path, code[m.end():end]))
        return out

    def constant_definitions(self, name, text_only=None):
        """[(path, expression)] of `constexpr ... name = expression;` definitions."""
        pattern = re.compile(r"\bconstexpr\b[^;=(){}]*?\b%s\s*=\s*([^;]+);" % re.escape(name))
        out = []
        items = text_only if text_only is not None else self.files.items()
        for path, code in items:
            out += [(path, m.group(1).strip()) for m in pattern.finditer(code)]
        return out

    def struct_member(self, struct, member):
        """(type, default expression or None) of a data member of `struct`."""
        for _, body in self.scope_body(struct):
            m = re.search(r"(?:^|[;{}]\s*)\s*([\w:<>]+)\s+%s\s*(?:=\s*([^;{]+)|\{([^}]*)\})?\s*;" % re.escape(member),
                          body, re.M)
            if m:
                return m.group(1), (m.group(2) or m.group(3))
        return None


class Resolver:
    """Turns a default-value expression of the code into a value: str, bool, float, colour
    (r, g, b), or NONE (a property without a value)."""

    NONE = ("no value",)

    def __init__(self, sources):
        self.sources = sources

    def value(self, expr, path, code, depth=0):
        expr = expr.strip()
        if depth > 12:
            raise ValueError("too deeply nested")
        m = re.match(r"^static_cast<[\w:\s]+>\((.*)\)$", expr, re.S)
        if m:
            return self.value(m.group(1), path, code, depth + 1)
        m = re.match(r"^QString(?:::fromStdString)?\((.*)\)$", expr, re.S)
        if m:
            return self.value(m.group(1), path, code, depth + 1)
        if expr in ("QVariant()", "QVariant{}"):
            return self.NONE
        text = literal_string(expr)
        if text is not None:
            return text
        if expr in ("true", "false"):
            return expr == "true"
        m = re.match(r"^QColor\(\s*(\d+)\s*,\s*(\d+)\s*,\s*(\d+)\s*(?:,\s*\d+\s*)?\)$", expr)
        if m:
            return tuple(int(g) for g in m.groups())
        # An arithmetic expression of numbers and names.
        names = {}

        def name_value(name):
            if name not in names:
                names[name] = self.name(name, path, code, depth + 1)
            return names[name]

        tokens = re.findall(r"[A-Za-z_][\w]*(?:(?:::|\.|->)[A-Za-z_]\w*)*|\d+\.?\d*(?:[eE][-+]?\d+)?[fFlLuU]*|\.\d+[fF]?|\S", expr)
        if len(tokens) == 1 and re.match(r"[A-Za-z_]", tokens[0]):
            return name_value(tokens[0])
        pieces = []
        for t in tokens:
            if re.match(r"^[A-Za-z_]", t):
                v = name_value(t)
                if isinstance(v, bool) or not isinstance(v, (int, float)):
                    raise ValueError("'%s' is not a number" % t)
                pieces.append(repr(float(v)))
            elif re.match(r"^\.?\d", t):
                pieces.append(t.rstrip("fFlLuU"))
            elif t in "+-*/()":
                pieces.append(t)
            else:
                raise ValueError("cannot evaluate '%s'" % expr)
        return evaluate(" ".join(pieces))

    def name(self, name, path, code, depth):
        parts = re.split(r"::|\.|->", name)
        if len(parts) == 1:
            return self.unqualified(name, path, code, depth)
        if "::" in name:
            scope, member = name.rsplit("::", 1)
            scope = scope.split("::")[-1]
            errors = []
            for scope_path, body in self.sources.scope_body(scope):
                for where, expr in self.sources.constant_definitions(member, [(scope_path, body)]):
                    if re.match(r"^[\w:]*::%s$" % re.escape(member), expr):
                        continue  # an alias of a class to the namespace's constant of the same name
                    try:
                        return self.value(expr, where, self.sources.files[where], depth + 1)
                    except ValueError as e:
                        errors.append(str(e))
            raise ValueError("'%s' not found%s" % (name, (": " + "; ".join(errors)) if errors else ""))
        # object.member.member: the object's type from its declaration in this file.
        obj = parts[0]
        m = re.search(r"\b(?:const\s+)?([\w:]+)\s+%s\s*(?:;|\{|\(|=)" % re.escape(obj), code)
        if not m:
            raise ValueError("the type of '%s' is not declared in %s" % (obj, os.path.basename(path)))
        struct = m.group(1).split("::")[-1]
        for member in parts[1:]:
            found = self.sources.struct_member(struct, member)
            if not found:
                raise ValueError("'%s' has no member '%s'" % (struct, member))
            member_type, default = found
            struct = member_type.split("::")[-1]
        if default is None:
            raise ValueError("'%s' has no default" % name)
        return self.value(default, path, code, depth + 1)

    def unqualified(self, name, path, code, depth):
        if name == "kPi" or name == "M_PI":
            return 3.14159265358979323846
        local = self.sources.constant_definitions(name, [(path, code)])
        if not local:
            # The header that belongs to this file (foo.cpp -> foo.h) first, then every file.
            stem = os.path.splitext(os.path.basename(path))[0]
            mine = [(p, c) for p, c in self.sources.files.items() if os.path.splitext(os.path.basename(p))[0] == stem]
            local = self.sources.constant_definitions(name, mine) or self.sources.constant_definitions(name)
        values = {}
        for where, expr in local:
            values[repr(self.value(expr, where, self.sources.files[where], depth + 1))] = where
        if not values:
            raise ValueError("'%s' not found" % name)
        if len(values) > 1:
            raise ValueError("'%s' is defined with different values (%s)" % (name, ", ".join(sorted(values))))
        where = list(values.values())[0]
        return self.value(local[0][1], where, self.sources.files[where], depth + 1)


def evaluate(expression):
    tree = ast.parse(expression, mode="eval")

    def ev(node):
        if isinstance(node, ast.Expression):
            return ev(node.body)
        if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
            return float(node.value)
        if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
            return -ev(node.operand) if isinstance(node.op, ast.USub) else ev(node.operand)
        if isinstance(node, ast.BinOp) and isinstance(node.op, (ast.Add, ast.Sub, ast.Mult, ast.Div)):
            a, b = ev(node.left), ev(node.right)
            return {ast.Add: a + b, ast.Sub: a - b, ast.Mult: a * b, ast.Div: a / b if b else float("nan")}[type(node.op)]
        raise ValueError("cannot evaluate '%s'" % expression)

    return ev(tree)


# (name argument, default argument, parent argument) of rviz's property constructors. None as the
# parent: the display itself.
SIGNATURES = {
    "Property": (0, 1, 3),
    "BoolProperty": (0, 1, 3),
    "FloatProperty": (0, 1, 3),
    "IntProperty": (0, 1, 3),
    "StringProperty": (0, 1, 3),
    "ColorProperty": (0, 1, 3),
    "EnumProperty": (0, 1, 3),
    "EditableEnumProperty": (0, 1, 3),
    "VectorProperty": (0, 1, 3),
    "QuaternionProperty": (0, 1, 3),
    "FilePathProperty": (0, 1, 3),
    "RosTopicProperty": (0, 1, 4),
    "TfFrameProperty": (0, 1, 3),
    "DisplayGroupVisibilityProperty": (3, 4, None),
}
NOT_USER_PROPERTIES = {"StatusProperty", "StatusList"}
TOP_LEVEL_PARENTS = {"this", "display", "parent_display", "nullptr", "NULL"}


class Found:
    def __init__(self, display, name, parent, default, path, line, options=()):
        self.display, self.name, self.parent, self.default = display, name, parent, default
        self.path, self.line, self.options = path, line, list(options)

    def key(self):
        return (self.display, self.parent or "", self.name)


def display_classes(root):
    """{class name (ProjectedPathDisplay): short name (ProjectedPath)} from plugin_description.xml."""
    text = read(os.path.join(root, "plugin_description.xml"))
    out = {}
    for m in re.finditer(r'<class\s+name="[^"/]+/(\w+)"\s+type="(?:\w+::)*(\w+)"', text):
        out[m.group(2)] = m.group(1)
    return out


def find_properties(root, sources, resolver):
    displays = display_classes(root)
    if not displays:
        problem("plugin_description.xml: no display classes found")
    folder_src = os.path.join(root, "src", "displays")
    folder_inc = os.path.join(root, "include", "rviz_projector", "displays")
    files = [p for p in sources.files if os.path.dirname(p) in (folder_src, folder_inc)]

    def owner(path):
        """The display a file's properties belong to."""
        code = sources.files[path]
        classes = set(re.findall(r"\b(\w+)::\1\s*\(", code))
        classes |= set(re.findall(r"\b(\w+)::\w+\s*\([^;{]*\)\s*(?:const\s*)?\{", code))
        for c in classes:
            if c in displays:
                return displays[c]
        for c in sorted(classes):
            for d in displays:
                for p, other in sources.files.items():
                    if p != path and re.search(r"\bclass\s+%s\b" % d, other) and re.search(r"\b%s\b" % c, other):
                        return displays[d]
        return None

    def helpers_of(code):
        """Functions returning rviz::XxxProperty* that take the property's name as a QString: {name:
        (name argument, default argument, parent argument, body start, body end)}."""
        out = {}
        for m in re.finditer(r"rviz::(\w+Property)\s*\*\s*(\w+)\s*\(([^)]*)\)\s*\{", code):
            params = [p.strip() for p in m.group(3).split(",")]
            index = next((i for i, p in enumerate(params) if re.search(r"QString\s*&?\s*\w+$", p)), None)
            parent = next((i for i, p in enumerate(params) if re.search(r"rviz::Property\s*\*\s*\w+$", p)), None)
            if index is not None:
                body_end = matching(code, m.end() - 1, "{", "}")
                out[m.group(2)] = (index, index + 1, parent, m.start(), body_end)
        return out

    # Helpers shared by the displays' files (config_check.cpp: boundedFloat), usable in any of them.
    shared = {}
    for path in files:
        for name, h in helpers_of(sources.files[path]).items():
            shared[name] = (h[0], h[1], h[2], -1, -1)

    found = []
    for path in sorted(files):
        code = sources.files[path]
        helpers = dict(shared)
        helpers.update(helpers_of(code))
        if not helpers and "Property" not in code:
            continue
        variables = {}  # variable -> property name (for parents)
        calls = []
        for m in re.finditer(r"\bnew\s+(?:rviz::)?(\w+)\s*\(", code):
            if m.group(1).endswith("Property") or m.group(1) in NOT_USER_PROPERTIES:
                calls.append((m.start(), m.end() - 1, m.group(1), None))
        for helper in helpers:
            for m in re.finditer(r"(?<![\w:.>])%s\s*\(" % helper, code):
                if re.search(r"\*\s*$", code[:m.start()]):
                    continue  # the definition itself
                calls.append((m.start(), m.end() - 1, None, helper))
        for start, open_paren, klass, helper in sorted(calls):
            close = matching(code, open_paren)
            args = split_args(code[open_paren + 1:close])
            line = line_of(code, start)
            where = "%s:%d" % (rel(root, path), line)
            if klass in NOT_USER_PROPERTIES:
                continue
            if helper:
                name_i, default_i, parent_i = helpers[helper][:3]
            elif klass in SIGNATURES:
                name_i, default_i, parent_i = SIGNATURES[klass]
            else:
                problem("%s: rviz::%s: the docs test does not know this property class (add its constructor's "
                        "argument positions to SIGNATURES in test/docs/check_docs.py)" % (where, klass))
                continue
            inside_helper = any(h[3] <= start <= h[4] for h in helpers.values())
            if len(args) <= max(name_i, default_i):
                problem("%s: cannot read the arguments of a property construction" % where)
                continue
            name = literal_string(args[name_i])
            if name is None:
                if not inside_helper:
                    problem("%s: a property whose name is not a string literal (%s): the docs test cannot "
                            "check it" % (where, args[name_i]))
                continue
            try:
                default = resolver.value(args[default_i], path, code)
            except (ValueError, SyntaxError, ZeroDivisionError) as e:
                problem("%s: property '%s': cannot resolve its default '%s': %s" % (where, name, args[default_i], e))
                continue
            assigned = re.search(r"([\w.>-]+)\s*=\s*$", code[:start])
            if assigned:
                variables[re.split(r"\.|->", assigned.group(1))[-1]] = name
            parent = None
            if parent_i is not None and parent_i < len(args):
                parent_expr = re.split(r"\.|->", args[parent_i].strip())[-1]
                if parent_expr not in TOP_LEVEL_PARENTS:
                    parent = variables.get(parent_expr, "?" + parent_expr)
            options = []
            if assigned:
                var = re.split(r"\.|->", assigned.group(1))[-1]
                for om in re.finditer(r"\b%s\s*->\s*addOption\s*\(([^;]*)\)\s*;" % re.escape(var), code):
                    option_expr = split_args(om.group(1))[0]
                    if "(" in option_expr or "->" in option_expr or "." in option_expr:
                        continue  # filled in at run time (e.g. the connected screens' names)
                    try:
                        options.append(resolver.value(option_expr, path, code))
                    except (ValueError, SyntaxError) as e:
                        problem("%s: option '%s' of '%s': %s" % (where, option_expr, name, e))
            display = owner(path)
            if display is None:
                problem("%s: property '%s': cannot tell which display it belongs to" % (where, name))
                continue
            found.append(Found(display, name, parent, default, rel(root, path), line, options))
    for f in found:
        if f.parent and f.parent.startswith("?"):
            problem("%s:%d: property '%s': its parent '%s' is not a property created in the same file"
                    % (f.path, f.line, f.name, f.parent[1:]))
    counts["display properties in src/displays"] = len(found)
    # Properties rviz's MessageFilterDisplay adds (Topic, Unreliable, Queue Size), and the defaults
    # a display sets for them (topic_property_->setValue(...)).
    inherited = message_filter_properties(sources, resolver)
    for display_class, short in displays.items():
        header = [(p, c) for p, c in sources.files.items() if re.search(r"\bclass\s+%s\b" % display_class, c)]
        if not header:
            problem("plugin_description.xml names %s, but no header declares it" % display_class)
            continue
        hpath, hcode = header[0]
        if "MessageFilterDisplay<" not in hcode:
            continue
        for name, (variable, default) in inherited.items():
            value = default
            for p, c in sources.files.items():
                if re.search(r"\b%s::%s\s*\(\s*\)" % (display_class, display_class), c):
                    m = re.search(r"\b%s\s*->\s*setValue\s*\(([^;]*)\)\s*;" % re.escape(variable), c)
                    if m:
                        try:
                            value = resolver.value(m.group(1), p, c)
                        except (ValueError, SyntaxError) as e:
                            problem("%s: %s's %s default '%s': %s" % (rel(root, p), short, name, m.group(1), e))
            found.append(Found(short, name, None, value, "rviz's MessageFilterDisplay", 0))
    return found


def message_filter_properties(sources, resolver):
    """{name: (member variable, default)} of rviz::MessageFilterDisplay, from rviz's installed header
    when there is one, else as rviz 1.14 defines them."""
    fallback = {"Topic": ("topic_property_", ""), "Unreliable": ("unreliable_property_", False),
                "Queue Size": ("queue_size_property_", 10.0)}
    header = "/usr/include/rviz/message_filter_display.h"
    if not os.path.exists(header):
        return fallback
    code = strip_comments(read(header))
    out = {}
    for m in re.finditer(r"(\w+)\s*=\s*new\s+(?:rviz::)?(\w+Property)\s*\(", code):
        close = matching(code, m.end() - 1)
        args = split_args(code[m.end():close])
        name = literal_string(args[0]) if args else None
        if name is None:
            continue
        try:
            out[name] = (m.group(1), resolver.value(args[1], header, code))
        except (ValueError, SyntaxError):
            out[name] = fallback.get(name, (m.group(1), None))
    return out or fallback


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


# ---- tools -------------------------------------------------------------------------------------

OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*|-[a-zA-Z])(?![\w-])")


def cmake_executables(root):
    """{executable: [source paths]} of the add_executable() calls of the package (tests and
    benchmarks excluded)."""
    texts = [read(os.path.join(root, "CMakeLists.txt"))]
    cmake_dir = os.path.join(root, "cmake")
    if os.path.isdir(cmake_dir):
        texts += [read(os.path.join(cmake_dir, f)) for f in sorted(os.listdir(cmake_dir)) if f.endswith(".cmake")]
    text = "\n".join(re.sub(r"#[^\n]*", "", t) for t in texts)
    project = (re.findall(r"\bproject\(\s*(\w+)", text) or ["rviz_projector"])[0]
    text = text.replace("${PROJECT_NAME}", project)
    variables = {}
    for m in re.finditer(r"\bset\(\s*([\w${}]+)\s+([^)]*)\)", text):
        variables[m.group(1)] = m.group(2).split()

    def expand(word, depth=0):
        m = re.match(r"^\$\{(.+)\}$", word)
        if not m or depth > 5:
            return [word]
        inner = m.group(1)
        inner = re.sub(r"\$\{([^}]+)\}", lambda g: " ".join(variables.get(g.group(1), [g.group(0)])), inner)
        return [w for v in variables.get(inner, []) for w in expand(v, depth + 1)]

    out = {}
    for m in re.finditer(r"(?<![\w])add_executable\(\s*([\w${}]+)([^)]*)\)", text):
        name = m.group(1)
        words = m.group(2).split()
        if "${" in name or name.startswith(project + "_") or "EXCLUDE_FROM_ALL" in words:
            continue
        out[name] = [os.path.join(root, w) for word in words for w in expand(word) if w.endswith((".cpp", ".h"))]
    return out


def usage_text(code):
    """The string literals of the function that holds the usage text ('usage' in a literal)."""
    for m in re.finditer(r"\bstd::string\s+(\w+)\s*\([^)]*\)\s*\{", code):
        end = matching(code, m.end() - 1, "{", "}")
        body = code[m.end():end]
        literals = STRING_LITERALS.findall(body)
        if any(re.search(r"\busage\b", s, re.I) for s in literals):
            return m.group(1), "".join(s.replace("\\n", "\n") for s in literals)
    return None, None


def table_tokens(section_lines, first_header):
    """The words written as code in the first column of a section's tables whose first header cell is
    `first_header` (Option, Parameter, Argument): what the section documents, not just mentions."""
    tokens = set()
    for header, rows in markdown_tables(section_lines):
        if not header or plain(header[0]).lower() != first_header.lower():
            continue
        for _, row in rows:
            for span in code_spans(row[0]):
                for word in re.split(r"[\s,;=:|()\[\]\"']+", span):
                    word = word.strip(".")
                    if word:
                        tokens.add(word)
    return tokens


def tool_section(doc_sections, name):
    for title, lines in doc_sections.items():
        if re.search(r"(?<![\w.-])%s(?![\w-])" % re.escape(name), title.replace("`", "")):
            return lines
    return None


def check_tools(root, sources):
    doc_path = os.path.join(root, DOC_TOOLS)
    if not os.path.exists(doc_path):
        problem("%s does not exist" % DOC_TOOLS)
        return
    doc_sections = sections(read(doc_path), 2)
    executables = cmake_executables(root)
    if len(executables) < 4:
        problem("only %d executables found in the CMake files: the docs test's parser is broken" % len(executables))
    bin_dir = os.environ.get("RP_TOOL_BIN_DIR", "")
    checked_options = checked_params = 0
    for tool, files in sorted(executables.items()):
        section = tool_section(doc_sections, tool)
        if section is None:
            problem("%s: no section for the tool %s (a '## `%s`' heading)" % (DOC_TOOLS, tool, tool))
            continue
        documented = table_tokens(section, "Option")
        parameters = table_tokens(section, "Parameter")
        codes = [(p, sources.files.get(p) or strip_comments(read(p))) for p in files if os.path.exists(p)]
        # Options: the help text in the source, the parser's accepted options, and the binary's --help.
        help_options, accepted, origins = set(), set(), []
        for p, code in codes:
            if '"--help"' not in code:
                continue
            function, text = usage_text(code)
            if text is None:
                problem("%s: accepts --help, but no function holding a usage text was found" % rel(root, p))
                continue
            origins.append("%s %s()" % (rel(root, p), function))
            help_options |= set(OPTION.findall(text))
            accepted |= set(re.findall(r'\barg\s*==\s*"(-[^"]+)"', code))
        binary = os.path.join(bin_dir, tool) if bin_dir else ""
        binary_options = set()
        if origins and binary and os.access(binary, os.X_OK):
            try:
                run = subprocess.run([binary, "--help"], capture_output=True, text=True, timeout=30,
                                     env=dict(os.environ, ROS_MASTER_URI=os.environ.get("ROS_MASTER_URI", "http://localhost:1")))
                output = run.stdout + run.stderr
                binary_options = set(OPTION.findall(output))
                if run.returncode != 0 or not binary_options:
                    problem("%s --help: exit status %d, %d options printed" % (binary, run.returncode, len(binary_options)))
                origins.append("`%s --help`" % binary)
            except (OSError, subprocess.TimeoutExpired) as e:
                problem("%s --help: %s" % (binary, e))
        elif origins and bin_dir:
            origins.append("no built binary in %s" % bin_dir)
        if origins:
            notes.append("%s options from %s" % (tool, " and ".join(origins)))
            option_sources[tool] = "source+binary" if binary_options else \
                ("source, not built" if bin_dir else "source")
        for option in sorted(help_options | accepted | binary_options):
            checked_options += 1
            if option not in documented:
                source = "the built binary's --help" if option in binary_options - help_options - accepted else \
                    ("its --help" if option in help_options else "its command line parser")
                problem("%s: option %s of %s (from %s) is not in the options table of its section (| `%s` | meaning |)"
                        % (DOC_TOOLS, option, tool, source, option))
        # Private parameters of ROS nodes.
        params = set()
        for p, code in codes:
            params |= set(re.findall(r"\b\w*[pP]aram\s*(?:<[^>()]*>)?\s*\(\s*(?:[\w.]+\s*,\s*)?\"([A-Za-z_]\w*)\"", code))
        for param in sorted(params):
            checked_params += 1
            if "~" + param not in parameters:
                problem("%s: parameter ~%s of %s is not in the parameter table of its section (| `~%s` | default | "
                        "meaning |)" % (DOC_TOOLS, param, tool, param))
    # Launch files: every argument a user can set.
    launch_dir = os.path.join(root, "launch")
    for f in sorted(os.listdir(launch_dir)) if os.path.isdir(launch_dir) else []:
        if not f.endswith(".launch"):
            continue
        section = tool_section(doc_sections, f)
        if section is None:
            problem("%s: no section for launch/%s (a '## `%s`' heading)" % (DOC_TOOLS, f, f))
            continue
        documented = table_tokens(section, "Argument")
        for m in re.finditer(r"<arg\s+([^>]*)/?>", read(os.path.join(launch_dir, f))):
            attributes = dict(re.findall(r'(\w+)="([^"]*)"', m.group(1)))
            if "value" in attributes or "name" not in attributes:
                continue
            checked_params += 1
            if attributes["name"] not in documented:
                problem("%s: argument %s of launch/%s is not in the argument table of its section (| `%s` | default | "
                        "meaning |)" % (DOC_TOOLS, attributes["name"], f, attributes["name"]))
    counts["tool options"] = checked_options
    counts["parameters and launch arguments"] = checked_params


# ---- source map, file references, README ------------------------------------------------------


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
                if f.endswith((".md", ".png", ".pyc")) or path == os.path.abspath(__file__):
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
