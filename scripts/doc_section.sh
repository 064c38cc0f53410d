# Sourced by the scripts that write generated blocks into documents.
# replace_doc_section DOC NAME FILE: replaces the text between the lines
# <!-- NAME:begin --> and <!-- NAME:end --> of DOC with FILE's contents;
# returns 1 (and says so on stderr) when DOC lacks that pair, leaving it alone.
replace_doc_section() {
  local doc=$1 name=$2 file=$3
  if ! grep -q "<!-- $name:begin -->" "$doc" || ! grep -q "<!-- $name:end -->" "$doc"; then
    echo "$doc has no <!-- $name:begin --> / <!-- $name:end --> pair: not refreshed ($file)" >&2
    return 1
  fi
  awk -v file="$file" -v begin="<!-- $name:begin -->" -v end="<!-- $name:end -->" '
    index($0, begin) { print; while ((getline line < file) > 0) print line; skip = 1; next }
    index($0, end) { skip = 0 }
    !skip { print }
  ' "$doc" >"$doc.tmp" && mv "$doc.tmp" "$doc"
}
