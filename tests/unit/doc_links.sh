#!/usr/bin/env bash
# Every relative link in the project's documents leads to a file that exists, and every link to a
# heading of a Markdown file (#anchor) to a heading that exists there, by GitHub's anchor rule
# (lower case, punctuation dropped, spaces as hyphens). Fenced code blocks are not read.
#   doc_links.sh REPOSITORY_ROOT
set -euo pipefail
root=${1:?usage: doc_links.sh REPOSITORY_ROOT}
cd "$root"
shopt -s nullglob
files=(README.md docs/*.md docs/*/*.md board/*.md tools/*/README.md)

anchors() {
  awk '/^```/ { code = !code; next }
       !code && /^#+ / { sub(/^#+ +/, ""); s = tolower($0); gsub(/[^a-z0-9 _-]/, "", s); gsub(/ /, "-", s); print s }' "$1"
}
links() {
  awk '/^```/ { code = !code; next }
       !code { line = $0
               while (match(line, /\]\([^) ]+\)/)) { print substr(line, RSTART + 2, RLENGTH - 3); line = substr(line, RSTART + RLENGTH) } }' "$1"
}

bad=0 checked=0
for file in "${files[@]}"; do
  dir=$(dirname "$file")
  while IFS= read -r link; do
    case $link in http://* | https://* | mailto:*) continue ;; esac
    checked=$((checked + 1))
    path=${link%%#*} anchor=''
    [[ $link == *#* ]] && anchor=${link#*#}
    target=$file  # a bare #anchor points into the document itself
    [ -n "$path" ] && target=$dir/$path
    if [ ! -e "$target" ]; then
      echo "$file: ($link): expected a file or folder at $target, found none"
      bad=1
    elif [ -n "$anchor" ] && [[ $target == *.md ]] && ! anchors "$target" | grep -qxF -- "$anchor"; then
      echo "$file: ($link): expected a heading with the anchor #$anchor in $target, found none"
      bad=1
    fi
  done < <(links "$file")
done
[ "$bad" = 0 ] && echo "ok: $checked links in ${#files[@]} documents resolve"
exit "$bad"
