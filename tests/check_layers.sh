#!/usr/bin/env bash
# Checks the dependency rule of the layers (DESIGN.md) on the #include lines:
#   geometry <- energies <- core -> optim ; scenes, python, bench depend on core.
set -u
root=${1:-.}
status=0
check() {  # folder, allowed folders...
  local folder=$1; shift
  local allowed="$folder $*"
  while IFS= read -r line; do
    inc=$(sed -E 's/.*#include "([a-z_]+)\/.*/\1/' <<<"$line")
    case " $allowed " in *" $inc "*) ;; *) echo "layering: $line (allowed: $allowed)"; status=1 ;; esac
  done < <(grep -rHn -E '#include "[a-z_]+/' "$root/$folder" --include='*.h' --include='*.cpp' 2>/dev/null)
}
check geometry
check optim
check energies geometry
check core geometry energies optim
check scenes core geometry energies optim
[ $status -eq 0 ] && echo "layering: ok"
exit $status
