#!/usr/bin/env bash
# Starts lcm-spy with the birotor types jar on its class path, so every
# channel (STRAIN, MOTOR, FORCE, ESTIMATOR_STATUS, ...) is decoded by name.
# Usage: tools/lcm-spy.sh [--lcm-url URL] [other lcm-spy options]
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
jar=""
for candidate in "${BIROTOR_TYPES_JAR:-}" "$here/build/lcmtypes/birotor_lcmtypes.jar" \
                 /usr/local/share/java/birotor_lcmtypes.jar /usr/share/java/birotor_lcmtypes.jar; do
  if [ -n "$candidate" ] && [ -f "$candidate" ]; then jar="$candidate"; break; fi
done
if [ -z "$jar" ]; then
  echo "lcm-spy.sh: error: birotor_lcmtypes.jar not found; build first (tools/setup.sh) or set BIROTOR_TYPES_JAR" >&2
  exit 1
fi
command -v lcm-spy > /dev/null || { echo "lcm-spy.sh: error: lcm-spy not installed (apt-get install liblcm-bin liblcm-java)" >&2; exit 1; }
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --lcm-url) args+=("--lcm-url=$2"); shift 2 ;;
    --lcm-url=*) args+=("$1"); shift ;;
    -h|--help) echo "Usage: tools/lcm-spy.sh [--lcm-url URL]   (jar: $jar)"; exit 0 ;;
    *) args+=("$1"); shift ;;
  esac
done
export CLASSPATH="$jar${CLASSPATH:+:$CLASSPATH}"
exec lcm-spy "${args[@]}"
