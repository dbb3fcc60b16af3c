// The one gnuplot driver of the project: every PNG (birotor-plot, birotor-eval
// --plot-dir, birotor-monitor --png, birotor-identify --plot) is drawn here.
// No path ever passes through a shell or into a gnuplot script, and nothing is
// left beside the PNG:
//  - gnuplot is started with posix_spawnp of the fixed argv {"gnuplot", "-d"}
//    (no shell, no init file);
//  - the script, with its data inline as datablocks ($name << EOD), is fed on
//    stdin from an unlinked temporary file;
//  - gnuplot writes the PNG to its stdout, which is a temporary file in the
//    target's folder; it is renamed over the target only when gnuplot exited 0
//    and the bytes are a PNG, and removed otherwise;
//  - gnuplot's stderr goes to an unlinked temporary file, read for the error.
#pragma once

#include <string>

namespace birotor {

// text as a gnuplot string literal in single quotes: a quote is doubled, and
// control characters (a newline would end the script line) become spaces.
std::string GnuplotQuoted(const std::string& text);

// Runs gnuplot on script and writes what it prints on stdout to png_path,
// atomically (temporary file + rename). The script sets a png terminal and no
// `set output`. False with a one-line *error when gnuplot cannot be started,
// fails, or prints no PNG; png_path is then left as it was.
bool RenderGnuplotPng(const std::string& script, const std::string& png_path, std::string* error);

}  // namespace birotor
