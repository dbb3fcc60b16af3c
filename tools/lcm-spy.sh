#!/usr/bin/env bash
# Starts lcm-spy with the birotor types jar on its class path, so every
# channel (STRAIN, MOTOR, FORCE, ESTIMATOR_STATUS, ...) is decoded by name.
# Usage: tools/lcm-spy.sh [--lcm-url URL] [other lcm-spy options]
# Installed as PREFIX/bin/birotor-lcm-spy; it then finds the jar installed in
# PREFIX/share/java (in the source tree: build/lcmtypes).
set -euo pipefail
here="$(cd "$(dirname "$(readlink -f "$0")")/.." && pwd)"
jar=""
for candidate in "${BIROTOR_TYPES_JAR:-}" "$here/share/java/birotor_lcmtypes.jar" \
                 "$here/build/lcmtypes/birotor_lcmtypes.jar" \
                 /usr/local/share/java/birotor_lcmtypes.jar /usr/share/java/birotor_lcmtypes.jar; do
  if [ -n "$candidate" ] && [ -f "$candidate" ]; then jar="$candidate"; break; fi
done
for arg in "$@"; do
  case "$arg" in
    -h|--help)
      echo "Usage: $(basename "$0") [--lcm-url URL] [other lcm-spy options]"
      echo "Starts lcm-spy with the birotor types (jar: ${jar:-not found}; set BIROTOR_TYPES_JAR to choose one)."
      exit 0 ;;
  esac
done
if [ -z "$jar" ]; then
  echo "$(basename "$0"): error: birotor_lcmtypes.jar not found; build first (tools/setup.sh) or set BIROTOR_TYPES_JAR" >&2
  exit 1
fi
lcm_jar=/usr/share/java/lcm.jar
[ -f "$lcm_jar" ] || { echo "$(basename "$0"): error: $lcm_jar not found (apt-get install liblcm-java)" >&2; exit 1; }
command -v java > /dev/null || { echo "$(basename "$0"): error: java not found (apt-get install default-jre-headless)" >&2; exit 1; }
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --lcm-url) args+=("--lcm-url=$2"); shift 2 ;;
    --lcm-url=*) args+=("$1"); shift ;;
    *) args+=("$1"); shift ;;
  esac
done
# Debian's /usr/bin/lcm-spy passes -Xincgc, which Java 17 rejects; start the
# class directly. jchart2d draws the per-channel charts.
classpath="$jar:$lcm_jar"
[ -f /usr/share/java/jchart2d.jar ] && classpath="$classpath:/usr/share/java/jchart2d.jar"
exec java -Djava.net.preferIPv4Stack=true -Xmx128m -cp "$classpath${CLASSPATH:+:$CLASSPATH}" lcm.spy.Spy "${args[@]}"
