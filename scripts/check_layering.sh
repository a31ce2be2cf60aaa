#!/usr/bin/env bash
# Enforces docs/architecture.md's dependency rule on #include lines:
#   app -> device -> firmware_protocol;  app -> physics, fx;  fx -> physics;  device -> physics
#   physics, fx, firmware_protocol: no VTK, no Qt, nothing of app or device.
set -u
root=${1:-$(dirname "$0")/..}
cd "$root" || exit 2
status=0
forbid() {  # forbid FOLDER PATTERN WHY
  local hits
  hits=$(grep -rnE "^\s*#\s*include\s*[<\"]($2)" "$1" --include='*.h' --include='*.hpp' --include='*.cpp' --include='*.cc' 2>/dev/null)
  if [ -n "$hits" ]; then
    echo "layering: $1 must not include $3:"; echo "$hits"; status=1
  fi
}
gui='vtk|Q[A-Z]|qt|QVTK'
forbid physics "app/|device/|fx/|firmware_protocol/|$gui" "app, device, fx, firmware_protocol, VTK or Qt"
forbid fx "app/|device/|firmware_protocol/|$gui" "app, device, firmware_protocol, VTK or Qt"
forbid firmware_protocol "app/|device/|physics/|fx/|$gui" "app, device, physics, fx, VTK or Qt"
forbid device "app/|fx/|$gui" "app, fx, VTK or Qt"
[ $status -eq 0 ] && echo "layering: OK (physics, fx, firmware_protocol, device include only what docs/architecture.md allows)"
exit $status
