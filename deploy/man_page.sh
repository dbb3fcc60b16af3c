#!/bin/sh
# The manual page of one installed program, made at build time from its
# --help by help2man, with the build tree's paths written as the package's
# (PACKAGE_PREFIX, /usr) and gzip -9n (no name or time stamp in the archive).
# The program runs under its installed name from a scratch folder on PATH, with
# a stand-in home so the user's folder reads ~/.config/birotor.
# Usage: man_page.sh OUTPUT.1.gz PROGRAM_FILE NAME VERSION BUILD_DIR PACKAGE_PREFIX
set -eu
output="$1"; program="$2"; name="$3"; version="$4"; build_dir="$(cd "$5" && pwd -P)"; prefix="$6"
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
ln -s "$program" "$scratch/$name"
home=/BIROTORMANHOME  # no '-': help2man writes it as '\-'
run_env() {
  env -u XDG_CONFIG_HOME HOME="$home" PATH="$scratch:$PATH" PYTHONPATH="$build_dir/python" \
    BIROTOR_TYPES_JAR="$build_dir/lcmtypes/birotor_lcmtypes.jar" "$@"
}
# NAME section: the first line of --help that is not a usage line, without a leading "<name>: ".
description="$(run_env "$name" --help 2>&1 | grep -v -i -e '^usage:' -e '^ *$' | head -1 | sed "s/^$name: //")"
[ -n "$description" ] || { echo "man_page.sh: $name --help printed no description" >&2; exit 1; }
run_env help2man --no-info --no-discard-stderr --section=1 --version-string="$version" \
  --name="$description" --output="$scratch/page.1" "$name"
# The build tree as printed and as help2man escapes it (each '-' as '\-').
build_escaped="$(printf '%s' "$build_dir" | sed 's/-/\\-/g')"
BUILD="$build_dir" BUILD_ESCAPED="$build_escaped" PREFIX="$prefix" HOME_DIR="$home" perl -pe '
  for my $build ($ENV{BUILD}, $ENV{BUILD_ESCAPED}) {
    s/\Q$build\E\/lcmtypes\//$ENV{PREFIX}\/share\/java\//g;
    s/\Q$build\E/$ENV{PREFIX}/g;
  }
  s/\Q$ENV{HOME_DIR}\E/~/g;
  # Long default lists in option lines: a break point after each comma, and
  # the page set ragged right (.ad l) so groff need not stretch such a line.
  s/,(?! )/,\\:/g if /^\\fB/;
  $_ .= ".ad l\n" if /^\.TH /;
' "$scratch/page.1" > "$scratch/page.fixed.1"
if grep -qF -e "$build_dir" -e "$build_escaped" -e "$home" "$scratch/page.fixed.1"; then
  echo "man_page.sh: the page of $name still names $build_dir" >&2
  exit 1
fi
gzip -9n < "$scratch/page.fixed.1" > "$output.tmp"
mv "$output.tmp" "$output"
