#!/usr/bin/env bash
# Checks the dependency rule of the layers (docs/architecture.md) on the #include lines. A place
# is a top folder (geometry, energies, optim, scenes, python, bench) or a room of core/
# (core/model, core/contact, core/dynamics, core/sensitivity; core itself: the Scene front door):
#   geometry <- energies <- core/model <- core/contact <- core/dynamics <- core <- core/sensitivity
#   optim is below core/model (it knows no physics); scenes, python, bench sit on top of core.
set -u
root=${1:-.}
status=0
place_of_include() {  # "core/contact/x.h" -> core/contact; "core/scene.h" -> core; "optim/x.h" -> optim
  sed -E 's/.*#include "([a-z_]+)\/([a-z_]+)\/.*/\1\/\2/; s/.*#include "([a-z_]+)\/[a-z_]+\.h".*/\1/' <<<"$1"
}
check() {  # folder (files directly in it, not its subfolders), allowed places...
  local folder=$1; shift
  local allowed="$folder $*"
  while IFS= read -r line; do
    local inc
    inc=$(place_of_include "$line")
    case " $allowed " in *" $inc "*) ;; *) echo "layering: $line (allowed: $allowed)"; status=1 ;; esac
  done < <(find "$root/$folder" -maxdepth 1 \( -name '*.h' -o -name '*.cpp' \) -print0 2>/dev/null |
           xargs -0 -r grep -Hn -E '#include "[a-z_]+/')
}
check geometry
check optim
check energies geometry
check core/model geometry energies optim
check core/contact core/model geometry energies optim
check core/dynamics core/contact core/model geometry energies optim
check core core/dynamics core/contact core/model geometry energies optim
check core/sensitivity core core/dynamics core/contact core/model geometry energies optim
check scenes core core/sensitivity core/dynamics core/contact core/model geometry energies optim
[ $status -eq 0 ] && echo "layering: ok"
exit $status
