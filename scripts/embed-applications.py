#!/usr/bin/env python3
"""Puts the tables and plots of one `weft bench applications` output into a Markdown document.

    scripts/embed-applications.py OUT DOC "HEADING" [--images-prefix PREFIX]

OUT is the folder the bench wrote (`applications.md`, `loss_<task>.png`, `speedup.png`), DOC the
document (docs/applications.md). The bench's Markdown goes into the section `## HEADING`, between
two markers this script writes:

    <!-- generated: scripts/embed-applications.py OUT -->
    ...
    <!-- end generated -->

Its title line is dropped and its `##` headings become `###`, so it nests under HEADING. The
section's own text before and after the markers (the invocation, the narrative) is kept. A
section without markers gets them at its end; a document without the section gets the section
at its end. Plots are copied beside DOC as images/<PREFIX>loss-<task>.png and
images/<PREFIX>speedup.png (PREFIX default "applications-") and linked at the block's end.

DOC is rewritten only when everything was read, through a temporary file renamed over it.
Bad input (a missing folder or file, markers out of order) exits 2 with
`error: <file>: <what>`. Standard library only.
"""

import os
import re
import shutil
import sys

END = "<!-- end generated -->"


def fail(where, what):
    print(f"error: {where}: {what}", file=sys.stderr)
    sys.exit(2)


def generated_block(out, doc, prefix):
    """The lines between the markers, and the (source, destination) images to copy."""
    source = os.path.join(out, "applications.md")
    if not os.path.isfile(source):
        fail(source, "not found (is OUT a `weft bench applications` output folder?)")
    with open(source, encoding="utf-8") as f:
        lines = f.read().splitlines()
    if not lines or not lines[0].startswith("# "):
        fail(source, "does not start with the bench's title line")
    body = lines[1:]
    while body and not body[0].strip():
        body.pop(0)
    body = ["#" + line if line.startswith("## ") else line for line in body]
    while body and not body[-1].strip():
        body.pop()
    images = []
    image_dir = os.path.join(os.path.dirname(doc), "images")
    names = sorted(n for n in os.listdir(out) if re.fullmatch(r"loss_[A-Za-z0-9_]+\.png", n))
    if os.path.isfile(os.path.join(out, "speedup.png")):
        names.append("speedup.png")
    links = []
    for name in names:
        stem = name[:-4]
        target = prefix + (stem.replace("loss_", "loss-", 1) if stem.startswith("loss_") else stem)
        images.append((os.path.join(out, name), os.path.join(image_dir, target + ".png")))
        label = stem[len("loss_"):] if stem.startswith("loss_") else stem
        links.append(f"![{label}](images/{target}.png)")
    for link in links:
        body += ["", link]
    begin = f"<!-- generated: scripts/embed-applications.py {out} -->"
    return [begin, ""] + body + ["", END], images


def embed(doc_lines, heading, block, doc):
    """doc_lines with block in section `## heading`."""
    title = "## " + heading
    starts = [i for i, line in enumerate(doc_lines) if line == title]
    if len(starts) > 1:
        fail(doc, f"'{title}' appears {len(starts)} times")
    if not starts:
        tail = [""] if doc_lines and doc_lines[-1].strip() else []
        return doc_lines + tail + [title, ""] + block
    start = starts[0]
    end = next((i for i in range(start + 1, len(doc_lines)) if doc_lines[i].startswith("## ")),
               len(doc_lines))
    section = doc_lines[start:end]
    begins = [i for i, line in enumerate(section) if line.startswith("<!-- generated:")]
    ends = [i for i, line in enumerate(section) if line == END]
    if not begins and not ends:
        while len(section) > 1 and not section[-1].strip():
            section.pop()
        section = section + [""] + block + [""]
    elif len(begins) == 1 and len(ends) == 1 and begins[0] < ends[0]:
        section = section[:begins[0]] + block + section[ends[0] + 1:]
    else:
        fail(doc, f"'{title}': its generated markers are not one begin before one end")
    return doc_lines[:start] + section + doc_lines[end:]


def main(argv):
    args = list(argv)
    prefix = "applications-"
    if "--images-prefix" in args:
        i = args.index("--images-prefix")
        if i + 1 >= len(args):
            fail("--images-prefix", "expects a value")
        prefix = args[i + 1]
        del args[i:i + 2]
    if len(args) != 3:
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        sys.exit(2)
    out, doc, heading = args
    if not os.path.isdir(out):
        fail(out, "not a folder")
    if not os.path.isfile(doc):
        fail(doc, "not found")
    if not heading.strip() or "\n" in heading:
        fail("HEADING", "expects one line of text")
    with open(doc, encoding="utf-8") as f:
        doc_lines = f.read().splitlines()
    block, images = generated_block(out, doc, prefix)
    new_lines = embed(doc_lines, heading, block, doc)
    for source, destination in images:
        os.makedirs(os.path.dirname(destination), exist_ok=True)
        shutil.copyfile(source, destination)
    temporary = doc + ".tmp-embed"
    with open(temporary, "w", encoding="utf-8") as f:
        f.write("\n".join(new_lines) + "\n")
    os.replace(temporary, doc)
    print(f"{doc}: '## {heading}' from {out} ({len(images)} plot(s))")


if __name__ == "__main__":
    main(sys.argv[1:])
