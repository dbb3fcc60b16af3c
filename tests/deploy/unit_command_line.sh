# Sourced by the deploy tests: unit_command_line UNIT ENV_FILE [ROOT] sets the
# array command_line to the unit's ExecStart line as systemd splits it, with
# the variables of ENV_FILE (and of the caller's environment after it, for
# BIROTOR_LCM_URL and the like given as overrides: set them in
# UNIT_OVERRIDES, "NAME=value" words) and /usr/bin/ programs taken from ROOT.
# systemd's rules: ${VAR} is one word, $VAR is split into words; the
# specifier %d is the unit's credentials folder: $CREDENTIALS_DIRECTORY
# (set it where LoadCredential= would have put the copies).
unit_command_line() {
  local unit="$1" env_file="$2" root="${3:-}" word name part
  set -a
  . "$env_file"
  set +a
  set -f  # no file-name expansion of the words (an LCM URL has a '?')
  for word in ${UNIT_OVERRIDES:-}; do export "$word"; done
  command_line=()
  for word in $(sed -n 's/^ExecStart=//p' "$unit"); do
    case "$word" in
      /usr/bin/*) command_line+=("$root$word") ;;
      '${'*'}') name="${word#\$\{}"; name="${name%\}}"; command_line+=("${!name}") ;;
      '$'*) name="${word#\$}"; for part in ${!name}; do command_line+=("$part"); done ;;
      *%d*) command_line+=("${word//%d/${CREDENTIALS_DIRECTORY:-}}") ;;
      *) command_line+=("$word") ;;
    esac
  done
  set +f
}
