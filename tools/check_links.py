#!/usr/bin/env python3
"""Checks the relative links and images of README.md and docs/*.md.

Every link or image target that is not a URL must name an existing file or directory
(relative to the page), and a `#fragment` must name a heading of the target page (GitHub's
anchors: lower case, punctuation dropped, spaces as hyphens, `-1`, `-2` ... for repeats).
Fenced code blocks and inline code are skipped. Exit status 1 lists every broken link as
`page:line: target: reason`.

Usage: python3 tools/check_links.py [ROOT]   (ROOT defaults to the repository root)
"""

import re
import sys
from pathlib import Path

# Pages that another change adds; accepted while they do not exist yet (with a note).
PENDING: set = set()

LINK = re.compile(r"!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*<?([^)\s>]+)>?(?:\s+\"[^\"]*\")?\s*\)")
HEADING = re.compile(r"^ {0,3}(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^ *(```|~~~)")
INLINE_CODE = re.compile(r"(`+)(.+?)\1")


def prose_lines(text):
    """(line number, line) of the lines outside fenced code blocks."""
    fence = None
    for number, line in enumerate(text.splitlines(), 1):
        match = FENCE.match(line)
        if match:
            if fence is None:
                fence = match.group(1)
            elif match.group(1) == fence:
                fence = None
            continue
        if fence is None:
            yield number, line


def slug(heading):
    """GitHub's anchor for a heading's text."""
    text = INLINE_CODE.sub(lambda m: m.group(2), heading)
    text = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", text)  # links keep their text
    text = re.sub(r"<[^>]+>", "", text).strip().lower()
    text = "".join(c for c in text if c.isalnum() or c in " -_")
    return text.replace(" ", "-")


def anchors(path):
    """Every heading anchor of a Markdown file."""
    seen = {}
    result = set()
    for _, line in prose_lines(path.read_text(encoding="utf-8")):
        match = HEADING.match(line)
        if not match:
            continue
        base = slug(match.group(2))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else f"{base}-{count}")
    return result


def check(root):
    pages = [root / "README.md"] + sorted((root / "docs").glob("*.md"))
    errors, notes = [], []
    for page in pages:
        for number, line in prose_lines(page.read_text(encoding="utf-8")):
            for match in LINK.finditer(INLINE_CODE.sub("", line)):
                target = match.group(1)
                if re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target):
                    continue  # https:, mailto: ...
                where = f"{page.relative_to(root)}:{number}: {target}"
                file_part, _, fragment = target.partition("#")
                resolved = (page.parent / file_part).resolve() if file_part else page
                if not resolved.exists():
                    relative = resolved.relative_to(root.resolve()).as_posix()
                    if relative in PENDING:
                        notes.append(f"{where}: not there yet (accepted, pending)")
                    else:
                        errors.append(f"{where}: no such file")
                    continue
                if fragment and resolved.suffix == ".md":
                    if fragment.lower() not in anchors(resolved):
                        errors.append(f"{where}: no heading #{fragment}")
    return pages, errors, notes


def main():
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).resolve().parent.parent
    pages, errors, notes = check(root)
    for note in notes:
        print(f"check_links: {note}", file=sys.stderr)
    for error in errors:
        print(f"check_links: {error}", file=sys.stderr)
    if errors:
        print(f"check_links: {len(errors)} broken link(s)", file=sys.stderr)
        return 1
    print(f"check_links: {len(pages)} pages, every relative link resolves")
    return 0


if __name__ == "__main__":
    sys.exit(main())
