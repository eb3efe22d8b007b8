"""RESULTS.md as a header and a list of sections, each from its heading (##, ### or ####) to the next heading:
split, merged with new sections in one stable order (none dropped), written atomically."""

import os
import re

from .common import BACKENDS

HEADING = re.compile(r"^#{2,4} \S")

# the order of the sections in the file (that of benchmark/RESULTS.md on 2026-12-05); a section not listed (added by
# hand) stays after the one it followed
ORDER = [f"### {b}: {text}" for b, text in BACKENDS.items()] + [
    "### The main program as a whole process",
    "### Design controls: constrained and guided faces",
    "### Automatic placement",
    "### Refinement to a local minimum",
    "### Against geometry-central's smoothest field",
    "### Against the fastest factorization of the machine",
    "### Against the peers: Crane's TCODS",
    "### The Python binding",
    "### The field editor",
    "### Scaling: log–log slopes",
    "### Integer choice per dimension",
    "### Feature pins",
    "#### Side by side with Directional (item 5)",
    "## The batch (trivial_connections-batch)",
]

# short names of the sections (scripts/regenerate_results.sh's steps name the sections they write by them)
KEYS = dict(zip(list(BACKENDS) + ["program", "controls", "placement", "refinement", "gc", "floor", "tcods", "python",
                                  "editor", "slopes", "integers", "pins", "directional", "batch"], ORDER))

# sections of prose without measurements of their own (never regenerated)
PROSE = {KEYS["refinement"]}


def _trim(lines):
    lines = list(lines)
    while lines and not lines[-1].strip():
        lines.pop()
    while lines and not lines[0].strip():
        lines.pop(0)
    return lines


def split(text):
    """(header lines, [(title, lines)]): the header is everything before the first section heading; each
    section's lines start with its heading, without trailing blank lines"""
    header, sections = [], []
    for line in text.split("\n"):
        if HEADING.match(line):
            sections.append((line, [line]))
        elif sections:
            sections[-1][1].append(line)
        else:
            header.append(line)
    return _trim(header), [(t, _trim(lines)) for t, lines in sections]


def split_file(path):
    with open(path) as f:
        return split(f.read())


def merge(old, new):
    """the sections of `old` with those of `new` in their place ([(title, lines)] both): the new one wins for a
    title in both, none of either is dropped; ORDER first, a title not in ORDER after the title it followed in its
    own list. Returns [(title, lines, 'new' | 'kept')]"""
    old_d, new_d = dict(old), dict(new)
    titles = [t for t in ORDER if t in old_d or t in new_d]
    for source in (old, new):
        previous = None
        for t, _ in source:
            if t not in titles:
                titles.insert(titles.index(previous) + 1 if previous in titles else len(titles), t)
            previous = t
    return [(t, new_d[t], "new") if t in new_d else (t, old_d[t], "kept") for t in titles]


def join(header, sections):
    """the text of the file: the header, then each section, one blank line between them"""
    blocks = [_trim(header)] + [_trim(lines) for _, lines, *rest in sections]
    return "\n\n".join("\n".join(b) for b in blocks if b) + "\n"


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def missing(before, after):
    """the titles of `before` that `after` lacks ([(title, ...)] both)"""
    kept = {t for t, *_ in after}
    return [t for t, *_ in before if t not in kept]


def has_date_line(lines):
    """whether the section says when it was measured: a line starting 'Measured', or a date in its first
    paragraph"""
    if any(line.startswith("Measured") for line in lines[1:]):
        return True
    body = _trim(lines[1:])
    first = body[:body.index("")] if "" in body else body
    return any(re.search(r"\b20\d\d-\d\d-\d\d\b", line) for line in first)
