#!/usr/bin/env bash
# Checks every relative link and image of the user documents (README.md,
# docs/**/*.md, bullet_integration/README.md, fuzz/README.md): the file it
# names exists, and a #fragment names a heading of that file (GitHub's
# anchors: lower case, punctuation dropped, spaces to hyphens).
#   bash scripts/check_doc_links.sh        exit 1 and a list if any is broken
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"
mapfile -t docs < <(find docs -name '*.md' | sort)
python3 - README.md bullet_integration/README.md fuzz/README.md "${docs[@]}" <<'PY'
import os, re, sys
def anchors(path):
    out, seen = set(), {}
    in_code = False
    for line in open(path, encoding='utf-8'):
        if line.startswith('```'):
            in_code = not in_code
        if in_code or not line.startswith('#'):
            continue
        h = re.sub(r'^#+\s*', '', line.strip())
        a = re.sub(r'[^\w\- ]', '', h.lower().replace('`', '')).replace(' ', '-')
        n = seen.get(a, 0)
        seen[a] = n + 1
        out.add(a if n == 0 else f'{a}-{n}')
    return out
bad = 0
for doc in sys.argv[1:]:
    text = open(doc, encoding='utf-8').read()
    text = re.sub(r'```.*?```', '', text, flags=re.S)  # links in code blocks are not links
    for target in re.findall(r'\]\(([^)\s]+)\)', text):
        if re.match(r'[a-z]+://', target) or target.startswith('mailto:'):
            continue
        path, _, frag = target.partition('#')
        full = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
        if not os.path.exists(full):
            print(f'{doc}: {target}: no such file {full}'); bad += 1
        elif frag and (not full.endswith('.md') or frag not in anchors(full)):
            print(f'{doc}: {target}: no heading #{frag} in {full}'); bad += 1
print(f'{len(sys.argv) - 1} documents checked, {bad} broken links')
sys.exit(1 if bad else 0)
PY
