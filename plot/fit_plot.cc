#include "plot/fit_plot.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>

#include "transport/output_file.h"

extern char** environ;

namespace birotor {
namespace {

// gnuplot string literal in single quotes ('' escapes a quote).
std::string Quoted(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

// Creates an empty temporary file named after `stem`; returns its path or "".
std::string TemporaryFile(const std::string& stem) {
  const char* dir = std::getenv("TMPDIR");
  std::string pattern = std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/" + stem + "XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = ::mkstemp(buffer.data());
  if (fd < 0) return "";
  ::close(fd);
  return std::string(buffer.data());
}

// Runs `gnuplot script` without a shell; its stderr goes to error_path.
bool RunGnuplot(const std::string& script_path, const std::string& error_path, std::string* error) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, error_path.c_str(), O_WRONLY | O_TRUNC, 0);
  char program[] = "gnuplot";
  std::vector<char> script(script_path.begin(), script_path.end());
  script.push_back('\0');
  char* argv[] = {program, script.data(), nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) {
    *error = "cannot run gnuplot (install gnuplot-nox)";
    return false;
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::ifstream messages(error_path);
    std::stringstream text;
    text << messages.rdbuf();
    *error = "gnuplot failed: " + text.str();
    return false;
  }
  return true;
}

}  // namespace

bool WriteFitPlot(const std::vector<FitPlot>& plots, const std::string& title, const std::string& png_path,
                  std::string* error) {
  if (plots.empty()) {
    *error = "no fit to plot";
    return false;
  }
  const std::string data_path = TemporaryFile("birotor_identify_plot_data_");
  const std::string script_path = TemporaryFile("birotor_identify_plot_gp_");
  const std::string error_path = TemporaryFile("birotor_identify_plot_err_");
  if (data_path.empty() || script_path.empty() || error_path.empty()) {
    *error = "cannot create temporary files for the plot";
    return false;
  }
  // One gnuplot data block per panel (blocks separated by two blank lines,
  // addressed with `index`), sorted by abscissa so the model draws as a line.
  {
    std::ofstream data(data_path);
    data.precision(10);
    for (const FitPlot& plot : plots) {
      std::vector<size_t> order(plot.x.size());
      std::iota(order.begin(), order.end(), 0);
      std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return plot.x[a] < plot.x[b]; });
      for (size_t i : order) {
        data << plot.x[i] << ' ' << plot.data[i] << ' ';
        if (std::isfinite(plot.model[i]))
          data << plot.model[i];
        else
          data << "NaN";
        data << '\n';
      }
      data << "\n\n";
    }
  }
  // gnuplot draws into a temporary file next to the PNG, renamed on success.
  OutputFile png;
  if (!png.Open(png_path, error)) return false;
  const int columns = plots.size() > 1 ? 2 : 1;
  const int rows = static_cast<int>((plots.size() + columns - 1) / columns);
  {
    std::ofstream script(script_path);
    script << "set terminal pngcairo size " << 700 * columns << "," << 380 * rows << " font 'sans,9'\n"
           << "set output " << Quoted(png.write_path()) << "\n"
           << "set datafile missing 'NaN'\n"
           << "set grid\nset key top left box opaque\n"
           << "set multiplot layout " << rows << "," << columns << " title " << Quoted(title) << "\n";
    for (size_t n = 0; n < plots.size(); ++n) {
      const FitPlot& plot = plots[n];
      script << "set title " << Quoted(plot.title) << "\n"
             << "set xlabel " << Quoted(plot.x_label) << "\n"
             << "set ylabel " << Quoted(plot.y_label) << "\n"
             << "plot " << Quoted(data_path) << " index " << n
             << " using 1:2 with points pt 7 ps 0.3 lc rgb '#1f77b4' title 'data', \\\n"
             << "     '' index " << n << " using 1:3 with lines lw 2 lc rgb '#d62728' title 'fit'\n";
    }
    script << "unset multiplot\n";
  }
  const bool ok = RunGnuplot(script_path, error_path, error);
  std::remove(data_path.c_str());
  std::remove(script_path.c_str());
  std::remove(error_path.c_str());
  return ok && png.Commit(error);
}

}  // namespace birotor
