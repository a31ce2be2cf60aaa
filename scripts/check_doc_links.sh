#!/usr/bin/env bash
# Checks that the documentation stands alone: every relative link and image in README.md and
# docs/**/*.md names a file (or folder) inside the repository, every #anchor names a heading of
# its page, and no backticked path such as `../x` leaves the repository. Web links (scheme:) are
# not followed. Code blocks and code spans are not links and are skipped.
#   check_doc_links.sh [REPOSITORY_ROOT]      exit 0: all resolve; 1: a list of those that do not
set -u
root=$(cd "${1:-$(dirname "$0")/..}" && pwd -P) || exit 2
cd "$root" || exit 2
export LC_ALL=C
status=0

# The links of a page, one "LINE<TAB>KIND<TAB>TARGET" a line. KIND "link": an inline link or image
# ](target) / ](target "title"), or a reference definition [x]: target, outside code blocks and
# code spans. KIND "code": a code span naming a path that starts with ../ (anywhere).
links() {
  awk '
    {
      line = $0
      rest = line
      while (match(rest, /`\.\.\/[^`[:space:]]*/)) {
        printf "%d\tcode\t%s\n", NR, substr(rest, RSTART + 1, RLENGTH - 1)
        rest = substr(rest, RSTART + RLENGTH)
      }
    }
    /^[[:space:]]*(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    /^(    |\t)/ && (prev_blank || in_indented) { in_indented = 1; next }
    {
      in_indented = 0
      prev_blank = (line ~ /^[[:space:]]*$/)
      gsub(/`[^`]*`/, "", line)
      if (match(line, /^ ? ? ?\[[^]]+\]:[[:space:]]*/)) {
        target = substr(line, RLENGTH + 1)
        sub(/^</, "", target); sub(/[[:space:]>].*$/, "", target)
        if (target != "") printf "%d\tlink\t%s\n", NR, target
      }
      rest = line
      while (match(rest, /\]\([[:space:]]*<?[^)[:space:]>]+/)) {
        target = substr(rest, RSTART + 2, RLENGTH - 2)
        sub(/^[[:space:]]*</, "", target); sub(/^[[:space:]]*/, "", target)
        printf "%d\tlink\t%s\n", NR, target
        rest = substr(rest, RSTART + RLENGTH)
      }
    }
  ' "$1"
}

# GitHub's anchors for the headings of a Markdown page (outside fenced code): lower case,
# punctuation dropped, spaces to hyphens, "-1", "-2"... for repeats.
anchors() {
  awk '
    /^[[:space:]]*(```|~~~)/ { fenced = !fenced; next }
    fenced { next }
    /^#+[[:space:]]/ {
      h = $0
      sub(/^#+[[:space:]]+/, "", h); sub(/[[:space:]]*#*[[:space:]]*$/, "", h)
      h = tolower(h)
      gsub(/[^a-z0-9 _-]/, "", h); gsub(/ /, "-", h)
      n = seen[h]++
      print (n ? h "-" n : h)
    }
  ' "$1"
}

fail() {  # fail PAGE LINE TARGET WHY
  echo "$1:$2: $3: $4"
  status=1
}

inside_repo() {  # inside_repo PATH: the path, resolved, lies in the repository
  local resolved
  resolved=$(realpath -m "$1")
  [ "$resolved" = "$root" ] || [ "${resolved#"$root"/}" != "$resolved" ]
}

check_page() {
  local page=$1 dir line_no kind target path anchor
  dir=$(dirname "$page")
  while IFS=$'\t' read -r line_no kind target; do
    if [ "$kind" = code ]; then
      inside_repo "$dir/$target" || fail "$page" "$line_no" "$target" "names a path outside the repository"
      continue
    fi
    case "$target" in
      [a-zA-Z]*:*) continue ;;  # https:, mailto: ...
    esac
    path=${target%%#*}
    anchor=""
    [ "$path" != "$target" ] && anchor=${target#*#}
    if [ -z "$path" ]; then
      path=$(basename "$page")
    elif [ "${path#/}" != "$path" ]; then
      fail "$page" "$line_no" "$target" "absolute path (link relative to the page instead)"
      continue
    fi
    if ! inside_repo "$dir/$path"; then
      fail "$page" "$line_no" "$target" "points outside the repository"
    elif [ ! -e "$dir/$path" ]; then
      fail "$page" "$line_no" "$target" "no such file"
    elif [ -n "$anchor" ] && [ "${path##*.}" = md ] && ! anchors "$dir/$path" | grep -qxF -- "$anchor"; then
      fail "$page" "$line_no" "$target" "no heading with this anchor"
    fi
  done < <(links "$page")
}

pages=(README.md)
while IFS= read -r p; do pages+=("$p"); done < <(find docs -name '*.md' | sort)
for page in "${pages[@]}"; do
  [ -f "$page" ] || { fail "$page" 0 "$page" "page missing"; continue; }
  check_page "$page"
done
[ $status -eq 0 ] && echo "doc links: OK (${#pages[@]} pages; every relative link resolves inside the repository)"
exit $status
