#!/usr/bin/env bash
# The folders of meso/ are layers (docs/architecture.md): a file may include headers of its own
# folder and of the folders below it, never of one above. This walks every tracked source of meso/
# (and the top-level modules that use it) and fails naming each include that points upward.
set -u
cd "$(dirname "$0")/.." || exit 1
git rev-parse --git-dir >/dev/null 2>&1 || { echo "skipped: not a git checkout"; exit 77; }
# Lowest first. common and flowdata sit below everything; image beside physics (no physics in it).
order=(common flowdata physics image scene effects domain backend backend/cpu backend/cuda engine
       analysis io populate run)
rank() { # layer index of a folder key, -1 when unknown
  local i
  for i in "${!order[@]}"; do [ "${order[$i]}" = "$1" ] && { echo "$i"; return; }; done
  echo -1
}
key_of_path() { # meso/backend/cpu/x.c -> backend/cpu; meso/scene/x.h -> scene; common/x.h -> common
  local p=$1
  case $p in
  meso/backend/cpu/* | backend/cpu/*) echo backend/cpu ;;
  meso/backend/cuda/* | backend/cuda/*) echo backend/cuda ;;
  meso/backend/* | backend/*) echo backend ;;
  meso/*) p=${p#meso/}; echo "${p%%/*}" ;;
  *) echo "${p%%/*}" ;;
  esac
}
bad=0; n=0
for f in $(git ls-files 'meso/*.c' 'meso/*.h' 'meso/*.cu' 'meso/*.cuh' 'flowdata/*.[ch]' 'common/*.[ch]'); do
  from=$(key_of_path "$f"); rf=$(rank "$from")
  [ "$rf" -lt 0 ] && continue
  while IFS= read -r inc; do
    case $inc in */*) ;; *) continue ;; esac # same-folder include
    to=$(key_of_path "$inc"); rt=$(rank "$to")
    [ "$rt" -lt 0 ] && continue
    n=$((n + 1))
    # backend/cpu and backend/cuda are siblings: neither includes the other
    if [ "$rt" -gt "$rf" ] || { [ "$from" != "$to" ] && [ "${from%/*}" = backend ] && [ "${to%/*}" = backend ] && [ "$to" != backend ]; }; then
      echo "$f includes \"$inc\": $to is above $from"
      bad=1
    fi
  done < <(grep -oE '^#include "[^"]+"' "$f" | sed 's/#include "\(.*\)"/\1/')
done
[ $bad -ne 0 ] && { echo "layering broken (order, lowest first: ${order[*]})"; exit 1; }
echo "$n cross-folder includes, all downward (${order[*]})"
