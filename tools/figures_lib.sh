# Functions of tools/figures.sh, sourced by it: timing, the run/timed
# wrappers that keep each step's output in $work, and the readers that pick
# single figures out of the tools' Markdown tables. Uses the caller's $work,
# $truth_b and fail().

now_s() { date +%s.%N; }
elapsed() { awk -v a="$1" -v b="$(now_s)" 'BEGIN { printf "%.2f", b - a }'; }
load() { cut -d' ' -f1-3 /proc/loadavg; }
step() { echo "figures: $*" >&2; }
# Runs a command, keeping its output in $work/<name>.out; fails with its tail.
run() {  # name command...
  local name="$1"; shift
  if ! "$@" > "$work/$name.out" 2> "$work/$name.err"; then
    tail -n 5 "$work/$name.err" >&2
    fail "step '$name' failed: $*"
  fi
}
# Runs a command and prints its wall time in seconds.
timed() {  # name command...
  local start
  start="$(now_s)"
  run "$@"
  elapsed "$start"
}

# The parameter table of an identification report against vehicle B's truth.
identification_table() {  # report.md
  awk -v truth="$truth_b" '
    BEGIN {
      n = split(truth, pairs, /[ \n]+/)
      for (i = 1; i <= n; ++i) { split(pairs[i], kv, "="); true_value[kv[1]] = kv[2] }
      print "| parameter | key | identified | one sigma | true | error | error / sigma |"
      print "|---|---|---|---|---|---|---|"
    }
    /^\| [^|]+ \| [a-z0-9_]+(\[[0-9]\])? \| [-+0-9.eE]+ \| [-+0-9.eE]+ \|/ {
      split($0, f, /[ ]*\|[ ]*/)
      symbol = f[2]; key = f[3]; value = f[4]; sigma = f[5]
      if (key in true_value) {
        t = true_value[key]
        printf "| %s | %s | %s | %s | %s | %+.3f %% | %.1f |\n", symbol, key, value, sigma, t,
               100 * (value - t) / t, (value - t) / sigma * (value >= t ? 1 : -1)
      } else {
        printf "| %s | %s | %s | %s | - | - | - |\n", symbol, key, value, sigma
      }
      ++rows
    }
    END { if (rows == 0) { print "figures.sh: no parameter rows in the report" > "/dev/stderr"; exit 1 } }
  ' "$1"
}

# One cell of a Markdown table (the first table of FILE whose header starts
# with "| scenario"), by the first two columns (the second "" for a table
# keyed by the first alone) and the column's header;
# "?" and a warning when there is none.
cell() {  # file column1 column2 header
  awk -v a="$2" -v b="$3" -v header="$4" '
    function trim(s) { gsub(/^[ ]+|[ ]+$/, "", s); return s }
    /^\| scenario/ && !n { n = split($0, h, "|"); for (i = 2; i < n; ++i) col[trim(h[i])] = i; next }
    n && /^\|/ {
      split($0, f, "|")
      row = trim(f[2]); sub(/ seed [0-9]+$/, "", row)  # "thrust_loss seed 4": the case flown on its own seed
      if (row == a && (b == "" || trim(f[3]) == b) && (header in col)) { print trim(f[col[header]]); found = 1; exit }
    }
    END { if (!found) { print "?"; print "figures.sh: warning: no cell " a " / " b " / " header > "/dev/stderr" } }
  ' "$1"
}
# CPU and wall time of one benchmark (its median row, or its only row with
# one repetition), in microseconds or milliseconds: "3.03 us CPU (3.10 us wall)".
benchmark_time() {  # name
  awk -v name="$1" '
    function show(value, unit) {
      if (unit == "ns") return sprintf("%.2f us", value / 1000)
      return sprintf("%.3g %s", value, unit)
    }
    $1 == name || $1 == name "_median" { printf "%s CPU (%s wall)", show($4, $5), show($2, $3); found = 1; exit }
    END { if (!found) printf "?" }' "$work/bench_est.out"
}

# Error of one identified key in a table: "+0.031 % (0.5 sigma)".
id_error() {  # table key
  awk -F' *\\| *' -v key="$2" '$3 == key { printf "%s (%s sigma)", $7, $8; found = 1 } END { if (!found) printf "?" }' "$1"
}
# One cell of the N-rotor control table of FILE (header "| case | mode | map"),
# by case, mode and map and the column's header; "?" and a warning when none.
control_cell() {  # file case mode map header
  awk -v c="$2" -v m="$3" -v p="$4" -v header="$5" '
    function trim(s) { gsub(/^[ ]+|[ ]+$/, "", s); return s }
    /^\| case \| mode \| map/ && !n { n = split($0, h, "|"); for (i = 2; i < n; ++i) col[trim(h[i])] = i; next }
    n && /^\|/ {
      split($0, f, "|")
      if (trim(f[2]) == c && trim(f[3]) == m && trim(f[4]) == p && (header in col)) { print trim(f[col[header]]); found = 1; exit }
    }
    END { if (!found) { print "?"; print "figures.sh: warning: no cell " c " / " m " / " p " / " header > "/dev/stderr" } }
  ' "$1"
}
