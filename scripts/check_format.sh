#!/usr/bin/env bash
# Checks that the tracked C++ sources are formatted with the project's
# .clang-format (clang-format --dry-run -Werror); lists the files that would
# change. Registered as the ctest test format_check (label format).
#   bash scripts/check_format.sh            check
#   bash scripts/check_format.sh --fix      reformat the files in place
# Environment: CLANG_FORMAT (default: clang-format, else clang-format-14).
# Exit status: 0 formatted, 1 files would change, 77 clang-format missing
# (ctest reports the test as skipped).
set -euo pipefail

root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$root"

fix=0
case "${1:-}" in
  "") ;;
  --fix) fix=1 ;;
  *) echo "usage: $0 [--fix]" >&2; exit 2 ;;
esac

cf=${CLANG_FORMAT:-}
if [[ -z $cf ]]; then
  for candidate in clang-format clang-format-14; do
    if command -v "$candidate" >/dev/null 2>&1; then cf=$candidate; break; fi
  done
fi
if [[ -z $cf ]] || ! command -v "$cf" >/dev/null 2>&1; then
  echo "format check skipped: clang-format not found (Debian: apt-get install clang-format)"
  exit 77
fi

# tracked C++ sources; outside a git checkout, every C++ source of the tree
if git -C "$root" rev-parse --is-inside-work-tree >/dev/null 2>&1; then
  mapfile -t files < <(git -C "$root" ls-files -- '*.cpp' '*.hpp' '*.cc' '*.h')
else
  mapfile -t files < <(find . \( -path ./.git -o -path './build*' \) -prune -o \
                         -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.cc' -o -name '*.h' \) \
                         -print | sed 's|^\./||' | sort)
fi
# a file listed by git but deleted in the work tree is not checked
existing=()
for f in "${files[@]}"; do [[ -f $f ]] && existing+=("$f"); done
files=("${existing[@]}")

if ((fix)); then
  "$cf" -i --style=file "${files[@]}"
  echo "reformatted ${#files[@]} files with $("$cf" --version)"
  exit 0
fi

bad=()
for f in "${files[@]}"; do
  if ! "$cf" --dry-run -Werror --style=file "$f" >/dev/null 2>&1; then
    bad+=("$f")
  fi
done
echo "$("$cf" --version): ${#files[@]} files checked, ${#bad[@]} not formatted"
if ((${#bad[@]})); then
  printf '  %s\n' "${bad[@]}"
  echo "fix with: bash scripts/check_format.sh --fix"
  exit 1
fi
