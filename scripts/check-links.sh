#!/usr/bin/env bash
# Fails when a tracked file names a repository path that is not in the repository:
#   - Markdown (*.md): every link or image [text](target) whose target is not a web address must be a tracked
#     file or folder (relative to the Markdown file), and a #heading after a Markdown file (or alone) must be one
#     of that file's headings (GitHub's anchors);
#   - Markdown, C/C++ and GLSL sources and headers, CMake files, scripts, the CI job and the deploy files: every
#     path that starts at a top-level folder of the repository (docs/x.md, tests/test_foo.cpp, scripts/y.sh,
#     engine/include/gusuku/...) must be tracked; `*` is a wildcard that must match a tracked file, and a
#     <placeholder> stands for any name under the folder before it;
#   - nothing may cite the old design note outside the repository: the design note is docs/design.md.
# Paths outside the repository (build/, out/, build-fuzz/, ../shared/data/) are not checked: they start at no
# top-level folder, and Markdown links may point at ../shared/data only.
#   bash scripts/check-links.sh        (from anywhere; reads the tracked files of the working tree)
set -euo pipefail
cd "$(dirname "$0")/.."

declare -A tracked=()  # every tracked file and every folder above one, without a trailing slash
while IFS= read -r file; do
  tracked["$file"]=1
  folder="$file"
  while [[ "$folder" == */* ]]; do
    folder="${folder%/*}"
    [[ -n "${tracked[$folder]:-}" ]] && break
    tracked["$folder"]=1
  done
done < <(git ls-files)
# A file being added in this working tree counts too (so the check can run before a commit).
while IFS= read -r file; do tracked["$file"]=1; done < <(git ls-files --others --exclude-standard)

# Top-level folders of the repository: a path in prose or code that starts with one of these is checked.
roots="engine|shaders|baker|bench|tests|docs|scripts|deploy|cmake|\\.ci"

problems=0
report() {  # FILE:LINE: message
  echo "$1: $2" >&2
  problems=$((problems + 1))
}

# "a/b/../c" -> "a/c"; prints nothing when the path leaves the repository.
normalise() {
  local -a parts=() out=()
  IFS=/ read -r -a parts <<<"$1"
  local part
  for part in "${parts[@]}"; do
    case "$part" in
      "" | .) ;;
      ..) if [ "${#out[@]}" -eq 0 ]; then return 0; fi; unset 'out[${#out[@]}-1]' ;;
      *) out+=("$part") ;;
    esac
  done
  local IFS=/
  echo "${out[*]}"
}

exists() {  # a tracked file or folder, or a wildcard pattern matching a tracked file
  local path="${1%/}"
  if [[ "$path" == *"*"* ]]; then
    # Read whole, not piped into `grep -q`: grep's early exit can kill git with SIGPIPE, and pipefail then calls a
    # wildcard that matches many files (engine/*.h) missing, at random (it failed one CI run that way).
    local matches
    matches="$(git ls-files -- "$path")"
    [[ -n "$matches" ]] && return 0
    compgen -G "$path" >/dev/null && return 0
    return 1
  fi
  [[ -n "${tracked[$path]:-}" ]]
}

# GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens.
declare -A anchors_of=()
anchors() {  # prints the anchors of a Markdown file, one a line
  local file="$1"
  if [[ -z "${anchors_of[$file]+set}" ]]; then
    anchors_of["$file"]="$(grep -E '^#{1,6} ' "$file" | sed -E 's/^#+ +//; s/ +#*$//' \
      | sed -E 's/\[([^]]*)\]\([^)]*\)/\1/g' | tr 'A-Z' 'a-z' | sed -E 's/[^a-z0-9 _-]//g; s/ /-/g' || true)"
  fi
  printf '%s\n' "${anchors_of[$file]}"
}

# 1. Markdown links and images.
while IFS= read -r file; do
  dir="$(dirname "$file")"
  # Link targets outside fenced code blocks: FILE:LINE:target
  while IFS=$'\t' read -r line target; do
    target="${target%% *}"  # a [text](path "title")
    case "$target" in
      http://* | https://* | mailto:*) continue ;;
    esac
    path="${target%%#*}"
    anchor=""
    [[ "$target" == *"#"* ]] && anchor="${target#*#}"
    if [[ -z "$path" ]]; then
      resolved="$file"
    else
      if [[ "$path" == *shared/DESIGN.md* ]]; then
        report "$file:$line" "links $target: the design note is docs/design.md"
        continue
      fi
      resolved="$(normalise "$dir/$path")"
      if [[ -z "$resolved" ]]; then
        # Outside the repository: only the shared data beside it is allowed.
        case "$(normalise "$PWD/$dir/$path")" in
          "$(normalise "$PWD/../shared/data")"*) continue ;;
        esac
        report "$file:$line" "links $target, outside the repository"
        continue
      fi
      if ! exists "$resolved"; then
        report "$file:$line" "links $target: $resolved is not in the repository"
        continue
      fi
    fi
    if [[ -n "$anchor" && "$resolved" == *.md ]]; then
      grep -qxF -- "$anchor" <<<"$(anchors "$resolved")" \
        || report "$file:$line" "links $target: $resolved has no heading #$anchor"
    fi
  done < <(awk '
      /^[ \t]*```/ { fenced = !fenced; next }
      fenced { next }
      {
        text = $0
        gsub(/`[^`]*`/, "", text)   # code spans are not links
        while (match(text, /\]\([^) ]+( "[^"]*")?\)/)) {
          target = substr(text, RSTART + 2, RLENGTH - 3)
          print NR "\t" target
          text = substr(text, RSTART + RLENGTH)
        }
      }' "$file")
done < <(git ls-files '*.md')

# 2. Repository paths named in prose, comments and code.
while IFS= read -r hit; do
  file="${hit%%:*}"
  rest="${hit#*:}"
  line="${rest%%:*}"
  token="${rest#*:}"
  [[ "$token" == [A-Za-z.]* ]] || token="${token:1}"  # the character before the path, if any
  token="${token%%[.]}"   # a full stop after it
  token="${token%%[.]}"
  [[ "$file" == scripts/check-links.sh ]] && continue
  check="$token"
  if [[ "$check" == *"<"* ]]; then check="${check%%<*}"; fi  # engine/src/<library>/: engine/src/ must exist
  check="$(sed -E 's/\{[^}]*\}/*/g' <<<"$check")"            # bake_{irradiance,accumulate}.h: bake_*.h
  exists "$check" && continue
  # In CMake files a relative path is relative to the file's folder (bench/CMakeLists.txt's bench/main.cpp).
  if [[ "$file" == *CMakeLists.txt || "$file" == *.cmake ]] && exists "$(normalise "$(dirname "$file")/$check")"; then
    continue
  fi
  # A path in a line that names the commit it was at is history, not a pointer ("... at commit a84ad4b").
  sed -n "${line}p" "$file" | grep -qE "commit [0-9a-f]{7,40}" && continue
  report "$file:$line" "names $token, which is not in the repository"
done < <(git grep -n -o -I -E "(^|[^A-Za-z0-9_./-])(${roots})/([A-Za-z0-9_.*<>/-]|\{[A-Za-z0-9_.,]*\})*" -- \
           '*.md' '*.h' '*.hpp' '*.c' '*.cpp' '*.comp' '*.vert' '*.frag' '*.glsl' '*.cmake' '*CMakeLists.txt' \
           '*.sh' '*.py' '*.yaml' '.ci/*' 2>/dev/null \
         || true)

# 3. The old design note, outside the repository.
while IFS= read -r hit; do
  [[ "${hit%%:*}" == scripts/check-links.sh ]] && continue
  report "$hit" "cites the old design note (DESIGN.md); cite docs/design.md and its section numbers"
done < <(git grep -n -I -E "DESIGN\\.md" -- . 2>/dev/null | cut -d: -f1,2 || true)

if [ "$problems" -ne 0 ]; then
  echo "check-links: $problems broken path(s) or link(s)" >&2
  exit 1
fi
echo "check-links: every repository path and link in the tracked files resolves"
