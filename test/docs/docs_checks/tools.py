"""(c) Every executable and launch file has a section in doc/reference/tools.md, with every option
(help text, parser, built binary's --help), node parameter and launch argument in its tables."""
import os
import re
import subprocess

from .common import code_spans, counts, markdown_tables, notes, option_sources, plain, problem, read, rel, sections
from .cpp import STRING_LITERALS, matching, strip_comments

DOC_TOOLS = "doc/reference/tools.md"

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
