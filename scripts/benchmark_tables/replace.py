"""Rewrites sections of an existing RESULTS.md in place (--section, --insert), the rest of the file kept."""

from .sections import join, merge, missing, split, split_file, write_atomically


def replace_sections(path, new_sections):
    """replaces the sections [(title, lines)] of the file (each up to the next ##, ### or #### heading), or inserts
    them in their place in the order of sections.ORDER; the rest is kept as it is; written atomically. Returns the
    merged [(title, lines, 'new' | 'kept')]"""
    header, old = split_file(path)
    merged = merge(old, new_sections)
    lost = missing(old, merged)
    if lost:  # cannot happen (merge keeps every title); checked all the same before the file is replaced
        raise RuntimeError(f"{path}: sections would vanish: {lost}")
    write_atomically(path, join(header, merged))
    return merged


def replace_section(path, title, section):
    """replaces the section `title` of the file by the lines `section` (which start with that heading)"""
    _, sections = split("\n".join(section))
    if not sections or sections[0][0] != title:
        sections = [(title, [title] + [line for line in section if line != title])]
    replace_sections(path, sections)


def read_fragments(paths):
    """the sections of Markdown fragments (files that start with a section heading)"""
    sections = []
    for path in paths:
        header, found = split_file(path)
        if header and any(line.strip() for line in header):
            raise ValueError(f"{path}: text before the first section heading")
        if not found:
            raise ValueError(f"{path}: no section heading (##, ### or ####)")
        sections += found
    return sections
