"""Rewrites one ### section of an existing RESULTS.md in place (--section), the rest of the file kept."""

def replace_section(path, title, section):
    """replaces the section `title` of the file (up to the next ### heading) by the lines `section`, or inserts it
    before the scaling slopes (else before the integer choice, else at the end)"""
    with open(path) as f:
        old = f.read().split("\n")
    while old and not old[-1].strip():
        old.pop()
    heading = [i for i, line in enumerate(old) if line.startswith("### ")]
    if title in old:
        start = old.index(title)
        end = next((i for i in heading if i > start), len(old))
    else:
        start = next((i for i in heading if old[i].startswith("### Scaling")),
                     next((i for i in heading if old[i].startswith("### Integer choice")), len(old)))
        end = start
    body = list(section)
    while body and not body[-1].strip():
        body.pop()
    if end < len(old):
        body.append("")
    elif start > 0 and old[start - 1].strip():
        body.insert(0, "")
    new = old[:start] + body + old[end:]
    with open(path, "w") as f:
        f.write("\n".join(new) + "\n")
