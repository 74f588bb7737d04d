"""Reading the package's C++ without a compiler: comments stripped, brackets matched, arguments split,
string literals read, and default-value expressions resolved to values (through the constants and
struct members of the headers)."""
import ast
import os
import re

from .common import read


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
