"""(b) The rviz properties the displays' code creates: `new rviz::XxxProperty(...)`, helper functions
that wrap it, DisplayGroupVisibilityProperty, and the properties rviz's MessageFilterDisplay adds,
each with its display, parent, default and enum options."""
import os
import re

from .common import counts, problem, read, rel
from .cpp import line_of, literal_string, matching, split_args, strip_comments

# (name argument, default argument, parent argument) of rviz's property constructors. None as the
# parent: the display itself.
SIGNATURES = dict.fromkeys(
    ("Property", "BoolProperty", "FloatProperty", "IntProperty", "StringProperty", "ColorProperty", "EnumProperty",
     "EditableEnumProperty", "VectorProperty", "QuaternionProperty", "FilePathProperty", "TfFrameProperty"),
    (0, 1, 3))
SIGNATURES["RosTopicProperty"] = (0, 1, 4)
SIGNATURES["DisplayGroupVisibilityProperty"] = (3, 4, None)
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
                        "argument positions to SIGNATURES in test/docs/docs_checks/properties.py)" % (where, klass))
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
