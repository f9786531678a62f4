#!/usr/bin/env python3
"""Every relative link in the front pages and the docs points at a file that exists.

Usage: check_doc_links.py REPO_ROOT

Scans README.md, CONTRIBUTING.md and docs/*.md for markdown links and images, inline
([text](target), ![alt](target)) and reference-style ([label]: target), outside fenced code
blocks and code spans. Links with a scheme (http:, https:, mailto:, ...) and same-page anchors
(#...) are skipped; a relative target, its #anchor and ?query cut off, must name an existing file
or folder, resolved from the folder of the page that links it. Exits 1 naming every missing target
(page:line: target), 0 when all exist.
"""
import glob
import os
import re
import sys
import urllib.parse

# [text](target "title") and ![alt](target); the text may hold one level of brackets
# (an image inside a link). The target is either <...> or has no spaces.
INLINE = re.compile(r'!?\[(?:[^\[\]]|\[[^\]]*\])*\]\(\s*(<[^>]*>|[^)\s]+)(?:\s+"[^"]*")?\s*\)')
REFERENCE = re.compile(r'^\s{0,3}\[[^\]]+\]:\s*(<[^>]*>|\S+)')
CODE_SPAN = re.compile(r'(`+)(?:(?!\1).)+?\1')
SCHEME = re.compile(r'^[A-Za-z][A-Za-z0-9+.-]*:')


def pages(root):
    found = [os.path.join(root, name) for name in ('README.md', 'CONTRIBUTING.md')]
    found += sorted(glob.glob(os.path.join(root, 'docs', '*.md')))
    return [p for p in found if os.path.isfile(p)]


def targets(path):
    """(line number, target) of every link in the page, outside code."""
    fence = None
    with open(path, encoding='utf-8') as f:
        for number, line in enumerate(f, 1):
            stripped = line.lstrip()
            marker = re.match(r'(`{3,}|~{3,})', stripped)
            if marker:
                if fence is None:
                    fence = marker.group(1)[0] * len(marker.group(1))
                elif stripped.startswith(fence):
                    fence = None
                continue
            if fence is not None:
                continue
            text = CODE_SPAN.sub('', line)
            for m in INLINE.finditer(text):
                yield number, m.group(1)
            m = REFERENCE.match(text)
            if m:
                yield number, m.group(1)


def missing(root):
    for page in pages(root):
        base = os.path.dirname(page)
        for number, target in targets(page):
            target = target.strip('<>')
            if not target or target.startswith('#') or SCHEME.match(target):
                continue
            file_part = urllib.parse.unquote(re.split(r'[#?]', target, maxsplit=1)[0])
            if not file_part:
                continue
            if not os.path.exists(os.path.normpath(os.path.join(base, file_part))):
                yield '%s:%d: %s' % (os.path.relpath(page, root), number, target)


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    root = os.path.abspath(sys.argv[1])
    if not os.path.isfile(os.path.join(root, 'README.md')):
        print('check_doc_links: no README.md in %s' % root, file=sys.stderr)
        return 2
    bad = list(missing(root))
    for line in bad:
        print('missing link target: ' + line)
    checked = len(pages(root))
    if bad:
        print('check_doc_links: %d missing target(s) in %d page(s)' % (len(bad), checked))
        return 1
    print('check_doc_links: every relative link in %d page(s) exists' % checked)
    return 0


if __name__ == '__main__':
    sys.exit(main())
