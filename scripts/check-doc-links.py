#!/usr/bin/env python3
"""Checks that every relative link in README.md and docs/ names a file or folder that exists.

  scripts/check-doc-links.py [ROOT]     check ROOT's README.md and ROOT/docs/**/*.md (default: the
                                        repository holding this script)
  scripts/check-doc-links.py --self-test

Links are Markdown inline links and images, `[text](target)` and `![alt](target)`, outside fenced
code blocks and inline code. A target with a scheme (https:, mailto:) or only an anchor (#part)
is not checked; an anchor after a path is dropped and the path is checked. Each broken link is
printed as `<file>:<line>: <target>: no such file`. Exit status: 0 when every link resolves, 1
when some do not, 2 on bad usage. Standard library only.
"""

import os
import re
import sys
import tempfile

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
SCHEME = re.compile(r"^[A-Za-z][A-Za-z0-9+.-]*:")
FENCE = re.compile(r"^\s*(```|~~~)")
INLINE_CODE = re.compile(r"`+[^`]*`+")


def documents(root):
    readme = os.path.join(root, "README.md")
    if os.path.isfile(readme):
        yield readme
    for folder, subfolders, files in os.walk(os.path.join(root, "docs")):
        subfolders.sort()
        for name in sorted(files):
            if name.endswith(".md"):
                yield os.path.join(folder, name)


def links(path):
    """(line number, target) of every link outside code."""
    in_fence = False
    with open(path, encoding="utf-8") as text:
        for number, line in enumerate(text, 1):
            if FENCE.match(line):
                in_fence = not in_fence
                continue
            if in_fence:
                continue
            for match in LINK.finditer(INLINE_CODE.sub("", line)):
                yield number, match.group(1)


def broken_links(root):
    broken = []
    for document in documents(root):
        for number, target in links(document):
            if SCHEME.match(target) or target.startswith("#"):
                continue
            path = target.split("#", 1)[0]
            resolved = os.path.normpath(os.path.join(os.path.dirname(document), path))
            if not os.path.exists(resolved):
                broken.append((os.path.relpath(document, root), number, target))
    return broken


def self_test():
    """The check finds a broken link and accepts good ones (so the ctest can fail)."""
    with tempfile.TemporaryDirectory() as root:
        os.makedirs(os.path.join(root, "docs", "sub"))
        os.makedirs(os.path.join(root, "docs", "images"))
        open(os.path.join(root, "docs", "images", "a.png"), "w").close()
        files = {
            "README.md": "[docs](docs/index.md) [web](https://example.org) [top](#weft)\n"
                         "```\n[in a fence](missing-in-fence.md)\n```\n"
                         "`[in code](missing-in-code.md)`\n",
            "docs/index.md": "![picture](images/a.png) [page](sub/page.md#part) [up](../README.md)\n",
            "docs/sub/page.md": "[back](../index.md) [gone](../nowhere.md) [also](missing/)\n",
        }
        for name, text in files.items():
            with open(os.path.join(root, name), "w", encoding="utf-8") as out:
                out.write(text)
        found = broken_links(root)
        expected = [("docs/sub/page.md", 1, "../nowhere.md"), ("docs/sub/page.md", 1, "missing/")]
        if found != expected:
            print("self-test: expected %r, found %r" % (expected, found), file=sys.stderr)
            return 1
    print("self-test: broken links found, good ones accepted")
    return 0


def main():
    arguments = sys.argv[1:]
    if arguments == ["--self-test"]:
        return self_test()
    if len(arguments) > 1 or (arguments and arguments[0].startswith("-")):
        print("usage: scripts/check-doc-links.py [ROOT] | --self-test", file=sys.stderr)
        return 2
    root = arguments[0] if arguments else os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    if not os.path.isfile(os.path.join(root, "README.md")):
        print("error: %s: no README.md" % root, file=sys.stderr)
        return 2
    broken = broken_links(root)
    for document, number, target in broken:
        print("%s:%d: %s: no such file" % (document, number, target))
    count = sum(1 for document in documents(root) for _ in links(document))
    if broken:
        print("%d of %d links broken" % (len(broken), count), file=sys.stderr)
        return 1
    print("%d links, all resolve" % count)
    return 0


if __name__ == "__main__":
    sys.exit(main())
