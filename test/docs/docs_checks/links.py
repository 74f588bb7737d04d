"""(a) Every relative link and image of every *.md resolves inside the repository, and every #anchor
is a heading (or an explicit <a name/id>) of its target."""
import os
import re
import urllib.parse

from .common import anchors, counts, markdown_files, problem, read, rel, split_fences, without_code_spans


LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\[\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+(?:\"[^\"]*\"|'[^']*'))?\s*\)")
REFERENCE = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)")


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
